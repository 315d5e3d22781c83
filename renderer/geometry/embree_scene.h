// The Embree 3 side of a scene: one device, one top-level scene, one triangle geometry
// per distinct mesh. Vertex and index buffers are shared with Embree
// (rtcSetSharedGeometryBuffer) from float copies this class keeps alive. A mesh used by
// one object has its transform baked into the vertices; a mesh used by several objects
// is built once as a child scene and instanced. Area lights are geometry too (quads as
// RTC_GEOMETRY_TYPE_QUAD, spheres as RTC_GEOMETRY_TYPE_SPHERE_POINT; embree_lights.cpp),
// so they occlude and are hit like any surface; light_of() tells their hits apart.
//
// Errors: the device error callback records the first error; check() throws it as
// std::runtime_error, so an Embree failure fails the run instead of being printed.
#pragma once

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "renderer/core/math.h"
#include "renderer/core/motion_step.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/mesh/mesh.h"

namespace pelage::renderer {

struct MeshData {
    std::string source;
    uint32_t num_vertices = 0, num_triangles = 0;
    std::vector<float> positions;     // xyz per vertex (+1 pad float: Embree reads 16 B)
    std::vector<uint32_t> triangles;  // 3 per triangle
    std::vector<float> corner_normals;    // 9 per triangle, or empty (flat shading)
    std::vector<float> corner_uvs;        // 6 per triangle, or empty
    std::vector<float> object_positions;  // untransformed copy for plugins (same layout)
    // Per triangle, posed lengths to the rest mesh's (rest_length_ratios(),
    // renderer/animation/rig.h) when a clip or a skin's default pose moved the mesh, so
    // footprints reach plugins in the pattern's units (PelageHit::footprint); empty when
    // the mesh is as loaded.
    std::vector<float> to_rest_length;
    // A mesh a clip poses: the skin's default pose (glTF 2.0 §3.7.3: the joints' global
    // transforms times their inverse bind matrices), xyz per vertex in object space,
    // the shape its coat is counted and sized on whatever the pose. A file's vertices
    // need not be in that shape: one laid out as Blender exports a Mixamo character
    // reads at 1/100 of it, under an armature's scale. Empty without a clip.
    std::vector<float> default_pose;
    // Motion blur (ObjectDesc::clip_motion_seconds): positions and corner normals at the
    // shutter's later steps 1 .. n − 1, step 0 being `positions` and `corner_normals`;
    // the surface moves linearly from step to step. Empty: the mesh does not move.
    std::vector<std::vector<float>> later_positions, later_normals;
    unsigned motion_steps() const { return 1 + unsigned(later_positions.size()); }
    // Vertex v's position at shutter time `time` in [0, 1].
    Vec3f position_at(uint32_t v, float time) const {
        const float *P = &positions[3 * size_t(v)];
        Vec3f p{P[0], P[1], P[2]};
        if (later_positions.empty()) return p;
        const MotionStep s = motion_step(time, later_positions.size());
        const float *A = s.i == 0 ? P : &later_positions[s.i - 1][3 * size_t(v)];
        const float *B = &later_positions[s.i][3 * size_t(v)];
        return Vec3f{A[0], A[1], A[2]} * (1 - s.f) + Vec3f{B[0], B[1], B[2]} * s.f;
    }
    // Corner c's (0 .. 3·triangles) shading normal at `time`, unnormalised.
    Vec3f corner_normal_at(size_t c, float time) const {
        const float *N = &corner_normals[3 * c];
        if (later_normals.empty()) return {N[0], N[1], N[2]};
        const MotionStep s = motion_step(time, later_positions.size());
        const float *A = s.i == 0 ? N : &later_normals[s.i - 1][3 * c];
        const float *B = &later_normals[s.i][3 * c];
        return Vec3f{A[0], A[1], A[2]} * (1 - s.f) + Vec3f{B[0], B[1], B[2]} * s.f;
    }
    // What shader plugins need of the mesh file beyond the rendered triangles, shared by
    // baked copies: the loaded positions before deformation or growth, exact (a .cells
    // file's mesh hash is over them), and the file's materials.
    struct Rest {
        std::vector<double> positions;  // xyz per vertex
        std::vector<sim::MeshMaterial> materials;
        std::vector<uint32_t> triangle_material;  // per triangle, or empty
    };
    std::shared_ptr<const Rest> rest;
};

struct ObjectGeometry {
    std::shared_ptr<const MeshData> mesh;
    bool baked = true;       // mesh already in world space
    Affine to_world;         // identity when baked
    Affine normal_to_world;  // inverse transpose of to_world's linear part
    // Scene lengths to the mesh's own (PelageHit::footprint): 1 / the transform's scale,
    // the cube root of its linear part's |determinant| (exact for uniform scales).
    float to_object_length = 1;
};

class EmbreeScene {
  public:
    // Loads every object's mesh (throws pelage::InputError naming the mesh file and the
    // object's JSON path) and commits the Embree scene.
    explicit EmbreeScene(const SceneDesc &scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    RTCScene scene() const { return m_scene; }
    RTCDevice device() const { return m_device; }  // for geometry added later (fur)
    const std::vector<ObjectGeometry> &objects() const { return m_objects; }
    // Object id for an Embree hit: instID[0] for instanced meshes, else geomID.
    uint32_t object_of(unsigned geom_id, unsigned inst_id) const {
        return inst_id != RTC_INVALID_GEOMETRY_ID ? m_object_of_instance[inst_id]
                                                  : m_object_of_geometry[geom_id];
    }
    // Light index (into SceneDesc::lights) for a hit on an area light, else -1.
    int light_of(unsigned geom_id, unsigned inst_id) const {
        return inst_id == RTC_INVALID_GEOMETRY_ID && geom_id < m_light_of_geometry.size()
                   ? m_light_of_geometry[geom_id]
                   : -1;
    }
    // The geometries attached here (meshes, instances, area lights): IDs 0 .. n − 1,
    // before anything is added later (fur).
    unsigned num_geometries() const {
        return unsigned(
            std::max({m_object_of_geometry.size(), m_object_of_instance.size(),
                      m_light_of_geometry.size()}));
    }
    // Radius of the bounding sphere of everything in the scene (0 when empty).
    float bounding_radius() const { return m_bounding_radius; }
    size_t num_triangles() const { return m_num_triangles; }
    // The time spent posing meshes by their clips (renderer/animation): skinning,
    // morphing and unwelding, summed over the objects.
    double pose_seconds() const { return m_pose_seconds; }
    // Whether a mesh moves during the shutter (MeshData::later_positions): rays then
    // carry a time.
    bool moves() const { return m_moves; }
    // Throws the first device error recorded so far, if any.
    void check() const;

  private:
    static void error_callback(void *user, RTCError code, const char *message);
    void attach_area_lights(const std::vector<LightDesc> &lights);
    void release();  // the Embree objects, in reverse order of creation

    RTCDevice m_device = nullptr;
    RTCScene m_scene = nullptr;
    std::vector<RTCScene> m_child_scenes;
    std::vector<ObjectGeometry> m_objects;
    std::vector<uint32_t> m_object_of_geometry, m_object_of_instance;
    std::vector<int> m_light_of_geometry;  // -1: not a light
    float m_bounding_radius = 0;
    size_t m_num_triangles = 0;
    double m_pose_seconds = 0;
    bool m_moves = false;
    mutable std::mutex m_error_mutex;
    std::string m_error;
};

}  // namespace pelage::renderer
