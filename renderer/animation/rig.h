// What a mesh file holds to move its mesh: the node graph, the skins (bones with their
// inverse bind matrices and per-vertex weights), the morph targets and the animation
// clips, read through assimp (glTF 2.0, FBX, Collada, ...). A rig is read for the same
// mesh reference as sim::load_mesh and numbers its vertices as read_assimp() does
// (sim/mesh/assimp_walk.h), so a pose is one position per vertex of the mesh as read,
// before welding; MeshCleanStats::source_vertex carries it to the cleaned mesh.
//
// Posing follows glTF 2.0 §3.7 (concepts: skins, morph targets, animations): a clip's
// channels replace their nodes' translation, rotation and scale (linear interpolation,
// spherical for rotations, the clip's first or last key outside its keys); each mesh
// vertex is first morphed, v + Σ w_k (target_k − v), then skinned,
// Σ_j w_j · G_j · IBM_j · v (G_j the joint node's global transform at the time), or, in a
// mesh without bones, placed by its node's global transform.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sim/mesh/mesh.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::renderer {

struct RigData;  // renderer/animation/rig_data.h

class Rig {
  public:
    // Whether a file without clips is an error: a clip is asked for, or only the
    // default pose of a skinned file is.
    enum class Clips { required, optional };
    // Reads the rig of `mesh_ref` ("file.glb" or "file.glb#object", as sim::load_mesh
    // takes it). Throws pelage::InputError naming the file: unreadable, not a format
    // with animation (OFF, PLY, OBJ, procedural meshes), no clips (when required), a
    // bone naming no node, a skinned vertex whose weights do not sum to 1.
    // With Clips::optional a file without clips is no error: listing a file's contents
    // (`pelage info`) and a still's default pose need it.
    static Rig read(const std::string &mesh_ref, Clips clips = Clips::required);
    // Whether the reference's format can carry a rig at all: files read through assimp,
    // not OFF, PLY, OBJ or procedural meshes.
    static bool format_has_animation(const std::string &mesh_ref);

    // The clip index of the default pose: every node at its own transform, no channel
    // (what glTF viewers show of a file without playing a clip).
    static constexpr int default_pose = -1;

    const std::string &path() const;
    // The clips' names in file order (assimp's names: glTF's animation names).
    const std::vector<std::string> &clip_names() const;
    // The clip of that name; throws InputError naming the file and listing the clips
    // when there is none (`field` names the scene key that asked, may be "").
    int clip(const std::string &name, const std::string &field = "") const;
    double duration_seconds(int clip) const;
    // Whether the clip moves any vertex of the mesh: a channel on a bone of its skins,
    // on a node above a mesh, or on its morph weights.
    bool moves_mesh(int clip) const;
    size_t num_vertices() const;  // read_assimp()'s vertex count for the same reference
    bool skinned() const;
    size_t num_bones() const;          // the distinct joint nodes of its skins
    size_t num_morph_targets() const;  // summed over its meshes

    // Every vertex at `seconds` into `clip` (or in the default pose): the rig's
    // numbering, object space of the file. Throws InputError naming the file and the
    // clip when a position is not finite.
    // With `normal_matrices`, also each vertex's normal transform at the time: the
    // cofactor matrix (det · A^−T, sign kept positive) of the linear part of the map its
    // morphed rest position goes through, after the inverse of its node's transform in
    // the file, row-major; normals as sim::read_assimp gives them (through that
    // transform) follow it, up to length.
    std::vector<sim::Vec3d> pose(
        int clip, double seconds,
        std::vector<std::array<double, 9>> *normal_matrices = nullptr) const;

    Rig(Rig &&) noexcept;
    Rig &operator=(Rig &&) noexcept;
    ~Rig();

  private:
    explicit Rig(std::unique_ptr<RigData> d);
    std::unique_ptr<RigData> m;
};

// Undoes the welding of `mesh`, loaded by sim::load_mesh with `report`: every triangle
// corner gets back the vertex it was read as, at the welded position. The triangles,
// their order and the shape stay; only vertices that coincided are separate again, so a
// seam or two touching parts whose skins differ can move apart.
void unweld(const sim::MeshLoadReport &report, sim::TriangleMesh *mesh);

// An unwelded mesh of the rig's own reference posed at `seconds` into `clip`; its corner
// normals, if any, go with the skin (morph targets' own normal changes are not read).
void pose_mesh(const Rig &rig, int clip, double seconds, sim::TriangleMesh *mesh);

// A still of a skinned file as glTF viewers show it (glTF 2.0 §3.7.3: a skinned mesh's
// node transform is ignored; its joints' global transforms times their inverse bind
// matrices place it): `mesh`, loaded by sim::load_mesh with `report`, moved to the rig's
// default pose, each welded vertex as the vertex it was read as
// (MeshCleanStats::source_vertex). Its vertices, triangles and their order stay, so a
// pattern grown on the mesh as loaded lies on it unchanged; its corner normals, if any,
// go with the skin.
void pose_default(const Rig &rig, const sim::MeshLoadReport &report,
                  sim::TriangleMesh *mesh);

// Per triangle of `posed`, a pose of `rest` (the same triangles), the factor that turns
// lengths on the posed surface into the rest surface's: sqrt(rest area / posed area),
// 1 where either is degenerate. A ray footprint measured on a posed mesh is in these
// units once multiplied (PelageHit::footprint is in the pattern's own units).
std::vector<float> rest_length_ratios(const std::vector<double> &rest_xyz,
                                      const sim::TriangleMesh &posed);

// A clip's time at a scene time: `seconds` as given, wrapped into [0, duration) when
// `loop`, held at the clip's ends otherwise.
double clip_time(double seconds, double duration, bool loop);

}  // namespace pelage::renderer
