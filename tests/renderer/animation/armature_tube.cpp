#include "tests/renderer/animation/armature_tube.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tests/renderer/animation/gltf_builder.h"

namespace pelage::test {

std::string armature_tube(int around, int along) {
    GltfBuilder b;
    std::vector<float> pos, nrm, weights;
    std::vector<uint8_t> joints;
    std::vector<uint16_t> idx;
    const double pi = 3.14159265358979;
    for (int r = 0; r <= along; ++r)
        for (int c = 0; c < around; ++c) {
            const double a = 2 * pi * c / around;
            const float y = float(armature_tube_height * r / along);
            pos.insert(pos.end(), {float(armature_tube_radius * std::cos(a)), y,
                                   float(armature_tube_radius * std::sin(a))});
            nrm.insert(nrm.end(), {float(std::cos(a)), 0, float(std::sin(a))});
            const float w = std::clamp((y - 0.5f) / 0.5f, 0.0f, 1.0f);
            joints.insert(joints.end(), {0, 1, 0, 0});
            weights.insert(weights.end(), {1 - w, w, 0, 0});
        }
    // Counter-clockwise seen from outside: outward faces.
    for (int r = 0; r < along; ++r)
        for (int c = 0; c < around; ++c) {
            const auto v = [&](int rr, int cc) {
                return uint16_t(rr * around + (cc % around));
            };
            idx.insert(idx.end(), {v(r, c), v(r + 1, c), v(r, c + 1), v(r, c + 1),
                                   v(r + 1, c), v(r + 1, c + 1)});
        }
    const int p = b.add(pos, "VEC3", true);
    const int n = b.add(nrm, "VEC3");
    const int jw = b.add(weights, "VEC4");
    const int j = b.add_raw(std::string(joints.begin(), joints.end()), 5121, "VEC4",
                            joints.size() / 4, nullptr);
    const int i = b.add_u16(idx, "SCALAR", idx.size());
    // The armature A = R(−90° about x) · 0.01, so A⁻¹ = 100 · R(90° about x): (x, y, z)
    // ↦ 100 (x, −z, y). hips' global bind transform is A, spine's A · T(0, 0, 75);
    // their inverses, column-major.
    const int ibm = b.add({100, 0, 0, 0, 0, 0, 100, 0, 0, -100, 0, 0, 0, 0, 0,   1,  //
                           100, 0, 0, 0, 0, 0, 100, 0, 0, -100, 0, 0, 0, 0, -75, 1},
                          "MAT4");
    const float h = float(std::sqrt(0.5));
    const float s15 = float(std::sin(15 * pi / 180)),
                c15 = float(std::cos(15 * pi / 180));
    const int times = b.add({0, 1}, "SCALAR");
    const int sway = b.add({0, 0, 0, 1, s15, 0, 0, c15}, "VEC4");  // 0°, then 30° about x
    b.doc["meshes"] = json::array(
        {{{"name", "tube"},
          {"primitives",
           {{{"attributes",
              {{"POSITION", p}, {"NORMAL", n}, {"JOINTS_0", j}, {"WEIGHTS_0", jw}}},
             {"indices", i}}}}}});
    b.doc["nodes"] = json::array({{{"name", "Armature"},
                                   {"rotation", {-h, 0, 0, h}},
                                   {"scale", {0.01, 0.01, 0.01}},
                                   {"children", {1, 2}}},
                                  {{"name", "body"}, {"mesh", 0}, {"skin", 0}},
                                  {{"name", "hips"}, {"children", {3}}},
                                  {{"name", "spine"}, {"translation", {0, 0, 75}}}});
    b.doc["skins"] = json::array(
        {{{"joints", {2, 3}}, {"inverseBindMatrices", ibm}, {"skeleton", 2}}});
    b.doc["scenes"] = json::array({{{"nodes", {0}}}});
    b.doc["scene"] = 0;
    b.doc["animations"] = json::array(
        {{{"name", "Sway"},
          {"samplers", {{{"input", times}, {"output", sway}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", 3}, {"path", "rotation"}}}}}}}});
    return b.text();
}

}  // namespace pelage::test
