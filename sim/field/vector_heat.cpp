#include "sim/field/vector_heat.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace pelage::sim {

namespace {

using Complex = std::complex<double>;
constexpr double two_pi = 6.283185307179586;

// Angle in (−π, π].
double wrap(double a) {
    a = std::fmod(a, two_pi);
    if (a > two_pi / 2) a -= two_pi;
    if (a <= -two_pi / 2) a += two_pi;
    return a;
}

// The per-vertex tangent bases: for every triangle corner, the angle (in the
// corner vertex's basis) of the edges to the next and the previous corner, and each
// vertex's angle scale.
struct VertexBases {
    std::vector<Vec3d> position;
    std::vector<std::array<std::array<double, 2>, 3>> edge_angle;  // [t][c][next, prev]
    std::vector<std::array<double, 3>> corner_angle;               // interior angles
    std::vector<double> scale;                                     // 2π/Θ or 1
};

double corner_angle(Vec3d p, Vec3d a, Vec3d b) {
    const Vec3d u = a - p, v = b - p;
    return std::atan2(length(cross(u, v)), dot(u, v));
}

VertexBases build_bases(const Crps &crps) {
    const Topology &topo = crps.topology();
    const size_t nt = crps.num_triangles(), nv = topo.fan_row.size() - 1;
    VertexBases b;
    b.position.assign(nv, Vec3d{});
    b.edge_angle.resize(nt);
    b.corner_angle.resize(nt);
    for (TriId t = 0; t < nt; ++t)
        for (int c = 0; c < 3; ++c)
            b.position[crps.corners(t)[c]] = crps.to_3d(t, crps.frame(t).v[c]);
    std::vector<double> angle_sum(nv, 0.0);
    std::vector<uint8_t> rim(nv, 0);  // on a boundary or non-manifold edge
    for (TriId t = 0; t < nt; ++t) {
        const auto &v = crps.corners(t);
        for (int c = 0; c < 3; ++c) {
            b.corner_angle[t][c] = corner_angle(
                b.position[v[c]], b.position[v[(c + 1) % 3]], b.position[v[(c + 2) % 3]]);
            angle_sum[v[c]] += b.corner_angle[t][c];
        }
    }
    for (EdgeId e = 0; e < topo.num_edges(); ++e)
        if (!topo.is_manifold(e))
            rim[topo.edge_vertices[e][0]] = rim[topo.edge_vertices[e][1]] = 1;
    b.scale.assign(nv, 1.0);
    for (VertId v = 0; v < nv; ++v)
        if (!rim[v] && angle_sum[v] > 0) b.scale[v] = two_pi / angle_sum[v];

    // Around each vertex, corner by corner: the edge counter-clockwise of another (about
    // the oriented normal) is `scale · corner angle` further on. Pieces the walk cannot
    // reach from the first (a non-manifold vertex) start again at 0.
    struct Rel {
        TriId t;
        int c;
        VertId from, to;
        double step;
        bool done;
    };
    std::vector<Rel> rel;
    std::vector<std::pair<VertId, double>> known;
    auto find = [&](VertId w) -> const double * {
        for (const auto &k : known)
            if (k.first == w) return &k.second;
        return nullptr;
    };
    for (VertId v = 0; v < nv; ++v) {
        rel.clear();
        known.clear();
        for (TriId t : topo.fan_of(v)) {
            const auto &cv = crps.corners(t);
            const int c = cv[0] == v ? 0 : (cv[1] == v ? 1 : 2);
            const VertId a = cv[(c + 1) % 3], bb = cv[(c + 2) % 3];
            const Vec3d n = crps.frame(t).normal;
            const bool ccw =
                dot(cross(b.position[a] - b.position[v], b.position[bb] - b.position[v]),
                    n) >= 0;
            rel.push_back({t, c, ccw ? a : bb, ccw ? bb : a,
                           b.scale[v] * b.corner_angle[t][c], false});
        }
        size_t left = rel.size();
        while (left > 0) {
            bool progress = false;
            for (Rel &r : rel) {
                if (r.done) continue;
                const double *f = find(r.from), *g = find(r.to);
                if (f && !g)
                    known.push_back({r.to, *f + r.step});
                else if (!f && g)
                    known.push_back({r.from, *g - r.step});
                else if (!f && !g)
                    continue;
                r.done = true;
                --left;
                progress = true;
            }
            if (!progress)  // a new piece of the fan
                for (Rel &r : rel)
                    if (!r.done) {
                        known.push_back({r.from, 0.0});
                        break;
                    }
        }
        for (const Rel &r : rel) {
            const auto &cv = crps.corners(r.t);
            b.edge_angle[r.t][r.c] = {*find(cv[(r.c + 1) % 3]), *find(cv[(r.c + 2) % 3])};
        }
    }
    return b;
}

}  // namespace

Vec3d field_to_world(const Crps &crps, TriId t, Vec2d a) {
    const Vec3d d = crps.frame(t).rotation.transpose_times(Vec3d{a.x, 0, a.y});
    const double len = length(d);
    return len > 0 ? d / len : Vec3d{};
}

Vec2d world_to_field(const Crps &crps, TriId t, Vec3d d) {
    const Vec3d c = crps.frame(t).rotation * d;
    return {c.x, c.z};
}

TangentField vector_heat_field(const Crps &crps,
                               const std::vector<TangentControl> &controls,
                               double magnitude, const FieldInterpolation &how) {
    const bool harmonic = how.method == FieldInterpolation::Method::harmonic;
    const size_t nt = crps.num_triangles();
    const VertexBases b = build_bases(crps);
    const size_t nv = b.position.size();
    const Topology &topo = crps.topology();

    // t = h², h the mean edge length.
    double h = 0;
    for (EdgeId e = 0; e < topo.num_edges(); ++e)
        h += length(b.position[topo.edge_vertices[e][0]] -
                    b.position[topo.edge_vertices[e][1]]);
    h = topo.num_edges() > 0 ? h / double(topo.num_edges()) : 0;
    double time = harmonic ? 1.0 : how.time_scale * h * h;

    // X0: each control in its corners' bases, by barycentric weight.
    Eigen::VectorXcd x0 = Eigen::VectorXcd::Zero(nv);
    std::vector<double> held(nv, 0.0);  // harmonic: each vertex's weight in the controls
    std::vector<uint8_t> piece_has_control(topo.num_components + 1, 0);
    for (const TangentControl &k : controls) {
        const TriId t = k.tri;
        piece_has_control[std::min<size_t>(topo.component[t], topo.num_components)] = 1;
        const Vec3d n = crps.frame(t).normal;
        const Vec3d d = k.direction / length(k.direction);
        for (int c = 0; c < 3; ++c) {
            const VertId v = crps.corners(t)[c];
            const Vec3d e =
                normalize(b.position[crps.corners(t)[(c + 1) % 3]] - b.position[v]);
            const double alpha = std::atan2(dot(cross(e, d), n), dot(e, d));
            x0[v] += k.barycentric[c] *
                     std::polar(1.0, b.edge_angle[t][c][0] + b.scale[v] * alpha);
            held[v] += k.barycentric[c];
        }
    }
    // The vertices a control can reach: those of a connected piece holding one.
    std::vector<uint8_t> reachable(nv, 0);
    for (TriId t = 0; t < nt; ++t)
        if (piece_has_control[std::min<size_t>(topo.component[t], topo.num_components)])
            for (VertId v : crps.corners(t)) reachable[v] = 1;

    // The heat decays by a constant factor per ring of triangles, so on a surface many
    // hundred rings across it underflows far from the controls: then t grows tenfold
    // until every reachable vertex has a vector (a longer flow is smoother still).
    Eigen::VectorXcd x;
    for (int attempt = 0;; ++attempt) {
        // M + t·L∇, with L∇ = Σ over corners c of the half-cotangent weight w of the
        // opposite edge ab times (|a⟩ − r_ba|b⟩)(⟨a| − r̄_ba⟨b|): Hermitian, and
        // positive semi-definite where the cotangents are positive.
        std::vector<Eigen::Triplet<Complex>> triplets;
        triplets.reserve(nt * 15);
        for (TriId t = 0; t < nt; ++t) {
            const auto &cv = crps.corners(t);
            const double third = crps.frame(t).area / 3;
            for (int c = 0; c < 3; ++c) {
                triplets.emplace_back(cv[c], cv[c], Complex(harmonic ? 0 : third, 0));
                const int ka = (c + 1) % 3, kb = (c + 2) % 3;
                const VertId a = cv[ka], bv = cv[kb];
                const double s = std::sin(b.corner_angle[t][c]);
                const double cot = std::clamp(
                    std::cos(b.corner_angle[t][c]) / std::max(s, 1e-12), -1e3, 1e3);
                const double w = 0.5 * cot * time;
                // φ_ab: edge a→b at a (a's next corner is b); φ_ba: edge b→a at b.
                const double phi_ab = b.edge_angle[t][ka][0],
                             phi_ba = b.edge_angle[t][kb][1];
                const Complex r = std::polar(1.0, phi_ab - phi_ba + two_pi / 2);  // b→a
                triplets.emplace_back(a, a, Complex(w, 0));
                triplets.emplace_back(bv, bv, Complex(w, 0));
                triplets.emplace_back(a, bv, -w * r);
                triplets.emplace_back(bv, a, -w * std::conj(r));
            }
        }
        Eigen::VectorXcd rhs = x0;
        if (harmonic) {
            // L∇ X = 0 away from the controls, X = the controls at their corners: each
            // corner is held to its control by a penalty far stiffer than any edge
            // (weighted by its barycentric share), and a vanishing mass keeps pieces
            // without a control solvable (they get zero).
            double stiffest = 0;
            std::vector<double> diag(nv, 0.0);
            for (const auto &tr : triplets)
                if (tr.row() == tr.col()) diag[tr.row()] += tr.value().real();
            for (double d : diag) stiffest = std::max(stiffest, d);
            const double hold = 1e8 * std::max(stiffest, 1e-300);
            for (VertId v = 0; v < nv; ++v) {
                triplets.emplace_back(v, v, Complex(1e-12 * stiffest, 0));
                if (held[v] > 0) {
                    triplets.emplace_back(v, v, Complex(hold * held[v], 0));
                    const double m = std::abs(x0[v]);
                    rhs[v] = m > 0 ? x0[v] / m * (hold * held[v]) : Complex(0, 0);
                }
            }
        }
        Eigen::SparseMatrix<Complex> A(nv, nv);
        A.setFromTriplets(triplets.begin(), triplets.end());
        Eigen::SimplicialLDLT<Eigen::SparseMatrix<Complex>> solver(A);
        if (solver.info() != Eigen::Success)
            throw std::runtime_error("vector heat method: factorisation failed");
        x = solver.solve(rhs);
        if (solver.info() != Eigen::Success)
            throw std::runtime_error("vector heat method: solve failed");
        bool reached = true;
        for (VertId v = 0; v < nv && reached; ++v)
            reached = !reachable[v] || std::abs(x[v]) > 1e-200;
        if (reached || harmonic || attempt == 8) break;
        time *= 10;
    }

    // Every triangle: its corners' vectors carried into its plane, averaged.
    TangentField field;
    field.a.assign(nt, Vec2d{});
    for (TriId t = 0; t < nt; ++t) {
        const Vec3d n = crps.frame(t).normal;
        Vec3d sum;
        double total = 0;
        for (int c = 0; c < 3; ++c) {
            const VertId v = crps.corners(t)[c];
            const double m = std::abs(x[v]);
            if (!(m > 0)) continue;
            const double alpha =
                wrap(std::arg(x[v]) - b.edge_angle[t][c][0]) / b.scale[v];
            const Vec3d e =
                normalize(b.position[crps.corners(t)[(c + 1) % 3]] - b.position[v]);
            sum += (e * std::cos(alpha) + cross(n, e) * std::sin(alpha)) * m;
            total += m;
        }
        const Vec2d p = world_to_field(crps, t, sum);
        const double len = length(p);
        // Corners pointing every way (below 1e-6 of their lengths): no direction.
        if (len > 1e-6 * total && len > 0) field.a[t] = p * (magnitude / len);
    }
    for (const TangentControl &k : controls) {
        const Vec2d p = world_to_field(crps, k.tri, k.direction);
        const double len = length(p);
        if (len > 0) field.a[k.tri] = p * (magnitude / len);
    }
    return field;
}

}  // namespace pelage::sim
