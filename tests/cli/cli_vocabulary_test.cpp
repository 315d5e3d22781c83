// One command-line vocabulary across the subcommands: `--res WxH` is accepted wherever
// there is a resolution, `-q` leaves standard output empty, `--stats-json` is written,
// and `colour`/`color` both read (docs/guide/compositing-outputs.md, "Options every
// command spells the same").
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

// A light of each kind, `light_colour` spliced into the environment light.
std::string tiny_scene(const std::string &light_colour = R"("colour": [0.5, 0.6, 0.8])",
                       const std::string &material = R"({"shader": "diffuse"})") {
    return R"({"camera": {"position": [0, 0.5, 3], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 20, "height": 14, "spp": 2},
      "lights": [{"type": "environment", )" +
           light_colour + R"(},
                 {"type": "distant", "direction": [-1, -1, -0.5], "colour": 1}],
      "objects": [{"mesh": "procedural:sphere:8x8", "material": )" +
           material + "}]}";
}

// Width and height of an image file (0, 0 when it cannot be read).
std::pair<int, int> image_size(const std::string &path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {0, 0};
    return {in->spec().full_width, in->spec().full_height};
}

std::vector<float> pixels(const std::string &path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return {};
    const OIIO::ImageSpec &s = in->spec();
    std::vector<float> px(size_t(s.width) * s.height * s.nchannels);
    in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, px.data());
    return px;
}

nlohmann::json read_json(const std::string &path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in, nullptr, false);
}

TEST(CliVocabulary, ResTakesWidthXHeightEverywhere) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", tiny_scene());
    // render: the EXR and its preview at exactly that size.
    std::string err;
    ASSERT_EQ(run_pelage("render " + scene + " -q --res 24x10 -o " + tmp.file("r.exr") +
                             " --preview " + tmp.file("r.png"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_EQ(image_size(tmp.file("r.exr")), std::make_pair(24, 10));
    EXPECT_EQ(image_size(tmp.file("r.png")), std::make_pair(24, 10));
    // bench render and bench noise measure at that size.
    std::string out;
    ASSERT_EQ(run_pelage("bench render --scene " + scene +
                             " --res 18x12 --spp 1 --repeat 1 -q --stats-json " +
                             tmp.file("br.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_EQ(out, "");
    const nlohmann::json br = read_json(tmp.file("br.json"));
    EXPECT_EQ(br["width"], 18) << br.dump();
    EXPECT_EQ(br["height"], 12);
    ASSERT_EQ(run_pelage("bench noise " + scene + " --res 12x8 --spp 1 --seeds 1 " +
                             "--reference-spp 4 --cache " + tmp.file("cache") +
                             " -q --stats-json " + tmp.file("bn.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_EQ(out, "");
    const nlohmann::json bn = read_json(tmp.file("bn.json"));
    EXPECT_EQ(bn["width"], 12) << bn.dump();
    EXPECT_EQ(bn["height"], 8);

    ASSERT_EQ(run_pelage("bench fur --strands 50 --segments 2 --res 16x10 --spp 1 -q "
                         "--stats-json " +
                             tmp.file("bf.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_EQ(out, "");
    const nlohmann::json bf = read_json(tmp.file("bf.json"));
    ASSERT_EQ(bf["runs"].size(), 1u) << bf.dump();
    EXPECT_EQ(bf["runs"][0]["width"], 16);
    EXPECT_EQ(bf["runs"][0]["height"], 10);

    // A fixed aspect takes one number; where the aspect is free it is refused, naming
    // --res and the form it takes.
    EXPECT_EQ(run_pelage("render " + scene + " -q --res 24 -o " + tmp.file("x.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("--res: \"24\": expected WIDTHxHEIGHT"), std::string::npos) << err;
    for (const char *bad : {"0x10", "24x", "24x10x2", "abc", "-4x4"}) {
        EXPECT_EQ(run_pelage(
                      "render " + scene + " -q --res " + bad + " -o " + tmp.file("x.exr"),
                      nullptr, &err),
                  2)
            << bad;
        EXPECT_NE(err.find("--res"), std::string::npos) << bad << ": " << err;
    }
    EXPECT_FALSE(std::filesystem::exists(tmp.file("x.exr")));
}

TEST(CliVocabulary, PreviewResIsWidthXHeightOrTheLongerSide) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, "procedural:sphere:8x8", 60);
    std::string err;
    // WxH: exactly that image, whatever the mesh's shape.
    ASSERT_EQ(run_pelage("preview " + cells + " --res 120x50 -o " + tmp.file("a.png"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_EQ(image_size(tmp.file("a.png")), std::make_pair(120, 50));
    // N: the longer side, the other following the mesh (a sphere seen along -z: square).
    ASSERT_EQ(run_pelage("preview " + cells + " --res 90 --direction 0 0 -1 -o " +
                             tmp.file("b.png"),
                         nullptr, &err),
              0)
        << err;
    const auto [w, h] = image_size(tmp.file("b.png"));
    EXPECT_EQ(std::max(w, h), 90);
    EXPECT_GE(std::min(w, h), 85);
    // --direction: another view of the same cells is another picture.
    ASSERT_EQ(run_pelage("preview " + cells + " --res 90 --direction 1 0 0 -o " +
                             tmp.file("c.png"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_NE(pixels(tmp.file("b.png")), pixels(tmp.file("c.png")));
    EXPECT_EQ(
        run_pelage("preview " + cells + " --direction 0 0 0 -o " + tmp.file("d.png"),
                   nullptr, &err),
        2);
    EXPECT_NE(err.find("--direction"), std::string::npos) << err;
}

// --seed is the pattern's seed wherever it is taken; the sampler's is --sampler-seed and
// the random points' --points-seed, and a command of those refuses --seed by name.
TEST(CliVocabulary, SeedIsThePatternsSeedAndOtherSeedsHaveTheirOwnNames) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", tiny_scene());
    std::string out, err;
    for (const char *seed : {"3", "4"})
        ASSERT_EQ(run_pelage("render " + scene + " -q --sampler-seed " + seed + " -o " +
                                 tmp.file(std::string("r") + seed + ".exr"),
                             &out, &err),
                  0)
            << err;
    // The sampler's seed reaches the sampler: 2 spp of another sequence is another
    // image.
    EXPECT_NE(pixels(tmp.file("r3.exr")), pixels(tmp.file("r4.exr")));

    const std::string cells = simulate_two_type_cells(tmp, "procedural:sphere:8x8", 60);
    struct Refused {
        std::string command, args, instead;
    };
    const Refused refused[] = {
        {"render", scene + " -q -o " + tmp.file("x.exr"), "--sampler-seed"},
        {"compare", scene + " -q --shaders worley --lookups 10 --res 8x6",
         "--sampler-seed"},
        {"stats", cells + " -q", "--points-seed"},
        {"crps", "--mesh procedural:sphere:8x8 -q", "--points-seed"},
        {"bench lookup", "--mesh procedural:sphere:8x8 -q", "--points-seed"},
        {"bench hair", "--configs 1 --theta-steps 16 -q", "--sampler-seed"}};
    for (const Refused &r : refused) {
        EXPECT_EQ(run_pelage(r.command + " " + r.args + " --seed 3", &out, &err), 2)
            << r.command;
        EXPECT_NE(err.find("--seed: is the pattern's seed"), std::string::npos)
            << r.command << ": " << err;
        EXPECT_NE(err.find("this command's seed is " + r.instead), std::string::npos)
            << r.command << ": " << err;
        // Hidden from the help, which shows the option to use.
        ASSERT_EQ(run_pelage(r.command + " --help", &out, &err), 0) << r.command;
        EXPECT_EQ(out.find("--seed "), std::string::npos) << r.command << ":\n" << out;
        EXPECT_NE(out.find(r.instead), std::string::npos) << r.command << ":\n" << out;
    }
    EXPECT_FALSE(std::filesystem::exists(tmp.file("x.exr")));
    // Where a pattern is grown, --seed is its seed.
    ASSERT_EQ(run_pelage("sim --help", &out, &err), 0);
    EXPECT_NE(out.find("--seed "), std::string::npos) << out;
}

TEST(CliVocabulary, QuietLeavesStandardOutputEmpty) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", tiny_scene());
    std::string out, err;
    // Without -q each prints a summary; with it, nothing, and the work is still done.
    ASSERT_EQ(run_pelage("render " + scene + " -o " + tmp.file("a.exr"), &out, &err), 0)
        << err;
    EXPECT_NE(out, "");
    ASSERT_EQ(run_pelage("render " + scene + " -q -o " + tmp.file("b.exr"), &out, &err),
              0)
        << err;
    EXPECT_EQ(out, "");
    EXPECT_EQ(pixels(tmp.file("a.exr")), pixels(tmp.file("b.exr")));

    const std::string sim =
        "sim --mesh procedural:sphere:8x8 --preset teo-table-7.2 "
        "--initial-cells 200 -o " +
        tmp.file("c.cells");
    ASSERT_EQ(run_pelage(sim, &out, &err), 0) << err;
    EXPECT_NE(out, "");
    ASSERT_EQ(run_pelage(sim + " --quiet", &out, &err), 0) << err;
    EXPECT_EQ(out, "");
    EXPECT_TRUE(std::filesystem::exists(tmp.file("c.cells")));

    const std::vector<std::string> commands = {"crps --mesh procedural:sphere:8x8",
                                               "stats " + tmp.file("c.cells"),
                                               "bench hair --configs 1 --theta-steps 16"};
    for (const std::string &cmd : commands) {
        ASSERT_EQ(run_pelage(cmd, &out, &err), 0) << cmd << ": " << err;
        EXPECT_NE(out, "") << cmd;
        ASSERT_EQ(run_pelage(cmd + " -q", &out, &err), 0) << cmd << ": " << err;
        EXPECT_EQ(out, "") << cmd;
    }
}

TEST(CliVocabulary, StatsJsonIsWrittenAndItsFolderCheckedFirst) {
    TempDir tmp;
    const std::string cells = simulate_two_type_cells(tmp, "procedural:sphere:8x8", 120);
    const std::string scene = tmp.write(
        "s.json", tiny_scene(R"("colour": 1)",
                             R"({"shader": "clonal_mosaic", "params": {}}, "cells": ")" +
                                 cells + "\""));
    std::string out, err;
    // compare: the report, at the --res asked for.
    ASSERT_EQ(
        run_pelage("compare " + scene +
                       " -q --shaders clonal_mosaic,worley --lookups 500 --res 16x12 "
                       "--stats-json " +
                       tmp.file("cmp.json"),
                   &out, &err),
        0)
        << err;
    EXPECT_EQ(out, "");
    const nlohmann::json cmp = read_json(tmp.file("cmp.json"));
    EXPECT_TRUE(cmp["shaders"].contains("worley")) << cmp.dump();
    EXPECT_EQ(cmp["width"], 16);
    EXPECT_EQ(cmp["height"], 12);

    // sim and render.
    ASSERT_EQ(run_pelage("sim -q --mesh procedural:sphere:8x8 --preset teo-table-7.2 "
                         "--initial-cells 100 --stats-json " +
                             tmp.file("sim.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_EQ(read_json(tmp.file("sim.json"))["initial_cells"], 100);
    ASSERT_EQ(run_pelage("render -q " + scene + " -o " + tmp.file("r.exr") +
                             " --stats-json " + tmp.file("r.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_EQ(read_json(tmp.file("r.json"))["width"], 20);

    // lookup: the distances it prints, summarised.
    const std::string points =
        tmp.write("p.txt", "0 1 0 0\n3 0.2 0.3 0.5\n7 0 0.5 0.5\n");
    ASSERT_EQ(run_pelage("lookup " + cells + " --mesh procedural:sphere:8x8 --points " +
                             points + " --stats-json " + tmp.file("l.json"),
                         &out, &err),
              0)
        << err;
    std::istringstream lines(out);
    double sum = 0, max = 0, d;
    unsigned id, type, n = 0;
    while (lines >> id >> type >> d) {
        sum += d;
        max = std::max(max, d);
        ++n;
    }
    ASSERT_EQ(n, 3u) << out;
    const nlohmann::json l = read_json(tmp.file("l.json"));
    EXPECT_EQ(l["queries"], 3);
    EXPECT_EQ(l["found"], 3);
    EXPECT_NEAR(l["mean_distance"].get<double>(), sum / 3, 1e-6 * (1 + sum));
    EXPECT_NEAR(l["max_distance"].get<double>(), max, 1e-6 * (1 + max));

    // merge: the tiles joined.
    for (const char *t : {"1/2", "2/2"})
        ASSERT_EQ(run_pelage("render -q " + scene + " --tile " + t + " -o " +
                                 tmp.file(std::string("t") + t[0] + ".exr"),
                             &out, &err),
                  0)
            << err;
    ASSERT_EQ(
        run_pelage("merge -q " + tmp.file("t1.exr") + " " + tmp.file("t2.exr") + " -o " +
                       tmp.file("m.exr") + " --stats-json " + tmp.file("m.json"),
                   &out, &err),
        0)
        << err;
    EXPECT_EQ(out, "");
    const nlohmann::json m = read_json(tmp.file("m.json"));
    EXPECT_EQ(m["tiles"], 2);
    EXPECT_EQ(m["width"], 20);
    EXPECT_EQ(m["height"], 14);
    EXPECT_EQ(pixels(tmp.file("m.exr")), pixels(tmp.file("r.exr")));

    // A FILE in a missing folder: refused as the command line is read, nothing done.
    EXPECT_EQ(run_pelage("sim --mesh procedural:sphere:8x8 --preset teo-table-7.2 -o " +
                             tmp.file("never.cells") + " --stats-json " +
                             tmp.file("no/such/s.json"),
                         &out, &err),
              2);
    EXPECT_NE(err.find("--stats-json"), std::string::npos) << err;
    EXPECT_NE(err.find("does not exist"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("never.cells")));
}

// matte and movie: their --stats-json against the files they wrote.
TEST(CliVocabulary, MatteAndMovieStatsJsonDescribeTheirFiles) {
    TempDir tmp;
    std::string out, err;
    std::string scene = tiny_scene();
    const std::string film_end = "\"spp\": 2}";
    scene.replace(scene.find(film_end), film_end.size(),
                  R"("spp": 2, "cryptomatte": ["object"]})");
    const std::string exr = tmp.file("c.exr");
    ASSERT_EQ(
        run_pelage("render -q " + tmp.write("c.json", scene) + " -o " + exr, &out, &err),
        0)
        << err;
    ASSERT_EQ(run_pelage("matte " + exr + " -q --name '*' -o " + tmp.file("m.exr") +
                             " --stats-json " + tmp.file("m.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_EQ(out, "");
    const std::vector<float> alpha = pixels(tmp.file("m.exr"));
    ASSERT_EQ(alpha.size(), 20u * 14u);
    double sum = 0;
    size_t covered = 0;
    for (const float a : alpha) {
        sum += a;
        covered += a > 0;
    }
    const nlohmann::json m = read_json(tmp.file("m.json"));
    EXPECT_EQ(m["names"], nlohmann::json::array({"object0"})) << m.dump();
    EXPECT_NEAR(m["coverage"].get<double>(), sum / alpha.size(), 1e-6);
    EXPECT_EQ(m["pixels_covered"], covered);
    EXPECT_GT(covered, 0u);
    EXPECT_LT(covered, alpha.size());

    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "ffmpeg is not installed (quickstart.sh does)";
    std::string animated = tiny_scene();
    animated.replace(
        animated.rfind('}'), 1,
        R"(, "animation": {"frames": 4, "fps": 8, "turntable": {"degrees": 20}}})");
    ASSERT_EQ(run_pelage("render -q " + tmp.write("a.json", animated) +
                             " --frames 0-3 -o " + tmp.file("f.####.exr"),
                         &out, &err),
              0)
        << err;
    ASSERT_EQ(run_pelage("movie -q " + tmp.file("f.####.exr") + " -o " +
                             tmp.file("f.mp4") + " --stats-json " + tmp.file("v.json"),
                         &out, &err),
              0)
        << err;
    EXPECT_EQ(out, "");
    const nlohmann::json v = read_json(tmp.file("v.json"));
    EXPECT_EQ(v["frames"], 4) << v.dump();
    EXPECT_EQ(v["first_frame"], 0);
    EXPECT_EQ(v["last_frame"], 3);
    EXPECT_EQ(v["fps"], 8.0);
    EXPECT_EQ(v["codec"], "h264");
    EXPECT_EQ(v["bytes"], std::filesystem::file_size(tmp.file("f.mp4")));
}

TEST(CliVocabulary, ColourAndColorBothReadAndBothGivenIsExitTwo) {
    TempDir tmp;
    std::string out, err;
    // A light: the same image either way.
    for (const char *key : {"colour", "color"}) {
        const std::string scene =
            tmp.write(std::string(key) + ".json",
                      tiny_scene("\"" + std::string(key) + "\": [0.9, 0.2, 0.1]"));
        ASSERT_EQ(run_pelage(
                      "render -q " + scene + " -o " + tmp.file(std::string(key) + ".exr"),
                      &out, &err),
                  0)
            << key << ": " << err;
    }
    EXPECT_EQ(pixels(tmp.file("colour.exr")), pixels(tmp.file("color.exr")));
    const std::string both =
        tmp.write("both.json",
                  tiny_scene(R"("colour": [0.9, 0.2, 0.1], "color": [0.9, 0.2, 0.1])"));
    EXPECT_EQ(run_pelage("render -q " + both + " -o " + tmp.file("both.exr"), &out, &err),
              2);
    EXPECT_NE(err.find("lights[0].colour: given twice"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("both.exr")));

    // A shader parameter spelled "colour" by its plugin.
    for (const char *key : {"spot_colour", "spot_color"}) {
        const std::string scene = tmp.write(
            std::string(key) + ".json",
            tiny_scene(R"("colour": 1)", R"({"shader": "worley", "params": {")" +
                                             std::string(key) + R"(": [0, 0.5, 1]}})"));
        ASSERT_EQ(run_pelage(
                      "render -q " + scene + " -o " + tmp.file(std::string(key) + ".exr"),
                      &out, &err),
                  0)
            << key << ": " << err;
    }
    EXPECT_EQ(pixels(tmp.file("spot_colour.exr")), pixels(tmp.file("spot_color.exr")));
    const std::string both_params = tmp.write(
        "both_params.json",
        tiny_scene(
            R"("colour": 1)",
            R"({"shader": "worley", "params": {"spot_colour": 1, "spot_color": 1}})"));
    EXPECT_EQ(
        run_pelage("render -q " + both_params + " -o " + tmp.file("x.exr"), &out, &err),
        2);
    EXPECT_NE(err.find("spot_colour: given twice"), std::string::npos) << err;

    // A preset's cell type: the same cells either way.
    const std::string preset = R"({"name": "p", "types": [
        {"name": "F", "COLOUR_KEY": [0.1, 0.05, 0.02], "division_time": 1, "initial_probability": 0.3},
        {"name": "B", "colour": [0.9, 0.6, 0.3], "division_time": "never", "initial_probability": 0.7}],
        "adhesion": [[0.5, 0.5], [0.5, 0.5]],
        "simulation": {"initial_cells": 80, "w_r": 2, "w_d": 0.1, "rho": 5, "end_time": 0.5}})";
    auto with_key = [&](const std::string &key) {
        std::string text = preset;
        text.replace(text.find("\"COLOUR_KEY\""), 12, key);
        return text;
    };
    for (const char *key : {"colour", "color"}) {
        const std::string file = tmp.write(std::string("p_") + key + ".json",
                                           with_key("\"" + std::string(key) + "\""));
        ASSERT_EQ(run_pelage("sim -q --mesh procedural:sphere:8x8 --preset " + file +
                                 " -o " + tmp.file(std::string(key) + ".cells"),
                             &out, &err),
                  0)
            << key << ": " << err;
    }
    // The cells themselves (positions, types, ids) are the same; the files differ only in
    // the preset text they record.
    std::string colour_cells, color_cells;
    ASSERT_EQ(run_pelage("cells " + tmp.file("colour.cells"), &colour_cells, &err), 0);
    ASSERT_EQ(run_pelage("cells " + tmp.file("color.cells"), &color_cells, &err), 0);
    EXPECT_GT(colour_cells.size(), 1000u);
    EXPECT_EQ(colour_cells, color_cells);
    const std::string both_preset =
        tmp.write("p_both.json", with_key(R"("colour": [0.1, 0.05, 0.02], "color")"));
    EXPECT_EQ(run_pelage("sim -q --mesh procedural:sphere:8x8 --preset " + both_preset +
                             " -o " + tmp.file("both.cells"),
                         &out, &err),
              2);
    EXPECT_NE(err.find("types[0].colour: given twice"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(tmp.file("both.cells")));
}

}  // namespace
}  // namespace pelage::test
