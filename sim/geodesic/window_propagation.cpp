#include "sim/geodesic/window_propagation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pelage::sim {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

double point_segment_distance(Vec2d p, Vec2d a, Vec2d b) {
    const Vec2d ab = b - a;
    const double len2 = length_squared(ab);
    const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return length(p - (a + ab * t));
}

}  // namespace

bool GeodesicWindow::covers(Vec2d q, double slack) const {
    if (edge == whole_face) return true;
    const Vec2d r0 = x0 - source, r1 = x1 - source, d = q - source;
    const double w = cross(r0, r1);
    const double tol = slack * length(d) * (length(r0) + length(r1));
    return (w >= 0) ? (cross(r0, d) >= -tol && cross(d, r1) >= -tol)
                    : (cross(r0, d) <= tol && cross(d, r1) <= tol);
}

double distance_from_windows(const GeodesicWindow *begin, const GeodesicWindow *end,
                             Vec2d q) {
    double best = inf;
    for (const GeodesicWindow *w = begin; w != end; ++w) {
        const double d = w->distance(q);  // cheaper than the wedge test: first
        if (d < best && w->covers(q)) best = d;
    }
    return best;
}

WindowPropagation::WindowPropagation(const GeodesicMesh &mesh) : m_mesh(&mesh) {
    const Crps &crps = mesh.crps();
    double scale = 0;
    for (TriId t = 0; t < crps.num_triangles(); ++t)
        scale = std::max(scale, crps.frame(t).bound_radius);
    m_eps = 1e-10 * scale;
    m_vertex_distance.assign(mesh.num_vertices(), inf);
    m_vertex_stamp.assign(mesh.num_vertices(), 0);
}

double WindowPropagation::known(VertId v) const {
    return m_vertex_stamp[v] == m_generation ? m_vertex_distance[v] : inf;
}

double WindowPropagation::vertex_distance(VertId v) const { return known(v); }

void WindowPropagation::push(const Pending &p) {
    ++m_stats.windows_created;
    if (p.w.min_distance > m_radius) return;
    m_pool.push_back(p);
    m_heap.push_back(
        {p.w.min_distance, m_order++, static_cast<uint32_t>(m_pool.size() - 1)});
    std::push_heap(m_heap.begin(), m_heap.end());
}

// A shorter path to v: pseudo-sources start a whole-face window on every triangle
// around them (Chen & Han's vertex sources).
void WindowPropagation::reach_vertex(VertId v, double d) {
    if (!(d < known(v) - m_eps)) return;
    m_vertex_distance[v] = d;
    m_vertex_stamp[v] = m_generation;
    if (!m_mesh->pseudo_source(v)) return;
    ++m_stats.pseudo_sources;
    const Crps &crps = m_mesh->crps();
    for (TriId h : m_mesh->fan_of(v)) {
        const auto &c = m_mesh->corners(h);
        const int k = c[0] == v ? 0 : (c[1] == v ? 1 : 2);
        Pending p;
        p.w.face = h;
        p.w.edge = GeodesicWindow::whole_face;
        p.w.source = crps.frame(h).v[k];
        p.w.sigma = d;
        p.w.min_distance = d;
        p.pseudo_vertex = v;
        push(p);
    }
}

void WindowPropagation::run(TriId t, Vec2d p_in, double radius,
                            std::vector<GeodesicWindow> &out) {
    out.clear();
    m_pool.clear();
    m_heap.clear();
    m_order = 0;
    m_stats = {};
    m_radius = radius;
    if (++m_generation == 0) {
        std::fill(m_vertex_stamp.begin(), m_vertex_stamp.end(), 0);
        m_generation = 1;
    }
    const Crps &crps = m_mesh->crps();
    const CrpsFrame &f = crps.frame(t);
    Vec2d p = p_in;
    // The source's own triangle, and every other triangle whose closure holds the
    // source (across an edge it lies on, around a corner it sits at): a wedge from a
    // point on the entry edge would be degenerate.
    auto whole_face = [&](TriId h, Vec2d at) {
        Pending s;
        s.w.face = h;
        s.w.source = at;
        s.pseudo_vertex = invalid_id;
        push(s);
    };
    // Sources within a millionth of the triangle's size from a corner or an edge (cell
    // positions are stored in float) are moved onto it: a wedge from a point a rounding
    // error off its entry edge is numerically degenerate.
    constexpr double snap = 1e-6;
    const Vec3d bary = barycentric_in(f, p);
    double b[3] = {bary.x, bary.y, bary.z};
    int at_corner = -1;
    for (int c = 0; c < 3; ++c)
        if (b[c] > 1 - snap) at_corner = c;
    if (at_corner < 0) {
        for (int c = 0; c < 3; ++c) b[c] = std::max(b[c], 0.0);
        for (int c = 0; c < 3; ++c)
            if (b[c] < snap) b[c] = 0;
        const double sum = b[0] + b[1] + b[2];
        p = (f.v[0] * b[0] + f.v[1] * b[1] + f.v[2] * b[2]) / sum;
    }
    if (at_corner >= 0) {
        const VertId v = m_mesh->corners(t)[at_corner];
        for (TriId h : m_mesh->fan_of(v)) {
            const auto &c = m_mesh->corners(h);
            whole_face(h, crps.frame(h).v[c[0] == v ? 0 : (c[1] == v ? 1 : 2)]);
        }
    } else {
        whole_face(t, p);
        for (int k = 0; k < 3; ++k) {
            if (b[(k + 2) % 3] != 0) continue;  // not on edge k (opposite corner k + 2)
            const GeodesicMesh::EdgeLink &l = m_mesh->link(t, k);
            if (l.across != invalid_id) whole_face(l.across, l.to_across.apply(p));
        }
    }

    while (!m_heap.empty()) {
        std::pop_heap(m_heap.begin(), m_heap.end());
        const Pending cur = m_pool[m_heap.back().slot];
        m_heap.pop_back();
        // A pseudo-source reached again by a shorter path has spawned newer windows.
        if (cur.pseudo_vertex != invalid_id &&
            cur.w.sigma > known(cur.pseudo_vertex) + m_eps)
            continue;
        out.push_back(cur.w);
        ++m_stats.windows_settled;
        if (cur.w.edge == GeodesicWindow::whole_face)
            propagate_whole_face(cur);
        else
            propagate_entry(cur);
    }
}

void WindowPropagation::propagate_whole_face(const Pending &p) {
    const Crps &crps = m_mesh->crps();
    const CrpsFrame &f = crps.frame(p.w.face);
    const auto &corners = m_mesh->corners(p.w.face);
    const Vec2d s = p.w.source;
    for (int k = 0; k < 3; ++k) reach_vertex(corners[k], p.w.sigma + length(f.v[k] - s));
    for (int k = 0; k < 3; ++k) {
        const Vec2d a = f.v[k], b = f.v[(k + 1) % 3];
        // An edge through the source is covered by the triangle across it (its own
        // whole-face window, or the fan of the pseudo-source).
        if (std::abs(cross(b - a, s - a)) <= m_eps * length(b - a)) continue;
        const uint8_t unsafe = (m_mesh->pseudo_source(corners[k]) ? 1 : 0) |
                               (m_mesh->pseudo_source(corners[(k + 1) % 3]) ? 2 : 0);
        add_child(p, k, a, b, unsafe);
    }
}

// The wedge crosses the triangle from its entry edge (a, b) towards c and leaves through
// the edges (b, c) and (c, a): each gets the part of it inside the wedge.
void WindowPropagation::propagate_entry(const Pending &p) {
    const Crps &crps = m_mesh->crps();
    const TriId t = p.w.face;
    const CrpsFrame &f = crps.frame(t);
    const auto &corners = m_mesh->corners(t);
    const int k = p.w.edge;
    const Vec2d s = p.w.source, r0 = p.w.x0 - s, r1 = p.w.x1 - s;
    const double w = cross(r0, r1);
    if (std::abs(w) <= m_eps * (length(r0) + length(r1))) return;  // a degenerate wedge
    const double sign = w > 0 ? 1.0 : -1.0;
    // Both ≥ 0 inside the wedge.
    auto side0 = [&](Vec2d y) { return sign * cross(r0, y - s); };
    auto side1 = [&](Vec2d y) { return sign * cross(y - s, r1); };
    const double tol = m_eps * (length(r0) + length(r1));

    const int kc = (k + 2) % 3;
    const Vec2d c = f.v[kc];
    if (side0(c) >= -tol && side1(c) >= -tol)
        reach_vertex(corners[kc], p.w.sigma + length(c - s));
    // The interval's ends at the entry edge's own corners reach them too.
    for (int e = 0; e < 2; ++e) {
        const Vec2d x = e ? p.w.x1 : p.w.x0;
        for (int cc : {k, (k + 1) % 3})
            if (length(x - f.v[cc]) <= m_eps)
                reach_vertex(corners[cc], p.w.sigma + length(f.v[cc] - s));
    }

    for (int exit : {(k + 1) % 3, (k + 2) % 3}) {
        const int iu = exit, iv = (exit + 1) % 3;
        const Vec2d u = f.v[iu], v = f.v[iv];
        double lo = 0, hi = 1;
        uint8_t lo_unsafe = m_mesh->pseudo_source(corners[iu]) ? 1 : 0;
        uint8_t hi_unsafe = m_mesh->pseudo_source(corners[iv]) ? 1 : 0;
        bool empty = false;
        const double fu[2] = {side0(u), side1(u)}, fv[2] = {side0(v), side1(v)};
        for (int ray = 0; ray < 2 && !empty; ++ray) {
            const uint8_t ray_unsafe = (p.w.unsafe >> ray) & 1;
            const double a = fu[ray], b = fv[ray];
            if (a < -tol && b < -tol) {
                empty = true;
            } else if (a < 0 && b > a) {
                const double x = a / (a - b);
                if (x > lo) lo = x, lo_unsafe = ray_unsafe;
            } else if (b < 0 && a > b) {
                const double x = a / (a - b);
                if (x < hi) hi = x, hi_unsafe = ray_unsafe;
            }
        }
        if (empty || (hi - lo) * length(v - u) <= m_eps) continue;
        add_child(p, exit, u + (v - u) * lo, u + (v - u) * hi,
                  static_cast<uint8_t>(lo_unsafe | (hi_unsafe << 1)));
    }
}

// The part [y0, y1] of edge `exit` (from its first corner towards its second) of the
// parent's triangle becomes a window of the triangle across it, unless a known vertex
// distance beats it everywhere (ICH's filter).
void WindowPropagation::add_child(const Pending &parent, int exit, Vec2d y0, Vec2d y1,
                                  uint8_t unsafe) {
    const Crps &crps = m_mesh->crps();
    const TriId t = parent.w.face;
    const GeodesicMesh::EdgeLink &l = m_mesh->link(t, exit);
    const CrpsFrame &f = crps.frame(t);
    const auto &corners = m_mesh->corners(t);
    const Vec2d s = parent.w.source;
    const double sigma = parent.w.sigma;
    const double min_d = sigma + point_segment_distance(s, y0, y1);
    if (min_d > m_radius) return;
    // Vertex tests. The window's distance changes by at most the distance moved along
    // the edge, a vertex path from an end of the edge by exactly that: when the vertex
    // path wins at the window's far end from the vertex, it wins all along. The third
    // corner is a vertex path to every point of the edge within its farther end.
    const int iu = exit, iv = (exit + 1) % 3, iw = (exit + 2) % 3;
    const double at0 = sigma + length(y0 - s), at1 = sigma + length(y1 - s);
    const double slack = 10 * m_eps;
    if (known(corners[iu]) + length(f.v[iu] - y1) < at1 - slack) return;
    if (known(corners[iv]) + length(f.v[iv] - y0) < at0 - slack) return;
    if (known(corners[iw]) + std::max(length(f.v[iw] - y0), length(f.v[iw] - y1)) <
        min_d - slack)
        return;
    if (l.across == invalid_id) return;  // a boundary: paths end here
    Pending c;
    c.w.face = l.across;
    c.w.edge = l.edge_in_across;
    c.w.unsafe = unsafe;
    c.w.source = l.to_across.apply(s);
    c.w.sigma = sigma;
    c.w.x0 = l.to_across.apply(y0);
    c.w.x1 = l.to_across.apply(y1);
    c.w.min_distance = min_d;
    c.pseudo_vertex = invalid_id;
    push(c);
}

}  // namespace pelage::sim
