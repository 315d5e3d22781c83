#include "sim/cells_report/cells_preview.h"

#include <algorithm>
#include <cmath>

namespace pelage::sim {

namespace {

Vec3d to_world(const CrpsFrame &f, Vec2d p) {
    return f.rotation.transpose_times({p.x + f.centre.x, f.y_offset, p.y + f.centre.y});
}

uint8_t to_srgb8(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    const double s =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return static_cast<uint8_t>(std::lround(s * 255));
}

}  // namespace

PreviewImage render_cells_preview(const CellsData &d, const PreviewOptions &o) {
    // --- Camera basis: w along the view, u and v across it ---
    Vec3d w = normalize(Vec3d{o.view[0], o.view[1], o.view[2]});
    const Vec3d up = std::abs(w.y) > 0.9 ? Vec3d{0, 0, 1} : Vec3d{0, 1, 0};
    const Vec3d u = normalize(cross(up, w)), v = cross(w, u);

    Bounds3 b;
    for (const auto &f : d.frames)
        for (const auto &p : f.v) {
            const Vec3d q = to_world(f, p);
            b.extend({dot(q, u), dot(q, v), dot(q, w)});
        }
    const double ex = std::max(b.hi.x - b.lo.x, 1e-12),
                 ey = std::max(b.hi.y - b.lo.y, 1e-12);
    // A 4-pixel margin on every side; a fixed image centres the mesh in what is left.
    const bool fixed = o.width > 0 && o.height > 0;
    const double scale = fixed ? std::min((o.width - 8) / ex, (o.height - 8) / ey)
                               : (o.size - 8) / std::max(ex, ey);
    PreviewImage img;
    img.width = fixed ? o.width : std::max(8, int(std::ceil(ex * scale)) + 8);
    img.height = fixed ? o.height : std::max(8, int(std::ceil(ey * scale)) + 8);
    const double ox = fixed ? 4 + 0.5 * (o.width - 8 - ex * scale) : 4,
                 oy = fixed ? 4 + 0.5 * (o.height - 8 - ey * scale) : 4;
    img.rgb.assign(size_t(img.width) * img.height * 3, 40);
    std::vector<double> depth(size_t(img.width) * img.height, 1e300);
    auto project = [&](Vec3d q) {
        return Vec3d{(dot(q, u) - b.lo.x) * scale + ox,
                     img.height - 1 - ((dot(q, v) - b.lo.y) * scale + oy), dot(q, w)};
    };

    // --- Flat-shaded triangles with a z-buffer (headlight: shade by |n·w|) ---
    for (const auto &f : d.frames) {
        const Vec3d a = project(to_world(f, f.v[0])), bb = project(to_world(f, f.v[1])),
                    c = project(to_world(f, f.v[2]));
        const double shade = 0.25 + 0.6 * std::abs(dot(f.normal, w));
        const uint8_t g = to_srgb8(shade * 0.5);
        const int x0 = std::max(0, int(std::floor(std::min({a.x, bb.x, c.x})))),
                  x1 =
                      std::min(img.width - 1, int(std::ceil(std::max({a.x, bb.x, c.x}))));
        const int y0 = std::max(0, int(std::floor(std::min({a.y, bb.y, c.y})))),
                  y1 = std::min(img.height - 1,
                                int(std::ceil(std::max({a.y, bb.y, c.y}))));
        const double area = (bb.x - a.x) * (c.y - a.y) - (c.x - a.x) * (bb.y - a.y);
        if (std::abs(area) < 1e-12) continue;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const double px = x + 0.5, py = y + 0.5;
                const double w0 =
                    ((bb.x - px) * (c.y - py) - (c.x - px) * (bb.y - py)) / area;
                const double w1 =
                    ((c.x - px) * (a.y - py) - (a.x - px) * (c.y - py)) / area;
                const double w2 = 1 - w0 - w1;
                if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                const double z = w0 * a.z + w1 * bb.z + w2 * c.z;
                const size_t i = size_t(y) * img.width + x;
                if (z >= depth[i]) continue;
                depth[i] = z;
                img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = g;
            }
    }

    // --- Cells as dots, visible when not behind the surface ---
    const double eps = 2.0 / scale;  // depth tolerance: a couple of pixels in world units
    for (size_t t = 0; t < d.num_triangles(); ++t)
        for (uint32_t c = d.cell_row[t]; c < d.cell_row[t + 1]; ++c) {
            const Vec3d p = project(to_world(d.frames[t], {d.x[c], d.z[c]}));
            const auto &col = d.types[d.type[c]].colour;
            for (int dy = -o.dot_radius; dy <= o.dot_radius; ++dy)
                for (int dx = -o.dot_radius; dx <= o.dot_radius; ++dx) {
                    const int x = int(p.x) + dx, y = int(p.y) + dy;
                    if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
                    const size_t i = size_t(y) * img.width + x;
                    if (p.z > depth[i] + eps) continue;
                    for (int k = 0; k < 3; ++k) img.rgb[3 * i + k] = to_srgb8(col[k]);
                }
        }
    return img;
}

}  // namespace pelage::sim
