// `pelage bench fur-comb`: does the hair follow the body? A preset's anisotropy field
// (the one its pattern follows) combs fur grown on the mesh through the fur's own
// parser and grower, and two angles are measured at every root, in its tangent plane:
// between the strand's first segment and the field there (how closely the groom follows
// the field, after comb angle, jitter and clumping), and between the strand and its
// nearest neighbours' (how smooth the coat is). The field's own angle between
// neighbouring roots is reported beside them, so a rough coat can be told from a rough
// field.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "apps/bench/bench.h"
#include "renderer/fur/comb_field.h"
#include "renderer/fur/fur_grow.h"
#include "renderer/fur/strand_shape.h"
#include "renderer/scene_file/scene_fur.h"
#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/mosaic/preset.h"

namespace pelage::renderer::cli {
namespace {

struct BenchFurCombOptions {
    std::string mesh = "scenes/meshes/cow.off", preset = "zebra", fur_keys = "{}";
    int neighbours = 4;
    ThreadOption threads;
    BenchOutput out;
};

constexpr double deg = 180 / 3.14159265358979323846;

// b, given in the tangent plane ⊥ nb, carried to the plane ⊥ na by the smallest rotation
// taking nb to na (the discrete parallel transport between neighbouring roots).
Vec3f transport(Vec3f b, Vec3f nb, Vec3f na) {
    const Vec3f axis = cross(nb, na);
    const float s = length(axis), c = dot(nb, na);
    if (!(s > 1e-7f)) return b;
    const Vec3f k = axis / s;
    // Rodrigues: b cos θ + (k × b) sin θ + k (k·b)(1 − cos θ)
    return b * c + cross(k, b) * s + k * (dot(k, b) * (1 - c));
}

// The angle in degrees between a projected onto the plane ⊥ na and b projected onto the
// plane ⊥ nb and carried to na's (so neighbouring roots on a curved skin compare as a
// groomer sees them); -1 when either projection vanishes.
double tangent_angle(Vec3f a, Vec3f na, Vec3f b, Vec3f nb) {
    const Vec3f pa = a - na * dot(a, na), pb = transport(b - nb * dot(b, nb), nb, na);
    const float la = length(pa), lb = length(pb);
    if (!(la > 1e-12f && lb > 1e-12f)) return -1;
    return std::acos(std::clamp(double(dot(pa, pb)) / (double(la) * lb), -1.0, 1.0)) *
           deg;
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    return v[k];
}

int run(const BenchFurCombOptions &o) {
    const auto threads = o.threads.apply();
    const sim::Preset preset = sim::load_preset(o.preset, data_path("scenes/presets"));
    const sim::FieldSpec &spec = preset.params.anisotropy_field;
    if (spec.kind == sim::FieldSpec::Kind::none)
        throw InputError(o.preset, 0, "simulation.anisotropy",
                         "the preset has no anisotropy field to comb along");
    const sim::Surface surface = sim::build_surface(o.mesh);

    // The fur block: the fur's defaults amended by --fur-keys, combed along the preset's
    // field.
    nlohmann::ordered_json fur =
        nlohmann::ordered_json::parse(o.fur_keys, nullptr, false);
    if (!fur.is_object())
        throw InputError("--fur-keys", 0, "", "expected a JSON object of fur keys");
    FurParams params = read_fur(fur, "--fur-keys", "--fur-keys");
    params.comb = FurParams::Comb::field;
    params.comb_field = spec;

    const sim::TriangleMesh &m = surface.mesh;
    std::vector<float> positions, normals;
    std::vector<uint32_t> triangles;
    for (const sim::Vec3d &p : m.positions)
        positions.insert(positions.end(), {float(p.x), float(p.y), float(p.z)});
    for (const auto &t : m.triangles)
        triangles.insert(triangles.end(), t.begin(), t.end());
    // Smooth normals (area-weighted at the vertices), as a smooth-shaded object's fur
    // grows from.
    std::vector<sim::Vec3d> vn(m.positions.size(), sim::Vec3d{0, 0, 0});
    for (size_t t = 0; t < m.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c)
            vn[m.triangles[t][c]] =
                vn[m.triangles[t][c]] + m.face_normal_unnormalized(sim::TriId(t));
    for (const auto &t : m.triangles)
        for (int c = 0; c < 3; ++c) {
            const sim::Vec3d v = vn[t[c]] * (1 / std::max(length(vn[t[c]]), 1e-300));
            normals.insert(normals.end(), {float(v.x), float(v.y), float(v.z)});
        }
    double radius = 0;
    {
        sim::Vec3d mean{0, 0, 0};
        for (const sim::Vec3d &p : m.positions) mean = mean + p;
        mean = mean * (1.0 / double(m.positions.size()));
        for (const sim::Vec3d &p : m.positions)
            radius = std::max(radius, length(p - mean));
    }
    params.scale_defaults_to(radius);
    const std::vector<float> comb =
        comb_by_corner(spec, surface, params.comb_towards, params.comb_smoothing);
    // The field as the preset gives it (oriented, not smoothed): what the strands are
    // measured against.
    const std::vector<float> raw = comb_by_corner(spec, surface, params.comb_towards, 0);
    SkinMesh skin;
    skin.positions = positions.data();
    skin.triangles = triangles.data();
    skin.corner_normals = normals.data();
    skin.num_vertices = uint32_t(m.positions.size());
    skin.num_triangles = uint32_t(m.triangles.size());
    skin.comb_by_corner = comb.data();
    const Strands s = grow_fur(
        params, skin, [](const SurfacePoint &, Vec3f, Vec3f) { return RootPigment{}; });

    // Each strand's root, normal and first-segment direction.
    const RootSampler sampler(skin);
    const size_t n = s.size();
    const bool round = params.curve == FurParams::Curve::round;
    std::vector<Vec3f> root(n), dir(n), normal(n), field(n), combed(n);
    for (size_t i = 0; i < n; ++i) {
        const float *P = &s.points[i * s.points_per_strand * 4 + (round ? 4 : 0)];
        root[i] = {P[0], P[1], P[2]};
        dir[i] = Vec3f{P[4], P[5], P[6]} - root[i];
        Vec3f p;
        sampler.point_normal(s.roots[i], &p, &normal[i]);
        SkinMesh unsmoothed = skin;
        unsmoothed.comb_by_corner = raw.data();
        field[i] = comb_at(params, unsmoothed, s.roots[i]);
        combed[i] = comb_at(params, skin, s.roots[i]);
    }
    std::vector<double> to_field, to_neighbour, field_to_neighbour;
    for (size_t i = 0; i < n; ++i)
        if (const double a = tangent_angle(dir[i], normal[i], field[i], normal[i]);
            a >= 0)
            to_field.push_back(a);

    // Nearest neighbours through a grid of cells about two strand spacings wide.
    const float cell = float(2 / std::sqrt(std::max(params.density, 1e-12)));
    auto key = [&](Vec3f p, int dx, int dy, int dz) {
        auto c = [&](float x, int d) {
            return uint64_t(int64_t(std::floor(x / cell)) + d) & 0x1fffff;
        };
        return c(p.x, dx) | c(p.y, dy) << 21 | c(p.z, dz) << 42;
    };
    std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
    for (size_t i = 0; i < n; ++i) grid[key(root[i], 0, 0, 0)].push_back(uint32_t(i));
    for (size_t i = 0; i < n; ++i) {
        std::vector<std::pair<float, uint32_t>> near;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find(key(root[i], dx, dy, dz));
                    if (it == grid.end()) continue;
                    for (uint32_t j : it->second) {
                        const Vec3f e = root[j] - root[i];
                        // Same side of the body: neighbours across a thin part (an ear)
                        // face the other way.
                        if (j != i && dot(normal[i], normal[j]) > 0.5f)
                            near.push_back({dot(e, e), j});
                    }
                }
        const size_t k = std::min(near.size(), size_t(o.neighbours));
        std::partial_sort(near.begin(), near.begin() + std::ptrdiff_t(k), near.end());
        for (size_t q = 0; q < k; ++q) {
            const uint32_t j = near[q].second;
            if (const double a = tangent_angle(dir[i], normal[i], dir[j], normal[j]);
                a >= 0)
                to_neighbour.push_back(a);
            if (const double a = tangent_angle(field[i], normal[i], field[j], normal[j]);
                a >= 0)
                field_to_neighbour.push_back(a);
        }
    }
    auto summary = [](const std::vector<double> &v) {
        const double over =
            double(std::count_if(v.begin(), v.end(), [](double a) { return a > 10; }));
        return nlohmann::json{{"samples", v.size()},
                              {"median_deg", quantile(v, 0.5)},
                              {"p90_deg", quantile(v, 0.9)},
                              {"p95_deg", quantile(v, 0.95)},
                              {"p99_deg", quantile(v, 0.99)},
                              {"over_10_deg", v.empty() ? 0.0 : over / double(v.size())}};
    };
    o.out.emit({{"mesh", o.mesh},
                {"preset", preset.name},
                {"fur_keys", nlohmann::json::parse(o.fur_keys)},
                {"strands", n},
                {"comb_jitter_deg", params.comb_jitter_deg},
                {"comb_smoothing", params.comb_smoothing},
                {"strand_to_field", summary(to_field)},
                {"strand_to_neighbours", summary(to_neighbour)},
                {"field_to_neighbours", summary(field_to_neighbour)}});
    return 0;
}

}  // namespace

Runner add_bench_fur_comb(CLI::App &bench) {
    auto o = std::make_shared<BenchFurCombOptions>();
    CLI::App *cmd = bench.add_subcommand(
        "fur-comb",
        "Fur combed along a preset's field: strand-to-field and neighbour angles (JSON)");
    cmd->add_option("--mesh", o->mesh, "The animal")->capture_default_str();
    cmd->add_option("--preset", o->preset, "The preset whose anisotropy field combs")
        ->capture_default_str();
    cmd->add_option("--fur-keys", o->fur_keys,
                    "A JSON object of fur keys, e.g. '{\"comb_jitter\": 0}'")
        ->capture_default_str();
    cmd->add_option("--neighbours", o->neighbours, "Nearest roots compared with each")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    o->threads.add_to(*cmd);
    o->out.add_to(*cmd);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
