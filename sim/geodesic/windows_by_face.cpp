#include "sim/geodesic/windows_by_face.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <limits>

namespace pelage::sim {

void WindowsByFace::build(const GeodesicMesh &mesh, std::span<const SurfacePoint> sources,
                          double radius) {
    const std::vector<double> radii(sources.size(), radius);
    build(mesh, sources, radii);
}

void WindowsByFace::build(const GeodesicMesh &mesh, std::span<const SurfacePoint> sources,
                          std::span<const double> radii, std::span<const uint8_t> faces) {
    const size_t nt = mesh.crps().num_triangles();
    const bool filtered = !faces.empty();
    // Per source, its windows (kept ones only); then counted and placed by triangle.
    std::vector<std::vector<GeodesicWindow>> per_source(sources.size());
    struct Scratch {
        std::unique_ptr<WindowPropagation> prop;
        std::vector<GeodesicWindow> out;
        size_t settled = 0;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sources.size(), 16),
                      [&](const auto &range) {
                          Scratch &s = scratch.local();
                          if (!s.prop) s.prop = std::make_unique<WindowPropagation>(mesh);
                          for (size_t i = range.begin(); i != range.end(); ++i) {
                              if (!(radii[i] > 0)) continue;
                              s.prop->run(sources[i].tri, sources[i].p, radii[i], s.out);
                              s.settled += s.out.size();
                              auto &mine = per_source[i];
                              for (const GeodesicWindow &w : s.out)
                                  if (!filtered || faces[w.face]) mine.push_back(w);
                              mine.shrink_to_fit();
                          }
                      });
    m_settled = 0;
    for (const Scratch &s : scratch) m_settled += s.settled;
    m_row.assign(nt + 1, 0);
    for (const auto &ws : per_source)
        for (const GeodesicWindow &w : ws) ++m_row[w.face + 1];
    for (size_t t = 0; t < nt; ++t) m_row[t + 1] += m_row[t];
    m_windows.resize(m_row[nt]);
    std::vector<uint32_t> fill(m_row.begin(), m_row.end() - 1);
    for (size_t i = 0; i < per_source.size(); ++i) {
        for (const GeodesicWindow &w : per_source[i])
            m_windows[fill[w.face]++] = {static_cast<uint32_t>(i), w};
        per_source[i] = {};
    }
}

WindowsByFace::Nearest WindowsByFace::nearest(TriId t, Vec2d q) const {
    Nearest best{invalid_id, std::numeric_limits<double>::infinity()};
    for (const SourcedWindow &sw : of(t))
        if (sw.window.covers(q)) {
            const double d = sw.window.distance(q);
            if (d < best.distance || (d == best.distance && sw.source < best.source))
                best = {sw.source, d};
        }
    return best;
}

double WindowsByFace::distance(TriId t, Vec2d q, uint32_t source) const {
    double best = std::numeric_limits<double>::infinity();
    for (const SourcedWindow &sw : of(t))
        if (sw.source == source && sw.window.covers(q))
            best = std::min(best, sw.window.distance(q));
    return best;
}

}  // namespace pelage::sim
