#include "sim/mesh/mesh_clean.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "sim/core/disjoint_sets.h"
#include "sim/core/input_error.h"

namespace pelage::sim {
namespace {

// A point's cell on a uniform grid of cell size eps from `origin`, and the cell's hash
// key (the weld's and the stitch's grids).
std::array<int64_t, 3> grid_cell(Vec3d q, Vec3d origin, double eps) {
    q = q - origin;
    return {static_cast<int64_t>(std::floor(q.x / eps)),
            static_cast<int64_t>(std::floor(q.y / eps)),
            static_cast<int64_t>(std::floor(q.z / eps))};
}
uint64_t key_of(int64_t x, int64_t y, int64_t z) {
    uint64_t h = static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h;
}

// Welds vertices on a uniform grid of cell size eps: a vertex joins the lowest-index
// representative found within eps in its own or the 26 neighbouring cells, so the result
// does not depend on hash-table order. Vertices no triangle uses stay as they are.
std::vector<VertId> weld_vertices(const std::vector<Vec3d> &p,
                                  const std::vector<char> &used, Vec3d origin, double eps,
                                  size_t *num_welded) {
    std::vector<VertId> rep(p.size());
    std::iota(rep.begin(), rep.end(), 0);
    if (!(eps > 0)) return rep;
    // Relative to the corner of the used vertices' box, their cell indices stay below
    // 1/weld_relative: no overflow.
    auto cell_of = [&](Vec3d q) { return grid_cell(q, origin, eps); };
    std::unordered_map<uint64_t, std::vector<VertId>> grid;
    grid.reserve(p.size());
    size_t welded = 0;
    for (VertId v = 0; v < p.size(); ++v) {
        if (!used[v]) continue;
        const auto c = cell_of(p[v]);
        VertId best = v;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = grid.find(key_of(c[0] + dx, c[1] + dy, c[2] + dz));
                    if (it == grid.end()) continue;
                    for (VertId u : it->second)
                        if (u < best && length_squared(p[u] - p[v]) <= eps * eps)
                            best = u;
                }
        rep[v] = best;
        if (best == v) {
            grid[key_of(c[0], c[1], c[2])].push_back(v);
        } else {
            ++welded;
        }
    }
    *num_welded = welded;
    return rep;
}

// Stitches an asset store's triangle soup: a boundary vertex (on an edge only one
// triangle holds) joins the lowest-index boundary vertex of *another* piece within
// stitch_relative of the diagonal and within a third of either's shortest edge, so
// that no edge of either piece collapses and a piece's own holes and slits stay open.
// Pieces cut apart by an exporter whose copies moved apart by more than the weld allows
// (per-part rounding, a slight offset per part) become one surface again, and the
// pattern grows across them. `rep` (after the weld) is updated in place.
size_t stitch_pieces(const TriangleMesh &in, const std::vector<char> &used, Vec3d origin,
                     double eps, std::vector<VertId> *rep) {
    if (!(eps > 0)) return 0;
    const std::vector<Vec3d> &p = in.positions;
    std::vector<VertId> &r = *rep;
    // Edges of the welded mesh and how many triangles hold each; pieces by triangles.
    std::unordered_map<uint64_t, int> edge_count;
    DisjointSets pieces(p.size());
    std::vector<double> shortest(p.size(), std::numeric_limits<double>::infinity());
    auto edge_key = [](VertId a, VertId b) {
        return uint64_t(std::min(a, b)) << 32 | uint64_t(std::max(a, b));
    };
    for (const auto &tri : in.triangles) {
        const std::array<VertId, 3> t = {r[tri[0]], r[tri[1]], r[tri[2]]};
        for (int c = 0; c < 3; ++c) {
            const VertId a = t[c], b = t[(c + 1) % 3];
            if (a == b) continue;
            ++edge_count[edge_key(a, b)];
            pieces.unite(a, b);
            const double l = length(p[a] - p[b]);
            shortest[a] = std::min(shortest[a], l);
            shortest[b] = std::min(shortest[b], l);
        }
    }
    std::vector<char> boundary(p.size(), 0);
    for (const auto &[key, count] : edge_count)
        if (count == 1) boundary[key >> 32] = boundary[key & 0xffffffffu] = 1;
    std::vector<VertId> piece_of(p.size());
    for (VertId v = 0; v < p.size(); ++v) piece_of[v] = pieces.find(v);
    // The same grid as the weld's, over boundary vertices only.
    std::unordered_map<uint64_t, std::vector<VertId>> grid;
    auto cell_of = [&](Vec3d q) { return grid_cell(q, origin, eps); };
    std::vector<VertId> target(p.size());
    std::iota(target.begin(), target.end(), 0);
    size_t stitched = 0;
    for (VertId v = 0; v < p.size(); ++v) {
        if (!used[v] || r[v] != v || !boundary[v]) continue;
        const auto c = cell_of(p[v]);
        VertId best = v;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = grid.find(key_of(c[0] + dx, c[1] + dy, c[2] + dz));
                    if (it == grid.end()) continue;
                    for (VertId u : it->second) {
                        if (u >= best || piece_of[u] == piece_of[v]) continue;
                        const double reach =
                            std::min({eps, shortest[u] / 3, shortest[v] / 3});
                        if (length_squared(p[u] - p[v]) <= reach * reach) best = u;
                    }
                }
        if (best == v) {
            grid[key_of(c[0], c[1], c[2])].push_back(v);
        } else {
            target[v] = best;
            ++stitched;
        }
    }
    for (VertId v = 0; v < p.size(); ++v) r[v] = target[r[v]];
    return stitched;
}

}  // namespace

TriangleMesh clean_mesh(const TriangleMesh &in, const std::string &source_path,
                        const MeshCleanOptions &opt, MeshCleanStats *stats) {
    MeshCleanStats local;
    MeshCleanStats &st = stats ? *stats : local;
    st = {};
    // The tolerances are relative to the size of what the triangles use: a reader may
    // keep every vertex of a file for one of its objects (FILE#NAME), and a small animal
    // of a large scene must not be welded at the scene's scale.
    std::vector<char> in_use(in.positions.size(), 0);
    Bounds3 box;
    for (const auto &tri : in.triangles)
        for (VertId v : tri)
            if (v < in_use.size() && !in_use[v]) {
                in_use[v] = 1;
                box.extend(in.positions[v]);
            }
    const double diag = box.diagonal();

    std::vector<VertId> rep = weld_vertices(
        in.positions, in_use, box.lo, opt.weld_relative * diag, &st.vertices_welded);
    st.vertices_stitched =
        stitch_pieces(in, in_use, box.lo, opt.stitch_relative * diag, &rep);
    // Compact the surviving vertices, keeping their file order.
    std::vector<VertId> new_index(in.positions.size(), invalid_id);
    TriangleMesh out;
    out.materials = in.materials;
    for (VertId v = 0; v < in.positions.size(); ++v)
        if (rep[v] == v) {
            new_index[v] = static_cast<VertId>(out.positions.size());
            out.positions.push_back(in.positions[v]);
            st.source_vertex.push_back(v);
        }
    // A welded vertex keeps the attributes of the vertex it was welded into.
    for (const auto &[name, values] : in.vertex_attributes) {
        std::vector<float> kept;
        kept.reserve(out.positions.size());
        for (VertId v = 0; v < in.positions.size(); ++v)
            if (rep[v] == v) kept.push_back(values[v]);
        out.vertex_attributes.push_back({name, std::move(kept)});
    }

    const bool has_n = !in.corner_normals.empty(), has_uv = !in.corner_uvs.empty();
    const double min_area = opt.area_relative * diag * diag;
    for (TriId t = 0; t < in.num_triangles(); ++t) {
        std::array<VertId, 3> tri;
        for (int c = 0; c < 3; ++c) tri[c] = new_index[rep[in.triangles[t][c]]];
        const bool repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2];
        const Vec3d p0 = out.positions[tri[0]];
        const double area =
            0.5 * length(cross(out.positions[tri[1]] - p0, out.positions[tri[2]] - p0));
        if (repeated || !(area > min_area)) {
            ++st.degenerate_dropped;
            continue;
        }
        out.triangles.push_back(tri);
        st.source_corners.push_back(in.triangles[t]);
        out.source_face.push_back(in.source_face.empty() ? t : in.source_face[t]);
        if (!in.triangle_material.empty())
            out.triangle_material.push_back(in.triangle_material[t]);
        for (int c = 0; c < 3; ++c) {
            if (has_n) out.corner_normals.push_back(in.corner_normals[3 * t + c]);
            if (has_uv) out.corner_uvs.push_back(in.corner_uvs[3 * t + c]);
        }
    }
    if (out.triangles.empty())
        throw InputError(source_path, 0, "",
                         "empty mesh: no triangle with non-zero area (" +
                             std::to_string(st.degenerate_dropped) +
                             " degenerate dropped)");

    std::vector<char> used(out.positions.size(), 0);
    for (const auto &tri : out.triangles)
        for (VertId v : tri) used[v] = 1;
    st.unused_vertices = static_cast<size_t>(std::count(used.begin(), used.end(), 0));
    return out;
}

}  // namespace pelage::sim
