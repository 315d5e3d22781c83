#include "sim/remesh/greedy_collapse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "sim/mesh/closest_point.h"
#include "sim/remesh/surface_topology.h"

namespace pelage::sim {

namespace {

// An input vertex a vertex stands for, besides itself, with the face it was last found
// within max_distance of (its witness).
struct Point {
    VertId v;
    TriId witness;
};

// The mesh as the collapses leave it: its faces (dead ones stay in place, so face ids
// are the input's), the faces around each vertex, and the input vertices each vertex
// stands for. Scratch lists live here so that a try at an edge allocates nothing.
class Collapser {
  public:
    Collapser(const TriangleMesh &mesh, const TopologyDetail &input,
              const GreedyCollapseOptions &options)
        : options(options),
          input(input),
          pos(mesh.positions),
          nv(mesh.num_vertices()),
          nf(mesh.num_triangles()),
          tri(mesh.triangles),
          alive(nf, 1),
          around(nv),
          stands_for(nv),
          edge2(options.edge_length * options.edge_length),
          cos_turn(std::cos(options.max_turn_degrees * 3.141592653589793 / 180)),
          max_distance2(options.max_distance * options.max_distance) {
        for (TriId t = 0; t < nf; ++t)
            for (VertId v : tri[t]) around[v].push_back(t);
    }

    // Passes over the faces in order, each edge shorter than edge_length tried both
    // ways, until a pass collapses nothing or max_passes are made.
    void collapse_short_edges() {
        for (int pass = 0; pass < options.max_passes; ++pass) {
            size_t collapsed = 0;
            for (TriId t = 0; t < nf; ++t)
                for (int c = 0; c < 3 && alive[t]; ++c) {
                    const VertId a = tri[t][c], b = tri[t][(c + 1) % 3];
                    if (length_squared(pos[a] - pos[b]) >= edge2) continue;
                    collapsed += collapse(b, a) || collapse(a, b);
                }
            if (collapsed == 0) break;
        }
    }

    // The faces left, in input order, over the vertices they use, in input order.
    TriangleMesh surviving_mesh() const {
        TriangleMesh out;
        std::vector<char> used(nv, 0);
        for (TriId t = 0; t < nf; ++t)
            if (alive[t])
                for (VertId v : tri[t]) used[v] = 1;
        std::vector<VertId> index(nv, invalid_id);
        for (VertId v = 0; v < nv; ++v)
            if (used[v]) {
                index[v] = VertId(out.positions.size());
                out.positions.push_back(pos[v]);
            }
        for (TriId t = 0; t < nf; ++t) {
            if (!alive[t]) continue;
            out.triangles.push_back(
                {index[tri[t][0]], index[tri[t][1]], index[tri[t][2]]});
            out.source_face.push_back(t);
        }
        return out;
    }

  private:
    bool has(TriId f, VertId v) const {
        return tri[f][0] == v || tri[f][1] == v || tri[f][2] == v;
    }
    Vec3d normal(const std::array<VertId, 3> &t) const {
        return cross(pos[t[1]] - pos[t[0]], pos[t[2]] - pos[t[0]]);
    }
    // The vertices sharing a face with v, sorted, each once.
    void neighbours(VertId v, std::vector<VertId> &out) const {
        out.clear();
        for (TriId f : around[v])
            for (VertId w : tri[f])
                if (w != v) out.push_back(w);
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
    }

    // b into a, which stays where it is; false when that would change the surface.
    bool collapse(VertId b, VertId a) {
        if (!ends_may_move(b, a)) return false;
        VertId opposite[2];
        if (!edge_has_two_faces(b, a, opposite)) return false;
        if (!link_condition_holds(b, a, opposite)) return false;
        if (!turns_no_face(b, a)) return false;
        TriId b_witness;
        if (!keeps_inputs_near(b, a, &b_witness)) return false;
        contract(b, a, b_witness);
        return true;
    }

    bool ends_may_move(VertId b, VertId a) const {
        if (input.on_boundary[b] || input.fans[b] > 1 || input.fans[a] > 1) return false;
        // A pole (the centre of a fanned cap, a UV sphere's tip) is left to CGAL: every
        // try at it would sort its whole ring.
        return around[a].size() + around[b].size() <= 2 * options.max_valence;
    }

    // The edge's two faces, each giving the vertex opposite it.
    bool edge_has_two_faces(VertId b, VertId a, VertId (&opposite)[2]) const {
        int on_edge = 0;
        for (TriId f : around[b])
            if (has(f, a)) {
                if (on_edge == 2) return false;
                for (VertId w : tri[f])
                    if (w != a && w != b) opposite[on_edge] = w;
                ++on_edge;
            }
        return on_edge == 2;
    }

    // The link condition: the ends share only the two opposite vertices, and each of
    // those keeps at least three neighbours (no tetrahedron flattens). Leaves b's
    // neighbours in nb.
    bool link_condition_holds(VertId b, VertId a, const VertId (&opposite)[2]) {
        neighbours(a, na);
        neighbours(b, nb);
        size_t common = 0;
        for (size_t i = 0, j = 0; i < na.size() && j < nb.size();) {
            if (na[i] < nb[j]) {
                ++i;
            } else if (nb[j] < na[i]) {
                ++j;
            } else {
                ++common;
                ++i;
                ++j;
            }
        }
        if (common != 2) return false;
        // (On a manifold a vertex has as many neighbours as faces, one more on a
        // boundary: counted without sorting a pole's ring.)
        for (VertId o : opposite)
            if (around[o].size() + (input.on_boundary[o] ? 1 : 0) <= 3) return false;
        return true;
    }

    // No face of b turns by more than the limit or flattens.
    bool turns_no_face(VertId b, VertId a) const {
        for (TriId f : around[b]) {
            if (has(f, a)) continue;
            std::array<VertId, 3> moved = tri[f];
            for (VertId &v : moved)
                if (v == b) v = a;
            const Vec3d n0 = normal(tri[f]), n1 = normal(moved);
            if (!(dot(n0, n1) > cos_turn * length(n0) * length(n1))) return false;
        }
        return true;
    }

    // Every input vertex stays within max_distance of a face of the surface: its
    // witness. A collapse changes the faces around b, so the points b stands for, and
    // those whose witness is one of b's faces (they stand with a or b's neighbours), are
    // checked again against the faces around their vertex after it. The bound is thus an
    // invariant, not a local guess. On success the new witnesses are set, and b's own
    // is in *b_witness; on failure none is changed.
    bool keeps_inputs_near(VertId b, VertId a, TriId *b_witness) {
        rewitness.clear();
        fan_after(a, b, a);
        *b_witness = near(b);
        if (*b_witness == invalid_id) return false;
        for (Point &p : stands_for[b]) {
            const TriId f = near(p.v);
            if (f == invalid_id) return false;
            rewitness.push_back({&p, f});
        }
        if (!recheck(a, b, a)) return false;
        for (VertId w : nb)
            if (w != a && !recheck(w, b, a)) return false;
        for (const auto &[p, f] : rewitness) p->witness = f;
        return true;
    }

    // The faces around w once b is moved onto a, into fan.
    void fan_after(VertId w, VertId b, VertId a) {
        fan.clear();
        const auto add = [&](TriId f) {
            if (has(f, a) && has(f, b)) return;
            std::array<VertId, 3> t = tri[f];
            for (VertId &v : t)
                if (v == b) v = a;
            fan.push_back({f, t});
        };
        for (TriId f : around[w]) add(f);
        if (w == a)
            for (TriId f : around[b])
                if (!has(f, a)) add(f);
    }

    // The first face of fan within max_distance of v, or invalid_id.
    TriId near(VertId v) const {
        for (const auto &[f, t] : fan)
            if (length_squared(
                    closest_point_on_triangle(pos[v], pos[t[0]], pos[t[1]], pos[t[2]]) -
                    pos[v]) <= max_distance2)
                return f;
        return invalid_id;
    }

    // The points w stands for whose witness is one of b's faces, against w's faces
    // after the collapse (fan holds a's when w is a).
    bool recheck(VertId w, VertId b, VertId a) {
        bool fan_made = w == a;
        for (Point &p : stands_for[w]) {
            if (!has(p.witness, b)) continue;
            if (!fan_made) {
                fan_after(w, b, a);
                fan_made = true;
            }
            const TriId f = near(p.v);
            if (f == invalid_id) return false;
            rewitness.push_back({&p, f});
        }
        return true;
    }

    // Moves b onto a: the edge's faces die, b's others become a's, and a stands for b
    // and all b stood for.
    void contract(VertId b, VertId a, TriId b_witness) {
        for (TriId f : around[b]) {
            if (has(f, a)) {
                alive[f] = 0;
                for (VertId w : tri[f]) {
                    if (w == b) continue;
                    auto &list = around[w];
                    list.erase(std::find(list.begin(), list.end(), f));
                }
            } else {
                for (VertId &v : tri[f])
                    if (v == b) v = a;
                around[a].push_back(f);
            }
        }
        around[b].clear();
        stands_for[a].push_back({b, b_witness});
        stands_for[a].insert(stands_for[a].end(), stands_for[b].begin(),
                             stands_for[b].end());
        stands_for[b] = {};
    }

    const GreedyCollapseOptions &options;
    const TopologyDetail &input;
    const std::vector<Vec3d> &pos;
    const size_t nv, nf;
    std::vector<std::array<VertId, 3>> tri;
    std::vector<char> alive;
    std::vector<std::vector<TriId>> around;
    std::vector<std::vector<Point>> stands_for;
    const double edge2, cos_turn, max_distance2;
    // Scratch: the ends' neighbours, a vertex's faces after a collapse, and the
    // witnesses a collapse would set.
    std::vector<VertId> na, nb;
    std::vector<std::pair<TriId, std::array<VertId, 3>>> fan;
    std::vector<std::pair<Point *, TriId>> rewitness;
};

}  // namespace

std::optional<TriangleMesh> greedy_collapse(const TriangleMesh &mesh,
                                            const GreedyCollapseOptions &options,
                                            std::string *refused) {
    const auto refuse = [&](const char *why) -> std::optional<TriangleMesh> {
        if (refused) *refused = why;
        return std::nullopt;
    };
    const TopologyDetail input = analyse_topology(mesh);
    if (!input.top.edge_manifold)
        return refuse("an edge has three faces, or two facing opposite ways");
    Collapser collapser(mesh, input, options);
    collapser.collapse_short_edges();
    TriangleMesh out = collapser.surviving_mesh();
    // A safety net under the link condition, which keeps the topology by construction.
    if (!(surface_topology(out) == input.top)) return refuse("the topology changed");
    return out;
}

}  // namespace pelage::sim
