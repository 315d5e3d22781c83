#include "renderer/fur/comb_field.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "sim/cells_io/cells_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

std::vector<float> comb_by_corner(const sim::FieldSpec &spec, const sim::Surface &surface,
                                  Vec3f towards, int smoothing) {
    const sim::TriangleMesh &mesh = surface.mesh;
    const size_t nt = mesh.triangles.size();
    const sim::TangentField field = sim::resolve_field(spec, surface.crps, 1.0);
    std::vector<sim::Vec3d> dir(nt, sim::Vec3d{0, 0, 0});
    for (size_t t = 0; t < nt && t < field.a.size(); ++t) {
        // The triangle's local 2D frame is (x, z) of R_t p (sim/crps/crps.h), so a local
        // vector (a.x, a.y) is R_tᵀ (a.x, 0, a.y) in the mesh's space.
        const sim::Vec2d a = field.a[t];
        dir[t] = surface.crps.frame(sim::TriId(t))
                     .rotation.transpose_times(sim::Vec3d{a.x, 0, a.y});
    }

    // --- Sense: `towards` where the field clearly has one, continuity elsewhere ---
    // Triangles whose direction is within 60° of ±towards take its sense; the rest are
    // reached breadth-first across shared edges and take their neighbour's, so a field
    // across `towards` (the spine, a leg's girth) does not part at every triangle.
    const sim::Vec3d up{towards.x, towards.y, towards.z};
    const double up_len = std::max(length(up), 1e-300);
    std::vector<int8_t> decided(nt, 0);
    std::vector<uint32_t> queue;
    for (size_t t = 0; t < nt; ++t) {
        const double l = length(dir[t]);
        if (!(l > 0)) continue;
        const double c = dot(dir[t], up) / (l * up_len);
        if (std::abs(c) < 0.5) continue;
        if (c < 0) dir[t] = dir[t] * -1.0;
        decided[t] = 1;
        queue.push_back(uint32_t(t));
    }
    std::unordered_map<uint64_t, std::vector<uint32_t>> by_edge;
    auto edge_key = [](uint32_t a, uint32_t b) {
        return a < b ? uint64_t(a) << 32 | b : uint64_t(b) << 32 | a;
    };
    for (uint32_t t = 0; t < nt; ++t)
        for (int c = 0; c < 3; ++c)
            by_edge[edge_key(mesh.triangles[t][c], mesh.triangles[t][(c + 1) % 3])]
                .push_back(t);
    auto visit = [&](size_t head) {
        for (; head < queue.size(); ++head) {
            const uint32_t t = queue[head];
            for (int c = 0; c < 3; ++c)
                for (uint32_t u : by_edge[edge_key(mesh.triangles[t][c],
                                                   mesh.triangles[t][(c + 1) % 3])]) {
                    if (decided[u] || !(length(dir[u]) > 0)) continue;
                    if (dot(dir[u], dir[t]) < 0) dir[u] = dir[u] * -1.0;
                    decided[u] = 1;
                    queue.push_back(u);
                }
        }
    };
    visit(0);
    // Parts where the field never points along `towards`: the sense nearest to it.
    for (size_t t = 0; t < nt; ++t) {
        if (decided[t] || !(length(dir[t]) > 0)) continue;
        if (dot(dir[t], up) < 0) dir[t] = dir[t] * -1.0;
        decided[t] = 1;
        const size_t head = queue.size();
        queue.push_back(uint32_t(t));
        visit(head);
    }

    // --- Corners: the area-weighted mean of the triangles around each vertex ---
    // (the triangles' direction is constant over each; blending corners makes the comb
    // continuous across edges, as a groomed coat is)
    std::vector<sim::Vec3d> at_vertex(mesh.positions.size(), sim::Vec3d{0, 0, 0});
    for (size_t t = 0; t < nt; ++t) {
        const double l = length(dir[t]);
        if (!(l > 0)) continue;
        const double area = mesh.triangle_area(sim::TriId(t));
        for (int c = 0; c < 3; ++c)
            at_vertex[mesh.triangles[t][c]] =
                at_vertex[mesh.triangles[t][c]] + dir[t] * (area / l);
    }
    // --- Smoothing: each vertex's direction averaged with its neighbours' ---
    // A field resolved where its controls point almost along the normal (a vertical
    // direction on the back) is rough from triangle to triangle; a coat is not. Each
    // pass replaces a direction by the mean of its own and its neighbours' (turned to
    // agree with it first, so a parting stays a parting), then keeps it tangent.
    if (smoothing > 0) {
        std::vector<sim::Vec3d> normal(mesh.positions.size(), sim::Vec3d{0, 0, 0});
        std::vector<std::vector<uint32_t>> around(mesh.positions.size());
        for (size_t t = 0; t < nt; ++t) {
            const sim::Vec3d n = mesh.face_normal_unnormalized(sim::TriId(t));
            for (int c = 0; c < 3; ++c) {
                const uint32_t v = mesh.triangles[t][c];
                normal[v] = normal[v] + n;
                for (int d = 1; d < 3; ++d)
                    around[v].push_back(mesh.triangles[t][(c + d) % 3]);
            }
        }
        for (auto &a : around) {
            std::sort(a.begin(), a.end());
            a.erase(std::unique(a.begin(), a.end()), a.end());
        }
        std::vector<sim::Vec3d> next(at_vertex.size());
        for (int pass = 0; pass < smoothing; ++pass) {
            for (size_t v = 0; v < at_vertex.size(); ++v) {
                sim::Vec3d sum = at_vertex[v];
                const double l = length(sum);
                if (l > 0) sum = sum * (1 / l);
                for (uint32_t u : around[v]) {
                    const sim::Vec3d w = at_vertex[u];
                    const double lw = length(w);
                    if (!(lw > 0)) continue;
                    sum = sum + w * ((dot(w, sum) < 0 ? -1.0 : 1.0) / lw);
                }
                const double ln = length(normal[v]);
                if (ln > 0) sum = sum - normal[v] * (dot(sum, normal[v]) / (ln * ln));
                next[v] = sum;
            }
            at_vertex.swap(next);
        }
    }

    std::vector<float> out(9 * nt, 0.0f);
    for (size_t t = 0; t < nt; ++t)
        for (int c = 0; c < 3; ++c) {
            const sim::Vec3d v = at_vertex[mesh.triangles[t][c]];
            const double l = length(v);
            if (!(l > 0)) continue;
            for (int k = 0; k < 3; ++k)
                out[9 * t + 3 * size_t(c) + size_t(k)] = float(v[k] / l);
        }
    return out;
}

void carry_to_pose(std::vector<float> &by_corner, const std::vector<uint32_t> &triangles,
                   const double *rest, const float *posed) {
    const size_t nt = triangles.size() / 3;
    for (size_t t = 0; t < nt && 9 * t + 8 < by_corner.size(); ++t) {
        const uint32_t *v = &triangles[3 * t];
        auto r = [&](int c) {
            const double *p = rest + 3 * size_t(v[c]);
            return sim::Vec3d{p[0], p[1], p[2]};
        };
        auto q = [&](int c) {
            const float *p = posed + 3 * size_t(v[c]);
            return sim::Vec3d{p[0], p[1], p[2]};
        };
        const sim::Vec3d e1 = r(1) - r(0), e2 = r(2) - r(0);
        const sim::Vec3d f1 = q(1) - q(0), f2 = q(2) - q(0);
        // d = a e1 + b e2 in the least-squares sense: the part of d in the plane.
        const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
        const double det = g11 * g22 - g12 * g12;
        for (int c = 0; c < 3; ++c) {
            float *d = &by_corner[9 * t + 3 * size_t(c)];
            const sim::Vec3d x{d[0], d[1], d[2]};
            sim::Vec3d y{0, 0, 0};
            if (det > 1e-12 * g11 * g22 && length(x) > 0) {
                const double u = dot(e1, x), w = dot(e2, x);
                y = f1 * ((g22 * u - g12 * w) / det) + f2 * ((g11 * w - g12 * u) / det);
            }
            const double l = length(y);
            for (int k = 0; k < 3; ++k) d[k] = l > 0 ? float(y[k] / l) : 0.0f;
        }
    }
}

sim::FieldSpec pattern_field(const std::string &cells_path, const std::string &field) {
    const nlohmann::json params =
        nlohmann::json::parse(sim::read_cells_params(cells_path), nullptr, false);
    // The simulation records the preset's field, null when it has none (sim/run/
    // cells_data.h); a file without the key was written by an older pelage.
    if (!params.is_object() || !params.contains("anisotropy_field"))
        throw InputError(cells_path, 0, field,
                         "\"field\" combs along the pattern's anisotropy field, but this "
                         ".cells file does not record it (written by an older pelage: "
                         "grow the pattern again with `pelage sim`)");
    const nlohmann::json &node = params["anisotropy_field"];
    const sim::FieldSpec spec =
        node.is_null() ? sim::FieldSpec()
                       : sim::parse_field_spec(node, "anisotropy_field", cells_path);
    if (spec.kind == sim::FieldSpec::Kind::none) {
        std::string preset;
        if (params.contains("preset") && params["preset"].is_object() &&
            params["preset"].contains("name") && params["preset"]["name"].is_string())
            preset = params["preset"]["name"].get<std::string>();
        throw InputError(cells_path, 0, field,
                         "\"field\" combs along the pattern's anisotropy field, but "
                         "preset \"" +
                             preset +
                             "\" has none (give the field itself, e.g. {\"along\": "
                             "\"body_axis\"})");
    }
    return spec;
}

}  // namespace pelage::renderer
