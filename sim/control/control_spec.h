// Spatial control of a Clonal Mosaic as a preset states it, before it meets a mesh:
// named regions (scalar maps over the surface with values in [0, 1]), neural-crest masks
// and local parameters. Queiroz & Walter, "Texture Synthesis of Contrasting Natural
// Patterns", §V.A ("neural crest model": foreground cells only where a mask is white) and
// its local parameters (type probabilities, initial density, w_r and w_a by body region,
// Table II), and Walter's
// thesis §6.9 (textures attached to body regions controlling cell existence, split rates
// and the repulsion radius). The spec is mesh-independent; surface_control.h resolves it
// on the simulation surface.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace pelage::sim {

// One region, a node of a small expression tree over other regions by index.
struct RegionSpec {
    enum class Kind { height, near, attribute, texture, any, all, negate };
    Kind kind = Kind::height;
    // height: t = position along `axis` as a fraction of the mesh's extent along it;
    // 1 where t <= below (and t >= above), fading to 0 over `blend` beyond.
    std::array<double, 3> axis{0, 1, 0};
    double below = 1, above = 0;
    bool has_below = false, has_above = false;
    // near: 1 within `within` (a fraction of the body length) of any point along the
    // surface, fading to 0 over `blend` beyond; points in "box" fractions or world units.
    std::vector<std::array<double, 3>> points;
    bool box_space = true;
    double within = 0;
    double blend = 0;  // height and near
    // attribute: a per-vertex scalar of the mesh file, clamped to [0, 1].
    std::string attribute;
    // texture: an image channel through the mesh's UVs (path resolved against the
    // preset's folder), clamped to [0, 1].
    std::string texture;
    int channel = 0;
    // any (max), all (min), negate (1 − x): indices of earlier regions.
    std::vector<int> operands;
};

// A parameter that is a plain number or varies by region: starting from `value`, each
// (region, v) pair in the listed order moves it to lerp(current, v, m(region)).
struct LocalValue {
    double value = 0;                        // the default (or the constant)
    std::vector<std::pair<int, double>> in;  // (region index, value)
    bool local() const { return !in.empty(); }
    // The largest value anywhere: lerps stay between the default and the regions'.
    double max() const {
        double m = value;
        for (const auto &[region, v] : in) m = v > m ? v : m;
        return m;
    }
};

// Queiroz §V.A: a cell of `type` where the mask m = 0 becomes `otherwise`; m is the
// region (only_in) or one minus it (not_in).
struct MaskSpec {
    int type = 0, otherwise = 0, region = 0;
    bool inside = true;  // only_in (true) or not_in (false)
};

struct ControlSpec {
    std::vector<std::string> region_names;
    std::vector<RegionSpec> regions;  // parallel to region_names; operands point back
    std::vector<MaskSpec> masks;
    // Simulation parameters that may vary by region (constant ones have no `in`; their
    // value is also in SimParams).
    LocalValue w_r, w_d, w_a, anisotropy_magnitude, initial_weight{1, {}};
    // Per cell type, indexed like the preset's types (empty: all constant).
    std::vector<LocalValue> division_time, initial_probability;
    // Adhesion α by region (Walter 1998 Table 1): starting from the preset's matrix, each
    // (region, matrix) pair in the listed order moves α[c][p] to lerp(current, α', m).
    std::vector<std::pair<int, std::vector<std::vector<double>>>> adhesion_in;

    bool any_local() const;
    // Masks and local values name regions, so regions alone say whether there is
    // anything to resolve (unused regions are resolved too: their errors show).
    bool empty() const { return regions.empty(); }
    // Whether a region reads the mesh's own data (vertex attributes or UVs), which a
    // simplified copy of the mesh does not carry.
    bool needs_mesh_data() const;
    int find_region(const std::string &name) const;  // −1 if absent
};

}  // namespace pelage::sim
