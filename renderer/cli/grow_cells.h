// Growing a Clonal Mosaic on a mesh, as `pelage sim`, `pelage look` and a scene object's
// "pattern" block ask for it: the preset read, the simulation surface chosen
// (simulation_surface.h), the cells grown and packed as a .cells file would hold them.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/cells_io/cells_file.h"
#include "sim/mosaic/cell_types.h"
#include "sim/mosaic/cm_simulation.h"
#include "sim/remesh/cell_scale_surface.h"

namespace pelage::renderer::cli {

struct GrowRequest {
    std::string mesh;    // a mesh file or a "procedural:..." spec
    std::string preset;  // a preset name (the shipped presets) or a preset file
    uint64_t seed = 1;
    uint64_t initial_cells = 0;  // > 0 overrides the preset's count
    std::string relax;           // "", "local" or "global" (overrides the preset)
    bool simplify = true;        // simulate on a copy at the cells' scale when finer
    bool progress = false;       // set-up lines and a bar on stderr
    std::string label = "pelage sim";  // names the progress lines
    // Told what the run does before it starts, e.g. that it simplifies the surface.
    std::function<void(const std::string &)> note;
};

struct GrownCells {
    sim::Preset preset;
    sim::CellsData data;  // what write_cells_file() stores
    sim::SimStats stats;
    sim::CellScaleReport cell_scale;
    size_t triangles = 0;  // of the simulation surface
    double body_length = 0;
    nlohmann::json params;  // the run's parameters, as data.params_json records them
};

// Reads the preset, builds the surface and grows the mosaic. Throws pelage::InputError
// on bad input (before any simulation work).
GrownCells grow_cells(const GrowRequest &request);

// Whether the .cells file at `path` was grown from `request`'s preset (same content),
// seed and mesh (same file content), so growing again would give the same file. `why`
// says what differs (or that the file is missing or unreadable).
bool cells_match(const std::string &path, const GrowRequest &request, std::string *why);

}  // namespace pelage::renderer::cli

namespace pelage::renderer {
struct SceneDesc;
}

namespace pelage::renderer::cli {

// Grows every object's "pattern" whose cells file is missing or was grown otherwise
// (cells_match), writing the file atomically; a line on stderr says why unless `quiet`
// (stdout may carry a command's JSON).
void grow_scene_patterns(const SceneDesc &scene, bool quiet);

}  // namespace pelage::renderer::cli
