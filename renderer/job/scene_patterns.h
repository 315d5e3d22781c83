// Growing a coat (sim/run/grow_cells.h) as the commands show it: the shipped presets'
// folder of this installation, set-up steps as a line counting seconds and the growth as
// a bar on stderr (when `show` and stderr is a terminal); and the scene objects'
// "pattern" blocks grown where their cells are missing or stale.
#pragma once

#include <functional>
#include <string>

#include "renderer/scene_file/scene_file.h"
#include "sim/run/grow_cells.h"

namespace pelage::renderer {

// `request`'s preset_dir, phase and progress are filled here; `label` names the lines.
sim::GrownCells grow_cells_shown(sim::GrowRequest request, const std::string &label,
                                 bool show);

// Grows every object's "pattern" whose cells file is missing or was grown otherwise
// (sim::cells_match), writing the file atomically. `note` (when set) is told why and
// what it took, or that a file was reused; with `show`, the growth draws its set-up
// steps and bar on a terminal.
void grow_scene_patterns(const SceneDesc &scene,
                         const std::function<void(const std::string &)> &note, bool show);
// The same, the notes on stderr unless `quiet` (stdout may carry a command's JSON).
void grow_scene_patterns(const SceneDesc &scene, bool quiet);

}  // namespace pelage::renderer
