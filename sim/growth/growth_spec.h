// A preset's "growth" block (docs/guide/growth-and-control.md, ## Growth): the shape of
// the body at ages of the simulation's time, independent of any mesh until resolved
// (growth_shape.h). Each key gives the shape at its age as
//   * a mesh file with the rest mesh's topology (path relative to the preset),
//   * a uniform scale of the rest mesh about its area centroid, or
//   * Walter's cylinders (thesis §5.5–5.6): a length and a radius scale per cylinder.
// Between keys the shape is interpolated per vertex, linearly or by a C1 cubic.
#pragma once

#include <array>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "sim/core/vec.h"

namespace pelage::sim {

enum class GrowthInterpolation { linear, smooth };

// A user cylinder (thesis §5.5): the axis runs from `from` (the pivot) to `to`; a point
// is inside when its projection falls on the axis segment and it lies within `radius`
// of the axis. Coordinates are those of the rest mesh. A child's pivot follows its
// parent's growth (only translation is inherited, thesis §5.5: scales are absolute).
struct GrowthCylinder {
    std::string name;
    Vec3d from, to;
    double radius = 0;
    int parent = -1;  // index into GrowthSpec::cylinders, −1 for a root
};

struct GrowthKey {
    enum class Kind { mesh, scale, cylinders };
    double age = 0;
    Kind kind = Kind::scale;
    std::string mesh;  // absolute or relative to the working directory (resolved)
    double scale = 1;  // Kind::scale
    // Kind::cylinders: (length, radius) scale per cylinder, parallel to
    // GrowthSpec::cylinders; (1, 1) for a cylinder the key does not name.
    std::vector<std::array<double, 2>> cylinder_scales;
    std::string path;  // "growth.keys[2]", for errors found when resolving
};

struct GrowthSpec {
    std::vector<GrowthCylinder> cylinders;
    std::vector<GrowthKey> keys;  // ages strictly increasing, at least one
    GrowthInterpolation interpolation = GrowthInterpolation::linear;
    double interval = 1;  // time between reshapes of the simulation surface
    // Walter thesis §6.8 (true, "pattern during growth"): the simulation runs on the
    // growing surface, divisions from its growth. §6.7 (false, "pattern then growth"):
    // it runs on the shape at the first age with the types' division times, and the
    // pattern then follows the surface to the rest shape.
    bool during = true;
    std::string file;  // the preset, for errors found when resolving
    bool has_mesh_keys() const;
};

// Parses the block at JSON path `path` ("growth") of preset `file`; mesh paths resolve
// against `base_dir`. InputError naming the file and the JSON path of the bad field.
GrowthSpec parse_growth(const nlohmann::json &node, const std::string &path,
                        const std::string &file, const std::string &base_dir);

}  // namespace pelage::sim

namespace pelage::sim {

// The "growth" block of the preset file at `path` (the renderer's "grow" needs only
// that): InputError naming the file when it cannot be read or has no growth block.
GrowthSpec load_growth(const std::string &path);

}  // namespace pelage::sim
