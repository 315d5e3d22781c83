#include "tests/renderer/animation/moving_plate.h"

#include <cmath>
#include <vector>

#include "tests/renderer/animation/gltf_builder.h"

namespace pelage::test {
namespace {

// A rectangle [x0, x1] × [y0, y1] at z = 0 on node "mover", animated by one clip of two
// keys (t = 0 and 1 s) on `path` ("translation" or "rotation") with `values`.
std::string moving_rectangle(float x0, float x1, float y0, float y1, const char *clip,
                             const char *path, const std::vector<float> &values,
                             const char *type) {
    GltfBuilder b;
    const std::vector<float> pos = {x0, y0, 0, x1, y0, 0, x1, y1, 0, x0, y1, 0};
    const int p = b.add(pos, "VEC3", true);
    const int i = b.add_u16({0, 1, 2, 0, 2, 3}, "SCALAR", 6);
    const int times = b.add({0, 1}, "SCALAR");
    const int out = b.add(values, type);
    b.doc["meshes"] = json::array(
        {{{"name", "plate"},
          {"primitives", {{{"attributes", {{"POSITION", p}}}, {"indices", i}}}}}});
    b.doc["nodes"] = json::array({{{"name", "mover"}, {"mesh", 0}}});
    b.doc["scenes"] = json::array({{{"nodes", {0}}}});
    b.doc["scene"] = 0;
    b.doc["animations"] = json::array(
        {{{"name", clip},
          {"samplers", {{{"input", times}, {"output", out}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", path}}}}}}}});
    return b.text();
}

}  // namespace

std::string sliding_plate() {
    return moving_rectangle(-1, 1, -2, 2, "slide", "translation", {0, 0, 0, 2, 0, 0},
                            "VEC3");
}

std::string spinning_bar() {
    const float s = std::sqrt(0.5f);  // 90° about z: (0, 0, sin 45°, cos 45°)
    return moving_rectangle(0, 3, -0.1f, 0.1f, "spin", "rotation",
                            {0, 0, 0, 1, 0, 0, s, s}, "VEC4");
}

}  // namespace pelage::test
