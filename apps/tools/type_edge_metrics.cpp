#include "apps/tools/type_edge_metrics.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>

namespace pelage::renderer {

TypeEdgeMetrics measure_type_edges(const std::vector<float> &image,
                                   const std::vector<float> &reference,
                                   const std::vector<float> &types, int width, int height,
                                   int stride, int interior, int max_distance,
                                   double tolerance, size_t min_pixels) {
    const size_t n = size_t(width) * height;
    auto type_at = [&](int x, int y) {
        return int(std::lround(types[size_t(y) * width + x]));
    };
    // Chebyshev distance to the nearest pixel whose 8-neighbourhood holds another type
    // (both sides of an edge are at distance 0), by breadth-first search.
    const int far = max_distance + 1;
    std::vector<int> dist(n, far);
    std::deque<size_t> queue;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const int t = type_at(x, y);
            if (t < 0) continue;
            bool edge = false;
            for (int dy = -1; dy <= 1 && !edge; ++dy)
                for (int dx = -1; dx <= 1 && !edge; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
                    const int u = type_at(xx, yy);
                    edge = u >= 0 && u != t;
                }
            if (edge) {
                dist[size_t(y) * width + x] = 0;
                queue.push_back(size_t(y) * width + x);
            }
        }
    while (!queue.empty()) {
        const size_t i = queue.front();
        queue.pop_front();
        const int x = int(i % width), y = int(i / width), d = dist[i] + 1;
        if (d > max_distance) continue;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int xx = x + dx, yy = y + dy;
                if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
                const size_t j = size_t(yy) * width + xx;
                if (dist[j] > d) {
                    dist[j] = d;
                    queue.push_back(j);
                }
            }
    }

    struct Sums {
        double image = 0, reference = 0;
        size_t pixels = 0;
    };
    std::map<int, std::vector<Sums>> by_type;  // per type: buckets 0..far
    auto grey = [&](const std::vector<float> &px, size_t i) {
        return (double(px[i * stride]) + px[i * stride + 1] + px[i * stride + 2]) / 3.0;
    };
    for (size_t i = 0; i < n; ++i) {
        const int t = int(std::lround(types[i]));
        if (t < 0) continue;
        const double a = grey(image, i), r = grey(reference, i);
        if (!std::isfinite(a) || !std::isfinite(r)) continue;
        std::vector<Sums> &b = by_type[t];
        b.resize(size_t(far) + 1);
        Sums &s = b[size_t(std::min(dist[i], far))];
        s.image += a;
        s.reference += r;
        ++s.pixels;
    }

    TypeEdgeMetrics out;
    for (const auto &[t, buckets] : by_type) {
        TypeEdgeMetrics::Type ty;
        ty.type = t;
        Sums inside;
        for (int d = 0; d <= far; ++d) {
            const Sums &s = buckets[size_t(d)];
            if (d >= interior) {
                inside.image += s.image;
                inside.reference += s.reference;
                inside.pixels += s.pixels;
            }
            if (d > max_distance) continue;
            ty.pixels_by_distance.push_back(s.pixels);
            const double e = s.reference > 0 ? s.image / s.reference - 1 : 0.0;
            ty.error_by_distance.push_back(e);
            if (d >= 1 && s.pixels >= min_pixels && std::abs(e) > tolerance)
                out.halo_pixels = std::max(out.halo_pixels, d);
        }
        ty.interior_pixels = inside.pixels;
        if (inside.pixels > 0) {
            ty.mean = inside.image / double(inside.pixels);
            ty.reference_mean = inside.reference / double(inside.pixels);
            ty.bias = ty.reference_mean > 0 ? ty.mean / ty.reference_mean - 1 : 0.0;
            if (inside.pixels >= min_pixels)
                out.max_bias = std::max(out.max_bias, std::abs(ty.bias));
        }
        out.types.push_back(std::move(ty));
    }
    return out;
}

}  // namespace pelage::renderer
