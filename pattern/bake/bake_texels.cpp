#include "pattern/bake/bake_texels.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pelage::pattern::bake {
namespace {

using sim::Vec2d;
using sim::Vec3d;

constexpr int band = 16;  // rows per parallel task

// The nearest point of segment ab to q, as the parameter along it.
double segment_param(Vec2d q, Vec2d a, Vec2d b) {
    const Vec2d ab = b - a;
    return std::clamp(dot(q - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
}

// Triangle t in tile `udim`'s texel coordinates; left invalid when its UV area is zero.
TexelTriangle texel_triangle(const sim::TriangleMesh &mesh, sim::TriId t, const Vec2d *uv,
                             int udim, int W, int H, double gutter, double scale) {
    const int ut = (udim - 1001) % 10, vt = (udim - 1001) / 10;
    TexelTriangle T{};
    for (int c = 0; c < 3; ++c) T.p[c] = {(uv[c].x - ut) * W, (1 - (uv[c].y - vt)) * H};
    const Vec2d a = T.p[1] - T.p[0], b = T.p[2] - T.p[0];
    const double det = cross(a, b);
    if (!(std::abs(det) > 1e-12)) return T;
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
    return T;
}

// Per band of rows, the tile's triangles whose boxes reach it, in the tile's order.
std::vector<std::vector<uint32_t>> triangles_by_band(
    const std::vector<TexelTriangle> &tris, const std::vector<uint32_t> &tile_tris,
    int H) {
    const int nbands = (H + band - 1) / band;
    std::vector<std::vector<uint32_t>> in_band(static_cast<size_t>(nbands));
    for (uint32_t t : tile_tris) {
        const int r0 = std::max(0, int(std::floor(tris[t].y0 - 0.5))),
                  r1 = std::min(H - 1, int(std::ceil(tris[t].y1 - 0.5)));
        for (int b = r0 / band; b <= r1 / band && r0 <= r1; ++b)
            in_band[size_t(b)].push_back(t);
    }
    return in_band;
}

// Offers the texels of band b within T's box to T; only this band's task writes them.
void offer_band(const TexelTriangle &T, uint32_t t, int b, int W, int H, double gutter,
                TexelOwners &owners) {
    const int y0 = std::max(b * band, int(std::floor(T.y0 - 0.5))),
              y1 = std::min({(b + 1) * band - 1, H - 1, int(std::ceil(T.y1 - 0.5))}),
              x0 = std::max(0, int(std::floor(T.x0 - 0.5))),
              x1 = std::min(W - 1, int(std::ceil(T.x1 - 0.5)));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const size_t i = size_t(y) * W + x;
            Vec3d bn;
            const float d = float(T.distance_to({x + 0.5, y + 0.5}, &bn));
            if (d == 0 && bn.x > 1e-9 && bn.y > 1e-9 && bn.z > 1e-9 &&
                owners.strictly_inside[i] < 255)
                ++owners.strictly_inside[i];
            if (d <= gutter && d < owners.dist[i]) {
                owners.dist[i] = d;
                owners.owner[i] = t;
            }
        }
}

}  // namespace

double TexelTriangle::distance_to(Vec2d q, Vec3d *b_nearest) const {
    const Vec3d b = barycentric(q);
    if (b.x >= 0 && b.y >= 0 && b.z >= 0) {
        *b_nearest = b;
        return 0;
    }
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
        const Vec2d A = p[k], B = p[(k + 1) % 3];
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

TexelLayout lay_out_texels(const BakeLayout &layout) {
    const sim::TriangleMesh &mesh = *layout.mesh;
    const size_t nt = mesh.num_triangles();
    const double gutter = layout.gutter;
    const double scale = layout.transfer ? layout.transfer->scale() : 1.0;
    TexelLayout out;
    out.tris.resize(nt);
    for (sim::TriId t = 0; t < nt; ++t) {
        const Vec2d *uv = &layout.corner_uvs[3 * size_t(t)];
        const int udim = tile_of(mesh, uv, t);
        out.tris[t] =
            texel_triangle(mesh, t, uv, udim, layout.width, layout.height, gutter, scale);
        if (!out.tris[t].valid) {
            ++out.degenerate_triangles;
            continue;
        }
        out.by_tile[udim].push_back(t);
    }
    return out;
}

TexelOwners find_owners(const std::vector<TexelTriangle> &tris,
                        const std::vector<uint32_t> &tile_tris, int W, int H,
                        double gutter) {
    const std::vector<std::vector<uint32_t>> in_band =
        triangles_by_band(tris, tile_tris, H);
    const int nbands = int(in_band.size());
    const size_t n = size_t(W) * H;
    TexelOwners owners;
    owners.dist.assign(n, std::numeric_limits<float>::infinity());
    owners.owner.assign(n, sim::invalid_id);
    owners.strictly_inside.assign(n, 0);
    tbb::parallel_for(tbb::blocked_range<int>(0, nbands, 1), [&](const auto &r) {
        for (int b = r.begin(); b != r.end(); ++b)
            for (uint32_t t : in_band[size_t(b)])
                offer_band(tris[t], t, b, W, H, gutter, owners);
    });
    return owners;
}

}  // namespace pelage::pattern::bake
