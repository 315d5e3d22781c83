#include "tests/renderer/animation/skinned_strip.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <vector>

#include "tests/renderer/animation/gltf_builder.h"

namespace pelage::test {

std::string skinned_strip(double weight_scale) {
    GltfBuilder b;
    std::vector<float> pos, joints_w, morph;
    std::vector<uint16_t> idx;
    std::vector<uint8_t> joints;
    const int columns = 9;
    for (int c = 0; c < columns; ++c)
        for (int r = 0; r < 2; ++r) {
            const float x = 4.0f * float(c) / float(columns - 1), y = 0.5f * float(r);
            pos.insert(pos.end(), {x, y, 0});
            const float w = std::clamp((x - 1) / 2, 0.0f, 1.0f);
            joints.insert(joints.end(), {0, 1, 0, 0});
            joints_w.insert(joints_w.end(), {float(weight_scale) * (1 - w),
                                             float(weight_scale) * w, 0, 0});
            morph.insert(morph.end(), {0, 0, x >= 3 ? 0.5f : 0.0f});
        }
    for (int c = 0; c + 1 < columns; ++c) {
        const uint16_t a = uint16_t(2 * c), d = uint16_t(a + 1), e = uint16_t(a + 2),
                       f = uint16_t(a + 3);
        idx.insert(idx.end(), {a, e, d, d, e, f});
    }
    const int p = b.add(pos, "VEC3", true);
    const int m = b.add(morph, "VEC3", true);
    const int jw = b.add(joints_w, "VEC4");
    const int j = b.add_raw(std::string(joints.begin(), joints.end()), 5121, "VEC4",
                            joints.size() / 4, nullptr);
    const int i = b.add_u16(idx, "SCALAR", idx.size());
    const std::vector<float> ear_pos = {0, 0, 0, 0.4f, 0, 0, 0, 0.3f, 0.2f};
    const int ep = b.add(ear_pos, "VEC3", true);
    const int ei = b.add_u16({0, 1, 2}, "SCALAR", 3);
    // Inverse bind matrices (column-major): the root at the origin, the tip at x = 2.
    const int ibm = b.add({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,  0, 0, 1,  //
                           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -2, 0, 0, 1},
                          "MAT4");
    const int times = b.add({0, 1, 2}, "SCALAR");
    const float s80 = std::sin(80 * 3.14159265f / 180),
                c80 = std::cos(80 * 3.14159265f / 180);
    const float s20 = std::sin(20 * 3.14159265f / 180),
                c20 = std::cos(20 * 3.14159265f / 180);
    const int tip_rot = b.add({0, 0, 0, 1, 0, 0, s80, c80, 0, 0, s20, c20}, "VEC4");
    const int root_pos = b.add({0, 0, 0, 0.5f, 0.25f, 0, 1, 0.5f, 0}, "VEC3");
    const int morph_w = b.add({0, 0.3f, 1}, "SCALAR");
    const int one_time = b.add({0}, "SCALAR");
    const int one_pos = b.add({0, 0, 0}, "VEC3");
    const int roll_times = b.add({0, 1}, "SCALAR");
    const float r45 = std::sqrt(0.5f);
    const int roll = b.add({0, 0, 0, 1, r45, 0, 0, r45}, "VEC4");  // 0°, then 90° about x
    b.doc["meshes"] = json::array(
        {{{"name", "strip"},
          {"weights", {0.0}},
          {"primitives",
           {{{"attributes", {{"POSITION", p}, {"JOINTS_0", j}, {"WEIGHTS_0", jw}}},
             {"indices", i},
             {"targets", {{{"POSITION", m}}}}}}}},
         {{"name", "ear"},
          {"primitives", {{{"attributes", {{"POSITION", ep}}}, {"indices", ei}}}}}});
    b.doc["nodes"] =
        json::array({{{"name", "strip"}, {"mesh", 0}, {"skin", 0}},
                     {{"name", "root"}, {"children", {2}}},
                     {{"name", "tip"}, {"translation", {2, 0, 0}}, {"children", {3}}},
                     {{"name", "ear"}, {"mesh", 1}, {"translation", {0.5, 0, 0}}}});
    b.doc["skins"] = json::array({{{"joints", {1, 2}}, {"inverseBindMatrices", ibm}}});
    b.doc["scenes"] = json::array({{{"nodes", {0, 1}}}});
    b.doc["scene"] = 0;
    b.doc["animations"] = json::array(
        {{{"name", "bend"},
          {"samplers",
           {{{"input", times}, {"output", tip_rot}},
            {{"input", times}, {"output", root_pos}},
            {{"input", times}, {"output", morph_w}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}},
            {{"sampler", 1}, {"target", {{"node", 1}, {"path", "translation"}}}},
            {{"sampler", 2}, {"target", {{"node", 0}, {"path", "weights"}}}}}}},
         {{"name", "still"},
          {"samplers", {{{"input", one_time}, {"output", one_pos}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}}},
         {{"name", "roll"},
          {"samplers", {{{"input", roll_times}, {"output", roll}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}});
    return b.text();
}

}  // namespace pelage::test
