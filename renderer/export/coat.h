// The coat as other tools take it: each patterned object's skin (its mesh in its own
// space, its transform, and the pattern per face) and each fur layer's strands (their
// control points, widths, and per strand the cell under the root), gathered from a
// scene built for rendering, so what is exported is what pelage renders. USD
// (usd_export.h) and glTF (glb_writer.h) write it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/scene/scene.h"

namespace pelage::renderer {

struct CoatSkin {
    std::string name;  // the scene object's name (or "object<i>")
    size_t object = 0;
    Affine to_world;  // object space to the scene's
    // The mesh in object space, as rendered (posed for a clip's frame).
    std::vector<float> points;      // xyz per vertex
    std::vector<uint32_t> indices;  // 3 per triangle
    std::vector<float> normals;     // xyz per corner (9 per triangle), or empty (flat)
    std::vector<float> uvs;         // uv per corner (6 per triangle), OBJ convention
    // The pattern at each face's centroid, as fur roots take it (Scene::shade_surface):
    // the colour the skin shows (linear), the cell's type (−1: none) and its stable id
    // (the "cell" matte; −1 when the shader has none).
    std::vector<float> face_colour;  // rgb per triangle
    std::vector<int32_t> face_cell_type, face_cell_id;
    std::string texture;  // the baked pattern's file, relative to the export, or ""
    size_t num_triangles() const { return indices.size() / 3; }
};

struct CoatGroom {
    std::string name;  // "<skin>_fur"
    size_t skin = 0;   // into CoatFrame::skins
    // Round strands are uniform cubic B-splines (their first and last control points
    // the phantoms Embree's curves use, so the curve starts at the root and ends at the
    // tip); flat ones are linear polylines.
    bool cubic = true;
    uint32_t points_per_strand = 0;
    std::vector<float> points;  // xyz per control point, object space
    std::vector<float> widths;  // per control point: the fibre's diameter
    // Per strand: the skin under the root, as the strand's pigment took it.
    std::vector<float> colour;  // rgb (linear)
    std::vector<int32_t> cell_type, cell_id;
    std::vector<SurfacePoint> roots;  // (triangle, b1, b2) of the skin's mesh
    size_t size() const { return roots.size(); }
};

struct CoatFrame {
    std::vector<CoatSkin> skins;
    std::vector<CoatGroom> grooms;
    size_t num_strands() const;
    size_t num_points() const;
};

struct CoatOptions {
    // The objects to export by name; empty: every patterned one (an object whose
    // material gives a cell type somewhere, or that has a .cells file).
    std::vector<std::string> objects;
    bool fur = true;
};

// The coat of `scene` (one frame). Throws pelage::InputError naming `scene_path` and
// the field when a named object does not exist or has no pattern, or when nothing in
// the scene has one.
CoatFrame gather_coat(const Scene &scene, const CoatOptions &options);

// The skin's UV at each root of `groom` (interpolated corner UVs), 2 per strand; empty
// when the skin has none.
std::vector<float> root_uvs(const CoatSkin &skin, const CoatGroom &groom);

// Object space of an affine map: its inverse (the linear part must be invertible).
Affine inverse(const Affine &a);

}  // namespace pelage::renderer
