// The scene `pelage look` writes: the object framed (renderer/camera/auto_frame.h), its
// pattern grown from a preset, on a ground plane under a sky and a sun. It is a complete
// scene file, so the user edits it and renders it again with `pelage render`.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/camera/auto_frame.h"

namespace pelage::renderer {

struct LookSetup {
    Framing framing;
    Vec3f up{0, 1, 0};
    // Paths as the scene file writes them (relative to the scene's folder or absolute).
    std::string mesh, cells, output, preview;
    std::string object_name = "animal";
    std::string preset = "giraffe-reticulata";
    uint64_t seed = 1;
    int width = 960, height = 540, spp = 64;
    std::string view = "Filmic";
    bool fur = false;
    bool denoise = false;
    bool comb_field = false;  // the preset has an anisotropy field: comb along it
    // The file's other objects, as they come (look_objects.h): the mesh reference, and
    // whether the file gives them materials (else a neutral grey).
    struct Prop {
        std::string name, mesh;
        bool materials = false;
        bool textures = true;   // false: colours only (an image is missing)
        bool animated = false;  // the animal's clip moves it too
    };
    std::vector<Prop> props;
    bool ground = true;  // false: the file has a floor of its own under the animal
    // A clip of the mesh file played on the animal ("" = none), over `frames` frames at
    // `fps` (the scene's animation block).
    std::string clip;
    float body_radius = 0;  // the rest pose's bounding radius, which sizes the fur (0:
                            // the framing's)
    int frames = 1;
    double fps = 24;
    double shutter = 0;  // motion blur over [0, shutter] of each frame (0: sharp)
};

// A mesh (a file, FILE#NAME or procedural:...) as a scene in `scene_dir` names it:
// relative when it sits in that folder (the two move together), absolute otherwise.
std::string mesh_reference(const std::string &mesh,
                           const std::filesystem::path &scene_dir);

// The scene, its keys in the order a person reads them (camera, film, lights, objects).
nlohmann::ordered_json look_scene(const LookSetup &s);

// JSON as scene files are written by hand: one key per line, short arrays of numbers
// on one line.
std::string format_scene_json(const nlohmann::ordered_json &j);

}  // namespace pelage::renderer
