// The neighbourhoods the relaxation's neighbour search reads (Teo 2006 §5.1.2): per
// triangle, the triangles of its unfolding within a radius, with the rigid maps between
// their frames, checked against exact geodesics so that no force acts through a fold.
#pragma once

#include <cstddef>
#include <vector>

#include "sim/crps/crps.h"
#include "sim/crps/rigid_map.h"

namespace pelage::sim {

// Unfoldings within a radius R ≥ r, built once and kept per triangle: r only shrinks as
// cells are added, so when r < R / (slack · filter_ratio) the entries farther than the
// new R are dropped (keeping the candidate set tight without unfolding again); the cache
// is built anew only when r > R (it would miss triangles) or the surface changes shape.
//
// The unfolding walks across edges only, so every map is the unfolding of an edge path
// (Teo's vertex maps rotate about a line, not along the surface). Around a vertex whose
// angles do not sum to 2π (a cone or a saddle: horns, ears, leg tops) paths on either
// side unfold a triangle to different places, and a planar unfolding overlaps itself
// or gapes: there a straight segment between two images is no path on the surface, and
// a triangle from elsewhere on the body can land near the master (the folds). A
// triangle reached from a first image that lands it elsewhere gets another image (up to
// max_images, those more than image_tolerance·R/2 apart). Unless every path agrees and
// no boundary is within reach (the unfolding is then the surface laid flat), each
// triangle's images are checked against exact geodesic distances from the master's
// centroid (sim/geodesic, Chen & Han window propagation) at the triangle's corners,
// edge midpoints and centroid: the image that agrees best is kept if it agrees within
// image_tolerance·R, and a triangle with no such image, or none within R along the
// surface, is dropped (validation.md, the relaxation's neighbours).
class Neighbourhoods {
  public:
    struct Entry {
        TriId tri;
        // The smallest R this entry belongs to: the distance from t to j in the
        // unfolding, and the image's disagreement with exact geodesics over
        // image_tolerance.
        float needs;
        RigidMap2 to_nbr;  // F[t→j]: carries a point of t into j's frame
    };
    static constexpr double slack = 1.15, filter_ratio = 1.1;
    static constexpr int max_images = 3;
    static constexpr double image_tolerance = 0.05;

    // Whether images are checked against exact geodesics (the default; off, the first
    // image of the breadth-first unfolding stands, as in Teo 2006 §4.1).
    void set_verified(bool verified) { m_verified = verified; }
    // Makes sure the cache covers radius r.
    void update(const Crps &crps, double r);
    // Forgets the cache: the next update rebuilds it (the surface changed shape).
    void invalidate() { m_radius = 0; }
    const std::vector<Entry> &of(TriId t) const { return m_entries[t]; }
    // Radius of t's bounding circle about its centroid (the origin of its 2D frame).
    double bounding_radius(TriId t) const { return m_bounding[t]; }
    double radius() const { return m_radius; }
    size_t rebuilds() const { return m_rebuilds; }
    size_t filters() const { return m_filters; }
    double seconds() const { return m_seconds; }  // total time spent building
    // The entries over all triangles, and the memory they take.
    size_t entries() const;
    size_t bytes() const;

  private:
    void filter(double R);

    std::vector<std::vector<Entry>> m_entries;
    std::vector<double> m_bounding;
    double m_radius = 0;
    size_t m_rebuilds = 0, m_filters = 0;
    double m_seconds = 0;
    bool m_verified = true;
};

}  // namespace pelage::sim
