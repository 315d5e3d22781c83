#include "shader/clonal_mosaic/bake.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace pelage::shader::clonal_mosaic {
namespace {

// Barycentrics of p in the atlas triangle; clamped to the triangle when `clamp`.
sim::Vec3d atlas_barycentric(const AtlasTriangle &a, sim::Vec2d p, bool clamp) {
    const sim::Vec2d e1 = a.corners[1] - a.corners[0], e2 = a.corners[2] - a.corners[0],
                     r = p - a.corners[0];
    const double det = cross(e1, e2);
    double b1 = cross(r, e2) / det, b2 = cross(e1, r) / det;
    if (clamp && (b1 < 0 || b2 < 0 || b1 + b2 > 1)) {
        // The nearest point of the triangle: the best of its three edges' nearest points.
        double best = 1e300;
        sim::Vec3d out;
        for (int k = 0; k < 3; ++k) {
            const sim::Vec2d A = a.corners[k], B = a.corners[(k + 1) % 3], AB = B - A;
            const double t =
                std::clamp(dot(p - A, AB) / std::max(dot(AB, AB), 1e-300), 0.0, 1.0);
            const double d = length_squared(p - (A + AB * t));
            if (d < best) {
                best = d;
                sim::Vec3d b{0, 0, 0};
                (&b.x)[k] = 1 - t;
                (&b.x)[(k + 1) % 3] = t;
                out = b;
            }
        }
        return out;
    }
    return {1 - b1 - b2, b1, b2};
}

}  // namespace

BakedPattern bake_pattern(const MosaicPattern &pattern, int resolution, int gutter) {
    const sim::Crps &crps = pattern.surface().crps;
    BakedPattern out;
    out.atlas = pack_atlas(crps, resolution, gutter);
    const size_t res = size_t(resolution);
    out.pixels.assign(res * res * BakedPattern::channels, 0.0f);
    for (size_t i = 0; i < res * res; ++i)
        out.pixels[i * BakedPattern::channels + 4] = -1,
                                                out.pixels[i * BakedPattern::channels +
                                                           5] = -1;
    std::vector<uint8_t> state(res * res, 0);  // 0 empty, 1 gutter, 2 inside

    auto write_texel = [&](size_t x, size_t y, sim::TriId t, const sim::Vec3d &b) {
        const sim::CrpsFrame &f = crps.frame(t);
        const sim::Vec2d p = f.v[0] * b.x + f.v[1] * b.y + f.v[2] * b.z;
        const ClosestCell c = pattern.index().find_nearest(t, {float(p.x), float(p.y)});
        float *px = &out.pixels[(y * res + x) * BakedPattern::channels];
        if (c.index == ClosestCell::none) return;
        const sim::CellType &type = pattern.types()[pattern.cells().type[c.index]];
        px[0] = type.colour[0];
        px[1] = type.colour[1];
        px[2] = type.colour[2];
        px[3] = 1;
        px[4] = float(pattern.cells().type[c.index]);
        px[5] = float(pattern.cells().id[c.index]);
    };
    auto texel_range = [&](const AtlasTriangle &a, int pad, int &x0, int &x1, int &y0,
                           int &y1) {
        double minx = 1e300, maxx = -1e300, miny = 1e300, maxy = -1e300;
        for (const auto &c : a.corners) {
            minx = std::min(minx, c.x);
            maxx = std::max(maxx, c.x);
            miny = std::min(miny, c.y);
            maxy = std::max(maxy, c.y);
        }
        x0 = std::max(0, int(std::floor(minx)) - pad);
        x1 = std::min(resolution - 1, int(std::ceil(maxx)) + pad);
        y0 = std::max(0, int(std::floor(miny)) - pad);
        y1 = std::min(resolution - 1, int(std::ceil(maxy)) + pad);
    };

    // --- Texels whose centre lies inside a triangle: triangles never overlap, so in
    // parallel ---
    tbb::parallel_for(tbb::blocked_range<size_t>(0, crps.num_triangles(), 16),
                      [&](const auto &range) {
                          for (size_t t = range.begin(); t != range.end(); ++t) {
                              const AtlasTriangle &a = out.atlas.triangles[t];
                              int x0, x1, y0, y1;
                              texel_range(a, 0, x0, x1, y0, y1);
                              for (int y = y0; y <= y1; ++y)
                                  for (int x = x0; x <= x1; ++x) {
                                      const sim::Vec3d b =
                                          atlas_barycentric(a, {x + 0.5, y + 0.5}, false);
                                      if (b.x < 0 || b.y < 0 || b.z < 0) continue;
                                      state[size_t(y) * res + x] = 2;
                                      write_texel(x, y, sim::TriId(t), b);
                                  }
                          }
                      });
    // --- Gutters: the nearest point of the nearest triangle; serial (gutters touch) ---
    for (sim::TriId t = 0; t < crps.num_triangles(); ++t) {
        const AtlasTriangle &a = out.atlas.triangles[t];
        int x0, x1, y0, y1;
        texel_range(a, gutter, x0, x1, y0, y1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                if (state[size_t(y) * res + x] != 0) continue;
                const sim::Vec3d b = atlas_barycentric(a, {x + 0.5, y + 0.5}, true);
                const sim::Vec2d p =
                    a.corners[0] * b.x + a.corners[1] * b.y + a.corners[2] * b.z;
                if (length(p - sim::Vec2d{x + 0.5, y + 0.5}) > gutter) continue;
                state[size_t(y) * res + x] = 1;
                write_texel(x, y, t, b);
            }
    }
    for (uint8_t s : state) {
        out.texels_inside += s == 2;
        out.texels_gutter += s == 1;
    }
    return out;
}

}  // namespace pelage::shader::clonal_mosaic
