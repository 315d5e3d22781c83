// `pelage movie` end to end, checked with ffmpeg's own tools: the codec, pixel format
// and colour tags ffprobe reads back, the frame count it decodes, the colour a decoder
// gets against the analytic sRGB encoding, the view recorded in the frames, stepped
// sequences, and clear errors (exit 2 before ffmpeg runs, exit 1 with ffmpeg's message
// when it fails).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/test_paths.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

// Every pixel sees the environment (the one object is behind the camera), so each frame
// is one flat colour: linear (0.8, 0.2, 0.1).
constexpr float env[3] = {0.8f, 0.2f, 0.1f};

std::string flat_scene(const TempDir &tmp) {
    return tmp.write("flat.json", R"({
      "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov": 30},
      "film": {"width": 32, "height": 24, "spp": 1},
      "lights": [{"type": "environment", "color": [0.8, 0.2, 0.1]}],
      "objects": [{"mesh": "procedural:icosphere:1",
                   "transform": {"scale": 0.1, "translate": [0, 0, -5]}}],
      "animation": {"frames": 12, "fps": 12, "turntable": {"degrees": 30}}})");
}

bool have_ffmpeg() { return std::system("command -v ffprobe >/dev/null 2>&1") == 0; }

std::string capture(const std::string &cmd) {
    std::string out;
    if (FILE *p = ::popen(cmd.c_str(), "r")) {
        char buf[4096];
        for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
        ::pclose(p);
    }
    return out;
}

// ffprobe's description of the first video stream, frames counted by decoding.
nlohmann::json probe(const std::string &movie) {
    const std::string j = capture(
        "ffprobe -v error -count_frames -select_streams v:0 "
        "-show_streams -of json '" +
        movie + "'");
    const auto doc = nlohmann::json::parse(j, nullptr, false);
    if (doc.is_discarded() || !doc.contains("streams") || doc["streams"].empty())
        return nlohmann::json::object();
    return doc["streams"][0];
}

// The centre pixel of the first frame, decoded by ffmpeg as the tags say: BT.709
// matrix, limited range.
std::vector<int> decoded_centre(const std::string &movie) {
    const std::string raw =
        capture("ffmpeg -v error -i '" + movie +
                "' -frames:v 1 -vf scale=in_color_matrix=bt709:in_range=tv,format=rgb24 "
                "-f rawvideo -");
    const size_t at = (size_t(12) * 32 + 16) * 3;
    if (raw.size() < at + 3) return {};
    return {(unsigned char)raw[at], (unsigned char)raw[at + 1],
            (unsigned char)raw[at + 2]};
}

// IEC 61966-2-1, the sRGB encoding, to 8 bits.
int srgb8(float linear) {
    const double v =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return int(std::lround(255 * v));
}

TEST(MovieCli, SteppedSequenceIsTaggedCountedAndDecodesToSrgb) {
    if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg is not installed (quickstart.sh does)";
    TempDir tmp;
    const std::string scene = flat_scene(tmp);
    ASSERT_EQ(run_pelage("render " + scene + " -q --frames 0-10 --step 5 -o " +
                         tmp.file("f.####.exr")),
              0);
    std::string out, err;
    ASSERT_EQ(run_pelage("movie " + tmp.file("f.%04d.exr") + " -o " + tmp.file("m.mp4"),
                         &out, &err),
              0)
        << err;
    EXPECT_NE(out.find("3 frames (0-10, step 5) at 12 fps, H.264 crf 18, view Standard"),
              std::string::npos)
        << out;
    const auto s = probe(tmp.file("m.mp4"));
    EXPECT_EQ(s.value("codec_name", ""), "h264") << s;
    EXPECT_EQ(s.value("pix_fmt", ""), "yuv420p") << s;
    EXPECT_EQ(s.value("color_range", ""), "tv") << s;
    EXPECT_EQ(s.value("color_space", ""), "bt709") << s;
    EXPECT_EQ(s.value("color_primaries", ""), "bt709") << s;
    EXPECT_EQ(s.value("color_transfer", ""), "iec61966-2-1") << s;
    EXPECT_EQ(s.value("nb_read_frames", ""), "3") << s;
    EXPECT_EQ(s.value("r_frame_rate", ""), "12/1") << s;
    const std::vector<int> rgb = decoded_centre(tmp.file("m.mp4"));
    ASSERT_EQ(rgb.size(), 3u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], srgb8(env[c]), 3) << "channel " << c;
    // No temporary left next to the movie.
    for (const auto &e : fs::directory_iterator(tmp.path()))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos)
            << e.path();
}

TEST(MovieCli, ProResInMovCarriesItsProfileAndTags) {
    if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg is not installed (quickstart.sh does)";
    TempDir tmp;
    ASSERT_EQ(run_pelage("render " + flat_scene(tmp) + " -q --frames 0-1 -o " +
                         tmp.file("f.####.exr")),
              0);
    // pix_fmt is what the decoder gives: 4444 decodes to 12 bits, whatever went in.
    struct Case {
        const char *profile, *name, *pix_fmt;
    };
    for (const Case c :
         {Case{"", "HQ", "yuv422p10le"}, Case{"4444", "4444", "yuv444p12le"}}) {
        const std::string movie = tmp.file(std::string("p") + c.profile + ".mov");
        std::string err;
        ASSERT_EQ(run_pelage(
                      "movie " + tmp.file("f.####.exr") + " -q --codec prores " +
                          (*c.profile ? "--prores-profile " + std::string(c.profile) + " "
                                      : "") +
                          "-o " + movie,
                      nullptr, &err),
                  0)
            << err;
        const auto s = probe(movie);
        EXPECT_EQ(s.value("codec_name", ""), "prores") << s;
        EXPECT_EQ(s.value("profile", ""), c.name) << s;
        EXPECT_EQ(s.value("pix_fmt", ""), c.pix_fmt) << s;
        EXPECT_EQ(s.value("color_space", ""), "bt709") << s;
        EXPECT_EQ(s.value("color_primaries", ""), "bt709") << s;
        EXPECT_EQ(s.value("color_transfer", ""), "iec61966-2-1") << s;
        EXPECT_EQ(s.value("nb_read_frames", ""), "2") << s;
        const std::vector<int> rgb = decoded_centre(movie);
        ASSERT_EQ(rgb.size(), 3u);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(rgb[ch], srgb8(env[ch]), 3) << ch;
    }
}

TEST(MovieCli, UsesTheViewTheFramesRecordAndRefusesAMix) {
    if (!have_ffmpeg()) GTEST_SKIP() << "ffmpeg is not installed (quickstart.sh does)";
    TempDir tmp;
    const std::string scene = flat_scene(tmp);
    ASSERT_EQ(run_pelage("render " + scene + " -q --view Filmic --frames 0-1 -o " +
                         tmp.file("f.####.exr") + " --preview " + tmp.file("p.####.png")),
              0);
    std::string out, err;
    ASSERT_EQ(run_pelage("movie " + tmp.file("f.####.exr") + " -o " + tmp.file("m.mp4"),
                         &out, &err),
              0)
        << err;
    EXPECT_NE(out.find("view Filmic (recorded in the frames)"), std::string::npos) << out;
    // The movie shows what the Filmic preview shows, not the Standard encoding.
    const std::string png = capture("ffmpeg -v error -i '" + tmp.file("p.0000.png") +
                                    "' -f rawvideo -pix_fmt rgb24 -");
    ASSERT_GE(png.size(), size_t(32 * 24 * 3));
    const std::vector<int> rgb = decoded_centre(tmp.file("m.mp4"));
    ASSERT_EQ(rgb.size(), 3u);
    const size_t at = (size_t(12) * 32 + 16) * 3;
    int off_standard = 0;
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(rgb[c], (unsigned char)png[at + c], 3) << "channel " << c;
        off_standard = std::max(off_standard, std::abs(rgb[c] - srgb8(env[c])));
    }
    EXPECT_GT(off_standard, 10) << "Filmic should not look like Standard here";

    // A frame rendered for another view: exit 2 naming both, unless --view decides.
    ASSERT_EQ(run_pelage("render " + scene + " -q --view Standard --frames 2 -o " +
                         tmp.file("f.####.exr")),
              0);
    EXPECT_EQ(run_pelage("movie " + tmp.file("f.####.exr") + " -o " + tmp.file("n.mp4"),
                         nullptr, &err),
              2);
    EXPECT_NE(err.find("--view: the frames were rendered for different views"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("f.0002.exr for \"Standard\""), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(tmp.file("n.mp4")));
    EXPECT_EQ(run_pelage("movie " + tmp.file("f.####.exr") + " -q --view Raw -o " +
                             tmp.file("n.mp4"),
                         nullptr, &err),
              0)
        << err;
    EXPECT_EQ(probe(tmp.file("n.mp4")).value("nb_read_frames", ""), "3");
}

TEST(MovieCli, BadOutputsAndCodecsAreRefusedBeforeEncoding) {
    TempDir tmp;
    ASSERT_EQ(run_pelage("render " + flat_scene(tmp) + " -q --frames 0-1 -o " +
                         tmp.file("f.####.exr")),
              0);
    const std::string frames = tmp.file("f.####.exr");
    struct Case {
        std::string args, field;
    };
    const Case cases[] = {
        {"-o " + tmp.file("m.gif"), "-o: \"" + tmp.file("m.gif") +
                                        "\": pelage movie "
                                        "writes .mp4, .mov or .mkv"},
        {"-o " + tmp.file("m"), "-o:"},
        {"--codec prores -o " + tmp.file("m.mp4"), "--codec: ProRes is written in"},
        {"--codec prores --crf 20 -o " + tmp.file("m.mov"), "--crf:"},
        {"--prores-profile lt -o " + tmp.file("m.mov"), "--prores-profile: needs"},
        {"--codec vp9 -o " + tmp.file("m.mp4"), "--codec"},
        {"--crf 52 -o " + tmp.file("m.mp4"), "--crf"},
        {"--view Nope -o " + tmp.file("m.mp4"), "--view"},
    };
    // ffmpeg must not even start: a PATH without it would turn any late check into
    // "ffmpeg not found" (exit 1).
    for (const Case &c : cases) {
        const std::string cmd = "PATH=" + tmp.file("empty") + " " + PELAGE_BINARY +
                                " movie " + frames + " " + c.args + " 2>" +
                                tmp.file("err");
        EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 2) << c.args;
        const std::string err = slurp(tmp.file("err"));
        EXPECT_NE(err.find(c.field), std::string::npos) << c.args << ": " << err;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()),
              4);  // the scene, two frames, err
}

TEST(MovieCli, AnFfmpegThatDiesEarlyIsReportedNotASigpipe) {
    TempDir tmp;
    ASSERT_EQ(run_pelage("render " + flat_scene(tmp) +
                         " -q --frames 0-11 --res 640x480 -o " + tmp.file("f.####.exr")),
              0);
    // An ffmpeg that refuses at once, as the real one does with a bad option, so every
    // frame write meets a closed pipe.
    fs::create_directories(tmp.file("bin"));
    tmp.write("bin/ffmpeg", "#!/bin/sh\necho 'Unknown encoder libx264' >&2\nexit 1\n");
    fs::permissions(tmp.file("bin/ffmpeg"), fs::perms::owner_all);
    const std::string cmd = "PATH=" + tmp.file("bin") + ":/usr/bin:/bin " +
                            PELAGE_BINARY + " movie " + tmp.file("f.####.exr") + " -o " +
                            tmp.file("m.mp4") + " 2>" + tmp.file("err");
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1);
    const std::string err = slurp(tmp.file("err"));
    EXPECT_NE(err.find("ffmpeg failed (exit 1)"), std::string::npos) << err;
    EXPECT_NE(err.find("Unknown encoder libx264"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(tmp.file("m.mp4")));
    for (const auto &e : fs::directory_iterator(tmp.path()))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos)
            << e.path();
}

}  // namespace
}  // namespace pelage::test
