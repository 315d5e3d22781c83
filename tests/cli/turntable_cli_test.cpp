// Turntables end to end: frame ranges split across runs give the same bytes as one run,
// --resume skips exactly the complete frames and redoes a damaged one, an interrupted
// frame is never written under its final name, bad animation
// fields are exit 2 naming the JSON path, `pelage movie` reports missing frames, and the
// clonal mosaic does not drift on a deforming mesh while worley and perlin do.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

std::string turntable_scene(const std::string &turntable) {
    return R"({"camera": {"position": [0, 0.5, 4], "look_at": [0, 0, 0], "fov": 40},
      "film": {"width": 32, "height": 24, "spp": 2},
      "lights": [{"type": "environment", "color": [0.6, 0.7, 0.9]},
                 {"type": "distant", "direction": [-1, -1, -0.5], "intensity": 3}],
      "objects": [{"mesh": "procedural:icosphere:2", "transform": {"scale": [1.3, 0.8, 0.9]}},
                  {"mesh": "procedural:plane:1x1", "transform": {"scale": 8, "translate": [0, -1, 0]}}],
      "animation": {"frames": 6, "fps": 24, "turntable": )" +
           turntable + "}}";
}

// The pelage:pixel_xxh3 attribute (16 hex digits) of an EXR, read from its header bytes.
std::string pixel_hash_of(const std::string &exr) {
    const std::string bytes = slurp(exr),
                      key = std::string("pelage:pixel_xxh3\0string\0", 25);
    const size_t at = bytes.find(key);
    return at == std::string::npos ? "" : bytes.substr(at + key.size() + 4, 16);
}

TEST(TurntableCli, SplitFrameRangesGiveIdenticalBytes) {
    TempDir tmp;
    for (const char *target : {"camera", "object"}) {
        const std::string shutter =
            std::string(target) == "camera" ? R"(, "shutter": [0, 0.5])" : "";
        const std::string scene = tmp.write(
            std::string("s_") + target + ".json",
            turntable_scene(
                std::string(R"({"axis": [0, 1, 0], "degrees": 360, "target": ")") +
                target + "\"" + shutter + "}"));
        fs::create_directories(tmp.file(std::string("one_") + target));
        fs::create_directories(tmp.file(std::string("split_") + target));
        const std::string one = tmp.file(std::string("one_") + target + "/f.####.exr");
        const std::string split =
            tmp.file(std::string("split_") + target + "/f.####.exr");
        std::string err;
        ASSERT_EQ(
            run_pelage("render " + scene + " -q --frames 0-5 -o " + one, nullptr, &err),
            0)
            << err;
        // Another "machine" (thread count differs too): 0-2, then 3-5 every other frame
        // and 4.
        ASSERT_EQ(
            run_pelage("render " + scene + " -q --threads 1 --frames 0-2 -o " + split),
            0);
        ASSERT_EQ(run_pelage("render " + scene + " -q --frames 3-5 --step 2 -o " + split),
                  0);
        ASSERT_EQ(run_pelage("render " + scene + " -q --frames 4 -o " + split), 0);
        std::string previous;
        for (int f = 0; f < 6; ++f) {
            const std::string name = "/f.000" + std::to_string(f) + ".exr";
            const std::string a = slurp(tmp.file(std::string("one_") + target + name));
            const std::string b = slurp(tmp.file(std::string("split_") + target + name));
            ASSERT_GT(a.size(), 1000u) << target << name;
            EXPECT_TRUE(a == b) << target << name << " differs between runs";
            EXPECT_TRUE(a != previous)
                << target << name << ": the turntable does not move";
            previous = a;
        }
    }
}

TEST(TurntableCli, ResumeSkipsCompleteFramesAndRedoesADamagedOne) {
    TempDir tmp;
    const std::string scene =
        tmp.write("s.json", turntable_scene(R"({"degrees": 90, "target": "camera"})"));
    const std::string pattern = tmp.file("f.####.exr");
    ASSERT_EQ(run_pelage("render " + scene + " -q --frames 0-3 -o " + pattern), 0);
    const std::string good = slurp(tmp.file("f.0002.exr"));
    // Frame 1 truncated (a copy cut short, as by a full disk), frame 3 missing, frame 0
    // with one pixel byte flipped near the end.
    fs::resize_file(tmp.file("f.0001.exr"), fs::file_size(tmp.file("f.0001.exr")) / 2);
    fs::remove(tmp.file("f.0003.exr"));
    {
        std::string f0 = slurp(tmp.file("f.0000.exr"));
        f0[f0.size() - 40] ^= 0x5a;
        std::ofstream(tmp.file("f.0000.exr"), std::ios::binary) << f0;
    }
    const auto mtime2 = fs::last_write_time(tmp.file("f.0002.exr"));
    std::string out, err;
    ASSERT_EQ(run_pelage("render " + scene + " --frames 0-3 --resume --stats-json " +
                             tmp.file("st.json") + " -o " + pattern,
                         &out, &err),
              0)
        << err;
    const auto st = nlohmann::json::parse(std::ifstream(tmp.file("st.json")));
    EXPECT_EQ(st["frames_skipped"], 1) << out;
    EXPECT_EQ(st["frames_rendered"], 3) << out;
    std::vector<int> redone;
    for (const auto &f : st["frames"]) redone.push_back(f["frame"].get<int>());
    EXPECT_EQ(redone, (std::vector<int>{0, 1, 3}));
    EXPECT_EQ(fs::last_write_time(tmp.file("f.0002.exr")), mtime2);
    EXPECT_TRUE(slurp(tmp.file("f.0002.exr")) == good);
    // Now every frame is complete, and a second resume renders nothing.
    ASSERT_EQ(run_pelage("render " + scene + " -q --frames 0-3 --resume --stats-json " +
                         tmp.file("st2.json") + " -o " + pattern),
              0);
    const auto st2 = nlohmann::json::parse(std::ifstream(tmp.file("st2.json")));
    EXPECT_EQ(st2["frames_skipped"], 4);
    EXPECT_EQ(st2["frames_rendered"], 0);
    // No temporaries are left behind.
    for (const auto &e : fs::directory_iterator(tmp.path()))
        EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
}

TEST(TurntableCli, AnOpenShutterBlursTheCamera) {
    TempDir tmp;
    const std::string sharp = tmp.write("a.json", turntable_scene(R"({"degrees": 90})"));
    const std::string closed =
        tmp.write("b.json", turntable_scene(R"({"degrees": 90, "shutter": [0, 0]})"));
    const std::string blur =
        tmp.write("c.json", turntable_scene(R"({"degrees": 90, "shutter": [0, 1]})"));
    for (const auto &[scene, name] : {std::pair{sharp, "a"}, {closed, "b"}, {blur, "c"}})
        ASSERT_EQ(run_pelage("render " + scene + " -q --frames 1 -o " +
                             tmp.file(std::string(name) + ".####.exr")),
                  0);
    // The headers name different scene files; the pixels are compared by their checksum.
    const std::string a = pixel_hash_of(tmp.file("a.0001.exr"));
    ASSERT_EQ(a.size(), 16u);
    EXPECT_EQ(a, pixel_hash_of(tmp.file("b.0001.exr")));  // a closed shutter is sharp
    EXPECT_NE(a, pixel_hash_of(tmp.file("c.0001.exr")));  // an open one is not
}

TEST(TurntableCli, AnInterruptedFrameNeverLandsUnderItsName) {
    TempDir tmp;
    // Frame 0 cheap, frame 1 far too many samples: Ctrl-C (SIGINT) stops it.
    const std::string scene = tmp.write("s.json", turntable_scene(R"({"degrees": 90})"));
    ASSERT_EQ(
        run_pelage("render " + scene + " -q --frames 0 -o " + tmp.file("f.####.exr")), 0);
    const std::string cmd = interrupt_after() + std::string(PELAGE_BINARY) + " render " +
                            scene + " -q --spp 1000000 --frames 1-2 -o " +
                            tmp.file("f.####.exr") + " 2>" + tmp.file("err.txt");
    EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 130);  // 128 + SIGINT
    EXPECT_NE(slurp(tmp.file("err.txt")).find("not written"), std::string::npos);
    EXPECT_TRUE(fs::exists(tmp.file("f.0000.exr")));
    EXPECT_FALSE(fs::exists(tmp.file("f.0001.exr")));
    EXPECT_FALSE(fs::exists(tmp.file("f.0002.exr")));
    for (const auto &e : fs::directory_iterator(tmp.path()))
        EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
}

TEST(TurntableCli, BadAnimationFieldsAreExit2NamingThePath) {
    TempDir tmp;
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"degrees": 360, "target": "camra"})", "animation.turntable.target"},
        {R"({"axis": [0, 0, 0]})", "animation.turntable.axis"},
        {R"({"shutter": [0.5, 0.2]})", "animation.turntable.shutter[1]"},
        {R"({"shutter": [0, 1.5]})", "animation.turntable.shutter[1]"},
        {R"({"target": "object", "shutter": [0, 0.5]})", "animation.turntable.shutter"},
        {R"({"spin": 1})", "animation.turntable.spin"},
    };
    for (const auto &[tt, path] : cases) {
        const std::string scene = tmp.write("s.json", turntable_scene(tt));
        std::string err;
        EXPECT_EQ(
            run_pelage("render " + scene + " -q --frames 0 -o " + tmp.file("f.####.exr"),
                       nullptr, &err),
            2)
            << tt;
        EXPECT_NE(err.find(path), std::string::npos) << tt << " → " << err;
    }
    // Frames past the animation, and a range without #### in the name.
    const std::string scene = tmp.write("s.json", turntable_scene("{}"));
    std::string err;
    EXPECT_EQ(run_pelage("render " + scene + " --frames 0-6 -o " + tmp.file("f.####.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("animation.frames"), std::string::npos) << err;
    EXPECT_EQ(run_pelage("render " + scene + " --frames 0-1 -o " + tmp.file("f.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("####"), std::string::npos) << err;
    EXPECT_EQ(run_pelage("render " + scene + " --frames 3-1 -o " + tmp.file("f.####.exr"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("--frames"), std::string::npos) << err;
    const std::string bad_frames = tmp.write(
        "b.json", R"({"camera": {}, "objects": [{"mesh": "procedural:icosphere:1"}],
                      "animation": {"frames": 0}})");
    EXPECT_EQ(
        run_pelage("render " + bad_frames + " -o " + tmp.file("x.exr"), nullptr, &err),
        2);
    EXPECT_NE(err.find("animation.frames"), std::string::npos) << err;
}

TEST(TurntableCli, MovieReportsMissingFramesClearly) {
    TempDir tmp;
    std::string err;
    EXPECT_EQ(run_pelage("movie " + tmp.file("f.####.exr") + " -o " + tmp.file("m.mp4"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("no frames found"), std::string::npos) << err;
    const std::string scene = tmp.write("s.json", turntable_scene(R"({"degrees": 60})"));
    ASSERT_EQ(
        run_pelage("render " + scene + " -q --frames 0-3 -o " + tmp.file("f.####.exr")),
        0);
    fs::remove(tmp.file("f.0002.exr"));
    EXPECT_EQ(run_pelage("movie " + tmp.file("f.####.exr") + " -o " + tmp.file("m.mp4"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("frame 2 missing"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(tmp.file("m.mp4")));
    // Without ffmpeg on PATH: exit 1 and a message saying so.
    ASSERT_EQ(
        run_pelage("render " + scene + " -q --frames 2 -o " + tmp.file("f.####.exr")), 0);
    const std::string no_ffmpeg = "PATH=" + tmp.file("empty") + " ";
    const std::string cmd = no_ffmpeg + PELAGE_BINARY + std::string(" movie ") +
                            tmp.file("f.####.exr") + " -o " + tmp.file("m.mp4") + " 2>" +
                            tmp.file("err");
    EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);
    EXPECT_NE(slurp(tmp.file("err")).find("ffmpeg not found"), std::string::npos);
    // With ffmpeg (Debian's, from quickstart.sh), a movie.
    if (std::system("command -v ffmpeg >/dev/null 2>&1") == 0) {
        ASSERT_EQ(run_pelage("movie " + tmp.file("f.####.exr") + " -q --fps 12 -o " +
                                 tmp.file("m.mp4"),
                             nullptr, &err),
                  0)
            << err;
        EXPECT_GT(fs::file_size(tmp.file("m.mp4")), 500u);
    }
}

// A 24×24 grid in x–z, and the same grid bent (a bump in y that grows with x and a
// shear in z): same vertices, same triangles, other positions.
std::string grid_obj(bool bent) {
    std::ostringstream o;
    const int n = 24;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = -1 + 2.0 * i / n, z = -1 + 2.0 * j / n, y = 0;
            if (bent) {
                y = 0.35 * std::sin(1.7 * (x + 1)) * (0.6 + 0.4 * z);
                z += 0.15 * x * x;
            }
            o << "v " << x << " " << y << " " << z << "\n";
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = 1 + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            o << "f " << a << " " << c << " " << b << "\nf " << b << " " << c << " " << d
              << "\n";
        }
    return o.str();
}

TEST(TurntableCli, ClonalMosaicDoesNotDriftOnADeformingMesh) {
    TempDir tmp;
    const std::string rest = tmp.write("rest.obj", grid_obj(false));
    tmp.write("bent.obj", grid_obj(true));
    const std::string preset = tmp.write("p.json", R"({"name": "t", "types": [
        {"name": "F", "colour": [0.1, 0.05, 0.02], "division_time": "never", "initial_probability": 0.3},
        {"name": "B", "colour": [0.9, 0.6, 0.3], "division_time": "never", "initial_probability": 0.7}],
        "adhesion": [[0.5, 0.0], [0.0, 0.5]],
        "simulation": {"initial_cells": 300, "initial_relax_steps": 5, "w_r": 2.0, "w_d": 0.1,
                       "rho": 2, "end_time": 1, "relax": "global"}})");
    ASSERT_EQ(run_pelage("sim --mesh " + rest + " --preset " + preset + " -o " +
                         tmp.file("s.cells")),
              0);
    const std::string scene =
        tmp.write("scene.json", R"({"camera": {"position": [0, 3, 2]},
      "film": {"width": 32, "height": 24, "spp": 2},
      "lights": [{"type": "environment"}],
      "objects": [{"mesh": "rest.obj", "cells": "s.cells", "deform": "bent.obj",
                   "material": {"shader": "clonal_mosaic"}}],
      "animation": {"frames": 3}})");
    std::string out, err;
    ASSERT_EQ(run_pelage("compare " + scene +
                             " --deform --lookups 4000 --shaders "
                             "clonal_mosaic,worley,perlin --stats-json " +
                             tmp.file("r.json"),
                         &out, &err),
              0)
        << err;
    const auto r = nlohmann::json::parse(std::ifstream(tmp.file("r.json")));
    const auto &d = r["pattern_drift"];
    EXPECT_EQ(d["clonal_mosaic"]["mean"].get<double>(), 0.0) << out;
    EXPECT_EQ(d["clonal_mosaic"]["max"].get<double>(), 0.0) << out;
    EXPECT_GT(d["worley"]["mean"].get<double>(), 0.01) << out;
    EXPECT_GT(d["perlin"]["mean"].get<double>(), 0.01) << out;
    EXPECT_EQ(d["worley"]["points"], 4000);

    // The deforming object renders at its pose per frame (rest, halfway, bent).
    ASSERT_EQ(
        run_pelage("render " + scene + " -q --frames 0-2 -o " + tmp.file("d.####.exr"),
                   nullptr, &err),
        0)
        << err;
    EXPECT_NE(pixel_hash_of(tmp.file("d.0000.exr")),
              pixel_hash_of(tmp.file("d.0002.exr")));

    // Another topology is refused, naming the field.
    std::string other = grid_obj(true);
    other.resize(other.rfind("f "));  // drop the last triangle
    tmp.write("bent.obj", other);
    EXPECT_EQ(
        run_pelage("render " + scene + " -q --frames 2 -o " + tmp.file("d.####.exr"),
                   nullptr, &err),
        2);
    EXPECT_NE(err.find("objects[0].deform"), std::string::npos) << err;
    EXPECT_NE(err.find("topology"), std::string::npos) << err;
}

}  // namespace
}  // namespace pelage::test
