#include "tests/oracle/exact_geodesic_oracle.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace pelage::test {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, CgalMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
using Bary = Traits::Barycentric_coordinates;
using FaceIndex = CgalMesh::Face_index;
using VertexIndex = CgalMesh::Vertex_index;
using sim::Vec3d;

constexpr double infinity = std::numeric_limits<double>::infinity();
// Weights this far outside [0, 1] are rounding of the caller's arithmetic and are
// clamped; anything further is a location off its triangle, which CGAL would extrapolate
// silently.
constexpr double weight_slack = 1e-9;
// Euclidean tests against a radius are widened by this relative amount, so that rounding
// can only add work, never leave out a source or a face the certificate counts on.
constexpr double radius_slack = 1e-9;

// A CGAL copy of a pelage mesh, face i being triangle i.
struct CgalCopy {
    CgalMesh mesh;
    // CGAL's barycentric coordinates on face f follow source(halfedge(f)),
    // target(halfedge(f)), target(next(halfedge(f))); that walk starts at pelage's corner
    // first_corner[f] and keeps the winding (checked when the face is added).
    std::vector<uint8_t> first_corner;
    size_t split_vertices = 0;
};

// The fans of each vertex: corner slot 3 t + k (corner k of triangle t) joins the slots
// of the same vertex in the triangles across the two edges that meet at it. A vertex
// whose slots fall into several groups is a pinch (two sheets touching at a point, as the
// welded cow has), which CGAL's halfedge structure cannot hold; each fan then gets a
// vertex of its own at the same position. Returns the group's representative per slot.
std::vector<uint32_t> fans_of_corners(const sim::TriangleMesh &mesh) {
    const size_t n = 3 * mesh.triangles.size();
    std::vector<uint32_t> parent(n);
    for (uint32_t i = 0; i < n; ++i) parent[i] = i;
    auto root = [&](uint32_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    // Keyed by the directed pair (vertex, other end): the first slot that reached it.
    std::unordered_map<uint64_t, uint32_t> first_slot;
    first_slot.reserve(2 * n);
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto &tri = mesh.triangles[t];
            const auto slot = static_cast<uint32_t>(3 * t + k);
            for (int other : {(k + 1) % 3, (k + 2) % 3}) {
                const uint64_t key = (uint64_t(tri[k]) << 32) | tri[other];
                const auto [it, added] = first_slot.emplace(key, slot);
                if (!added) parent[root(slot)] = root(it->second);
            }
        }
    for (uint32_t i = 0; i < n; ++i) parent[i] = root(i);
    return parent;
}

CgalCopy copy_to_cgal(const sim::TriangleMesh &mesh) {
    CgalCopy out;
    CgalMesh &cm = out.mesh;
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
        for (sim::VertId v : mesh.triangles[t])
            if (v >= mesh.positions.size())
                throw std::runtime_error("ExactGeodesicOracle: triangle " +
                                         std::to_string(t) + " names vertex " +
                                         std::to_string(v) + ", past the end");
    // One CGAL vertex per fan, made when a triangle first reaches it. Vertices no
    // triangle uses stay out: CGAL's saddle and boundary tests walk each vertex's
    // halfedges, which an isolated vertex does not have.
    const std::vector<uint32_t> fan = fans_of_corners(mesh);
    std::unordered_map<uint32_t, VertexIndex> fan_vertex;
    std::vector<bool> placed(mesh.positions.size(), false);
    std::vector<VertexIndex> corner(fan.size());
    for (size_t slot = 0; slot < fan.size(); ++slot) {
        const auto [it, added] = fan_vertex.emplace(fan[slot], VertexIndex());
        if (added) {
            const sim::VertId v = mesh.triangles[slot / 3][slot % 3];
            const Vec3d p = mesh.positions[v];
            it->second = cm.add_vertex(Point3(p.x, p.y, p.z));
            out.split_vertices += placed[v];
            placed[v] = true;
        }
        corner[slot] = it->second;
    }

    out.first_corner.resize(mesh.triangles.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const VertexIndex *c = &corner[3 * t];
        const FaceIndex f = cm.add_face(c[0], c[1], c[2]);
        if (f == CgalMesh::null_face())
            throw std::runtime_error(
                "ExactGeodesicOracle: CGAL rejects triangle " + std::to_string(t) +
                " (an edge of three or more triangles, a repeated corner, or a winding "
                "that disagrees with a neighbour)");
        if (size_t(f) != t)
            throw std::runtime_error("ExactGeodesicOracle: CGAL numbers triangle " +
                                     std::to_string(t) + " as face " +
                                     std::to_string(size_t(f)));
        const auto h = cm.halfedge(f);
        int k = 0;
        while (k < 3 && c[k] != cm.source(h)) ++k;
        if (k == 3 || c[(k + 1) % 3] != cm.target(h) ||
            c[(k + 2) % 3] != cm.target(cm.next(h)))
            throw std::runtime_error("ExactGeodesicOracle: CGAL's face " +
                                     std::to_string(t) +
                                     " does not walk the corners of pelage's triangle");
        out.first_corner[t] = static_cast<uint8_t>(k);
    }
    if (cm.number_of_faces() != mesh.triangles.size())
        throw std::runtime_error("ExactGeodesicOracle: CGAL has " +
                                 std::to_string(cm.number_of_faces()) + " faces for " +
                                 std::to_string(mesh.triangles.size()) + " triangles");
    return out;
}

// `l` with its weights clamped into the triangle; throws for a location off it.
SurfaceLocation checked(const SurfaceLocation &l, size_t num_triangles) {
    if (l.tri >= num_triangles)
        throw std::invalid_argument("SurfaceLocation: triangle " + std::to_string(l.tri) +
                                    " out of range (" + std::to_string(num_triangles) +
                                    " triangles)");
    if (!(l.b1 >= -weight_slack && l.b2 >= -weight_slack &&
          l.b1 + l.b2 <= 1 + weight_slack))
        throw std::invalid_argument("SurfaceLocation: weights (" + std::to_string(l.b1) +
                                    ", " + std::to_string(l.b2) + ") outside triangle " +
                                    std::to_string(l.tri));
    const double b1 = std::clamp(l.b1, 0.0, 1.0);
    return {l.tri, b1, std::clamp(l.b2, 0.0, 1.0 - b1)};
}

// A checked location as CGAL's face location on `c`.
std::pair<FaceIndex, Bary> cgal_location(const CgalCopy &c, const SurfaceLocation &l) {
    const double w[3] = {1.0 - l.b1 - l.b2, l.b1, l.b2};
    const int k = c.first_corner[l.tri];
    return {FaceIndex(l.tri), Bary{w[k], w[(k + 1) % 3], w[(k + 2) % 3]}};
}

// One sequence tree from `source`; +infinity where CGAL reaches nothing (its -1).
std::vector<double> single_source(const CgalCopy &c, const SurfaceLocation &source,
                                  std::span<const SurfaceLocation> targets) {
    ShortestPath paths(c.mesh);
    const auto [f, b] = cgal_location(c, source);
    paths.add_source_point(f, b);
    paths.build_sequence_tree();
    std::vector<double> out;
    out.reserve(targets.size());
    for (const SurfaceLocation &t : targets) {
        const auto [tf, tb] = cgal_location(c, t);
        const double d = paths.shortest_distance_to_source_points(tf, tb).first;
        out.push_back(d < 0 ? infinity : d);
    }
    return out;
}

// Ericson, Real-Time Collision Detection, 5.1.5: the closest point of triangle abc to p,
// by the Voronoi region of p.
double squared_distance_to_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return length_squared(ap);
    const Vec3d bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return length_squared(bp);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return length_squared(ap - ab * (d1 / (d1 - d3)));
    const Vec3d cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return length_squared(cp);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return length_squared(ap - ac * (d2 / (d2 - d6)));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return length_squared(bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    const double inv = 1 / (va + vb + vc);
    return length_squared(ap - ab * (vb * inv) - ac * (vc * inv));
}

}  // namespace

struct ExactGeodesicOracle::Impl {
    sim::TriangleMesh mesh;  // positions and triangles only
    CgalCopy full;
    // The triangles around each vertex (CSR), for growing patches.
    std::vector<uint32_t> vertex_face_row;
    std::vector<sim::TriId> vertex_faces;
    double area = 0, diagonal = 0;

    Vec3d point(const SurfaceLocation &l) const {
        return mesh.vertex(l.tri, 0) * (1 - l.b1 - l.b2) + mesh.vertex(l.tri, 1) * l.b1 +
               mesh.vertex(l.tri, 2) * l.b2;
    }
};

ExactGeodesicOracle::ExactGeodesicOracle(const sim::TriangleMesh &mesh)
    : m_impl(std::make_unique<Impl>()) {
    Impl &im = *m_impl;
    im.full = copy_to_cgal(mesh);
    im.mesh.positions = mesh.positions;
    im.mesh.triangles = mesh.triangles;
    im.area = mesh.surface_area();
    im.diagonal = mesh.bounds().diagonal();
    im.vertex_face_row.assign(mesh.positions.size() + 1, 0);
    for (const auto &tri : mesh.triangles)
        for (sim::VertId v : tri) ++im.vertex_face_row[v + 1];
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        im.vertex_face_row[v + 1] += im.vertex_face_row[v];
    im.vertex_faces.resize(im.vertex_face_row.back());
    std::vector<uint32_t> fill(im.vertex_face_row.begin(), im.vertex_face_row.end() - 1);
    for (sim::TriId t = 0; t < mesh.triangles.size(); ++t)
        for (sim::VertId v : mesh.triangles[t]) im.vertex_faces[fill[v]++] = t;
}

ExactGeodesicOracle::~ExactGeodesicOracle() = default;
ExactGeodesicOracle::ExactGeodesicOracle(ExactGeodesicOracle &&) noexcept = default;
ExactGeodesicOracle &ExactGeodesicOracle::operator=(ExactGeodesicOracle &&) noexcept =
    default;

size_t ExactGeodesicOracle::num_triangles() const { return m_impl->mesh.num_triangles(); }
size_t ExactGeodesicOracle::split_vertices() const { return m_impl->full.split_vertices; }

std::vector<double> ExactGeodesicOracle::distances(
    const SurfaceLocation &source, std::span<const SurfaceLocation> targets) const {
    const size_t nt = num_triangles();
    std::vector<SurfaceLocation> at;
    at.reserve(targets.size());
    for (const SurfaceLocation &t : targets) at.push_back(checked(t, nt));
    return single_source(m_impl->full, checked(source, nt), at);
}

std::vector<ExactGeodesicOracle::Nearest> ExactGeodesicOracle::nearest(
    std::span<const SurfaceLocation> sources,
    std::span<const SurfaceLocation> targets) const {
    // CGAL's own multi-source sequence tree is not used: on the cow it names a farther
    // source for some targets (a few percent at 2 000 sources) and leaves whole faces
    // unreached. Every distance here comes from a single-source tree, on a patch.
    //
    // The patch of source s for radius R holds the triangles within Euclidean distance R
    // of s, grown from s's triangle through shared vertices. A geodesic of length d <= R
    // from s never leaves that ball, so on the patch it has the same length; longer ones
    // can only grow on the patch. Each round evaluates every (source, target) pair within
    // Euclidean distance R; a target whose best distance is at most R is then exact,
    // since any source nearer along the surface is also nearer in space. The others go
    // to the next round with R doubled, until R spans the mesh and the whole mesh is
    // used.
    const Impl &im = *m_impl;
    const size_t ntri = num_triangles();
    std::vector<SurfaceLocation> from, at;
    from.reserve(sources.size());
    at.reserve(targets.size());
    for (const SurfaceLocation &s : sources) from.push_back(checked(s, ntri));
    for (const SurfaceLocation &t : targets) at.push_back(checked(t, ntri));
    std::vector<Nearest> best(at.size(), Nearest{sim::invalid_id, infinity});
    if (from.empty() || at.empty()) return best;

    std::vector<Vec3d> ps(from.size()), pt(at.size());
    for (size_t i = 0; i < from.size(); ++i) ps[i] = im.point(from[i]);
    for (size_t i = 0; i < at.size(); ++i) pt[i] = im.point(at[i]);
    auto offer = [&](uint32_t target, uint32_t source, double d) {
        Nearest &b = best[target];
        if (d == infinity) return;  // out of reach names no source
        if (d < b.distance || (d == b.distance && source < b.source)) b = {source, d};
    };

    std::vector<uint32_t> pending(at.size());
    for (uint32_t i = 0; i < pending.size(); ++i) pending[i] = i;
    // Twice the spacing of the sources leaves a target with no source within R only
    // rarely (e^-4pi when they are spread evenly).
    double radius = 2 * std::sqrt(im.area / double(from.size()));
    if (!(radius > 0)) radius = im.diagonal;

    // Per-triangle scratch, stamped by patch so nothing is cleared between sources.
    std::vector<uint32_t> face_stamp(ntri, 0), face_local(ntri, 0);
    std::vector<uint32_t> vertex_stamp(im.mesh.positions.size(), 0),
        vertex_local(im.mesh.positions.size(), 0);
    uint32_t stamp = 0;
    std::vector<sim::TriId> queue;
    std::vector<uint32_t> near;
    std::vector<SurfaceLocation> local_targets;

    while (!pending.empty()) {
        const bool whole = !(radius < im.diagonal);  // also ends a degenerate mesh
        if (whole && pending.size() < from.size()) {
            // Fewer trees from the targets than from the sources; distance is symmetric.
            for (uint32_t t : pending) {
                const std::vector<double> d = single_source(im.full, at[t], from);
                for (uint32_t s = 0; s < from.size(); ++s) offer(t, s, d[s]);
            }
            break;
        }
        const double reach = radius * (1 + radius_slack), reach2 = reach * reach;
        // Pending targets in a hash grid of cell `radius`: a source looks at 27 cells.
        std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
        auto cell_of = [&](Vec3d p, int dx, int dy, int dz) {
            const auto c = [&](double x, int d) {
                return uint64_t(int64_t(std::floor(x / radius)) + d) & 0x1fffff;
            };
            return (c(p.x, dx) << 42) | (c(p.y, dy) << 21) | c(p.z, dz);
        };
        for (uint32_t t : pending) grid[cell_of(pt[t], 0, 0, 0)].push_back(t);

        for (uint32_t s = 0; s < from.size(); ++s) {
            near.clear();
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        const auto it = grid.find(cell_of(ps[s], dx, dy, dz));
                        if (it == grid.end()) continue;
                        for (uint32_t t : it->second)
                            if (length_squared(pt[t] - ps[s]) <= reach2)
                                near.push_back(t);
                    }
            if (near.empty()) continue;
            if (whole) {
                local_targets.clear();
                for (uint32_t t : near) local_targets.push_back(at[t]);
                const std::vector<double> d =
                    single_source(im.full, from[s], local_targets);
                for (size_t i = 0; i < near.size(); ++i) offer(near[i], s, d[i]);
                continue;
            }
            // The patch, grown from the source's triangle.
            ++stamp;
            sim::TriangleMesh patch;
            queue.assign(1, from[s].tri);
            face_stamp[from[s].tri] = stamp;
            for (size_t q = 0; q < queue.size(); ++q) {
                const sim::TriId f = queue[q];
                const auto &tri = im.mesh.triangles[f];
                std::array<sim::VertId, 3> local;
                for (int k = 0; k < 3; ++k) {
                    const sim::VertId v = tri[k];
                    if (vertex_stamp[v] != stamp) {
                        vertex_stamp[v] = stamp;
                        vertex_local[v] = static_cast<uint32_t>(patch.positions.size());
                        patch.positions.push_back(im.mesh.positions[v]);
                    }
                    local[k] = vertex_local[v];
                }
                face_local[f] = static_cast<uint32_t>(patch.triangles.size());
                patch.triangles.push_back(local);
                for (sim::VertId v : tri)
                    for (uint32_t i = im.vertex_face_row[v];
                         i < im.vertex_face_row[v + 1]; ++i) {
                        const sim::TriId g = im.vertex_faces[i];
                        if (face_stamp[g] == stamp) continue;
                        face_stamp[g] = stamp;  // looked at, inside or not
                        const auto &gt = im.mesh.triangles[g];
                        if (squared_distance_to_triangle(
                                ps[s], im.mesh.positions[gt[0]], im.mesh.positions[gt[1]],
                                im.mesh.positions[gt[2]]) <= reach2)
                            queue.push_back(g);
                    }
            }
            // A target whose triangle is not in the patch is farther than R along the
            // surface: it gets nothing from this source in this round.
            std::vector<uint32_t> in_patch;
            local_targets.clear();
            // The stamp also marks triangles looked at and left out; queue[q] is local
            // triangle q.
            const size_t patch_faces = queue.size();
            for (uint32_t t : near) {
                const sim::TriId f = at[t].tri;
                if (face_stamp[f] != stamp) continue;
                const uint32_t lf = face_local[f];
                if (lf >= patch_faces || queue[lf] != f) continue;
                in_patch.push_back(t);
                local_targets.push_back({lf, at[t].b1, at[t].b2});
            }
            if (in_patch.empty()) continue;
            const CgalCopy copy = copy_to_cgal(patch);
            const SurfaceLocation src{face_local[from[s].tri], from[s].b1, from[s].b2};
            const std::vector<double> d = single_source(copy, src, local_targets);
            for (size_t i = 0; i < in_patch.size(); ++i) offer(in_patch[i], s, d[i]);
        }

        std::vector<uint32_t> next;
        for (uint32_t t : pending)
            if (!(best[t].distance <= radius) && !whole) next.push_back(t);
        pending.swap(next);
        radius *= 2;
    }
    return best;
}

sim::Vec3d ExactGeodesicOracle::position(const SurfaceLocation &l) const {
    const auto [f, b] = cgal_location(m_impl->full, checked(l, num_triangles()));
    const Point3 p = ShortestPath::point(f, b, m_impl->full.mesh);
    return {p.x(), p.y(), p.z()};
}

}  // namespace pelage::test
