// Growing a Clonal Mosaic on a mesh from a preset, as `pelage sim`, `pelage look` and a
// scene object's "pattern" block ask for it: the preset read, the simulation surface
// chosen (simulation_surface.h), the cells grown and packed as a .cells file would hold
// them. The library's one call from a mesh and a preset to a coat; what it shows the
// user (set-up steps, a progress bar, notes) goes through the request's callbacks.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/cells_io/cells_file.h"
#include "sim/crps/surface.h"
#include "sim/mosaic/cm_simulation.h"
#include "sim/mosaic/preset.h"
#include "sim/remesh/cell_scale_surface.h"

namespace pelage::sim {

struct GrowRequest {
    std::string mesh;        // a mesh file or a "procedural:..." spec
    std::string preset;      // a preset name (of `preset_dir`) or a preset file
    std::string preset_dir;  // the shipped presets' folder
    // Where `preset` was given, for an unknown name's error: the file ("" for the
    // command line) and its field ("--preset", "objects[0].pattern.preset").
    std::string preset_file, preset_field = "--preset";
    uint64_t seed = 1;
    uint64_t initial_cells = 0;  // > 0 overrides the preset's count
    std::string relax;           // "", "local" or "global" (overrides the preset)
    bool simplify = true;        // simulate on a copy at the cells' scale when finer
    // Told the name of each set-up step as it starts and "" as it ends.
    std::function<void(const std::string &)> phase;
    // Told the growth's fraction done, from 0 before the first step to 1.
    std::function<void(double)> progress;
    // Told what the run does before it starts, e.g. that it simplifies the surface.
    std::function<void(const std::string &)> note;
    // A live view of the run (`pelage explore`): asked after the initial relaxation and
    // after every relaxation step whether a snapshot is wanted, then handed the cells as
    // they stand, packed as a .cells file holds them (params_json empty) on the
    // simulation surface. Not called when unset; neither changes the run.
    std::function<bool()> snapshot_due;
    std::function<void(const Surface &surface, CellsData &&cells)> snapshot;
    // Asked as often as snapshot_due; true abandons the run: grow_cells() throws
    // GrowCancelled.
    std::function<bool()> cancelled;
};

// Thrown by grow_cells() when the request's `cancelled` says so.
struct GrowCancelled {};

struct GrownCells {
    Preset preset;
    CellsData data;  // what write_cells_file() stores
    SimStats stats;
    CellScaleReport cell_scale;
    size_t triangles = 0;  // of the simulation surface
    double body_length = 0;
    nlohmann::json params;  // the run's parameters, as data.params_json records them
};

// Reads the preset, builds the surface and grows the mosaic. Throws pelage::InputError
// on bad input (before any simulation work).
GrownCells grow_cells(const GrowRequest &request);

// Whether the .cells file at `path` was grown from `request`'s preset (same content),
// seed and mesh (same file content), so growing again would give the same cells, and
// records what this pelage's readers take from it (the anisotropy field). `why` says
// what differs (or that the file is missing or unreadable).
bool cells_match(const std::string &path, const GrowRequest &request, std::string *why);

}  // namespace pelage::sim
