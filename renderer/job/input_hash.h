// Content hashes of what a render reads: the files a scene names and the settings that
// determine its pixels. `pelage render` records the settings hash in every EXR
// (pelage:settings_xxh3) so that --resume and `pelage merge` trust only output made
// with the same inputs; `pelage bench noise` keys its cached reference on the files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/core/content_hash.h"

namespace pelage::renderer {

// The files `desc` reads, in a fixed order: those its input fields name (every field
// scene_fields.h declares FieldUse::input: meshes, deformation meshes, cells files,
// preset files, environment images) as the parser met them, then the meshes a growth
// block's keys name and every string in a material's parameters that names an existing
// file (a texture's image), relative to the scene's folder.
std::vector<std::string> scene_input_files(const SceneDesc &desc);

// The settings hash of a render: the scene's text `scene_text` as canonical JSON with the
// film's resolution, spp, noise threshold and view as `desc` has them (command-line
// overrides applied) and its output names left out, then `seed`, the contents of
// scene_input_files(desc) and of the shader plugins its materials load, and the pelage
// version. Equal hashes mean the same pixels.
std::string settings_hash(const SceneDesc &desc, const std::string &scene_text,
                          const PluginRegistry &plugins, uint64_t seed,
                          const std::string &version);

// The hash of frame `frame` of a render whose settings hash is `settings`: what an EXR
// records as pelage:settings_xxh3.
std::string frame_settings_hash(const std::string &settings, int frame);

// The pelage:settings_xxh3 an EXR records, "" when it has none or cannot be read.
std::string recorded_settings_hash(const std::string &exr);
// A string attribute of an EXR's header, "" when absent or unreadable.
std::string exr_string_attribute(const std::string &exr, const std::string &name);

}  // namespace pelage::renderer
