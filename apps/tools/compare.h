// `pelage compare`: the same scene rendered once per shader on its patterned objects
// (same camera, lights, seed), with render times and in-process shading cost per lookup —
// the comparison of Teo 2006 Table 7.9 (CM vs Perlin, Worley, texture).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/scene_file/scene_file.h"
#include "shader/pelage_shader.h"

namespace pelage::renderer {

struct CompareOptions {
    std::vector<std::string> shaders{"clonal_mosaic", "worley", "perlin", "texture",
                                     "diffuse"};
    // The shader the others are measured against: the report's ratios are
    // "<reference>_vs_<shader>".
    std::string reference = "clonal_mosaic";
    uint64_t seed = 0;
    size_t lookups = 200000;  // surface points timed per shader
    // Renders (and shading timings) per shader, the shaders alternating round by round;
    // the times reported are each shader's minimum: on a shared machine other jobs only
    // ever add time, so the minimum is the least disturbed estimate.
    int repeats = 1;
    // Give the baselines the mosaic's look (matched_baseline_params) unless the scene's
    // own material is that shader; false: the plugins' defaults.
    bool match_baselines = true;
    // For a shader that maps an image by UV (maps_image_by_uv): an atlas of the mosaic
    // and the mesh with its UVs (`pelage bake`), used when the scene's material is not
    // that shader already.
    std::string texture_file, texture_mesh;
    float texels_per_unit = 0;
};

struct CompareRun {
    std::string shader;
    double seconds = 0;      // the whole render, wall clock (minimum over the repeats)
    double cpu_seconds = 0;  // ... CPU time of all threads (the ratios use it)
    std::vector<double> cpu_seconds_each;  // every repeat's, in order
    double ns_per_lookup =
        0;  // shade() alone, same points for every shader, thread CPU time
    std::vector<float> rgb;  // resolved beauty, linear RGB, width × height × 3
};

struct CompareResult {
    std::string reference;  // CompareOptions::reference
    int width = 0, height = 0;
    std::vector<CompareRun> runs;
    nlohmann::json params =
        nlohmann::json::object();  // per shader, the params it ran with
    nlohmann::json report()
        const;  // the `--stats-json` contract (docs/guide/compositing-outputs.md)
};

// Pattern drift under deformation: for each shader, the mean (and max) over `points`
// area-uniform surface points (triangle, barycentrics) of the rest mesh of
// |albedo(rest) - albedo(pose)|, averaged over R, G, B. The pose is the object's last
// "deform" mesh, or its animation clip at eight times over the clip (the points then
// count every pose). A pattern attached to the surface (clonal_mosaic) has drift 0; one
// on object-space position (worley, perlin) swims.
struct DriftRun {
    std::string shader;
    double mean = 0, max = 0;
    size_t points = 0;
};
struct DriftResult {
    size_t object = 0;  // the deforming patterned object measured
    std::string pose;   // its pose mesh
    std::vector<DriftRun> runs;
    nlohmann::json report() const;
};
// InputError when no patterned object has a "deform" or a clip.
DriftResult measure_pattern_drift(const SceneDesc &desc, const CompareOptions &options);

// The patterned objects are those with a "cells" file; each shader is applied to them
// with the scene's params when the scene names that shader, otherwise matched params
// (options.match_baselines) or the atlas (maps_image_by_uv), the plugin's defaults for
// the rest. InputError when the scene has no patterned object.
CompareResult compare_shaders(const SceneDesc &desc, const CompareOptions &options);

// What compare knows of a plugin, read from its own parameter table and AOV names.
//
// The slot of the AOV called `name` in the plugin's aov_names, or -1.
int aov_slot(const PelageShaderPlugin &plugin, const std::string &name);

// How a baseline's look is matched to a mosaic. Both take the RGB parameters
// "spot_colour" and "base_colour" and the FLOAT "frequency".
enum class BaselineModel {
    none,      // not a two-colour baseline: the plugin's defaults
    cellular,  // Poisson feature points ("mean_points" per cube) of which a
               // "spot_fraction" are spots: Worley 1996 cellular noise
    // a noise (its AOV "noise") above a "threshold" is a spot: thresholded fBm
    thresholded_noise,
};
BaselineModel baseline_model(const PelageShaderPlugin &plugin);

// A plugin that maps an image: STRING "file" by the mesh's UVs, FLOAT "texels_per_unit".
bool maps_image_by_uv(const PelageShaderPlugin &plugin);

// The look of a .cells mosaic as baseline parameters for `plugin` (baseline_model):
// spot and base colours (types F and B when present), the spot fraction, and a frequency
// giving about as many spots per unit area. For thresholded noise, compare_shaders turns
// the spot fraction into the threshold from the noise's distribution on the surface. An
// empty object for other plugins.
nlohmann::json matched_baseline_params(const PelageShaderPlugin &plugin,
                                       const std::string &cells_path);

}  // namespace pelage::renderer
