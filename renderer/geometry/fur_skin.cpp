#include "renderer/geometry/fur_skin.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "renderer/fur/comb_field.h"
#include "renderer/fur/groom_regions.h"
#include "shader/sdk/rest_mesh.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace {

// The mesh at motion step `step` (MeshData::later_positions), in world space: positions
// and shading normals.
void world_mesh(const ObjectGeometry &og, unsigned step, std::vector<float> *positions,
                std::vector<float> *normals) {
    const MeshData &m = *og.mesh;
    const std::vector<float> &P = step == 0 ? m.positions : m.later_positions[step - 1];
    positions->assign(P.begin(), P.begin() + 3 * size_t(m.num_vertices));
    *normals = step == 0 || m.later_normals.empty() ? m.corner_normals
                                                    : m.later_normals[step - 1];
    if (og.baked) return;
    std::vector<float> &w = *positions;
    for (uint32_t v = 0; v < m.num_vertices; ++v) {
        const Vec3f p = og.to_world.point({w[3 * v], w[3 * v + 1], w[3 * v + 2]});
        w[3 * v] = p.x;
        w[3 * v + 1] = p.y;
        w[3 * v + 2] = p.z;
    }
    std::vector<float> &N = *normals;
    for (size_t i = 0; i + 2 < N.size(); i += 3) {
        const Vec3f n = normalize(og.normal_to_world.vector({N[i], N[i + 1], N[i + 2]}));
        N[i] = n.x;
        N[i + 1] = n.y;
        N[i + 2] = n.z;
    }
}

// The object's size, which the fur's unset defaults scale with
// (FurParams::scale_defaults_to): the largest distance of a vertex from the vertices'
// mean, which does not change as a turntable turns the object.
double object_radius(const std::vector<float> &positions) {
    const size_t n = positions.size() / 3;
    if (n == 0) return 1.0;
    double mean[3] = {0, 0, 0};
    for (size_t i = 0; i < 3 * n; ++i) mean[i % 3] += positions[i];
    for (double &m : mean) m /= double(n);
    double r2 = 0;
    for (size_t v = 0; v < n; ++v) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = positions[3 * v + k] - mean[k];
            d2 += d * d;
        }
        r2 = std::max(r2, d2);
    }
    return r2 > 0 ? std::sqrt(r2) : 1.0;
}

// The object's mesh as loaded (rest positions, its own space, and its UVs), as a shader
// plugin sees it: shader::sdk::rest_mesh copies it.
PelageMeshView rest_view(const MeshData &m) {
    PelageMeshView view{};
    view.num_vertices = m.num_vertices;
    view.num_triangles = m.num_triangles;
    view.rest_positions = m.rest->positions.data();
    view.triangles = m.triangles.data();
    view.corner_uvs = m.corner_uvs.empty() ? nullptr : m.corner_uvs.data();
    return view;
}

// The rest shape placed by the object's transform.
std::vector<float> rest_in_place(const MeshData &m, const Affine &transform) {
    std::vector<float> out(3 * size_t(m.num_vertices));
    for (uint32_t v = 0; v < m.num_vertices; ++v) {
        // A clip's skin rests in its default pose; a deformed mesh as loaded.
        const Vec3f p =
            transform.point(m.default_pose.empty()
                                ? Vec3f{float(m.rest->positions[3 * v]),
                                        float(m.rest->positions[3 * v + 1]),
                                        float(m.rest->positions[3 * v + 2])}
                                : Vec3f{m.default_pose[3 * v], m.default_pose[3 * v + 1],
                                        m.default_pose[3 * v + 2]});
        out[3 * v] = p.x;
        out[3 * v + 1] = p.y;
        out[3 * v + 2] = p.z;
    }
    return out;
}

// A comb along a field: a direction per triangle corner, resolved on the rest surface,
// carried to the object's pose and turned with the object like comb_direction.
std::vector<float> comb_corners(const SceneDesc &desc, size_t i, const FurParams &params,
                                const MeshData &m, const sim::Surface &rest) {
    const ObjectDesc &od = desc.objects[i];
    const std::string field = "objects[" + std::to_string(i) + "].fur";
    if (params.comb_pattern_field && od.cells.empty())
        throw InputError(desc.path, 0, field + ".comb",
                         "\"field\" combs along the pattern's anisotropy field, "
                         "but the object has no \"cells\" (give a field such as "
                         "{\"along\": \"body_axis\"} instead)");
    const sim::FieldSpec spec = params.comb_pattern_field
                                    ? pattern_field(od.cells, field + ".comb")
                                    : params.comb_field;
    std::vector<float> comb =
        comb_by_corner(spec, rest, od.fur->comb_towards, params.comb_smoothing);
    // A deformed pose (deform, growth): the comb goes with the skin.
    bool posed = false;
    for (size_t k = 0; k < 3 * size_t(m.num_vertices) && !posed; ++k)
        posed = m.object_positions[k] != float(m.rest->positions[k]);
    if (posed)
        carry_to_pose(comb, m.triangles, m.rest->positions.data(),
                      m.object_positions.data());
    for (size_t t = 0; t < comb.size(); t += 3) {
        const Vec3f w = od.transform.vector({comb[t], comb[t + 1], comb[t + 2]});
        comb[t] = w.x, comb[t + 1] = w.y, comb[t + 2] = w.z;
    }
    return comb;
}

}  // namespace

FurSkin::FurSkin(const SceneDesc &desc, size_t i, const ObjectGeometry &og)
    : m_params(*desc.objects[i].fur) {
    const ObjectDesc &od = desc.objects[i];
    const MeshData &m = *og.mesh;
    // The comb is in object space, so the coat turns with its object (turntables);
    // gravity stays world −y.
    if (const Vec3f w = od.transform.vector(m_params.comb_direction); length(w) > 0)
        m_params.comb_direction = w;
    world_mesh(og, 0, &m_positions, &m_normals);
    // A posed skin (a clip, a deformation) carries the coat grown on its rest shape:
    // the same roots, counted and sized by the rest mesh in this frame's placement,
    // whatever the pose.
    const bool posed_skin = od.clip || !od.deform.empty();
    if (posed_skin) m_rest_positions = rest_in_place(m, od.transform);
    m_params.scale_defaults_to(
        object_radius(posed_skin ? m_rest_positions : m_positions));
    m_mesh.positions = m_positions.data();
    if (posed_skin) m_mesh.rest_positions = m_rest_positions.data();
    m_mesh.triangles = m.triangles.data();
    m_mesh.corner_normals = m_normals.empty() ? nullptr : m_normals.data();
    m_mesh.num_vertices = m.num_vertices;
    m_mesh.num_triangles = m.num_triangles;

    // The rest surface (the rendered triangles before any transform), for what is
    // resolved on the skin as a preset's would be: a comb field, the groom's regions.
    std::optional<sim::Surface> rest;
    auto rest_surface = [&]() -> const sim::Surface & {
        if (!rest) rest = sim::build_surface(shader::sdk::rest_mesh(rest_view(m), true));
        return *rest;
    };
    if (m_params.comb == FurParams::Comb::field) {
        m_comb = comb_corners(desc, i, m_params, m, rest_surface());
        m_mesh.comb_by_corner = m_comb.data();
    }
    // The groom's regions: weights at every triangle corner.
    if (!m_params.regions.empty()) {
        m_regions = region_corners(m_params.regions, rest_surface(), desc.path,
                                   "objects[" + std::to_string(i) + "].fur");
        m_mesh.region_corners = m_regions.data();
        m_mesh.num_regions = uint32_t(m_params.regions.region_names.size());
    }
}

FurSkin::FurSkin(const FurSkin &opening, const ObjectGeometry &og, unsigned step)
    : m_params(opening.m_params),
      m_rest_positions(opening.m_rest_positions),
      m_regions(opening.m_regions),
      m_mesh(opening.m_mesh) {
    world_mesh(og, step, &m_positions, &m_normals);
    m_mesh.positions = m_positions.data();
    m_mesh.corner_normals = m_normals.empty() ? nullptr : m_normals.data();
    if (!m_rest_positions.empty()) m_mesh.rest_positions = m_rest_positions.data();
    if (!m_regions.empty()) m_mesh.region_corners = m_regions.data();
    if (!opening.m_comb.empty()) {
        // From the opening's world pose to this step's (the comb is in world space).
        m_comb = opening.m_comb;
        const std::vector<double> from(opening.m_positions.begin(),
                                       opening.m_positions.end());
        carry_to_pose(m_comb, og.mesh->triangles, from.data(), m_positions.data());
        m_mesh.comb_by_corner = m_comb.data();
    }
}

}  // namespace pelage::renderer
