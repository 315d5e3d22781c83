#include "renderer/geometry/embree_scene.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "renderer/animation/rig.h"
#include "renderer/core/setup_phase.h"
#include "renderer/geometry/deform.h"
#include "sim/core/input_error.h"
#include "sim/growth/growth_shape.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::renderer {

namespace {

// Area-weighted vertex normals over the welded surface (`welded`: the triangles' welded
// corners), one per triangle corner; a corner whose normals cancel takes its face's.
std::vector<sim::Vec3d> smooth_corner_normals(
    const sim::TriangleMesh &mesh, const std::vector<std::array<sim::VertId, 3>> &welded,
    size_t num_welded) {
    std::vector<sim::Vec3d> vn(num_welded);
    for (size_t t = 0; t < mesh.num_triangles(); ++t) {
        const sim::Vec3d n =
            mesh.face_normal_unnormalized(sim::TriId(t));  // |n| = 2 area
        for (int c = 0; c < 3; ++c) vn[welded[t][c]] += n;
    }
    std::vector<sim::Vec3d> out(3 * mesh.num_triangles());
    for (size_t t = 0; t < mesh.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) {
            const sim::Vec3d n = vn[welded[t][c]];
            const double len = sim::length(n);
            out[3 * t + c] =
                len > 0 ? n / len : mesh.face_normal_unnormalized(sim::TriId(t));
        }
    return out;
}

// xyz floats, plus one pad float (Embree reads vertices 16 bytes at a time).
std::vector<float> float_positions(const std::vector<sim::Vec3d> &v) {
    std::vector<float> out(3 * v.size() + 1, 0.0f);
    for (size_t i = 0; i < v.size(); ++i)
        for (int k = 0; k < 3; ++k) out[3 * i + size_t(k)] = float(v[i][k]);
    return out;
}

std::shared_ptr<MeshData> load_mesh_data(const ObjectDesc &o,
                                         const std::string &scene_path, size_t index,
                                         double *pose_seconds) {
    sim::TriangleMesh mesh;
    sim::MeshLoadReport report;
    try {
        mesh = sim::load_mesh(o.mesh, &report);
    } catch (const InputError &e) {
        // Keep the mesh file's own location, and say which object asked for it.
        throw InputError(
            e.file(), e.line(), e.field(),
            std::string(e.what()).substr(std::string(e.what()).find(": ") + 2) +
                " (objects[" + std::to_string(index) + "].mesh in " + scene_path + ")");
    }
    // A clip poses each corner as the vertex it was read as: welding is undone first,
    // so the rest positions below are per read vertex too. A skinned file without a
    // clip is shown in its default pose (glTF 2.0 §3.7.3), welded as loaded: the
    // pattern grown on that mesh lies on it unchanged. A deformation or growth shape
    // applies to the mesh as loaded.
    std::optional<Rig> rig;
    const bool default_pose = !o.clip && report.read.skinned_pieces > 0 &&
                              !(!o.deform_mesh.empty() && o.deform_weight > 0) && !o.grow;
    // Smooth normals average over the welded vertices (the surface's own), also when
    // the corners are posed apart.
    std::vector<std::array<sim::VertId, 3>> welded = mesh.triangles;
    size_t num_welded = mesh.num_vertices();
    const auto pose_start = std::chrono::steady_clock::now();
    if (o.clip || default_pose) {
        rig = Rig::read(o.mesh, o.clip ? Rig::Clips::required : Rig::Clips::optional);
        if (o.clip) unweld(report, &mesh);
        // Shading normals are made on the rest surface and go with the skin (recomputed
        // on a pose, averages across a crease that the pose folds point into the body).
        if (o.normals == ObjectDesc::Normals::flat)
            mesh.corner_normals.clear();
        else if (mesh.corner_normals.empty() && o.normals == ObjectDesc::Normals::smooth)
            mesh.corner_normals = smooth_corner_normals(mesh, welded, num_welded);
    }
    auto rest = std::make_shared<MeshData::Rest>();
    rest->positions.reserve(3 * mesh.num_vertices());
    for (const sim::Vec3d &v : mesh.positions)
        rest->positions.insert(rest->positions.end(), {v.x, v.y, v.z});
    rest->materials = mesh.materials;
    rest->triangle_material = mesh.triangle_material;
    if (!o.deform_mesh.empty() && o.deform_weight > 0)
        apply_pose(mesh, o.deform_mesh, o.deform_weight, scene_path,
                   "objects[" + std::to_string(index) + "].deform");
    // Motion blur: the later steps of the shutter, each posed from the rest.
    std::vector<std::vector<float>> later_positions, later_normals;
    std::vector<float> to_rest_length, bind_pose;
    if (rig && default_pose) {
        pose_default(*rig, report, &mesh);
        to_rest_length = rest_length_ratios(rest->positions, mesh);
        *pose_seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - pose_start)
                .count();
    } else if (rig) {
        for (const sim::Vec3d &v : rig->pose(Rig::default_pose, 0))
            bind_pose.insert(bind_pose.end(), {float(v.x), float(v.y), float(v.z)});
        const int clip = rig->clip(o.clip->name);
        for (size_t k = 1; k < o.clip_motion_seconds.size(); ++k) {
            sim::TriangleMesh step = mesh;
            pose_mesh(*rig, clip, o.clip_motion_seconds[k], &step);
            later_positions.push_back(float_positions(step.positions));
            if (!step.corner_normals.empty())
                later_normals.push_back(float_positions(step.corner_normals));
        }
        pose_mesh(*rig, clip, o.clip_seconds, &mesh);
        // The shutter's opening pose stands for the others: a step of the shutter
        // stretches the skin far less than the pose does from the rest.
        to_rest_length = rest_length_ratios(rest->positions, mesh);
        // A pose that holds through the shutter (a clip past its end, a pause) is still:
        // its rays need no time.
        const std::vector<float> opening = float_positions(mesh.positions);
        if (std::all_of(later_positions.begin(), later_positions.end(),
                        [&](const std::vector<float> &p) { return p == opening; })) {
            later_positions.clear();
            later_normals.clear();
        }
        *pose_seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - pose_start)
                .count();
    }
    if (o.grow) {
        // The shape at the age, vertex by vertex: the pattern, stored per (triangle,
        // barycentric point), rides on it (sim/growth/growth_shape.h).
        mesh.positions = sim::resolve_growth(sim::load_growth(o.grow->preset), mesh, mesh)
                             .at(o.grow_age);
        mesh.corner_normals.clear();
    }
    auto m = std::make_shared<MeshData>();
    m->source = o.mesh;
    m->rest = std::move(rest);
    m->num_vertices = uint32_t(mesh.num_vertices());
    m->num_triangles = uint32_t(mesh.num_triangles());
    m->object_positions = float_positions(mesh.positions);
    m->to_rest_length = std::move(to_rest_length);
    m->default_pose = std::move(bind_pose);
    m->triangles.resize(size_t(m->num_triangles) * 3);
    for (size_t t = 0; t < mesh.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) m->triangles[3 * t + c] = mesh.triangles[t][c];
    // --- Shading normals: from the file, area-weighted smooth, or none (flat) ---
    const bool file_normals =
        !mesh.corner_normals.empty() && o.normals != ObjectDesc::Normals::flat;
    if (file_normals) {
        m->corner_normals.resize(size_t(m->num_triangles) * 9);
        for (size_t i = 0; i < mesh.corner_normals.size(); ++i) {
            const sim::Vec3d n = mesh.corner_normals[i];
            m->corner_normals[3 * i + 0] = float(n.x);
            m->corner_normals[3 * i + 1] = float(n.y);
            m->corner_normals[3 * i + 2] = float(n.z);
        }
    } else if (o.normals == ObjectDesc::Normals::smooth) {
        const std::vector<sim::Vec3d> cn =
            smooth_corner_normals(mesh, welded, num_welded);
        m->corner_normals.resize(size_t(m->num_triangles) * 9);
        for (size_t t = 0; t < mesh.num_triangles(); ++t)
            for (int c = 0; c < 3; ++c) {
                const sim::Vec3d n = cn[3 * t + c];
                for (int k = 0; k < 3; ++k)
                    m->corner_normals[9 * t + 3 * c + k] = float(n[k]);
            }
    }
    if (!mesh.corner_uvs.empty()) {
        m->corner_uvs.resize(size_t(m->num_triangles) * 6);
        for (size_t i = 0; i < mesh.corner_uvs.size(); ++i) {
            m->corner_uvs[2 * i + 0] = float(mesh.corner_uvs[i].x);
            m->corner_uvs[2 * i + 1] = float(mesh.corner_uvs[i].y);
        }
    }
    m->positions = m->object_positions;
    m->later_positions = std::move(later_positions);
    // Normals from the file or smooth ones move with the skin; flat shading has none.
    if (!m->corner_normals.empty()) m->later_normals = std::move(later_normals);
    return m;
}

// A baked copy: positions and normals moved to world space.
std::shared_ptr<MeshData> bake(const MeshData &src, const Affine &to_world,
                               const Affine &normal_m) {
    auto m = std::make_shared<MeshData>(src);
    auto move_points = [&](std::vector<float> &P) {
        for (size_t i = 0; i + 2 < P.size(); i += 3) {
            const Vec3f p = to_world.point({P[i], P[i + 1], P[i + 2]});
            P[i] = p.x, P[i + 1] = p.y, P[i + 2] = p.z;
        }
    };
    auto turn_normals = [&](std::vector<float> &N) {
        for (size_t i = 0; i + 2 < N.size(); i += 3) {
            const Vec3f n = normalize(normal_m.vector({N[i], N[i + 1], N[i + 2]}));
            N[i] = n.x, N[i + 1] = n.y, N[i + 2] = n.z;
        }
    };
    move_points(m->positions);
    turn_normals(m->corner_normals);
    for (auto &P : m->later_positions) move_points(P);
    for (auto &N : m->later_normals) turn_normals(N);
    return m;
}

RTCGeometry make_triangle_geometry(RTCDevice device, const MeshData &m) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // A moving mesh: one vertex buffer per time step over the shutter (rays' time 0 at
    // its opening, 1 at its closing).
    rtcSetGeometryTimeStepCount(g, m.motion_steps());
    for (unsigned k = 0; k < m.motion_steps(); ++k)
        rtcSetSharedGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, k, RTC_FORMAT_FLOAT3,
            k == 0 ? m.positions.data() : m.later_positions[k - 1].data(), 0,
            3 * sizeof(float), m.num_vertices);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               m.triangles.data(), 0, 3 * sizeof(uint32_t),
                               m.num_triangles);
    rtcCommitGeometry(g);
    return g;
}

}  // namespace

void EmbreeScene::error_callback(void *user, RTCError code, const char *message) {
    auto *self = static_cast<EmbreeScene *>(user);
    std::lock_guard<std::mutex> lock(self->m_error_mutex);
    if (self->m_error.empty())
        self->m_error =
            "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

void EmbreeScene::check() const {
    std::lock_guard<std::mutex> lock(m_error_mutex);
    if (!m_error.empty()) throw std::runtime_error(m_error);
}

EmbreeScene::EmbreeScene(const SceneDesc &scene) {
    m_device = rtcNewDevice(nullptr);
    if (!m_device)
        throw std::runtime_error("cannot create the Embree device (error " +
                                 std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    // A throw below (a bad mesh, an Embree error) skips the destructor: release what was
    // created so far (the bad-scene corpus checks this under LeakSanitizer).
    struct ReleaseOnThrow {
        EmbreeScene &s;
        bool armed = true;
        ~ReleaseOnThrow() {
            if (armed) s.release();
        }
    } guard{*this};
    rtcSetDeviceErrorFunction(m_device, error_callback, this);
    m_scene = rtcNewScene(m_device);
    rtcSetSceneBuildQuality(m_scene, RTC_BUILD_QUALITY_HIGH);

    // --- Load each distinct mesh once; count its users ---
    // A mesh is its file, its normals and its pose.
    using Key = std::tuple<std::string, int, std::string, float>;
    auto key_of = [](const ObjectDesc &o) {
        if (o.grow)
            return Key{o.mesh, int(o.normals),
                       "grow " + o.grow->preset + " " + std::to_string(o.grow_age), 1.0f};
        if (o.clip) {
            char t[32];
            std::string times;
            for (const double seconds : o.clip_motion_seconds.empty()
                                            ? std::vector<double>{o.clip_seconds}
                                            : o.clip_motion_seconds) {
                std::snprintf(t, sizeof t, " %.17g", seconds);
                times += t;
            }
            return Key{o.mesh, int(o.normals), "clip " + o.clip->name + times, 1.0f};
        }
        return o.deform_weight > 0
                   ? Key{o.mesh, int(o.normals), o.deform_mesh, o.deform_weight}
                   : Key{o.mesh, int(o.normals), std::string(), 0.0f};
    };
    std::map<Key, std::shared_ptr<MeshData>> loaded;
    std::map<Key, int> users;
    for (const auto &o : scene.objects) ++users[key_of(o)];
    std::map<Key, RTCScene> child_of;
    m_objects.resize(scene.objects.size());
    std::optional<SetupPhase> phase(std::in_place, "loading meshes");
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const ObjectDesc &o = scene.objects[i];
        const Key key = key_of(o);
        auto &mesh = loaded[key];
        if (!mesh) mesh = load_mesh_data(o, scene.path, i, &m_pose_seconds);
        m_moves = m_moves || mesh->motion_steps() > 1;
        ObjectGeometry &og = m_objects[i];
        const Affine normal_m = o.transform.normal_matrix();
        if (const float det = std::abs(o.transform.determinant3()); det > 0)
            og.to_object_length = 1 / std::cbrt(det);
        m_num_triangles += mesh->num_triangles;
        if (users[key] == 1) {
            og.baked = true;
            og.mesh =
                o.transform.is_identity() ? mesh : bake(*mesh, o.transform, normal_m);
            RTCGeometry g = make_triangle_geometry(m_device, *og.mesh);
            const unsigned id = rtcAttachGeometry(m_scene, g);
            rtcReleaseGeometry(g);
            if (m_object_of_geometry.size() <= id) m_object_of_geometry.resize(id + 1, 0);
            m_object_of_geometry[id] = uint32_t(i);
        } else {
            og.baked = false;
            og.mesh = mesh;
            og.to_world = o.transform;
            og.normal_to_world = normal_m;
            RTCScene &child = child_of[key];
            if (!child) {
                child = rtcNewScene(m_device);
                RTCGeometry g = make_triangle_geometry(m_device, *mesh);
                rtcAttachGeometry(child, g);
                rtcReleaseGeometry(g);
                rtcCommitScene(child);
                m_child_scenes.push_back(child);
            }
            RTCGeometry inst = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(inst, child);
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR,
                                    &o.transform.m[0][0]);
            rtcCommitGeometry(inst);
            const unsigned id = rtcAttachGeometry(m_scene, inst);
            rtcReleaseGeometry(inst);
            if (m_object_of_instance.size() <= id) m_object_of_instance.resize(id + 1, 0);
            m_object_of_instance[id] = uint32_t(i);
        }
    }
    attach_area_lights(scene.lights);
    phase.reset();
    phase.emplace("building the BVH");
    rtcCommitScene(m_scene);
    check();
    RTCBounds b;
    rtcGetSceneBounds(m_scene, &b);
    if (b.lower_x <= b.upper_x)
        m_bounding_radius =
            0.5f * length(Vec3f{b.upper_x - b.lower_x, b.upper_y - b.lower_y,
                                b.upper_z - b.lower_z});
    guard.armed = false;
}

EmbreeScene::~EmbreeScene() { release(); }

void EmbreeScene::release() {
    for (RTCScene s : m_child_scenes) rtcReleaseScene(s);
    m_child_scenes.clear();
    if (m_scene) rtcReleaseScene(m_scene);
    if (m_device) rtcReleaseDevice(m_device);
    m_scene = nullptr;
    m_device = nullptr;
}

}  // namespace pelage::renderer
