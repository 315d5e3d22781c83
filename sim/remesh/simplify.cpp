#include "sim/remesh/simplify.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <Edge_collapse/Bounded_distance_placement.h>
#include <Edge_collapse/Bounded_normal_change_filter.h>
#include <Edge_collapse/Edge_length_cost.h>
#include <Edge_collapse/Edge_length_stop_predicate.h>
#include <Edge_collapse/LindstromTurk_placement.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace pelage::sim {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;
namespace SMS = CGAL::Surface_mesh_simplification;
namespace PMP = CGAL::Polygon_mesh_processing;

CgalMesh to_cgal(const TriangleMesh &mesh) {
    std::vector<Point> points;
    points.reserve(mesh.num_vertices());
    for (const Vec3d &p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
    std::vector<std::array<size_t, 3>> faces;
    faces.reserve(mesh.num_triangles());
    for (const auto &t : mesh.triangles) faces.push_back({t[0], t[1], t[2]});
    // Splits vertices where fans meet only at a point (and edges shared by more than
    // two faces), which a halfedge mesh cannot hold; keeps the input's orientation
    // where it is consistent.
    PMP::orient_polygon_soup(points, faces);
    CgalMesh cm;
    PMP::polygon_soup_to_polygon_mesh(points, faces, cm);
    return cm;
}

}  // namespace

double max_vertex_distance(const TriangleMesh &from, const TriangleMesh &to) {
    if (to.num_triangles() == 0) return std::numeric_limits<double>::infinity();
    std::vector<char> used(from.num_vertices(), 0);
    for (const auto &t : from.triangles)
        for (VertId v : t) used[v] = 1;
    std::vector<Point> points;
    for (size_t v = 0; v < from.num_vertices(); ++v)
        if (used[v])
            points.emplace_back(from.positions[v].x, from.positions[v].y,
                                from.positions[v].z);
    if (points.empty()) return 0;
    return PMP::max_distance_to_triangle_mesh<CGAL::Sequential_tag>(points, to_cgal(to));
}

double mean_edge_length(const TriangleMesh &mesh) {
    double sum = 0;
    for (TriId t = 0; t < mesh.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c)
            sum += length(mesh.vertex(t, (c + 1) % 3) - mesh.vertex(t, c));
    return mesh.num_triangles() > 0 ? sum / (3.0 * double(mesh.num_triangles())) : 0.0;
}

namespace {

// Collapses edges of cm under `placement` until none is shorter than edge_length.
template <typename Placement>
void collapse(CgalMesh &cm, double edge_length, const Placement &placement) {
    SMS::Edge_length_stop_predicate<double> stop(edge_length);
    SMS::Bounded_normal_change_filter<> filter;
    SMS::edge_collapse(cm, stop,
                       CGAL::parameters::get_cost(SMS::Edge_length_cost<CgalMesh>())
                           .get_placement(placement)
                           .filter(filter));
}

}  // namespace

TriangleMesh simplify(const TriangleMesh &mesh, const SimplifyOptions &options) {
    CgalMesh cm = to_cgal(mesh);
    using Base = SMS::LindstromTurk_placement<CgalMesh>;
    if (options.reference) {
        // The bound measured against the reference's triangles, as CGAL's own placement
        // does against the mesh it starts from.
        using Triangles = std::vector<Kernel::Triangle_3>;
        using Tree = CGAL::AABB_tree<CGAL::AABB_traits<
            Kernel, CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>>>;
        Triangles triangles;
        const TriangleMesh &ref = *options.reference;
        triangles.reserve(ref.num_triangles());
        for (TriId t = 0; t < ref.num_triangles(); ++t) {
            const Vec3d a = ref.vertex(t, 0), b = ref.vertex(t, 1), c = ref.vertex(t, 2);
            triangles.emplace_back(Point(a.x, a.y, a.z), Point(b.x, b.y, b.z),
                                   Point(c.x, c.y, c.z));
        }
        Tree tree(triangles.begin(), triangles.end());
        tree.build();
        tree.accelerate_distance_queries();
        collapse(
            cm, options.edge_length,
            SMS::Bounded_distance_placement<Base, Tree>(options.max_deviation, tree));
    } else {
        collapse(cm, options.edge_length,
                 SMS::Bounded_distance_placement<Base, Kernel>(options.max_deviation));
    }
    cm.collect_garbage();

    TriangleMesh out;
    out.positions.reserve(cm.number_of_vertices());
    for (auto v : cm.vertices()) {
        const Point &p = cm.point(v);
        out.positions.push_back({p.x(), p.y(), p.z()});
    }
    out.triangles.reserve(cm.number_of_faces());
    for (auto f : cm.faces()) {
        std::array<VertId, 3> tri{};
        int k = 0;
        for (auto v : CGAL::vertices_around_face(cm.halfedge(f), cm))
            tri[k++] = static_cast<VertId>(v.idx());
        out.source_face.push_back(static_cast<uint32_t>(out.triangles.size()));
        out.triangles.push_back(tri);
    }
    return out;
}

}  // namespace pelage::sim
