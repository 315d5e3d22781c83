// `pelage presets` lists every shipped preset (the files of scenes/presets, listed here
// on their own) with the file's own animal, description and source, and the animals of
// issue 57 each have one; a mistyped name is exit 2 naming the closest preset, on the
// command line and at its JSON path in a scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

TEST(PresetsCli, ListsEveryShippedPresetWithItsOwnDescription) {
    std::set<std::string> files;
    const std::string dir = std::string(PELAGE_SOURCE_DIR) + "/scenes/presets";
    for (const auto &e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".json") files.insert(e.path().stem().string());
    ASSERT_GE(files.size(), 20u);
    std::string out, err;
    ASSERT_EQ(run_pelage("presets --json", &out, &err), 0) << err;
    const nlohmann::json j = nlohmann::json::parse(out);
    std::set<std::string> listed;
    for (const nlohmann::json &p : j["presets"]) {
        const std::string name = p["name"];
        listed.insert(name);
        std::ifstream in(dir + "/" + name + ".json");
        const nlohmann::json file = nlohmann::json::parse(in);
        EXPECT_EQ(p["description"], file["description"]) << name;
        EXPECT_EQ(p["source"], file.value("source", "")) << name;
        EXPECT_EQ(p["animal"], file.value("animal", "")) << name;
        EXPECT_EQ(p["extends"], file.value("extends", "")) << name;
        EXPECT_FALSE(p["description"].get<std::string>().empty()) << name;
    }
    EXPECT_EQ(listed, files);
    // Issue 57's animals each have a preset naming its animal and its colours' source.
    for (const char *animal :
         {"leopard", "snow-leopard", "cheetah", "jaguar", "serval", "ocelot", "puma",
          "lion", "tiger", "zebra", "plains-zebra", "giraffe-reticulata",
          "giraffe-tippelskirchi", "giraffe-rothschildi", "holstein-cow"}) {
        bool found = false;
        for (const nlohmann::json &p : j["presets"])
            if (p["name"] == animal) {
                found = true;
                EXPECT_FALSE(p["animal"].get<std::string>().empty()) << animal;
                EXPECT_FALSE(p["source"].get<std::string>().empty()) << animal;
            }
        EXPECT_TRUE(found) << animal;
    }
    // The text form names each one on a line of its own.
    ASSERT_EQ(run_pelage("presets", &out, &err), 0) << err;
    for (const std::string &name : files)
        EXPECT_NE(("\n" + out).find("\n" + name + "\n"), std::string::npos) << name;
    EXPECT_NE(out.find("\nsnow-leopard\n  animal: snow leopard (Panthera uncia)\n"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("  extends: teo-leopard (its cells, with these colours)\n"),
              std::string::npos)
        << out;
}

TEST(PresetsCli, AMistypedNameNamesTheClosestPresetWhereItWasGiven) {
    std::string out, err;
    EXPECT_EQ(run_pelage("presets girafe-reticulata", &out, &err), 2);
    EXPECT_NE(err.find("NAME: unknown preset 'girafe-reticulata' (did you mean "
                       "'giraffe-reticulata'?)"),
              std::string::npos)
        << err;
    TempDir tmp;
    EXPECT_EQ(run_pelage("sim --mesh procedural:sphere:8x8 --preset teo-leapard -q -o " +
                             tmp.file("x.cells"),
                         &out, &err),
              2);
    EXPECT_NE(err.find("--preset: unknown preset 'teo-leapard' (did you mean "
                       "'teo-leopard'?)"),
              std::string::npos)
        << err;
    const std::string scene = tmp.write("s.json", R"({
        "camera": {},
        "objects": [{"mesh": "procedural:sphere:8x8", "cells": "s.cells",
                     "pattern": {"preset": "zebar"},
                     "material": {"shader": "clonal_mosaic"}}]
    })");
    EXPECT_EQ(run_pelage("render " + scene + " -q -o " + tmp.file("s.exr"), &out, &err),
              2);
    EXPECT_NE(err.find(scene + ": objects[0].pattern.preset: unknown preset 'zebar' "
                               "(did you mean 'zebra'?)"),
              std::string::npos)
        << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("s.exr")));
}

}  // namespace
}  // namespace pelage::test
