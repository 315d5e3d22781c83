#include "shader/clonal_mosaic/atlas.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace pelage::shader::clonal_mosaic {
namespace {

struct Placed {
    double c, s;  // rotation taking the longest edge to +x
    double minx, miny, w, h;
};

// Shelf packing at `scale`: returns false when it overflows the square.
bool shelf_pack(const std::vector<Placed> &shapes, const std::vector<size_t> &order,
                double scale, int res, int gutter, std::vector<sim::Vec2d> *origin) {
    double x = gutter, y = gutter, shelf = 0;
    origin->assign(shapes.size(), {});
    for (size_t i : order) {
        const double w = std::ceil(shapes[i].w * scale) + gutter,
                     h = std::ceil(shapes[i].h * scale) + gutter;
        if (x + w > res) {
            x = gutter;
            y += shelf;
            shelf = 0;
        }
        if (x + w > res || y + h > res) return false;
        (*origin)[i] = {x, y};
        x += w;
        shelf = std::max(shelf, h);
    }
    return true;
}

}  // namespace

Atlas pack_atlas(const sim::Crps &crps, int resolution, int gutter) {
    const size_t nt = crps.num_triangles();
    std::vector<Placed> shapes(nt);
    for (sim::TriId t = 0; t < nt; ++t) {
        const auto &v = crps.frame(t).v;
        int longest = 0;
        double best = -1;
        for (int k = 0; k < 3; ++k) {
            const double l = length(v[(k + 1) % 3] - v[k]);
            if (l > best) {
                best = l;
                longest = k;
            }
        }
        const sim::Vec2d d = (v[(longest + 1) % 3] - v[longest]) / best;
        Placed &p = shapes[t];
        p.c = d.x;
        p.s = -d.y;  // rotate by -angle(d)
        double minx = 1e300, miny = 1e300, maxx = -1e300, maxy = -1e300;
        for (int k = 0; k < 3; ++k) {
            const double x = p.c * v[k].x - p.s * v[k].y, y = p.s * v[k].x + p.c * v[k].y;
            minx = std::min(minx, x);
            maxx = std::max(maxx, x);
            miny = std::min(miny, y);
            maxy = std::max(maxy, y);
        }
        p.minx = minx;
        p.miny = miny;
        p.w = maxx - minx;
        p.h = maxy - miny;
    }
    std::vector<size_t> order(nt);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return shapes[a].h > shapes[b].h; });

    // Largest scale that fits: bisection between a surely-fitting and a surely-failing
    // one.
    double area = 0;
    for (const Placed &p : shapes) area += p.w * p.h;
    double hi = std::sqrt(double(resolution) * resolution / std::max(area, 1e-300)),
           lo = 0;
    std::vector<sim::Vec2d> origin;
    for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (shelf_pack(shapes, order, mid, resolution, gutter, &origin))
            lo = mid;
        else
            hi = mid;
    }
    if (!(lo > 0) || !shelf_pack(shapes, order, lo, resolution, gutter, &origin))
        throw std::invalid_argument("a " + std::to_string(resolution) +
                                    "² atlas cannot hold " + std::to_string(nt) +
                                    " triangles with gutters; raise --res");

    Atlas atlas;
    atlas.resolution = resolution;
    atlas.texels_per_unit = lo;
    atlas.triangles.resize(nt);
    for (sim::TriId t = 0; t < nt; ++t) {
        const Placed &p = shapes[t];
        AtlasTriangle &a = atlas.triangles[t];
        // atlas = scale · (R·v - min) + origin
        a.a00 = float(lo * p.c);
        a.a01 = float(-lo * p.s);
        a.a10 = float(lo * p.s);
        a.a11 = float(lo * p.c);
        a.ox = float(origin[t].x - lo * p.minx);
        a.oy = float(origin[t].y - lo * p.miny);
        for (int k = 0; k < 3; ++k) {
            const sim::Vec2d v = crps.frame(t).v[k];
            a.corners[k] = {lo * (p.c * v.x - p.s * v.y - p.minx) + origin[t].x,
                            lo * (p.s * v.x + p.c * v.y - p.miny) + origin[t].y};
        }
    }
    return atlas;
}

}  // namespace pelage::shader::clonal_mosaic
