#include "renderer/export/coat.h"

#include <tbb/parallel_for.h>

#include <cstring>

#include "sim/core/input_error.h"

namespace pelage::renderer {
namespace {

// The slot of the "cell" matte in a plugin's matte ids (the stable cell id), or −1.
int cell_matte_slot(const PelageShaderPlugin &plugin) {
    for (int k = 0;
         plugin.matte_names && k < PELAGE_SHADER_MATTE_SLOTS && plugin.matte_names[k];
         ++k)
        if (std::strcmp(plugin.matte_names[k], "cell") == 0) return k;
    return -1;
}

// World-space point and unit normal at (triangle, b1, b2) of an object's mesh: the
// interpolated corner normals where the mesh has them, else the face's.
struct WorldMesh {
    const MeshData &mesh;
    const ObjectGeometry &geometry;
    Vec3f vertex(uint32_t v) const {
        const float *P = &mesh.positions[3 * size_t(v)];
        const Vec3f p{P[0], P[1], P[2]};
        return geometry.baked ? p : geometry.to_world.point(p);
    }
    void point_normal(const SurfacePoint &s, Vec3f *p, Vec3f *n) const {
        const uint32_t *tri = &mesh.triangles[3 * size_t(s.triangle)];
        const float b0 = 1 - s.b1 - s.b2;
        const Vec3f a = vertex(tri[0]), b = vertex(tri[1]), c = vertex(tri[2]);
        *p = a * b0 + b * s.b1 + c * s.b2;
        Vec3f nn = cross(b - a, c - a);
        if (!mesh.corner_normals.empty()) {
            const float *N = &mesh.corner_normals[9 * size_t(s.triangle)];
            nn = Vec3f{N[0], N[1], N[2]} * b0 + Vec3f{N[3], N[4], N[5]} * s.b1 +
                 Vec3f{N[6], N[7], N[8]} * s.b2;
            if (!geometry.baked) nn = geometry.normal_to_world.vector(nn);
        }
        const float l = length(nn);
        *n = l > 0 ? nn / l : Vec3f{0, 0, 1};
    }
};

CoatSkin gather_skin(const Scene &scene, size_t i) {
    const ObjectDesc &od = scene.desc().objects[i];
    const ObjectGeometry &og = scene.geometry().objects()[i];
    const MeshData &m = *og.mesh;
    CoatSkin skin;
    skin.object = i;
    skin.name = od.name.empty() ? "object" + std::to_string(i) : od.name;
    skin.to_world = og.baked ? od.transform : og.to_world;
    skin.points.assign(m.object_positions.begin(),
                       m.object_positions.begin() + 3 * size_t(m.num_vertices));
    skin.indices = m.triangles;
    skin.uvs = m.corner_uvs;
    if (!m.corner_normals.empty()) {
        skin.normals = m.corner_normals;
        if (og.baked) {
            // World normals back to object space: n_obj ∝ Lᵀ n_world, L the linear part
            // (world normals are L⁻ᵀ n_obj).
            const Affine &L = skin.to_world;
            for (size_t k = 0; k + 2 < skin.normals.size(); k += 3) {
                const float *w = &skin.normals[k];
                Vec3f o{L.m[0][0] * w[0] + L.m[1][0] * w[1] + L.m[2][0] * w[2],
                        L.m[0][1] * w[0] + L.m[1][1] * w[1] + L.m[2][1] * w[2],
                        L.m[0][2] * w[0] + L.m[1][2] * w[1] + L.m[2][2] * w[2]};
                const float l = length(o);
                if (l > 0) o = o / l;
                skin.normals[k] = o.x, skin.normals[k + 1] = o.y,
                skin.normals[k + 2] = o.z;
            }
        }
    }
    const size_t nt = m.num_triangles;
    skin.face_colour.resize(3 * nt);
    skin.face_cell_type.resize(nt);
    skin.face_cell_id.resize(nt);
    const int cell_slot = cell_matte_slot(*scene.materials()[i].plugin);
    const WorldMesh world{m, og};
    tbb::parallel_for(size_t(0), nt, [&](size_t t) {
        const SurfacePoint s{uint32_t(t), 1.0f / 3, 1.0f / 3};
        Vec3f p, n;
        world.point_normal(s, &p, &n);
        const PelageShade sh = scene.shade_surface(i, s, p, n);
        for (int k = 0; k < 3; ++k) skin.face_colour[3 * t + size_t(k)] = sh.albedo[k];
        skin.face_cell_type[t] = std::max(sh.cell_type, -1);
        skin.face_cell_id[t] = cell_slot >= 0 && (sh.matte_written >> cell_slot & 1)
                                   ? int32_t(sh.matte[cell_slot])
                                   : -1;
    });
    return skin;
}

CoatGroom gather_groom(const Scene &scene, const FurLayer &layer, size_t skin_index,
                       const CoatSkin &skin) {
    const size_t i = layer.object;
    const ObjectGeometry &og = scene.geometry().objects()[i];
    const Strands &st = layer.strands;
    CoatGroom g;
    g.name = skin.name + "_fur";
    g.skin = skin_index;
    g.cubic = layer.round;
    g.points_per_strand = st.points_per_strand;
    g.roots = st.roots;
    const size_t n = st.size(), ppp = st.points_per_strand;
    const Affine to_object = inverse(skin.to_world);
    g.points.resize(3 * n * ppp);
    g.widths.resize(n * ppp);
    g.colour.resize(3 * n);
    g.cell_type.resize(n);
    g.cell_id.resize(n);
    const int cell_slot = cell_matte_slot(*scene.materials()[i].plugin);
    const WorldMesh world{*og.mesh, og};
    tbb::parallel_for(size_t(0), n, [&](size_t s) {
        for (size_t k = 0; k < ppp; ++k) {
            const float *P = &st.points[4 * (s * ppp + k)];
            const Vec3f o = to_object.point({P[0], P[1], P[2]});
            float *out = &g.points[3 * (s * ppp + k)];
            out[0] = o.x, out[1] = o.y, out[2] = o.z;
            g.widths[s * ppp + k] = 2 * P[3] * og.to_object_length;
        }
        Vec3f p, nn;
        world.point_normal(st.roots[s], &p, &nn);
        const PelageShade sh = scene.shade_surface(i, st.roots[s], p, nn);
        for (int k = 0; k < 3; ++k) g.colour[3 * s + size_t(k)] = sh.albedo[k];
        g.cell_type[s] = std::max(sh.cell_type, -1);
        g.cell_id[s] = cell_slot >= 0 && (sh.matte_written >> cell_slot & 1)
                           ? int32_t(sh.matte[cell_slot])
                           : -1;
    });
    return g;
}

}  // namespace

size_t CoatFrame::num_strands() const {
    size_t n = 0;
    for (const CoatGroom &g : grooms) n += g.size();
    return n;
}

size_t CoatFrame::num_points() const {
    size_t n = 0;
    for (const CoatGroom &g : grooms) n += g.points.size() / 3;
    return n;
}

Affine inverse(const Affine &a) {
    // L⁻¹ is the transpose of the normal matrix L⁻ᵀ; the translation is −L⁻¹ t.
    const Affine nt = a.normal_matrix();
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.m[i][j] = nt.m[j][i];
    const Vec3f t = r.vector({a.m[0][3], a.m[1][3], a.m[2][3]});
    r.m[0][3] = -t.x, r.m[1][3] = -t.y, r.m[2][3] = -t.z;
    return r;
}

std::vector<float> root_uvs(const CoatSkin &skin, const CoatGroom &groom) {
    std::vector<float> uv;
    if (skin.uvs.empty()) return uv;
    uv.resize(2 * groom.size());
    for (size_t s = 0; s < groom.size(); ++s) {
        const SurfacePoint &r = groom.roots[s];
        const float *U = &skin.uvs[6 * size_t(r.triangle)];
        const float b0 = 1 - r.b1 - r.b2;
        uv[2 * s] = b0 * U[0] + r.b1 * U[2] + r.b2 * U[4];
        uv[2 * s + 1] = b0 * U[1] + r.b1 * U[3] + r.b2 * U[5];
    }
    return uv;
}

CoatFrame gather_coat(const Scene &scene, const CoatOptions &options) {
    const SceneDesc &desc = scene.desc();
    std::vector<size_t> chosen;
    for (size_t k = 0; k < options.objects.size(); ++k) {
        size_t found = desc.objects.size();
        for (size_t i = 0; i < desc.objects.size(); ++i)
            if (desc.objects[i].name == options.objects[k]) found = i;
        if (found == desc.objects.size()) {
            std::string names;
            for (const ObjectDesc &o : desc.objects)
                names += (names.empty() ? "" : ", ") + ("\"" + o.name + "\"");
            throw InputError(desc.path, 0, "--object",
                             "no object is named \"" + options.objects[k] +
                                 "\"; the scene's objects: " + names);
        }
        chosen.push_back(found);
    }
    const bool all = chosen.empty();
    if (all)
        for (size_t i = 0; i < desc.objects.size(); ++i) chosen.push_back(i);

    CoatFrame frame;
    for (size_t i : chosen) {
        CoatSkin skin = gather_skin(scene, i);
        bool patterned = !desc.objects[i].cells.empty();
        for (int32_t t : skin.face_cell_type) patterned = patterned || t >= 0;
        if (!patterned) {
            if (all) continue;  // the ground, a prop: not part of the coat
            throw InputError(desc.path, 0, "--object",
                             "object \"" + desc.objects[i].name +
                                 "\" has no pattern: its material (shader \"" +
                                 desc.objects[i].material.shader +
                                 "\") gives no cell type anywhere");
        }
        frame.skins.push_back(std::move(skin));
    }
    if (frame.skins.empty())
        throw InputError(desc.path, 0, "objects",
                         "no object has a pattern to export (a material that gives cell "
                         "types, such as clonal_mosaic with a .cells file)");
    if (options.fur && scene.fur())
        for (const FurLayer &layer : scene.fur()->layers())
            for (size_t k = 0; k < frame.skins.size(); ++k)
                if (frame.skins[k].object == layer.object)
                    frame.grooms.push_back(gather_groom(scene, layer, k, frame.skins[k]));
    return frame;
}

}  // namespace pelage::renderer
