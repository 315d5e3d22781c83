// Render-farm conventions end to end: frame lists and padding tokens as farm managers
// write them, animation.first_frame numbering, exit 2 for every bad list; --resume
// trusting only frames of the same settings; tiled stills merged into the whole
// render's exact bytes; wall, set-up and write times in --stats-json.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

// A small camera turntable; `animation_extra` adds keys to the animation block.
std::string farm_scene(const std::string &animation_extra = "",
                       const std::string &film_extra = "") {
    return R"({"camera": {"position": [0, 0.5, 4], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 24, "height": 16, "spp": 2)" +
           film_extra + R"(},
      "lights": [{"type": "environment", "color": [0.6, 0.7, 0.9]},
                 {"type": "distant", "direction": [-1, -1, -0.5], "intensity": 3}],
      "objects": [{"mesh": "procedural:icosphere:2", "transform": {"scale": [1.3, 0.8, 0.9]}},
                  {"mesh": "procedural:plane:1x1", "transform": {"scale": 8, "translate": [0, -1, 0]}}],
      "animation": {"frames": 12, "turntable": {"degrees": 360})" +
           animation_extra + "}}";
}

// The pelage:pixel_xxh3 attribute (16 hex digits) of an EXR, read from its header bytes.
std::string pixel_hash_of(const std::string &exr) {
    const std::string bytes = slurp(exr),
                      key = std::string("pelage:pixel_xxh3\0string\0", 25);
    const size_t at = bytes.find(key);
    return at == std::string::npos ? "" : bytes.substr(at + key.size() + 4, 16);
}

std::vector<std::string> files_in(const std::string &dir) {
    std::vector<std::string> names;
    for (const auto &e : fs::directory_iterator(dir))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

TEST(FarmCli, FrameListsRenderExactlyTheFramesNamed) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", farm_scene());
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {"1,5,9", {"f.0001.exr", "f.0005.exr", "f.0009.exr"}},
        {"0-11x5", {"f.0000.exr", "f.0005.exr", "f.0010.exr"}},
        {"0-4x4,7", {"f.0000.exr", "f.0004.exr", "f.0007.exr"}},
    };
    int n = 0;
    for (const auto &[spec, want] : cases) {
        const std::string dir = tmp.file("list" + std::to_string(n++));
        fs::create_directories(dir);
        std::string err;
        ASSERT_EQ(run_pelage("render " + scene + " -q --frames " + spec + " -o " + dir +
                                 "/f.####.exr",
                             nullptr, &err),
                  0)
            << spec << ": " << err;
        EXPECT_EQ(files_in(dir), want) << spec;
    }
}

TEST(FarmCli, PaddingTokensOfEveryFormNameTheFrames) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", farm_scene());
    for (const std::string pattern : {"a.%04d.exr", "a.$F4.exr", "a.###.exr"}) {
        const std::string dir = tmp.file(pattern[2] == '%'   ? "printf"
                                         : pattern[2] == '$' ? "houdini"
                                                             : "hash");
        fs::create_directories(dir);
        // Single quotes: the shell must not expand $F4.
        ASSERT_EQ(run_pelage("render " + scene + " -q --frames 2-3 -o '" + dir + "/" +
                             pattern + "'"),
                  0)
            << pattern;
        const std::string w = pattern == "a.###.exr" ? "00" : "000";
        EXPECT_EQ(files_in(dir),
                  std::vector<std::string>({"a." + w + "2.exr", "a." + w + "3.exr"}))
            << pattern;
    }
}

TEST(FarmCli, FirstFrameRenumbersWithoutChangingPixels) {
    TempDir tmp;
    const std::string zero = tmp.write("zero.json", farm_scene()),
                      vfx = tmp.write("vfx.json", farm_scene(R"(, "first_frame": 1001)"));
    fs::create_directories(tmp.file("z"));
    fs::create_directories(tmp.file("v"));
    ASSERT_EQ(
        run_pelage("render " + zero + " -q --frames 0-2 -o " + tmp.file("z/f.####.exr")),
        0);
    std::string err;
    ASSERT_EQ(run_pelage("render " + vfx + " -q --frames 1001-1003 -o " +
                             tmp.file("v/f.####.exr"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_EQ(files_in(tmp.file("v")),
              std::vector<std::string>({"f.1001.exr", "f.1002.exr", "f.1003.exr"}));
    for (int f = 0; f < 3; ++f) {
        const std::string a =
            pixel_hash_of(tmp.file("z/f.000" + std::to_string(f) + ".exr"));
        EXPECT_EQ(a.size(), 16u);
        EXPECT_EQ(a, pixel_hash_of(tmp.file("v/f.100" + std::to_string(f + 1) + ".exr")))
            << "frame " << f;
    }
    // Frames outside 1001-1012 are refused, naming the field and the item.
    for (const std::string spec : {"0-2", "1000", "1005,1013", "1010-1020x5"}) {
        EXPECT_EQ(run_pelage("render " + vfx + " -q --frames " + spec + " -o " +
                                 tmp.file("v/g.####.exr"),
                             nullptr, &err),
                  2)
            << spec;
        EXPECT_NE(err.find("animation.frames"), std::string::npos) << err;
        EXPECT_NE(err.find("1001-1012"), std::string::npos) << err;
    }
}

TEST(FarmCli, BadFrameListsAreExit2NamingTheItem) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", farm_scene());
    const std::string out = " -o " + tmp.file("f.####.exr");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"'5 9'", "\"5 9\""}, {"7abc", "\"7abc\""},         {"1,,3", "empty item"},
        {"5-2", "backwards"}, {"0-10x0", "step"},           {"-1", "\"-1\""},
        {"1,5x", "\"5x\""},   {"99999999999", "too large"},
    };
    for (const auto &[spec, why] : cases) {
        std::string err;
        EXPECT_EQ(
            run_pelage("render " + scene + " -q --frames " + spec + out, nullptr, &err),
            2)
            << spec;
        EXPECT_NE(err.find("--frames"), std::string::npos) << spec << ": " << err;
        EXPECT_NE(err.find(why), std::string::npos) << spec << ": " << err;
    }
    // Several frames without a padding token, and --frames on a still.
    std::string err;
    EXPECT_EQ(run_pelage("render " + scene + " -q --frames 1,2 -o " + tmp.file("f.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("-o"), std::string::npos) << err;
    const std::string still = tmp.write(
        "still.json", R"({"camera": {}, "film": {"width": 8, "height": 8, "spp": 1},
                          "objects": [{"mesh": "procedural:icosphere:1"}]})");
    EXPECT_EQ(
        run_pelage("render " + still + " -q --frames 0-3 -o " + tmp.file("s.####.exr"),
                   nullptr, &err),
        2);
    EXPECT_NE(err.find("still"), std::string::npos) << err;
    EXPECT_NE(err.find("--frames"), std::string::npos) << err;
    for (const auto &name : files_in(tmp.path().string()))
        EXPECT_EQ(name.rfind(".json"), name.size() - 5) << name << " was written";
}

// Occurrences of `needle` in `text`.
int count_of(const std::string &text, const std::string &needle) {
    int n = 0;
    for (size_t at = text.find(needle); at != std::string::npos;
         at = text.find(needle, at + 1))
        ++n;
    return n;
}

// A quad, as an OBJ a test can change.
std::string quad_obj(float lift) {
    return "v -1 0 -1\nv 1 0 -1\nv 1 " + std::to_string(lift) +
           " 1\nv -1 0 1\nf 1 2 3\nf 1 3 4\n";
}

TEST(FarmCli, ResumeSkipsOnlyFramesOfTheSameSettings) {
    TempDir tmp;
    tmp.write("quad.obj", quad_obj(0));
    const std::string scene =
        tmp.write("s.json",
                  R"({"camera": {"position": [0, 1.5, 4], "look_at": [0, 0, 0]},
            "film": {"width": 16, "height": 12, "spp": 2},
            "lights": [{"type": "environment", "color": [0.8, 0.8, 0.9]}],
            "objects": [{"mesh": "quad.obj"}],
            "animation": {"frames": 3, "turntable": {"degrees": 90}}})");
    const std::string out = " -o " + tmp.file("f.####.exr");
    ASSERT_EQ(run_pelage("render " + scene + " -q --frames 0-2" + out), 0);
    const std::string first = slurp(tmp.file("f.0001.exr"));
    EXPECT_EQ(pixel_hash_of(tmp.file("f.0001.exr")).size(), 16u);
    EXPECT_NE(first.find("pelage:settings_xxh3"), std::string::npos);
    // The same settings, one of them now given on the command line: all skipped.
    std::string log;
    ASSERT_EQ(
        run_pelage("render " + scene + " --spp 2 --frames 0-2 --resume" + out, &log), 0);
    EXPECT_EQ(count_of(log, "complete, skipped"), 3) << log;
    EXPECT_TRUE(slurp(tmp.file("f.0001.exr")) == first);
    // Another spp, then also another resolution, seed and mesh: every frame again,
    // saying why; then skipped again.
    std::string args;
    for (const std::string change :
         {" --spp 4", " --res 12x12", " --sampler-seed 3", "mesh"}) {
        if (change == "mesh")
            tmp.write("quad.obj", quad_obj(0.5f));
        else
            args += change;
        const std::string cmd = "render " + scene + args + " --frames 0-2 --resume" + out;
        ASSERT_EQ(run_pelage(cmd, &log), 0) << change;
        EXPECT_EQ(count_of(log, "rendered with other settings, rendering again"), 3)
            << change << ": " << log;
        EXPECT_EQ(count_of(log, "skipped"), 1) << change << ": " << log;  // the summary
        ASSERT_EQ(run_pelage(cmd, &log), 0);
        EXPECT_EQ(count_of(log, "complete, skipped"), 3) << change << ": " << log;
    }
    EXPECT_FALSE(slurp(tmp.file("f.0001.exr")) == first);
}

// A still of a sphere on a floor, `width` × `height`, with `film_extra` film keys.
std::string still_scene(int width, int height, const std::string &film_extra) {
    return R"({"camera": {"position": [0, 0.5, 4], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": )" +
           std::to_string(width) + R"(, "height": )" + std::to_string(height) +
           film_extra + R"(},
      "lights": [{"type": "environment", "color": [0.6, 0.7, 0.9]},
                 {"type": "distant", "direction": [-1, -1, -0.5], "intensity": 3}],
      "objects": [{"mesh": "procedural:icosphere:2", "transform": {"scale": [1.3, 0.8, 0.9]}},
                  {"mesh": "procedural:plane:1x1", "transform": {"scale": 8, "translate": [0, -1, 0]}}]})";
}

TEST(FarmCli, MergedTilesAreTheWholeRenderByteForByte) {
    TempDir tmp;
    // Fixed spp, and adaptive sampling stopping pixels early (a band's edge depends on
    // its neighbours' noise).
    const std::vector<std::pair<std::string, std::string>> looks = {
        {"fixed", R"(, "spp": 4)"},
        {"adaptive", R"(, "spp": 64, "noise_threshold": 0.05, "min_spp": 2)"},
        // Cryptomatte (each band's manifest lists the objects it shows; the merge's
        // lists all), layers of other types and another compression.
        {"mattes", R"(, "spp": 4, "cryptomatte": true, "compression": "piz",
                      "layers": {"N": false, "depth": "half"})"},
        // The denoiser reads a neighbourhood: each band renders its support around it,
        // with and without adaptive sampling.
        {"denoised", R"(, "spp": 4, "denoise": true)"},
        {"denoised_adaptive",
         R"(, "spp": 32, "noise_threshold": 0.05, "min_spp": 2, "denoise": true)"}};
    for (const auto &[look, film] : looks) {
        const std::string scene = tmp.write(look + ".json", still_scene(40, 37, film));
        const std::string whole = tmp.file(look + "_whole.exr");
        std::string log, err;
        ASSERT_EQ(run_pelage("render " + scene + " -o " + whole, &log, &err), 0) << err;
        if (look == "adaptive") {  // the pixels did stop at different counts
            const size_t at = log.find("adaptive, mean ");
            ASSERT_NE(at, std::string::npos) << log;
            const double mean = std::stod(log.substr(at + 15));
            EXPECT_GT(mean, 2.0) << log;
            EXPECT_LT(mean, 60.0) << log;
        }
        for (const int n : {1, 3, 16}) {
            const std::string dir = tmp.file(look + std::to_string(n));
            fs::create_directories(dir);
            std::string tiles;
            for (int i = n; i >= 1; --i) {  // any order, and one thread for some
                const std::string tile = dir + "/t" + std::to_string(i) + ".exr";
                ASSERT_EQ(run_pelage("render " + scene + " -q --tile " +
                                         std::to_string(i) + "/" + std::to_string(n) +
                                         " -o " + tile + (i % 2 ? " --threads 1" : ""),
                                     nullptr, &err),
                          0)
                    << look << " " << i << "/" << n << ": " << err;
                tiles += " " + tile;
            }
            const std::string merged = dir + "/merged.exr";
            ASSERT_EQ(run_pelage("merge" + tiles + " -o " + merged, &log, &err), 0)
                << err;
            const std::string a = slurp(whole), b = slurp(merged);
            ASSERT_GT(a.size(), 1000u);
            EXPECT_TRUE(a == b)
                << look << ", " << n << " tiles: the merged EXR differs "
                << "from the whole render (cmp " << whole << " " << merged << ")";
        }
    }
}

TEST(FarmCli, MergeRefusesTilesThatDoNotBelongTogether) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", still_scene(24, 20, R"(, "spp": 2)"));
    auto tile = [&](int i, const std::string &name, const std::string &extra = "") {
        return run_pelage("render " + scene + " -q --tile " + std::to_string(i) +
                          "/4 -o " + tmp.file(name) + extra);
    };
    for (int i = 1; i <= 4; ++i) ASSERT_EQ(tile(i, "t" + std::to_string(i) + ".exr"), 0);
    ASSERT_EQ(tile(3, "other3.exr", " --spp 4"), 0);
    const std::string out = " -o " + tmp.file("m.exr");
    std::string err;
    // A missing tile.
    EXPECT_EQ(run_pelage("merge " + tmp.file("t1.exr") + " " + tmp.file("t2.exr") + " " +
                             tmp.file("t4.exr") + out,
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("tile(s) 3 of 4 missing"), std::string::npos) << err;
    // A tile of other settings, named.
    EXPECT_EQ(run_pelage("merge " + tmp.file("t1.exr") + " " + tmp.file("t2.exr") + " " +
                             tmp.file("other3.exr") + " " + tmp.file("t4.exr") + out,
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("other3.exr"), std::string::npos) << err;
    EXPECT_NE(err.find("other settings"), std::string::npos) << err;
    // The same tile twice.
    EXPECT_EQ(run_pelage("merge " + tmp.file("t1.exr") + " " + tmp.file("t2.exr") + " " +
                             tmp.file("t2.exr") + " " + tmp.file("t4.exr") + out,
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("again"), std::string::npos) << err;
    // A whole render is not a tile.
    ASSERT_EQ(run_pelage("render " + scene + " -q -o " + tmp.file("whole.exr")), 0);
    EXPECT_EQ(run_pelage("merge " + tmp.file("whole.exr") + out, nullptr, &err), 2);
    EXPECT_NE(err.find("pelage:tile"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(tmp.file("m.exr")));
    // Bad --tile values, and --tile without -o.
    for (const std::string bad : {"0/4", "5/4", "3", "a/4", "1/0", " 1/4", "1/21"}) {
        EXPECT_EQ(run_pelage("render " + scene + " -q --tile '" + bad + "'" + out,
                             nullptr, &err),
                  2)
            << bad;
        EXPECT_NE(err.find("--tile"), std::string::npos) << bad << ": " << err;
    }
    EXPECT_EQ(run_pelage("render " + scene + " -q --tile 1/4", nullptr, &err), 2);
    EXPECT_NE(err.find("-o"), std::string::npos) << err;
    // --resume skips a complete tile of the same settings, and redoes one of others.
    std::string log;
    ASSERT_EQ(tile(2, "t2.exr", " --resume"), 0);
    ASSERT_EQ(
        run_pelage("render " + scene + " --tile 2/4 --resume -o " + tmp.file("t2.exr"),
                   &log),
        0);
    EXPECT_NE(log.find("complete, skipped"), std::string::npos) << log;
    ASSERT_EQ(run_pelage(
                  "render " + scene + " --tile 2/4 --resume -o " + tmp.file("other3.exr"),
                  &log),
              0);
    EXPECT_NE(log.find("rendered with other settings"), std::string::npos) << log;
}

TEST(FarmCli, StatsJsonHasWallSetupAndWriteTimes) {
    TempDir tmp;
    const std::string scene = tmp.write("s.json", farm_scene());
    for (const std::string frames : {"", " --frames 0-1"}) {
        std::string log;
        ASSERT_EQ(
            run_pelage("render " + scene + frames + " -o " + tmp.file("f.####.exr") +
                           " --stats-json " + tmp.file("st.json"),
                       &log),
            0);
        const auto s = nlohmann::json::parse(std::ifstream(tmp.file("st.json")));
        for (const char *k :
             {"seconds", "wall_seconds", "setup_seconds", "write_seconds"})
            ASSERT_TRUE(s.contains(k) && s[k].is_number()) << k << frames;
        const double wall = s["wall_seconds"], setup = s["setup_seconds"],
                     render = s["seconds"], write = s["write_seconds"];
        EXPECT_GT(setup, 0.0);
        EXPECT_GT(write, 0.0);
        EXPECT_GE(wall, setup + render + write) << frames;
        EXPECT_NE(log.find("wall "), std::string::npos) << log;
        EXPECT_NE(log.find("writing "), std::string::npos) << log;
    }
}

}  // namespace
}  // namespace pelage::test
