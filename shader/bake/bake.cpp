#include "shader/bake/bake.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "sim/crps/cell_walk.h"

namespace pelage::shader::bake {
namespace {

using sim::Vec2d;
using sim::Vec3d;

// A layout triangle in its tile's texel coordinates (x right, y down), with the affine
// map from texel offsets to barycentric coordinates and to surface displacements.
struct TexelTriangle {
    std::array<Vec2d, 3> p;
    double i00 = 0, i01 = 0, i10 = 0, i11 = 0;  // inverse of [p1 - p0, p2 - p0]
    Vec3d jx, jy;           // surface displacement per texel along x and y
    float footprint = 0;    // the texel's width on the surface (pattern units)
    double x0, x1, y0, y1;  // bounding box
    bool valid = false;

    Vec3d barycentric(Vec2d q) const {
        const Vec2d r = q - p[0];
        const double b1 = i00 * r.x + i01 * r.y, b2 = i10 * r.x + i11 * r.y;
        return {1 - b1 - b2, b1, b2};
    }
};

// The nearest point of segment ab to q, as the parameter along it.
double segment_param(Vec2d q, Vec2d a, Vec2d b) {
    const Vec2d ab = b - a;
    return std::clamp(dot(q - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
}

// Distance from q to the triangle (0 inside) and the barycentrics of its nearest point.
double distance_to(const TexelTriangle &t, Vec2d q, Vec3d *b_nearest) {
    const Vec3d b = t.barycentric(q);
    if (b.x >= 0 && b.y >= 0 && b.z >= 0) {
        *b_nearest = b;
        return 0;
    }
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
        const Vec2d A = t.p[k], B = t.p[(k + 1) % 3];
        const double s = segment_param(q, A, B), d = length(q - (A + (B - A) * s));
        if (d < best) {
            best = d;
            double w[3] = {0, 0, 0};
            w[k] = 1 - s;
            w[(k + 1) % 3] = s;
            *b_nearest = {w[0], w[1], w[2]};
        }
    }
    return best;
}

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
        const sim::CellType &t = pattern.types()[cells.type[k]];
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

}  // namespace

int udim_of(Vec2d uv) {
    const double u = std::floor(uv.x), v = std::floor(uv.y);
    if (!(u >= 0 && u <= 9 && v >= 0 && v <= 9))
        throw std::invalid_argument(
            "UV (" + std::to_string(uv.x) + ", " + std::to_string(uv.y) +
            ") lies outside the UDIM tiles 1001-1100 (0 <= u < 10, 0 <= v < 10)");
    return 1001 + int(u) + 10 * int(v);
}

namespace {

// The tile of triangle t (its UV centroid's), checking every corner's range.
int tile_of(const sim::TriangleMesh &mesh, const Vec2d *uv, sim::TriId t) {
    try {
        const int udim = udim_of((uv[0] + uv[1] + uv[2]) / 3);
        for (int c = 0; c < 3; ++c)  // corners may lie on the tiles' far borders
            if (!(uv[c].x >= 0 && uv[c].x <= 10 && uv[c].y >= 0 && uv[c].y <= 10))
                udim_of(uv[c]);
        return udim;
    } catch (const std::invalid_argument &e) {
        const uint32_t face = t < mesh.source_face.size() ? mesh.source_face[t] : t;
        throw std::invalid_argument("triangle " + std::to_string(t) + " (face " +
                                    std::to_string(face + 1) + "): " + e.what());
    }
}

}  // namespace

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
    const sim::TriangleMesh &mesh = *layout.mesh;
    const size_t nt = mesh.num_triangles();
    udim_tiles(mesh, layout.corner_uvs);  // every check, before any work
    const int W = layout.width, H = layout.height, C = BakeResult::channels;
    const double gutter = layout.gutter;
    const double scale = layout.transfer ? layout.transfer->scale() : 1.0;

    BakeResult out;
    out.width = W;
    out.height = H;
    // --- Each triangle in its tile's texel coordinates ---
    std::vector<TexelTriangle> tris(nt);
    std::map<int, std::vector<uint32_t>> by_tile;
    for (sim::TriId t = 0; t < nt; ++t) {
        const Vec2d *uv = &layout.corner_uvs[3 * size_t(t)];
        const int udim = tile_of(mesh, uv, t);
        const int ut = (udim - 1001) % 10, vt = (udim - 1001) / 10;
        TexelTriangle &T = tris[t];
        for (int c = 0; c < 3; ++c)
            T.p[c] = {(uv[c].x - ut) * W, (1 - (uv[c].y - vt)) * H};
        const Vec2d a = T.p[1] - T.p[0], b = T.p[2] - T.p[0];
        const double det = cross(a, b);
        if (!(std::abs(det) > 1e-12)) {
            ++out.degenerate_triangles;
            continue;
        }
        T.i00 = b.y / det;
        T.i01 = -b.x / det;
        T.i10 = -a.y / det;
        T.i11 = a.x / det;
        const Vec3d E1 = mesh.vertex(t, 1) - mesh.vertex(t, 0),
                    E2 = mesh.vertex(t, 2) - mesh.vertex(t, 0);
        T.jx = (E1 * T.i00 + E2 * T.i10) * scale;
        T.jy = (E1 * T.i01 + E2 * T.i11) * scale;
        // The larger singular value of [jx jy]: the texel's widest extent on the surface.
        const double xx = dot(T.jx, T.jx), yy = dot(T.jy, T.jy), xy = dot(T.jx, T.jy);
        const double tr = 0.5 * (xx + yy),
                     dd = std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
        T.footprint = float(std::sqrt(tr + dd));
        T.x0 = std::min({T.p[0].x, T.p[1].x, T.p[2].x}) - gutter;
        T.x1 = std::max({T.p[0].x, T.p[1].x, T.p[2].x}) + gutter;
        T.y0 = std::min({T.p[0].y, T.p[1].y, T.p[2].y}) - gutter;
        T.y1 = std::max({T.p[0].y, T.p[1].y, T.p[2].y}) + gutter;
        T.valid = true;
        by_tile[udim].push_back(t);
    }

    const Looks looks = looks_of(pattern);
    const sim::Crps &crps = pattern.surface().crps;
    constexpr int band = 16;  // rows per parallel task
    out.num_tiles = by_tile.size();
    for (const auto &[udim, list] : by_tile) {
        // --- Owners: per texel, the nearest triangle within the gutter (the first one,
        // by id, among those that hold its centre) ---
        const int nbands = (H + band - 1) / band;
        std::vector<std::vector<uint32_t>> in_band(static_cast<size_t>(nbands));
        for (uint32_t t : list) {
            const int r0 = std::max(0, int(std::floor(tris[t].y0 - 0.5))),
                      r1 = std::min(H - 1, int(std::ceil(tris[t].y1 - 0.5)));
            for (int b = r0 / band; b <= r1 / band && r0 <= r1; ++b)
                in_band[size_t(b)].push_back(t);
        }
        const size_t n = size_t(W) * H;
        std::vector<float> dist(n, std::numeric_limits<float>::infinity());
        std::vector<uint32_t> owner(n, sim::invalid_id);
        std::vector<uint8_t> strictly_inside(n, 0);
        tbb::parallel_for(tbb::blocked_range<int>(0, nbands, 1), [&](const auto &r) {
            for (int b = r.begin(); b != r.end(); ++b)
                for (uint32_t t : in_band[size_t(b)]) {
                    const TexelTriangle &T = tris[t];
                    const int y0 = std::max(b * band, int(std::floor(T.y0 - 0.5))),
                              y1 = std::min({(b + 1) * band - 1, H - 1,
                                             int(std::ceil(T.y1 - 0.5))}),
                              x0 = std::max(0, int(std::floor(T.x0 - 0.5))),
                              x1 = std::min(W - 1, int(std::ceil(T.x1 - 0.5)));
                    for (int y = y0; y <= y1; ++y)
                        for (int x = x0; x <= x1; ++x) {
                            const size_t i = size_t(y) * W + x;
                            Vec3d bn;
                            const float d =
                                float(distance_to(T, {x + 0.5, y + 0.5}, &bn));
                            if (d == 0 && bn.x > 1e-9 && bn.y > 1e-9 && bn.z > 1e-9 &&
                                strictly_inside[i] < 255)
                                ++strictly_inside[i];
                            if (d <= gutter && d < dist[i]) {
                                dist[i] = d;
                                owner[i] = t;
                            }
                        }
                }
        });

        // --- Each owned texel's look ---
        BakedTile tile;
        tile.udim = udim;
        tile.pixels.assign(n * C, 0.0f);
        for (size_t i = 0; i < n; ++i)
            for (int c = 4; c < C; ++c) tile.pixels[i * C + c] = -1;
        tbb::parallel_for(tbb::blocked_range<int>(0, H, 4), [&](const auto &r) {
            for (int y = r.begin(); y != r.end(); ++y)
                for (int x = 0; x < W; ++x) {
                    const size_t i = size_t(y) * W + x;
                    if (owner[i] == sim::invalid_id) continue;
                    const TexelTriangle &T = tris[owner[i]];
                    const Vec2d q{x + 0.5, y + 0.5};
                    Vec3d b;
                    distance_to(T, q, &b);
                    sim::TriId s = owner[i];
                    float b1 = float(b.y), b2 = float(b.z);
                    if (layout.transfer) {
                        const auto at = layout.transfer->map(s, b1, b2);
                        s = at.tri;
                        b1 = at.b1;
                        b2 = at.b2;
                    }
                    if (dist[i] > 0) {
                        // Walk from the border point by the texel's offset, over the
                        // surface into whatever triangle lies there.
                        const Vec2d from = T.p[0] * b.x + T.p[1] * b.y + T.p[2] * b.z;
                        const Vec2d off = q - from;
                        const Vec3d d3 = T.jx * off.x + T.jy * off.y;
                        const sim::CrpsFrame &f = crps.frame(s);
                        const Vec3d dl = f.rotation * d3;
                        const Vec2d start = crps.barycentric_to_2d(
                            s, {1.0 - double(b1) - double(b2), double(b1), double(b2)});
                        const sim::SurfacePoint end =
                            sim::walk(crps, {s, start}, {dl.x, dl.z});
                        const Vec3d be = crps.to_barycentric(end.tri, end.p);
                        s = end.tri;
                        b1 = float(be.y);
                        b2 = float(be.z);
                    }
                    shade_texel(pattern, looks, s, b1, b2, T.footprint,
                                &tile.pixels[i * C]);
                }
        });
        std::vector<uint8_t> covered(n);
        for (size_t i = 0; i < n; ++i) {
            covered[i] = tile.pixels[i * C + 3] > 0;
            out.texels_inside += owner[i] != sim::invalid_id && dist[i] == 0;
            out.texels_gutter += owner[i] != sim::invalid_id && dist[i] > 0;
            out.texels_overlapped += strictly_inside[i] >= 2;
        }
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

}  // namespace pelage::shader::bake
