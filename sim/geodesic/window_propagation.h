// Exact polyhedral geodesic distances from a point, within a radius, by window
// propagation: J. Chen & Y. Han, "Shortest paths on a polyhedron", SoCG 1990, with the
// window filter of S.-Q. Xin & G.-J. Wang, "Improving Chen and Han's algorithm on the
// discrete geodesic problem", ACM TOG 28(4) 2009 (ICH), on the CRPS's per-triangle
// frames (Teo 2006 ch. 4).
//
// A *window* is the set of straight paths that reach a triangle through an interval of
// one of its edges from one unfolding of the surface: in the triangle's own frame, a
// virtual source s, the interval [x0, x1] and σ, the length of the path before s (zero
// unless s is a pseudo-source vertex). For q in the window's wedge — the rays from s
// through the interval — σ + |q − s| is the length of a path on the surface. The
// distance from the source to q is the least such length over the windows on q's
// triangle whose wedge holds q (Mitchell, Mount & Papadimitriou 1987, §3); a window
// whose source lies on the triangle (the source's own triangle, a pseudo-source at a
// corner) covers all of it.
//
// Outside its wedge a window's formula is not the length of a path. Past a ray through
// a convex vertex it is longer than the path around the vertex's other side, so a
// search may use it there; past a ray through a pseudo-source vertex (saddle or
// boundary) it can be shorter than any path — the folds of a planar unfolding — and a
// search must test the wedge. `unsafe` says which sides need the test.
//
// Windows are settled in order of their least distance, so the propagation stops at
// the radius: every window that realises a distance of at most `radius` is reported.
// A window is dropped when a known vertex distance beats it over its whole interval
// (ICH's filter; the vertex distances are lengths of real paths, so the test never drops
// a window that realises the distance anywhere).
#pragma once

#include <cstdint>
#include <vector>

#include "sim/geodesic/geodesic_mesh.h"

namespace pelage::sim {

struct GeodesicWindow {
    static constexpr uint8_t whole_face = 3;

    TriId face = 0;
    uint8_t edge = whole_face;  // the entry edge (joins corners edge, edge + 1)
    uint8_t unsafe = 0;  // bit 0: past the ray s→x0 may underestimate; bit 1: s→x1
    Vec2d source;        // the virtual source, in face's frame
    double sigma = 0;
    Vec2d x0, x1;             // the entry interval (unused for whole_face)
    double min_distance = 0;  // a lower bound of σ + |q − s| over the face

    // Whether q (in face's frame) lies in the wedge; `slack` widens it by that fraction
    // of the distance, so points on the ray between two windows belong to both.
    bool covers(Vec2d q, double slack = 1e-9) const;
    double distance(Vec2d q) const { return sigma + length(q - source); }
};

struct PropagationStats {
    size_t windows_settled = 0;  // reported
    size_t windows_created = 0;  // including those filtered or beyond the radius
    size_t pseudo_sources = 0;   // vertices that spawned windows
};

class WindowPropagation {
  public:
    explicit WindowPropagation(const GeodesicMesh &mesh);

    // Windows within `radius` of the surface point (t, p) (p in t's frame), settled in
    // order of min_distance. `out` is cleared first.
    void run(TriId t, Vec2d p, double radius, std::vector<GeodesicWindow> &out);

    // The distance to the last run's source from a known vertex (+inf when no path of at
    // most the radius reached it).
    double vertex_distance(VertId v) const;
    const PropagationStats &stats() const { return m_stats; }

  private:
    struct Pending {
        GeodesicWindow w;
        VertId pseudo_vertex;  // the pseudo-source this window starts from, or invalid_id
    };
    struct QueueItem {
        double key;
        uint64_t order;  // ties settle in creation order: deterministic
        uint32_t slot;
        bool operator<(const QueueItem &o) const {
            return key != o.key ? key > o.key : order > o.order;  // a min-heap
        }
    };

    void push(const Pending &p);
    void reach_vertex(VertId v, double d);
    void propagate_whole_face(const Pending &p);
    void propagate_entry(const Pending &p);
    void add_child(const Pending &parent, int exit_edge, Vec2d y0, Vec2d y1,
                   uint8_t unsafe);
    double known(VertId v) const;

    const GeodesicMesh *m_mesh;
    double m_eps = 0;  // lengths below this are rounding (relative to the mesh's size)
    double m_radius = 0;
    std::vector<double> m_vertex_distance;
    std::vector<uint32_t> m_vertex_stamp;
    uint32_t m_generation = 0;
    std::vector<Pending> m_pool;
    std::vector<QueueItem> m_heap;
    uint64_t m_order = 0;
    PropagationStats m_stats;
};

// The geodesic distance at q (in the face's frame) from the windows of one source on
// that face: the least σ + |q − s| over the windows whose wedge holds q; +inf when none.
double distance_from_windows(const GeodesicWindow *begin, const GeodesicWindow *end,
                             Vec2d q);

}  // namespace pelage::sim
