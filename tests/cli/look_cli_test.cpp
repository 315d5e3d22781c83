// `pelage look MESH`: a picture of any mesh whatever its units, the scene it writes
// renders again from anywhere, fur scaled to the animal, bad input refused before any
// file is written.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sim/mesh/mesh_load.h"
#include "tests/renderer/animation/skinned_strip.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

// The pixel box of object 0 (the animal) in the EXR's id.object layer, as fractions of
// the image: {x0, y0, x1, y1}; all −1 when it is nowhere.
std::array<double, 4> animal_box(const std::string &exr) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) return {-1, -1, -1, -1};
    const OIIO::ImageSpec &s = in->spec();
    const int c = s.channelindex("id.object");
    if (c < 0) return {-1, -1, -1, -1};
    std::vector<float> id(size_t(s.width) * s.height);
    in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, id.data());
    int x0 = s.width, y0 = s.height, x1 = -1, y1 = -1;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x)
            if (id[size_t(y) * s.width + x] == 0) {
                x0 = std::min(x0, x);
                y0 = std::min(y0, y);
                x1 = std::max(x1, x);
                y1 = std::max(y1, y);
            }
    if (x1 < 0) return {-1, -1, -1, -1};
    return {double(x0) / s.width, double(y0) / s.height, double(x1 + 1) / s.width,
            double(y1 + 1) / s.height};
}

// Framed: inside the image with a margin, and filling it along one side.
void expect_framed(const std::string &exr, const std::string &what) {
    const auto b = animal_box(exr);
    ASSERT_GE(b[0], 0) << what << ": the animal is not in the picture";
    for (int k = 0; k < 2; ++k) {
        EXPECT_GT(b[k], 0.01) << what;
        EXPECT_LT(b[k + 2], 0.99) << what;
    }
    EXPECT_GT(std::max(b[2] - b[0], b[3] - b[1]), 0.75) << what << ": framed too loosely";
}

TEST(LookCli, FramesMeshesOfAnyUnitsAndWritesAReusableScene) {
    // The elk is in the hundreds of units, the cow about one unit long.
    for (const std::string name : {"elk", "cow"}) {
        TempDir tmp;
        const std::string out = tmp.file(name + ".exr");
        std::string stdout_text, err;
        ASSERT_EQ(
            run_pelage("look " + sample_mesh(name + ".off") + " --preset " +
                           two_type_preset(tmp, 400) + " --res 96x54 --spp 2 -o " + out,
                       &stdout_text, &err),
            0)
            << err;
        for (const char *ext : {".exr", ".json", ".cells", "_preview.png"})
            EXPECT_TRUE(fs::exists(tmp.file(name + ext))) << name << ext;
        expect_framed(out, name);
        // A matte skin, not a plastic coat (docs/guide/look.md#the-skin).
        const auto scene = nlohmann::json::parse(std::ifstream(tmp.file(name + ".json")));
        EXPECT_EQ(scene["objects"][0]["material"].value("bsdf", ""), "lambert") << name;
        EXPECT_FALSE(scene["objects"][0]["material"].contains("roughness")) << name;

        // The scene names its cells and outputs relative to itself: copied with its
        // cells elsewhere, it renders from any working folder without growing again.
        TempDir moved;
        fs::copy_file(tmp.file(name + ".json"), moved.file("scene.json"));
        fs::copy_file(tmp.file(name + ".cells"), moved.file(name + ".cells"));
        ASSERT_EQ(run_pelage("render " + moved.file("scene.json"), &stdout_text, &err), 0)
            << err;
        EXPECT_EQ(err.find("growing"), std::string::npos) << err;
        EXPECT_TRUE(fs::exists(moved.file(name + ".exr")));
        EXPECT_TRUE(fs::exists(moved.file(name + "_preview.png")));
        expect_framed(moved.file(name + ".exr"), name + " moved");
    }
}

TEST(LookCli, FurStrandCountDoesNotDependOnTheUnits) {
    std::vector<double> strands;
    for (const std::string name : {"elk", "cow"}) {
        TempDir tmp;
        std::string err;
        ASSERT_EQ(run_pelage("look " + sample_mesh(name + ".off") + " --preset " +
                                 two_type_preset(tmp, 400) +
                                 " --fur -q --res 32x18 --spp 1 -o " + tmp.file("a.exr") +
                                 " --stats-json " + tmp.file("s.json"),
                             nullptr, &err),
                  0)
            << err;
        const auto s = nlohmann::json::parse(std::ifstream(tmp.file("s.json")));
        strands.push_back(s.value("fur_strands", 0.0));
    }
    // Both near the shipped cow's 300 000 strands per unit of (radius / 0.608)²; the
    // elk's body has its own proportions, so only the order of magnitude must agree.
    for (const double n : strands) {
        EXPECT_GT(n, 5e4);
        EXPECT_LT(n, 2e6);
    }
}

// A file as they come: an animal, a floor larger than it and an eye of its own. The
// pattern grows on the animal (the largest object that is not flat), named on stderr;
// the others render as they are, the file's floor under the animal standing for the
// ground; the camera frames the animal.
TEST(LookCli, AFileOfSeveralObjectsGrowsThePatternOnTheAnimal) {
    TempDir tmp;
    const sim::TriangleMesh body = sim::load_mesh("procedural:icosphere:2");
    const sim::TriangleMesh eye = sim::load_mesh("procedural:icosphere:1");
    double lowest = 0;
    for (const sim::Vec3d &p : body.positions) lowest = std::min(lowest, p.y);
    std::ostringstream obj;
    obj.precision(17);
    for (const sim::Vec3d &p : body.positions)
        obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (const sim::Vec3d &p : eye.positions)
        obj << "v " << 0.1 * p.x + 1.05 << " " << 0.1 * p.y + 0.3 << " " << 0.1 * p.z
            << "\n";
    obj << "v -3 " << lowest << " -3\nv 3 " << lowest << " -3\nv 3 " << lowest
        << " 3\nv -3 " << lowest << " 3\n";
    const size_t nb = body.num_vertices(), ne = eye.num_vertices();
    obj << "o floor\nf " << nb + ne + 1 << " " << nb + ne + 4 << " " << nb + ne + 3 << " "
        << nb + ne + 2 << "\n";
    obj << "o body\n";
    for (const auto &t : body.triangles)
        obj << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    obj << "o eye\n";
    for (const auto &t : eye.triangles)
        obj << "f " << t[0] + nb + 1 << " " << t[1] + nb + 1 << " " << t[2] + nb + 1
            << "\n";
    const std::string file = tmp.write("animal.obj", obj.str());
    const std::string out = tmp.file("animal.exr");
    std::string stdout_text, err;
    ASSERT_EQ(run_pelage("look " + file + " --preset " + two_type_preset(tmp, 400) +
                             " --res 96x54 --spp 2 -o " + out,
                         &stdout_text, &err),
              0)
        << err;
    EXPECT_NE(err.find("growing the pattern on \"body\""), std::string::npos) << err;
    std::ifstream in(tmp.file("animal.json"));
    const nlohmann::json scene = nlohmann::json::parse(in);
    std::map<std::string, std::string> shader_of;
    for (const auto &o : scene["objects"]) {
        const std::string mesh = o["mesh"];
        shader_of[mesh.substr(mesh.find('#') + 1)] = o["material"]["shader"];
    }
    EXPECT_EQ(scene["objects"][0]["mesh"], "animal.obj#body");
    EXPECT_EQ(shader_of["body"], "clonal_mosaic");
    EXPECT_EQ(shader_of["floor"], "diffuse");
    EXPECT_EQ(shader_of["eye"], "diffuse");
    EXPECT_EQ(shader_of.size(), 3u) << "the file's floor stands for the ground";
    expect_framed(out, "the body");
}

// The pixels of an EXR's R, G, B channels.
std::vector<float> rgb_pixels(const std::string &exr) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    std::vector<float> px(size_t(s.width) * s.height * 3);
    in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, px.data());
    return px;
}

TEST(LookCli, PlaysAClipFramedOnEveryPose) {
    // The strip's tip turns 160° between frames 0 and 24: a camera framed on the rest
    // pose alone would lose it.
    TempDir tmp;
    const std::string mesh = tmp.write("strip.gltf", skinned_strip());
    std::string err;
    ASSERT_EQ(run_pelage("look " + mesh + " --clip bend --frames 0-24x12 --res 96x54 " +
                             "--spp 2 --shutter 0.5 -o " + tmp.file("strip.exr"),
                         nullptr, &err),
              0)
        << err;
    // The pattern grown on a finer copy of the strip says so once, not once per frame.
    size_t notes = 0;
    for (size_t at = 0; (at = err.find("was grown on ", at)) != std::string::npos; ++at)
        ++notes;
    EXPECT_EQ(notes, 1u) << err;
    for (const std::string f : {"0000", "0012", "0024"}) {
        const auto b = animal_box(tmp.file("strip." + f + ".exr"));
        ASSERT_GE(b[0], 0) << "frame " << f << ": the strip is not in the picture";
        for (int k = 0; k < 2; ++k) {
            EXPECT_GT(b[k], 0.01) << "frame " << f;
            EXPECT_LT(b[k + 2], 0.99) << "frame " << f;
        }
    }
    // The scene plays the clip, and renders a frame again to the same pixels.
    std::ifstream scene_file(tmp.file("strip.json"));
    const nlohmann::json scene = nlohmann::json::parse(scene_file);
    EXPECT_EQ(scene["objects"][0]["animation"]["clip"], "bend");
    // The file's other object (the joints' subtree, which holds the triangle on the tip
    // joint) goes with it.
    EXPECT_EQ(scene["objects"][1]["name"], "root");
    EXPECT_EQ(scene["objects"][1]["animation"]["clip"], "bend");
    EXPECT_EQ(scene["animation"]["frames"], 25);
    EXPECT_EQ(scene["animation"]["shutter"], nlohmann::json({0.0, 0.5}));  // blurred
    ASSERT_EQ(run_pelage("render " + tmp.file("strip.json") + " --frames 12 -q -o " +
                             tmp.file("again.####.exr"),
                         nullptr, &err),
              0)
        << err;
    const std::vector<float> first = rgb_pixels(tmp.file("strip.0012.exr"));
    ASSERT_FALSE(first.empty());
    EXPECT_EQ(first, rgb_pixels(tmp.file("again.0012.exr")));
    EXPECT_NE(first, rgb_pixels(tmp.file("strip.0000.exr")));  // it does move
    // The coat stays on the skin over the whole clip; a pattern in space swims.
    ASSERT_EQ(run_pelage("compare " + tmp.file("strip.json") +
                             " --deform --lookups 2000 --shaders clonal_mosaic,perlin "
                             "--stats-json " +
                             tmp.file("drift.json"),
                         nullptr, &err),
              0)
        << err;
    std::ifstream drift_file(tmp.file("drift.json"));
    const nlohmann::json drift = nlohmann::json::parse(drift_file)["pattern_drift"];
    EXPECT_EQ(drift["clonal_mosaic"]["max"].get<double>(), 0.0);
    EXPECT_GT(drift["perlin"]["mean"].get<double>(), 0.01);
    EXPECT_EQ(drift["perlin"]["points"], 2000 * 8);  // eight times over the clip

    // A clip the file does not have, and frames without a clip: exit 2, nothing written.
    TempDir bad;
    const std::string out = bad.file("x.exr");
    EXPECT_EQ(run_pelage("look " + mesh + " --clip walk -o " + out, nullptr, &err), 2);
    EXPECT_NE(err.find("\"bend\", \"still\""), std::string::npos) << err;
    EXPECT_EQ(run_pelage("look " + mesh + " --frames 0-3 -o " + out, nullptr, &err), 2);
    EXPECT_NE(err.find("--clip"), std::string::npos) << err;
    EXPECT_TRUE(fs::is_empty(bad.path()));
}

// The file's bytes, "" when it cannot be read.
std::string file_bytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(LookCli, ASecondLookReusesItsCellsAndAChangedRecipeGrowsThemAgain) {
    TempDir tmp;
    const std::string preset = two_type_preset(tmp, 300);
    const std::string look = "look procedural:sphere:12x12 --res 32x18 --spp 1 -o " +
                             tmp.file("ball.exr") + " --preset " + preset;
    const std::string cells = tmp.file("ball.cells");
    std::string out, err;
    ASSERT_EQ(run_pelage(look, &out, &err), 0) << err;
    EXPECT_NE(err.find("ball.cells: no file, growing"), std::string::npos) << err;
    const std::string first = file_bytes(cells);
    ASSERT_FALSE(first.empty());
    const auto first_time = fs::last_write_time(cells);

    // The same mesh, preset and seed: the file is used as it is, and the user is told.
    ASSERT_EQ(run_pelage(look, &out, &err), 0) << err;
    EXPECT_EQ(err.find("growing"), std::string::npos) << err;
    EXPECT_NE(err.find("ball.cells: grown from the same mesh, preset and seed; reused"),
              std::string::npos)
        << err;
    EXPECT_EQ(fs::last_write_time(cells), first_time);
    EXPECT_EQ(file_bytes(cells), first);

    // Another seed, then another preset (by content): grown again, saying which.
    ASSERT_EQ(run_pelage(look + " --seed 2", &out, &err), 0) << err;
    EXPECT_NE(err.find("ball.cells: grown with another seed, growing"), std::string::npos)
        << err;
    const std::string reseeded = file_bytes(cells);
    EXPECT_NE(reseeded, first);
    two_type_preset(tmp, 200);
    ASSERT_EQ(run_pelage(look + " --seed 2", &out, &err), 0) << err;
    EXPECT_NE(err.find("ball.cells: grown from another preset, growing"),
              std::string::npos)
        << err;
    EXPECT_NE(file_bytes(cells), reseeded);
}

TEST(LookCli, BadInputWritesNothing) {
    TempDir tmp;
    const std::string out = tmp.file("x.exr");
    std::string err;
    EXPECT_EQ(run_pelage("look " + tmp.file("missing.off") + " -o " + out, nullptr, &err),
              2);
    EXPECT_NE(err.find("missing.off"), std::string::npos) << err;
    EXPECT_EQ(
        run_pelage("look " + sample_mesh("cow.off") + " --up w -o " + out, nullptr, &err),
        2);
    EXPECT_NE(err.find("--up"), std::string::npos) << err;
    EXPECT_EQ(run_pelage("look " + sample_mesh("cow.off") + " -o " + tmp.file("x.png"),
                         nullptr, &err),
              2);
    EXPECT_EQ(run_pelage(
                  "look " + sample_mesh("cow.off") + " --preset no-such-preset -o " + out,
                  nullptr, &err),
              2);
    EXPECT_NE(err.find("no-such-preset"), std::string::npos) << err;
    EXPECT_TRUE(fs::is_empty(tmp.path()));
}

}  // namespace
}  // namespace pelage::test
