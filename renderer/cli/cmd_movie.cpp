// `pelage movie out.####.exr -o turntable.mp4`: an EXR sequence through OpenColorIO to
// display, encoded by ffmpeg (renderer/image/movie.h). Missing frames and a missing
// ffmpeg are reported before anything is encoded.
#include <cstdio>
#include <filesystem>

#include "renderer/cli/common.h"
#include "renderer/image/movie.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

struct MovieCliOptions {
    std::string pattern, output, view = "Standard";
    double fps = 0;  // 0: the frames' pelage:fps, else 24
    bool quiet = false;
};

int run(const MovieCliOptions &o) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::absolute(fs::path(o.output)).parent_path();
    if (!fs::is_directory(dir))
        throw InputError(
            "", 0, "-o",
            "\"" + o.output + "\": folder " + dir.string() + " does not exist");
    const auto frames = renderer::find_frame_sequence(o.pattern, "frames");
    const renderer::DisplayTransform display(o.view, "");
    const std::string ffmpeg = renderer::find_ffmpeg();
    if (ffmpeg.empty()) {
        std::fprintf(stderr,
                     "pelage movie: ffmpeg not found on PATH; install Debian's ffmpeg "
                     "(sudo apt-get install ffmpeg; quickstart.sh does) or encode the "
                     "%zu frames yourself\n",
                     frames.size());
        return 1;
    }
    double fps = o.fps;
    if (fps <= 0) fps = renderer::recorded_fps(frames.front().path);
    if (fps <= 0) fps = 24;
    renderer::encode_movie(frames, o.output, fps, display, ffmpeg);
    if (!o.quiet)
        std::printf("%s: %zu frames (%d-%d) at %g fps, view %s\n", o.output.c_str(),
                    frames.size(), frames.front().frame, frames.back().frame, fps,
                    o.view.c_str());
    return 0;
}

}  // namespace

Runner add_movie_command(CLI::App &app) {
    auto o = std::make_shared<MovieCliOptions>();
    CLI::App *sub = app.add_subcommand(
        "movie", "Encode an EXR sequence (out.####.exr) to a movie with ffmpeg");
    sub->add_option("frames", o->pattern, "Frame pattern, e.g. out.####.exr")->required();
    sub->add_option("-o,--output", o->output, "Movie file (.mp4)")->required();
    sub->add_option(
           "--fps", o->fps,
           "Frames per second (default: the scene's animation.fps recorded in the "
           "frames, else 24)")
        ->check(CLI::Range(0.001, 1000.0));
    sub->add_option("--view", o->view, "OpenColorIO view (Standard, Filmic, Raw)");
    sub->add_flag("-q,--quiet", o->quiet, "No summary line");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
