// Issue 57: "the rendered patch hue under look's light is within a stated distance of
// the preset's colour, measured from the type mattes". `pelage bench preset-colour`
// calibrates each type's colour under look's sun and sky by a grey render of the same
// scene and reports CIE 1976 ΔE*ab against the preset. One preset (snow-leopard: a
// near-black, a pale and a mid type), on a sphere, at 640x360 and 2 spp, about 5 s per
// skin; the whole list is the benchmark's (docs/guide/look.md), not CI's.
//
// The stated distance: ΔE*ab at most 2.3 (a just noticeable difference) for every type,
// over at least 50 pixels each (those 2 pixels inside the type's matte). A Lambertian
// skin meets it: 1.2 on the near-black rims, the most sensitive to light from their
// pale neighbours, 0.1 on the others (measured with the HEAD of 2 Dec 2026 by the same
// steps); a glossy coat does not (its reflection of the sky lifts the rims
// towards grey, ΔE 5.7), which the second test checks the measurement sees.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

nlohmann::json bench(const std::string &skin) {
    std::string out, err;
    EXPECT_EQ(run_pelage("bench preset-colour --presets snow-leopard --mesh "
                         "procedural:sphere:24x24 --res 640x360 --spp 2 --threads 2" +
                             skin,
                         &out, &err),
              0)
        << err;
    const auto j = nlohmann::json::parse(out, nullptr, false);
    EXPECT_TRUE(j.is_object()) << out;
    return j;
}

// The types of the one preset measured, each with enough pixels to mean something.
nlohmann::json measured_types(const nlohmann::json &j) {
    if (!j.is_object() || j["presets"].size() != 1) return nlohmann::json::array();
    const nlohmann::json &types = j["presets"][0]["types"];
    EXPECT_EQ(types.size(), 3u) << types.dump();
    for (const auto &t : types) EXPECT_GE(t["pixels"].get<int>(), 50) << t.dump();
    return types;
}

TEST(PresetColourCli, LooksSkinShowsEachTypesColourWithinAJustNoticeableDifference) {
    const nlohmann::json j = bench("");
    for (const auto &t : measured_types(j))
        EXPECT_LE(t.value("delta_e76", 1e9), 2.3) << t.dump();
}

TEST(PresetColourCli, TheMeasurementTellsAMatteSkinFromAGlossyCoat) {
    auto rim = [](const nlohmann::json &types) {
        for (const auto &t : types)
            if (t["type"] == "F") return t.value("delta_e76", -1.0);
        return -1.0;
    };
    const nlohmann::json matte = measured_types(bench(" --bsdf lambert"));
    for (const auto &t : matte) EXPECT_LE(t.value("delta_e76", 1e9), 2.3) << t.dump();
    // The coat reflects a few per cent of the sky and sun: over a rim of albedo 0.03
    // that lifts what the eye sees by about half (ΔE 5.7 against the matte's 1.2).
    const nlohmann::json coated = measured_types(bench(" --bsdf coated"));
    EXPECT_GT(rim(coated), 4.0) << coated.dump();
    EXPECT_GT(rim(coated), rim(matte) + 3.0) << coated.dump() << "\n" << matte.dump();
}

}  // namespace
}  // namespace pelage::test
