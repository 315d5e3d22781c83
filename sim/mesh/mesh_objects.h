// The objects inside a mesh file: a mesh reference "PATH#NAME" selects the object NAME
// of the file PATH (an OBJ `o`/`g` name, a glTF/FBX/... node or mesh name). The reference
// is one string so that every place a mesh path goes (scene files, --mesh options, .cells
// files, the shader ABI's mesh_path) carries the selection unchanged.
#pragma once

#include <string>
#include <vector>

namespace pelage::sim {

struct MeshSpec {
    std::string path;
    std::string object;  // "" = every object of the file, merged
};

// Splits "zoo.glb#giraffe" into {"zoo.glb", "giraffe"}: at the first '#' that follows a
// mesh extension pelage reads (so a '#' elsewhere in a path stays part of it). A spec
// without one is a path. Throws InputError for "zoo.glb#" (no name after the '#').
MeshSpec parse_mesh_spec(const std::string &spec);

// A mesh reference's identity by content (16 hex digits), so that a scene and its files
// can move together: a file's bytes, then for FILE#NAME the object's name; a
// procedural:... spec its text. "" when the file cannot be read.
std::string mesh_reference_hash(const std::string &spec);

// `names` without empty strings and repeats, in their first order.
std::vector<std::string> unique_names(const std::vector<std::string> &names);

// InputError(path): "no object named "x" (the file's objects: a, b, c)".
[[noreturn]] void fail_unknown_object(const std::string &path, const std::string &object,
                                      const std::vector<std::string> &names);

}  // namespace pelage::sim
