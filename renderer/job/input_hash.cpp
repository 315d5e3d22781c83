#include "renderer/job/input_hash.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "sim/growth/growth_spec.h"
#include "sim/mesh/mesh_objects.h"

namespace pelage::renderer {

namespace fs = std::filesystem;

namespace {

void add_param_files(const nlohmann::json &v, const std::string &dir,
                     std::vector<std::string> *files) {
    if (v.is_string()) {
        const std::string s = v.get<std::string>();
        if (s.empty() || s.size() > 4096) return;
        fs::path p(s);
        if (p.is_relative() && !dir.empty()) p = fs::path(dir) / p;
        std::error_code ec;
        if (fs::is_regular_file(p, ec)) files->push_back(p.lexically_normal().string());
    } else if (v.is_structured()) {
        for (const auto &item : v) add_param_files(item, dir, files);
    }
}

}  // namespace

std::vector<std::string> scene_input_files(const SceneDesc &desc) {
    // The files the scene's input fields name (scene_fields.h), as the parser met them.
    std::vector<std::string> files;
    for (const SceneDesc::InputFile &in : desc.inputs) files.push_back(in.path);
    // And what those files name in turn: a growth block's key meshes, the files among a
    // material's plugin parameters.
    for (const ObjectDesc &obj : desc.objects) {
        if (obj.grow)
            for (const sim::GrowthKey &k : sim::load_growth(obj.grow->preset).keys)
                if (k.kind == sim::GrowthKey::Kind::mesh)
                    files.push_back(sim::parse_mesh_spec(k.mesh).path);
        add_param_files(obj.material.params, desc.dir, &files);
    }
    return files;
}

std::string settings_hash(const SceneDesc &desc, const std::string &scene_text,
                          const PluginRegistry &plugins, uint64_t seed,
                          const std::string &version) {
    ContentHash h;
    // The scene as parsed JSON: whitespace and key order do not count, and std::map
    // objects dump with sorted keys. The film carries the values rendered.
    nlohmann::json j = nlohmann::json::parse(scene_text, nullptr, false, true);
    if (j.is_object()) {
        nlohmann::json &film = j["film"];
        if (!film.is_object()) film = nlohmann::json::object();
        film.erase("output");
        film.erase("preview");
        film["width"] = desc.film.width;
        film["height"] = desc.film.height;
        film["spp"] = desc.film.spp;
        film["noise_threshold"] = desc.film.noise_threshold;
        film["view"] = desc.film.view;
        if (desc.film.denoise) film["denoise"] = true;  // --denoise changes the file
        h.add(j.dump());
    } else {
        h.add(scene_text);  // parse_scene accepted it, so this does not happen
    }
    h.add("seed " + std::to_string(seed));
    for (const std::string &f : scene_input_files(desc)) h.add_file(f);
    std::set<std::string> shaders;
    for (const ObjectDesc &obj : desc.objects) shaders.insert(obj.material.shader);
    for (const std::string &name : shaders) {
        const auto it = plugins.plugins().find(name);
        h.add(name);
        if (it != plugins.plugins().end()) h.add_file(it->second.file);
    }
    h.add("pelage " + version);
    return h.hex();
}

std::string frame_settings_hash(const std::string &settings, int frame) {
    ContentHash h;
    h.add(settings);
    h.add("frame " + std::to_string(frame));
    return h.hex();
}

std::string exr_string_attribute(const std::string &exr, const std::string &name) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) {
        OIIO::geterror();  // clears the message this failure left
        return "";
    }
    return in->spec().get_string_attribute(name);
}

std::string recorded_settings_hash(const std::string &exr) {
    return exr_string_attribute(exr, "pelage:settings_xxh3");
}

}  // namespace pelage::renderer
