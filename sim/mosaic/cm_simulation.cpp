#include "sim/mosaic/cm_simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "sim/core/input_error.h"
#include "sim/crps/body_length.h"
#include "sim/mesh/closest_point.h"
#include "sim/mosaic/anisotropy_field.h"
#include "sim/mosaic/run_progress.h"

namespace pelage::sim {

namespace {

double now_seconds() {
    return std::chrono::duration<double>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

CmSimulation::CmSimulation(const Crps &crps, CellTypes types, SimParams params,
                           uint64_t seed)
    : m_crps(crps),
      m_types(std::move(types)),
      m_params(params),
      m_seed(seed),
      m_cells(crps.num_triangles()),
      m_steps_left(crps.num_triangles(), 0) {
    for (TriId t = 0; t < crps.num_triangles(); ++t) m_area += crps.frame(t).area;
    build_field(m_params);
}

void CmSimulation::build_field(const SimParams &p) {
    m_field_params = p;
    if (!m_growth) {
        m_field = anisotropy_field(p, m_crps);
        remember_field(m_crps);
        return;
    }
    // A growing run starts from the first key's shape, which may be far from the rest
    // pose (a calf's proportions): the field's box-space points and body axis mean the
    // rest pose, as the regions' do and as `pelage stats` reads them.
    const Crps rest = m_growth->rest_crps();
    m_field = anisotropy_field(p, rest);
    remember_field(rest);
    carry_field();
}

void CmSimulation::remember_field(const Crps &crps) {
    // Each vector in its triangle's edge basis, for carry_field() to carry it.
    m_field_edge_coords.resize(m_field.a.size());
    m_field_length.resize(m_field.a.size());
    for (TriId t = 0; t < m_field.a.size(); ++t) {
        const Vec2d e1 = crps.frame(t).v[1] - crps.frame(t).v[0];
        const Vec2d e2 = crps.frame(t).v[2] - crps.frame(t).v[0];
        const Vec2d a = m_field.a[t];
        const double det = cross(e1, e2);  // nonzero: the CRPS has no degenerate triangle
        m_field_edge_coords[t] = {cross(a, e2) / det, cross(e1, a) / det};
        m_field_length[t] = length(a);
    }
}

void CmSimulation::set_control(SurfaceControl control) {
    m_control = std::move(control);
    m_control.evaluate_on(m_crps);
    const ControlSpec &s = m_control.spec();
    // A local w_a needs the field where its default is 0; a local anisotropy magnitude
    // scales a unit field cell by cell.
    if (s.w_a.max() > 0 && (s.w_a.local() || s.anisotropy_magnitude.local())) {
        SimParams p = m_params;
        p.w_a = s.w_a.max();
        if (s.anisotropy_magnitude.local()) p.anisotropy_magnitude = 1.0;
        build_field(p);
    }
}

double CmSimulation::max_radius() const {
    const LocalValue &w = m_control.spec().w_r;
    if (!w.local()) return radius();
    return radius() / m_params.w_r * w.max();
}

double CmSimulation::radius() const {
    // Walter 1998 §3.3: r = w_r·sqrt(A/m)
    const double m = std::max<double>(1.0, double(m_cells.size()));
    return m_params.w_r * std::sqrt(m_area / m);
}

std::vector<size_t> CmSimulation::count_by_type() const {
    std::vector<size_t> n(m_types.size(), 0);
    for (uint8_t t : m_cells.types()) ++n[t];
    return n;
}

double CmSimulation::division_delay(int type, CounterRng &rng, SurfacePoint at) const {
    const std::vector<LocalValue> &local = m_control.spec().division_time;
    // A local division time is read where the cell is when it is scheduled.
    const double mean = size_t(type) < local.size() && local[type].local()
                            ? m_control.value(local[type], at.tri, at.p)
                            : m_types[type].division_time;
    if (m_params.division_distribution == DivisionDistribution::exponential) {
        // Divisions as a Poisson process: exponential inter-division times (Teo §3.2).
        return std::max(rng.exponential(mean), 1e-9);
    }
    // Walter 1998 §3.4: "given by a Poisson distribution with average equal to the rate
    // of division": integer time units. A zero delay is raised to one relaxation step so
    // a cell never divides twice at the same instant (deviation; P(0) = e^-mean is tiny
    // for the published means).
    const double d = double(rng.poisson(mean));
    return d > 0 ? d : 1.0 / m_params.rho;
}

std::vector<TriId> CmSimulation::all_triangles_with_cells() const {
    std::vector<TriId> out;
    for (TriId t = 0; t < m_crps.num_triangles(); ++t)
        if (!m_cells.on(t).empty()) out.push_back(t);
    return out;
}

void CmSimulation::fill_local_parameters(const std::vector<TriId> &active,
                                         RelaxContext *ctx) {
    const ControlSpec &s = m_control.spec();
    const bool w_a = s.w_a.local() && !ctx->uniform_alpha,
               scale = s.anisotropy_magnitude.local() && !ctx->uniform_alpha,
               adhesion = !s.adhesion_in.empty() && !ctx->uniform_alpha;
    if (adhesion) {
        // Each moving cell's row of 1 − α, lerped towards each region's matrix by the
        // region's value where the cell stands (the initial phase keeps one α).
        m_cell_one_minus_alpha.resize(m_cells.size() * max_cell_types);
        for (TriId t : active)
            for (CellId c : m_cells.on(t)) {
                const int type = m_cells.type(c);
                double *row = m_cell_one_minus_alpha.data() + size_t(c) * max_cell_types;
                for (int q = 0; q < m_types.size(); ++q) {
                    double a = m_types.alpha(type, q);
                    for (const auto &[region, matrix] : s.adhesion_in)
                        a += (matrix[size_t(type)][size_t(q)] - a) *
                             m_control.region(region, t, m_cells.pos(c));
                    row[q] = 1.0 - a;
                }
            }
        ctx->cell_one_minus_alpha = m_cell_one_minus_alpha.data();
    }
    if (!s.w_r.local() && !s.w_d.local() && !w_a && !scale) return;
    const size_t n = m_cells.size();
    const double unit_r = radius() / m_params.w_r;  // sqrt(A/m)
    if (s.w_r.local()) m_cell_r.resize(n);
    if (s.w_d.local()) m_cell_w_d.resize(n);
    if (w_a) m_cell_w_a.resize(n);
    if (scale) m_cell_a_scale.resize(n);
    for (TriId t : active)
        for (CellId c : m_cells.on(t)) {
            const Vec2d p = m_cells.pos(c);
            if (s.w_r.local()) m_cell_r[c] = unit_r * m_control.value(s.w_r, t, p);
            if (s.w_d.local()) m_cell_w_d[c] = m_control.value(s.w_d, t, p);
            if (w_a) m_cell_w_a[c] = m_control.value(s.w_a, t, p);
            if (scale) m_cell_a_scale[c] = m_control.value(s.anisotropy_magnitude, t, p);
        }
    if (s.w_r.local()) ctx->cell_r = m_cell_r.data();
    if (s.w_d.local()) ctx->cell_w_d = m_cell_w_d.data();
    if (w_a) ctx->cell_w_a = m_cell_w_a.data();
    if (scale) ctx->cell_a_scale = m_cell_a_scale.data();
}

void CmSimulation::schedule(CellId c, double time) {
    if (m_due.size() <= c) m_due.resize(size_t(c) + 1, HUGE_VAL);
    m_due[c] = time;
    m_heap.push_back({time, c});
    std::push_heap(m_heap.begin(), m_heap.end(), std::greater<>());
}

void CmSimulation::apply_masks_after_move(const std::vector<CellId> &moved) {
    for (CellId c : moved) {
        const SurfacePoint at{m_cells.tri(c), m_cells.pos(c)};
        const int from = m_cells.type(c);
        const int to = m_control.masked_type_where_zero(from, at.tri, at.p);
        if (to == from) continue;
        m_cells.set_type(c, static_cast<uint8_t>(to));
        if (m_due.empty()) continue;  // initialisation: scheduled afterwards
        // Growing, the rate is the surface's (grow()), not the type's: it stands.
        if (m_growth) continue;
        // Queiroz's switchCellType redraws the division time for the new type.
        m_due[c] = HUGE_VAL;  // the pending event, if any, is stale
        CounterRng rng(m_seed, RandomStream::mask_switch, m_switches++);
        if (m_types[to].divides()) schedule(c, m_now + division_delay(to, rng, at));
    }
}

RelaxStepResult CmSimulation::relax(const std::vector<TriId> &active,
                                    bool uniform_alpha) {
    RelaxContext ctx;
    ctx.crps = &m_crps;
    ctx.types = &m_types;
    ctx.field = &m_field;
    ctx.r = max_radius();
    ctx.w_d = m_params.w_d;
    ctx.w_a = uniform_alpha ? 0.0
                            : (m_control.spec().w_a.local() ? m_control.spec().w_a.max()
                                                            : m_params.w_a);
    ctx.uniform_alpha = uniform_alpha;
    ctx.alpha = m_params.initial_relax_alpha;
    ctx.seed = m_seed;
    fill_local_parameters(active, &ctx);
    std::vector<CellId> moved;
    if (!m_control.spec().masks.empty())
        for (TriId t : active)
            moved.insert(moved.end(), m_cells.on(t).begin(), m_cells.on(t).end());
    const RelaxStepResult r = m_relaxer.step(ctx, m_cells, active);
    m_stats.cell_steps += r.cells_moved;
    apply_masks_after_move(moved);
    return r;
}

uint64_t initial_cell_count(const SimParams &params, const Crps &crps) {
    if (params.initial_cells > 0) return params.initial_cells;
    double area = 0;
    for (TriId t = 0; t < crps.num_triangles(); ++t) area += crps.frame(t).area;
    double n = params.initial_density * area;
    if (params.initial_spacing > 0) {
        const double d = params.initial_spacing * body_axis(crps).length;
        n = 2 * area / (std::sqrt(3.0) * d * d);
    }
    if (!(n <= max_initial_cells))
        throw InputError("", 0,
                         params.initial_spacing > 0 ? "simulation.initial_spacing"
                                                    : "simulation.initial_density",
                         "gives " + std::to_string(n) +
                             " initial cells on this mesh (at "
                             "most " +
                             std::to_string(max_initial_cells) + "): use a larger value");
    return static_cast<uint64_t>(std::llround(n));
}

void CmSimulation::initialize(uint64_t override_cells) {
    const double t0 = now_seconds();
    const size_t nt = m_crps.num_triangles();
    const uint64_t n = std::max<uint64_t>(
        override_cells > 0 ? override_cells : initial_cell_count(m_params, m_crps), 1);
    if (m_params.target_cells > 0 && m_params.initial_cells > 0 &&
        n != m_params.initial_cells) {
        // A target count belongs to the preset's initial count: keep their ratio, so a
        // run with more or fewer cells grows by the same factor.
        m_params.target_cells = static_cast<uint64_t>(std::llround(
            double(m_params.target_cells) * double(n) / double(m_params.initial_cells)));
    }
    m_cells.reserve(std::max<uint64_t>(n, m_params.target_cells));

    // --- Turk's method (Walter thesis §6.4): triangle by cumulative area, then a
    //     uniform point in it from two square-rooted numbers ---
    // Queiroz §V: a local initial_weight scales each triangle's share (area × weight).
    const ControlSpec &control = m_control.spec();
    std::vector<double> cumulative(nt);
    double sum = 0;
    for (TriId t = 0; t < nt; ++t)
        cumulative[t] =
            (sum += control.initial_weight.local()
                        ? m_crps.frame(t).area *
                              m_control.triangle_mean(control.initial_weight, t)
                        : m_crps.frame(t).area);
    if (!(sum > 0))
        throw InputError("", 0, "simulation.initial_weight",
                         "is 0 over the whole surface: no initial cell can be placed");
    bool local_types = false;
    for (const LocalValue &v : control.initial_probability)
        local_types = local_types || v.local();
    // --- Initial types: exactly round(P_k·n) cells of type k (largest remainder), in a
    //     seeded random order. Walter lets "the system" pick F cells at random; exact
    //     proportions remove the binomial spread of the few founders (20 F cells in
    //     the reticulata run), which otherwise dominates the final counts. ---
    std::vector<uint8_t> initial_type;
    {
        std::vector<uint64_t> count(m_types.size());
        std::vector<std::pair<double, int>> remainder;
        uint64_t assigned = 0;
        for (int k = 0; k < m_types.size(); ++k) {
            const double exact = m_types[k].initial_probability * double(n);
            count[k] = static_cast<uint64_t>(std::floor(exact));
            assigned += count[k];
            remainder.push_back(
                {-(exact - std::floor(exact)), k});  // largest first, then lower k
        }
        std::sort(remainder.begin(), remainder.end());
        for (size_t i = 0; assigned < n; ++i, ++assigned)
            ++count[remainder[i % remainder.size()].second];
        for (int k = 0; k < m_types.size(); ++k)
            initial_type.insert(initial_type.end(), count[k], uint8_t(k));
        CounterRng shuffle(m_seed, RandomStream::initial_type, 0);
        for (uint64_t i = n; i > 1; --i)
            std::swap(initial_type[i - 1], initial_type[shuffle.next_u64() % i]);
    }
    for (uint64_t i = 0; i < n; ++i) {
        CounterRng rng(m_seed, RandomStream::initial_position, i);
        const double u = rng.uniform() * sum;
        TriId t =
            static_cast<TriId>(std::upper_bound(cumulative.begin(), cumulative.end(), u) -
                               cumulative.begin());
        t = std::min<TriId>(t, static_cast<TriId>(nt - 1));
        const double s = std::sqrt(rng.uniform()), v = rng.uniform();
        const auto &f = m_crps.frame(t);
        const Vec2d p = f.v[0] * (1 - s) + f.v[1] * (s * (1 - v)) + f.v[2] * (s * v);
        int type = initial_type[i];
        if (local_types) {
            // Queiroz §V: each cell's type from the probabilities where it stands,
            // normalised to sum to 1 (a draw per cell: proportions vary by region).
            std::vector<double> prob(size_t(m_types.size()));
            double total = 0;
            for (int k = 0; k < m_types.size(); ++k)
                total += prob[size_t(k)] =
                    control.initial_probability[size_t(k)].local()
                        ? m_control.value(control.initial_probability[size_t(k)], t, p)
                        : m_types[k].initial_probability;
            if (!(total > 0)) {  // every type 0 here: the defaults
                total = 0;
                for (int k = 0; k < m_types.size(); ++k)
                    total += prob[size_t(k)] = m_types[k].initial_probability;
            }
            CounterRng draw(m_seed, RandomStream::local_type, i);
            double u = draw.uniform() * total;
            type = m_types.size() - 1;
            for (int k = 0; k < m_types.size(); ++k) {
                if (u < prob[size_t(k)]) {
                    type = k;
                    break;
                }
                u -= prob[size_t(k)];
            }
        }
        if (!control.masks.empty()) {
            CounterRng mask(m_seed, RandomStream::mask_initial, i);
            type = m_control.draw_masked_type(type, t, p, mask);
        }
        m_cells.add({t, p}, static_cast<uint8_t>(type));
    }
    m_stats.initial_cells = n;

    // --- Initial relaxation with one α for every pair (Walter 1998 §3.3), global ---
    for (int k = 0; k < m_params.initial_relax_steps; ++k) {
        const RelaxStepResult r = relax(all_triangles_with_cells(), true);
        ++m_stats.initial_relax_steps;
        if (r.max_move < m_params.initial_relax_tolerance * radius()) break;
    }

    // --- First division of every initial cell ---
    m_heap.clear();
    m_due.assign(m_cells.size(), HUGE_VAL);
    for (CellId c = 0; c < m_cells.size(); ++c) {
        if (!m_types[m_cells.type(c)].divides()) continue;
        CounterRng rng(m_seed, RandomStream::initial_division, c);
        m_due[c] = division_delay(m_cells.type(c), rng, {m_cells.tri(c), m_cells.pos(c)});
        m_heap.push_back({m_due[c], c});
    }
    std::make_heap(m_heap.begin(), m_heap.end(), std::greater<>());
    m_stats.seconds_initial = now_seconds() - t0;
}

void CmSimulation::mark_local(SurfacePoint at) {
    // The cached unfolding of the child's triangle covers radius R ≥ r; the triangles
    // within r of the child are among its entries (bounding circle first, then exact).
    const double r = max_radius();  // every cell's own radius is at most this
    Neighbourhoods &nb = m_relaxer.neighbourhoods();
    nb.update(m_crps, r);
    for (const Neighbourhoods::Entry &e : nb.of(at.tri)) {
        const double reach = r + nb.bounding_radius(e.tri);
        const Vec2d q = e.to_nbr.apply(at.p);
        if (length_squared(q) > reach * reach) continue;
        if (point_triangle_distance(q, m_crps.frame(e.tri).v.data()) > r) continue;
        if (m_steps_left[e.tri] == 0) m_marked.push_back(e.tri);
        m_steps_left[e.tri] = m_params.local_steps;
    }
}

std::vector<TriId> CmSimulation::take_local_active() {
    std::sort(m_marked.begin(), m_marked.end());
    std::vector<TriId> active = m_marked;
    // Teo Fig. 5.6: decrease each triangle's step count; drop it at zero.
    size_t keep = 0;
    for (TriId t : m_marked)
        if (--m_steps_left[t] > 0) m_marked[keep++] = t;
    m_marked.resize(keep);
    return active;
}

void CmSimulation::divide(Event e) {
    std::pop_heap(m_heap.begin(), m_heap.end(), std::greater<>());
    m_heap.pop_back();
    if (e.time != m_due[e.cell]) return;  // rescheduled since (a mask switched it)
    const uint64_t k = m_stats.divisions++;
    CounterRng rng(m_seed, RandomStream::division, k);
    const CellId parent = e.cell;
    const int parent_type = m_cells.type(parent);
    const int mutated_type = m_types.mutate(parent_type, rng.uniform());
    // Walter 1998 §3.4: the child is uniformly random within a circle of diameter 1% of
    // r around the parent (radius child_radius_factor·r), then walked onto the surface.
    const double rad = m_params.child_radius_factor * radius() * std::sqrt(rng.uniform());
    const double angle = 6.283185307179586 * rng.uniform();
    const SurfacePoint from{m_cells.tri(parent), m_cells.pos(parent)};
    const SurfacePoint at =
        walk(m_crps, from, {rad * std::cos(angle), rad * std::sin(angle)});
    // Queiroz §V.A: a child of a masked type becomes `otherwise` with probability 1 − m.
    int child_type = mutated_type;
    if (!m_control.spec().masks.empty()) {
        CounterRng mask(m_seed, RandomStream::mask_division, k);
        child_type = m_control.draw_masked_type(child_type, at.tri, at.p, mask);
    }
    // The child belongs to its parent's clone (Walter 1998 §3: a clone is every
    // descendant of one initial cell, whatever types mutation gave them).
    const CellId child =
        m_cells.add(at, static_cast<uint8_t>(child_type), m_cells.founder(parent));
    if (m_growth) {
        // Growth sets the rates (set_growth): the parent keeps its rate until the next
        // reshape, the child gets its own then.
        const double mean = m_growth_mean[parent];
        m_growth_mean.push_back(std::numeric_limits<double>::infinity());
        m_due.push_back(HUGE_VAL);
        if (mean < std::numeric_limits<double>::infinity())
            schedule(parent, e.time + std::max(rng.exponential(mean), 1e-9));
        else
            m_due[parent] = HUGE_VAL;
        if (m_params.relax == RelaxMode::local) mark_local(at);
        return;
    }
    // Both are rescheduled: parent and child divide again after their own delays.
    m_due.push_back(HUGE_VAL);
    if (m_types[parent_type].divides())
        schedule(parent, e.time + division_delay(parent_type, rng, from));
    else
        m_due[parent] = HUGE_VAL;
    if (m_types[child_type].divides())
        schedule(child, e.time + division_delay(child_type, rng, at));
    if (m_params.relax == RelaxMode::local) mark_local(at);
}

void CmSimulation::set_growth(GrowingSurface *surface) {
    if (surface && &surface->crps() != &m_crps)
        throw std::invalid_argument("CmSimulation::set_growth: built on another CRPS");
    m_growth = surface;
    if (m_growth && !m_field.empty()) build_field(m_field_params);
}

void CmSimulation::surface_changed() {
    m_area = 0;
    for (TriId t = 0; t < m_crps.num_triangles(); ++t) m_area += m_crps.frame(t).area;
    m_relaxer.neighbourhoods().invalidate();
    carry_field();
}

void CmSimulation::carry_field() {
    // The field is a property of the skin, so it moves with it: each triangle's vector
    // keeps its coordinates in the triangle's edge basis (v1 − v0, v2 − v0), the way the
    // growth map's differential carries a tangent vector, and keeps its length.
    for (TriId t = 0; t < m_field.a.size(); ++t) {
        const Vec2d e1 = m_crps.frame(t).v[1] - m_crps.frame(t).v[0];
        const Vec2d e2 = m_crps.frame(t).v[2] - m_crps.frame(t).v[0];
        const Vec2d a = e1 * m_field_edge_coords[t].x + e2 * m_field_edge_coords[t].y;
        const double len = length(a);
        m_field.a[t] = len > 0 ? a * (m_field_length[t] / len) : Vec2d{0, 0};
    }
}

void CmSimulation::grow(uint64_t update, double time) {
    const double interval =
        double(std::max<uint64_t>(
            1, uint64_t(std::llround(m_growth->shape().interval() * m_params.rho)))) /
        m_params.rho;
    m_growth->reshape(time, m_cells);
    surface_changed();
    const LocalValue &weight = m_control.spec().initial_weight;
    if (m_cell_area == 0) {
        m_cell_area = m_area / double(std::max<size_t>(1, m_cells.size()));
        if (weight.local()) {
            m_weight_mean = 0;
            for (TriId t = 0; t < m_crps.num_triangles(); ++t)
                m_weight_mean +=
                    m_crps.frame(t).area * m_control.triangle_mean(weight, t) / m_area;
        }
    }
    m_stats.growth.push_back({time, m_area, m_cells.size()});
    std::vector<double> now(m_crps.num_triangles());
    for (TriId t = 0; t < now.size(); ++t) now[t] = m_crps.frame(t).area;
    std::vector<double> next = m_growth->triangle_areas(time + interval);
    if (weight.local() && m_weight_mean > 0) {
        // Queiroz §V: a local initial weight w makes a region w / W̄ times as dense as
        // the mean (W̄ the area-weighted mean weight, initialize()). The growth keeps
        // each region's density: a cell there has the area a·W̄/w, so a triangle gains
        // ΔA·w/(a·W̄) cells, the same total as a uniform weight under uniform growth.
        for (TriId t = 0; t < now.size(); ++t) {
            const double f = m_control.triangle_mean(weight, t) / m_weight_mean;
            now[t] *= f;
            next[t] *= f;
        }
    }
    // A local division time changes the relative rates where it holds (the growth still
    // sets how many cells a triangle gains).
    const std::vector<LocalValue> &local = m_control.spec().division_time;
    std::vector<double> rates;
    if (std::any_of(local.begin(), local.end(),
                    [](const LocalValue &v) { return v.local(); })) {
        rates.resize(m_cells.size());
        for (CellId c = 0; c < m_cells.size(); ++c) {
            const int type = m_cells.type(c);
            rates[c] =
                !m_types[type].divides() ? 0.0
                : size_t(type) < local.size() && local[type].local()
                    ? 1 / m_control.value(local[type], m_cells.tri(c), m_cells.pos(c))
                    : 1 / m_types[type].division_time;
        }
    }
    double lost = 0;
    const std::vector<double> expected =
        growth_divisions(m_crps, m_cells, m_types, now, next, m_cell_area, &lost,
                         rates.empty() ? nullptr : &rates);
    m_stats.growth_lost_cells += lost;
    // Every cell's next division from its rate over this interval: r = Δt / (k g_i).
    m_growth_mean.assign(m_cells.size(), std::numeric_limits<double>::infinity());
    m_heap.clear();
    m_due.assign(m_cells.size(), HUGE_VAL);
    for (CellId c = 0; c < m_cells.size(); ++c) {
        if (!(expected[c] > 0)) continue;
        m_growth_mean[c] = interval / expected[c];
        CounterRng rng(m_seed, RandomStream::growth_division, (update << 32) | c);
        m_due[c] = time + std::max(rng.exponential(m_growth_mean[c]), 1e-9);
        m_heap.push_back({m_due[c], c});
    }
    std::make_heap(m_heap.begin(), m_heap.end(), std::greater<>());
}

void CmSimulation::run(const std::function<void(double)> &progress) {
    const double t0 = now_seconds();
    const double dt = 1.0 / m_params.rho;
    const double end_time = m_growth && m_params.end_time == 0
                                ? m_growth->shape().last_age()
                                : m_params.end_time;
    const uint64_t n_steps =
        static_cast<uint64_t>(std::ceil(end_time * m_params.rho - 1e-9));
    const uint64_t growth_steps =
        m_growth
            ? std::max<uint64_t>(
                  1, uint64_t(std::llround(m_growth->shape().interval() * m_params.rho)))
            : 0;
    const uint64_t target = m_params.target_cells;
    const bool open_ended = n_steps == 0 && target > 0;
    constexpr uint64_t max_open_steps = 10'000'000;     // same cap as the preset checker
    RunProgress work(n_steps, target, m_cells.size());  // by cells relaxed, not by steps
    for (uint64_t step = 0; open_ended ? step < max_open_steps : step < n_steps; ++step) {
        const double t_next = double(step + 1) * dt;
        m_now = t_next;
        bool reached = false;
        if (m_growth && step % growth_steps == 0)
            grow(step / growth_steps, double(step) * dt);
        // --- Divisions due in this step, in heap order ---
        while (!m_heap.empty() && m_heap.front().time <= t_next) {
            if (target > 0 && m_cells.size() >= target) {
                reached = true;
                break;
            }
            divide(m_heap.front());
        }
        if (target > 0 && m_cells.size() >= target) reached = true;
        // --- One relaxation event ---
        const std::vector<TriId> active = m_params.relax == RelaxMode::global
                                              ? all_triangles_with_cells()
                                              : take_local_active();
        if (!active.empty()) relax(active, false);
        ++m_stats.relax_steps;
        m_stats.final_time = t_next;
        if (progress) progress(work.after_step(step, m_cells.size()));
        if (reached) break;
        if (open_ended && m_heap.empty()) break;
    }
    if (m_growth) {
        m_growth->reshape(m_stats.final_time, m_cells);
        surface_changed();
        m_stats.growth.push_back({m_stats.final_time, m_area, m_cells.size()});
    }
    m_stats.final_radius = radius();
    m_stats.seconds_neighbourhoods = m_relaxer.neighbourhoods().seconds();
    m_stats.neighbourhood_builds = m_relaxer.neighbourhoods().rebuilds();
    m_stats.seconds_force_sum = m_relaxer.force_seconds();
    m_stats.interacting_pairs = m_relaxer.interacting_pairs();
    m_stats.seconds_total = m_stats.seconds_initial + (now_seconds() - t0);
}

}  // namespace pelage::sim
