// Which object of a multi-object file `pelage look` grows the pattern on. Files from the
// wild hold an animal with its ground, props and parts (the heffalump: an elephant, its
// ground plane, a grid and primitives); a pattern grown across all of them at once is
// neither what the user means nor affordable. The animal is the largest object by area
// that is not flat (a ground, a backdrop or a card is); the others keep their own
// materials.
#pragma once

#include <string>
#include <vector>

namespace pelage::renderer {

struct LookObject {
    std::string name;  // selects it: "PATH#name" (sim/mesh/mesh_objects.h)
    double area = 0;
    bool flat = false;            // every triangle in one plane (within 1 %)
    double flat_height = 0;       // a flat object's plane: dot(point, up)
    bool flat_facing_up = false;  // its normal within 8° of ±up
    bool materials = false;       // the file gives its triangles materials
    std::string missing_texture;  // one of them names an image that is not there
};

struct LookObjects {
    // Empty when the file is one object (or every name selects all of it): grow on the
    // whole file.
    std::string animal;
    std::vector<LookObject> others;  // disjoint from the animal and from each other
    size_t left_out = 0;  // triangles no object's name selects on its own (not rendered)
};

// Loads `path` and each object it names (at most `max_names`, in file order; names that
// select the whole file are skipped, and so are names overlapping an object already
// taken), and chooses the animal. `up` gives the flat objects' heights.
LookObjects choose_look_objects(const std::string &path, const double up[3],
                                size_t max_names = 64);

}  // namespace pelage::renderer
