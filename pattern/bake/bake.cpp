#include "pattern/bake/bake.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "pattern/bake/bake_texels.h"
#include "sim/crps/cell_walk.h"

namespace pelage::pattern::bake {
namespace {

using sim::Vec2d;
using sim::Vec3d;

// What a texel shows, from the cells around its surface point.
struct Looks {
    std::vector<std::array<float, 3>> rgb;  // per cell (mosaic::CellTable order)
    std::vector<float> type, id, founder;
};

Looks looks_of(const mosaic::MosaicPattern &pattern) {
    const mosaic::CellTable &cells = pattern.cells();
    const sim::CellsData &d = pattern.data();
    // Ids are dense (cells are never destroyed): the file's founders by id.
    std::vector<uint32_t> founder_of;
    if (!d.founder.empty()) {
        founder_of.assign(d.id.size(), 0);
        for (size_t k = 0; k < d.id.size(); ++k)
            if (d.id[k] < founder_of.size()) founder_of[d.id[k]] = d.founder[k];
    }
    Looks l;
    l.rgb.resize(cells.size());
    l.type.resize(cells.size());
    l.id.resize(cells.size());
    l.founder.resize(cells.size());
    for (size_t k = 0; k < cells.size(); ++k) {
        const sim::CellsFileType &t = pattern.types()[cells.type[k]];
        for (int c = 0; c < 3; ++c) l.rgb[k][c] = std::clamp(t.colour[c], 0.0f, 1.0f);
        l.type[k] = float(cells.type[k]);
        l.id[k] = float(cells.id[k]);  // exact below 2^24 cells
        const uint32_t id = cells.id[k];
        l.founder[k] = float(id < founder_of.size() ? founder_of[id] : id);
    }
    return l;
}

// The clonal_mosaic shader's camera-hit filter (clonal_mosaic_plugin.cpp, shade_blend):
// the nearest three cells within F1 + 2w, weighted 1 - smoothstep(0, 2w, F_i - F1).
void shade_texel(const mosaic::MosaicPattern &pattern, const Looks &looks, sim::TriId tri,
                 float b1, float b2, float w, float *px) {
    if (pattern.cover().carries(tri)) {
        // A piece without cells of its own shows the closest cell-bearing surface's.
        const auto at = pattern.cover().map(tri, b1, b2);
        tri = at.tri;
        b1 = at.b1;
        b2 = at.b2;
    }
    const auto n = pattern.index().find_three_within(tri, b1, b2, 2 * w);
    if (n.index[0] == mosaic::ClosestCell::none) return;  // a component without cells
    const float f1 = std::sqrt(n.d2[0]);
    const float inv_width = 1 / std::max(2 * w, std::numeric_limits<float>::min());
    float rgb[3] = {0, 0, 0}, total = 0;
    for (int i = 0; i < 3 && n.index[i] != mosaic::ClosestCell::none; ++i) {
        const float x = std::min((std::sqrt(n.d2[i]) - f1) * inv_width, 1.0f);
        const float weight = i == 0 ? 1.0f : 1 - x * x * (3 - 2 * x);
        if (weight <= 0) break;
        for (int k = 0; k < 3; ++k) rgb[k] += weight * looks.rgb[n.index[i]][k];
        total += weight;
    }
    for (int k = 0; k < 3; ++k) px[k] = rgb[k] / total;
    px[3] = 1;
    px[4] = looks.type[n.index[0]];
    px[5] = looks.id[n.index[0]];
    px[6] = looks.founder[n.index[0]];
}

// Texels beyond the gutters: the mean of their already filled 4-neighbours, ring by
// ring outwards (deterministic: a ring reads only earlier rings).
void fill_empty(std::vector<float> &px, const std::vector<uint8_t> &covered, int W,
                int H) {
    const int C = BakeResult::channels;
    std::vector<int32_t> ring(covered.size(), -1);
    std::vector<size_t> frontier, next;
    for (size_t i = 0; i < covered.size(); ++i)
        if (covered[i]) {
            ring[i] = 0;
            frontier.push_back(i);
        }
    for (int32_t r = 1; !frontier.empty(); ++r) {
        next.clear();
        for (size_t i : frontier) {
            const int x = int(i % size_t(W)), y = int(i / size_t(W));
            const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
            for (int k = 0; k < 4; ++k) {
                if (nx[k] < 0 || ny[k] < 0 || nx[k] >= W || ny[k] >= H) continue;
                const size_t j = size_t(ny[k]) * W + nx[k];
                if (ring[j] >= 0) continue;
                ring[j] = r;
                next.push_back(j);
            }
        }
        for (size_t j : next) {
            const int x = int(j % size_t(W)), y = int(j / size_t(W));
            const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
            float sum[3] = {0, 0, 0};
            int n = 0;
            for (int k = 0; k < 4; ++k) {
                if (nx[k] < 0 || ny[k] < 0 || nx[k] >= W || ny[k] >= H) continue;
                const size_t i = size_t(ny[k]) * W + nx[k];
                if (ring[i] < 0 || ring[i] >= r) continue;
                for (int c = 0; c < 3; ++c) sum[c] += px[i * C + c];
                ++n;
            }
            for (int c = 0; c < 3; ++c) px[j * C + c] = sum[c] / float(n);
        }
        frontier.swap(next);
    }
}

// The surface point texel centre q shows, owned by triangle `owner` (T) at distance
// `dist`: the nearest point of T, carried onto the pattern's mesh, and for a gutter texel
// walked on from there by the texel's offset.
struct TexelPoint {
    sim::TriId tri;
    float b1, b2;
};

TexelPoint texel_point(const BakeLayout &layout, const sim::Crps &crps,
                       const TexelTriangle &T, sim::TriId owner, float dist, Vec2d q) {
    Vec3d b;
    T.distance_to(q, &b);
    sim::TriId s = owner;
    float b1 = float(b.y), b2 = float(b.z);
    if (layout.transfer) {
        const auto at = layout.transfer->map(s, b1, b2);
        s = at.tri;
        b1 = at.b1;
        b2 = at.b2;
    }
    if (dist > 0) {
        // Walk from the border point by the texel's offset, over the surface into
        // whatever triangle lies there.
        const Vec2d from = T.p[0] * b.x + T.p[1] * b.y + T.p[2] * b.z;
        const Vec2d off = q - from;
        const Vec3d d3 = T.jx * off.x + T.jy * off.y;
        const sim::CrpsFrame &f = crps.frame(s);
        const Vec3d dl = f.rotation * d3;
        const Vec2d start = crps.barycentric_to_2d(
            s, {1.0 - double(b1) - double(b2), double(b1), double(b2)});
        const sim::SurfacePoint end = sim::walk(crps, {s, start}, {dl.x, dl.z});
        const Vec3d be = crps.to_barycentric(end.tri, end.p);
        s = end.tri;
        b1 = float(be.y);
        b2 = float(be.z);
    }
    return {s, b1, b2};
}

// Each owned texel's look, rows in parallel; the others stay black, transparent and
// without ids.
void shade_tile(const mosaic::MosaicPattern &pattern, const Looks &looks,
                const BakeLayout &layout, const std::vector<TexelTriangle> &tris,
                const TexelOwners &owners, std::vector<float> &pixels) {
    const int W = layout.width, H = layout.height, C = BakeResult::channels;
    const sim::Crps &crps = pattern.surface().crps;
    const size_t n = size_t(W) * H;
    pixels.assign(n * C, 0.0f);
    for (size_t i = 0; i < n; ++i)
        for (int c = 4; c < C; ++c) pixels[i * C + c] = -1;
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 4), [&](const auto &r) {
        for (int y = r.begin(); y != r.end(); ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * W + x;
                if (owners.owner[i] == sim::invalid_id) continue;
                const TexelTriangle &T = tris[owners.owner[i]];
                const TexelPoint at = texel_point(layout, crps, T, owners.owner[i],
                                                  owners.dist[i], {x + 0.5, y + 0.5});
                shade_texel(pattern, looks, at.tri, at.b1, at.b2, T.footprint,
                            &pixels[i * C]);
            }
    });
}

// Adds the tile's texels to the result's counts; returns which texels are covered.
std::vector<uint8_t> count_texels(const TexelOwners &owners,
                                  const std::vector<float> &pixels, BakeResult &out) {
    const int C = BakeResult::channels;
    const size_t n = owners.owner.size();
    std::vector<uint8_t> covered(n);
    for (size_t i = 0; i < n; ++i) {
        covered[i] = pixels[i * C + 3] > 0;
        out.texels_inside += owners.owner[i] != sim::invalid_id && owners.dist[i] == 0;
        out.texels_gutter += owners.owner[i] != sim::invalid_id && owners.dist[i] > 0;
        out.texels_overlapped += owners.strictly_inside[i] >= 2;
    }
    return covered;
}

}  // namespace

int udim_of(Vec2d uv) {
    const double u = std::floor(uv.x), v = std::floor(uv.y);
    if (!(u >= 0 && u <= 9 && v >= 0 && v <= 9))
        throw std::invalid_argument(
            "UV (" + std::to_string(uv.x) + ", " + std::to_string(uv.y) +
            ") lies outside the UDIM tiles 1001-1100 (0 <= u < 10, 0 <= v < 10)");
    return 1001 + int(u) + 10 * int(v);
}

std::vector<int> udim_tiles(const sim::TriangleMesh &mesh,
                            const std::vector<sim::Vec2d> &corner_uvs) {
    if (corner_uvs.size() != 3 * mesh.num_triangles())
        throw std::invalid_argument("the layout needs 3 UVs per triangle");
    std::vector<int> tiles;
    for (sim::TriId t = 0; t < mesh.num_triangles(); ++t)
        tiles.push_back(tile_of(mesh, &corner_uvs[3 * size_t(t)], t));
    std::sort(tiles.begin(), tiles.end());
    tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
    return tiles;
}

BakeResult bake_layout(const mosaic::MosaicPattern &pattern, const BakeLayout &layout,
                       const std::function<void(BakedTile &&)> &on_tile) {
    udim_tiles(*layout.mesh, layout.corner_uvs);  // every check, before any work
    const int W = layout.width, H = layout.height;
    const double gutter = layout.gutter;

    BakeResult out;
    out.width = W;
    out.height = H;
    const TexelLayout texels = lay_out_texels(layout);
    out.degenerate_triangles = texels.degenerate_triangles;

    const Looks looks = looks_of(pattern);
    out.num_tiles = texels.by_tile.size();
    for (const auto &[udim, list] : texels.by_tile) {
        const TexelOwners owners = find_owners(texels.tris, list, W, H, gutter);
        BakedTile tile;
        tile.udim = udim;
        shade_tile(pattern, looks, layout, texels.tris, owners, tile.pixels);
        const std::vector<uint8_t> covered = count_texels(owners, tile.pixels, out);
        fill_empty(tile.pixels, covered, W, H);
        if (on_tile)
            on_tile(std::move(tile));
        else
            out.tiles.push_back(std::move(tile));
    }
    return out;
}

BakedAtlas bake_atlas(const mosaic::MosaicPattern &pattern, int width, int height,
                      int gutter, const sim::Surface *render) {
    const bool carried = render && pattern.transfer();
    const sim::Surface &surface = carried ? *render : pattern.surface();
    BakedAtlas out;
    AtlasOptions options;
    options.gutter = gutter;
    out.atlas = pack_atlas(surface.crps, width, height, options);
    BakeLayout layout;
    layout.mesh = &surface.mesh;
    layout.transfer = carried ? pattern.transfer() : nullptr;
    layout.width = width;
    layout.height = height;
    layout.gutter = gutter;
    layout.corner_uvs.reserve(3 * surface.mesh.num_triangles());
    for (sim::TriId t = 0; t < surface.mesh.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) layout.corner_uvs.push_back(out.atlas.uv(t, c));
    out.image = bake_layout(pattern, layout);
    return out;
}

}  // namespace pelage::pattern::bake
