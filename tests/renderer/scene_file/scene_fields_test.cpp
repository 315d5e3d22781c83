// renderer/scene_file/scene_fields: the reference tables of docs/guide/scene-format.md
// and fur.md are the field table's; every declared field is one the parser reads; an
// unknown key is named with the closest declared one; and the files a scene's input
// fields name are what it records as its inputs, outputs left out.
#include "renderer/scene_file/scene_fields.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "renderer/scene_file/scene_file.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {
namespace {

std::string read_text(const std::string &path) {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(SceneFields, TheGuidesTablesAreTheFieldTable) {
    ASSERT_GE(scene_field_tables().size(), 9u);
    for (const std::string &table : scene_field_tables()) {
        const std::string page = scene_field_page(table);
        const std::string doc = read_text(std::string(PELAGE_SOURCE_DIR) + "/" + page);
        ASSERT_FALSE(doc.empty()) << page;
        const std::string begin = "<!-- BEGIN generated: fields-" + table + " -->";
        const std::string end = "<!-- END generated: fields-" + table + " -->";
        const size_t a = doc.find(begin);
        ASSERT_NE(a, std::string::npos) << "no table " << table << " in the guide";
        const size_t from = doc.find('\n', a) + 1;
        const size_t b = doc.find(end, from);
        ASSERT_NE(b, std::string::npos) << table;
        EXPECT_EQ(doc.substr(from, b - from), scene_fields_markdown(table))
            << page << "'s " << table
            << " table differs from scene_fields.cpp: regenerate it with "
               "python3 docs/tools/make_tables.py";
    }
}

TEST(SceneFields, EveryDeclaredFieldIsReadByTheParser) {
    // The parser refuses to read an undeclared key (a logic_error); the other way, a
    // declared key no reader asks for would be "unknown" in every scene. Each key is
    // asked for by name in the parser's source.
    const std::string dir = std::string(PELAGE_SOURCE_DIR) + "/renderer/scene_file/";
    const std::string src =
        read_text(dir + "scene_file.cpp") + read_text(dir + "scene_fur.cpp");
    ASSERT_FALSE(src.empty());
    for (const SceneField &f : scene_fields()) {
        // A groom's KEY_by_type is asked for as KEY + "_by_type".
        std::string key(f.key);
        if (const size_t by = key.rfind("_by_type");
            by != std::string::npos && f.block == "objects.fur")
            key = key.substr(0, by);
        EXPECT_NE(src.find("\"" + key + "\""), std::string::npos)
            << f.block << "." << f.key;
    }
}

std::string error_of(const std::string &text) {
    try {
        parse_scene(text, "/tmp/s.json");
    } catch (const InputError &e) {
        return e.what();
    }
    return "";
}

TEST(SceneFields, AnUnknownKeyIsNamedWithTheClosestField) {
    const std::string base = R"("objects": [{"mesh": "procedural:sphere"}])";
    EXPECT_NE(error_of(R"({"camera": {"fvo": 40}, )" + base + "}")
                  .find("camera.fvo: unknown field (did you mean \"fov\"?)"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"camera": {}, "objects": [{"mesh": "procedural:sphere", )"
                       R"("materail": {}}]})")
                  .find("objects[0].materail: unknown field (did you mean "
                        "\"material\"?)"),
              std::string::npos);
    // Nothing close: no guess.
    const std::string far = error_of(R"({"camera": {"zzzzzz": 1}, )" + base + "}");
    EXPECT_NE(far.find("camera.zzzzzz: unknown field"), std::string::npos);
    EXPECT_EQ(far.find("did you mean"), std::string::npos);
}

TEST(SceneFields, InputFieldsAreTheScenesInputs) {
    const SceneDesc d = parse_scene(R"({
        "camera": {},
        "film": {"output": "out.exr", "preview": "out.png"},
        "lights": [{"type": "environment", "image": "sky.exr"}],
        "objects": [
            {"mesh": "cow.obj", "cells": "cow.cells", "deform": ["a.obj", "b.ply#leg"]},
            {"mesh": "procedural:sphere"},
            {"mesh": "zoo.glb#giraffe", "cells": "g.cells",
             "pattern": {"preset": "presets/mine.json"}}
        ],
        "animation": {"frames": 2}
    })",
                                    "/scenes/s.json");
    std::vector<std::pair<std::string, std::string>> got;
    for (const SceneDesc::InputFile &in : d.inputs) got.push_back({in.field, in.path});
    const std::vector<std::pair<std::string, std::string>> want = {
        {"lights[0].image", "/scenes/sky.exr"},
        {"objects[0].mesh", "/scenes/cow.obj"},
        {"objects[0].cells", "/scenes/cow.cells"},
        {"objects[0].deform[0]", "/scenes/a.obj"},
        {"objects[0].deform[1]", "/scenes/b.ply"},
        {"objects[2].mesh", "/scenes/zoo.glb"},
        {"objects[2].cells", "/scenes/g.cells"},
        {"objects[2].pattern.preset", "/scenes/presets/mine.json"},
    };
    EXPECT_EQ(got, want);
}

}  // namespace
}  // namespace pelage::renderer
