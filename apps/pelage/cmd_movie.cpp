// `pelage movie out.####.exr -o turntable.mp4`: an EXR sequence through OpenColorIO to
// display, encoded by ffmpeg (renderer/image/movie.h). The view is the one the frames
// were rendered for unless --view says otherwise. A bad container or codec, missing
// frames and a missing ffmpeg are reported before anything is encoded. --stats-json keys:
// output, frames, first_frame, last_frame, step, fps, codec, crf or prores_profile, view,
// view_recorded, bytes, seconds.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "apps/common/common.h"
#include "renderer/image/movie.h"
#include "sim/core/input_error.h"

namespace pelage::renderer::cli {
namespace {

struct MovieCliOptions {
    std::string pattern, output, view;  // view "": the frames' pelage:view
    double fps = 0;                     // 0: the frames' pelage:fps, else 24
    std::string codec = "h264", prores_profile;
    int crf = -1;  // -1: the default
    QuietOption quiet;
    StatsJsonOption stats_json;
};

// --view, else the view recorded in the frames (all the same), else Standard.
std::string choose_view(const MovieCliOptions &o, const FrameSequence &seq,
                        bool *recorded) {
    *recorded = false;
    if (!o.view.empty()) return o.view;
    const std::string first = renderer::recorded_view(seq.frames.front().path);
    for (const FrameFile &f : seq.frames) {
        const std::string v = renderer::recorded_view(f.path);
        if (v != first)
            throw InputError("", 0, "--view",
                             "the frames were rendered for different views: " +
                                 seq.frames.front().path + " for " +
                                 (first.empty() ? "none recorded" : "\"" + first + "\"") +
                                 ", " + f.path + " for " +
                                 (v.empty() ? "none recorded" : "\"" + v + "\"") +
                                 "; choose one with --view");
    }
    *recorded = !first.empty();
    return first.empty() ? "Standard" : first;
}

int run(const MovieCliOptions &o) {
    namespace fs = std::filesystem;
    const Timer timer;
    renderer::MovieSettings settings;
    settings.codec = o.codec;
    if (o.crf >= 0) {
        if (o.codec != "h264")
            throw InputError("", 0, "--crf",
                             "sets H.264's quality; not with --codec " + o.codec);
        settings.crf = o.crf;
    }
    if (!o.prores_profile.empty()) {
        if (o.codec != "prores")
            throw InputError("", 0, "--prores-profile", "needs --codec prores");
        settings.prores_profile = o.prores_profile;
    }
    renderer::check_movie_settings(o.output, settings);
    const fs::path dir = fs::absolute(fs::path(o.output)).parent_path();
    if (!fs::is_directory(dir))
        throw InputError(
            "", 0, "-o",
            "\"" + o.output + "\": folder " + dir.string() + " does not exist");
    const FrameSequence seq = renderer::find_frame_sequence(o.pattern, "frames");
    const auto &frames = seq.frames;
    bool recorded = false;
    const std::string view = choose_view(o, seq, &recorded);
    std::optional<renderer::DisplayTransform> display;
    try {
        display.emplace(view, "");
    } catch (const InputError &e) {
        if (!recorded) throw InputError("", 0, "--view", e.what());
        throw InputError(frames.front().path, 0, "pelage:view",
                         std::string(e.what()) + "; choose one with --view");
    }
    const std::string ffmpeg = renderer::find_ffmpeg();
    if (ffmpeg.empty()) {
        std::fprintf(stderr,
                     "pelage movie: ffmpeg not found on PATH; install Debian's ffmpeg "
                     "(sudo apt-get install ffmpeg; quickstart.sh does) or encode the "
                     "%zu frames yourself\n",
                     frames.size());
        return 1;
    }
    settings.fps = o.fps;
    if (settings.fps <= 0) settings.fps = renderer::recorded_fps(frames.front().path);
    if (settings.fps <= 0) settings.fps = 24;
    renderer::encode_movie(frames, o.output, settings, *display, ffmpeg);
    if (!o.quiet) {
        const std::string step =
            seq.step > 1 ? ", step " + std::to_string(seq.step) : std::string();
        const std::string codec = o.codec == "prores"
                                      ? "ProRes " + settings.prores_profile
                                      : "H.264 crf " + std::to_string(settings.crf);
        std::printf("%s: %zu frames (%d-%d%s) at %g fps, %s, view %s%s\n",
                    o.output.c_str(), frames.size(), frames.front().frame,
                    frames.back().frame, step.c_str(), settings.fps, codec.c_str(),
                    view.c_str(), recorded ? " (recorded in the frames)" : "");
    }
    if (o.stats_json.wanted()) {
        nlohmann::json j = {{"output", o.output},
                            {"frames", frames.size()},
                            {"first_frame", frames.front().frame},
                            {"last_frame", frames.back().frame},
                            {"step", seq.step},
                            {"fps", settings.fps},
                            {"codec", o.codec},
                            {"view", view},
                            {"view_recorded", recorded},
                            {"bytes", fs::file_size(o.output)},
                            {"seconds", timer.seconds()}};
        if (o.codec == "prores")
            j["prores_profile"] = settings.prores_profile;
        else
            j["crf"] = settings.crf;
        o.stats_json.write(j);
    }
    return 0;
}

}  // namespace

Runner add_movie_command(CLI::App &app) {
    auto o = std::make_shared<MovieCliOptions>();
    CLI::App *sub = app.add_subcommand(
        "movie", "Encode an EXR sequence (out.####.exr) to a movie with ffmpeg");
    sub->add_option("frames", o->pattern,
                    "Frame pattern: out.####.exr, out.%04d.exr or out.$F4.exr")
        ->required();
    sub->add_option("-o,--output", o->output, "Movie file (.mp4, .mov or .mkv)")
        ->required();
    sub->add_option(
           "--fps", o->fps,
           "Frames per second (default: the scene's animation.fps recorded in the "
           "frames, else 24)")
        ->check(CLI::Range(0.001, 1000.0));
    sub->add_option("--view", o->view,
                    "OpenColorIO view (Standard, Filmic, Raw; default: the view the "
                    "frames were rendered for, else Standard)");
    sub->add_option("--codec", o->codec, "h264 (default) or prores (.mov only)")
        ->check(CLI::IsMember({"h264", "prores"}));
    sub->add_option("--crf", o->crf,
                    "H.264 quality: 0 lossless, 18 (default) visually lossless, 51 worst")
        ->check(CLI::Range(0, 51));
    sub->add_option("--prores-profile", o->prores_profile,
                    "proxy, lt, standard, hq (default), 4444 or 4444xq")
        ->check(CLI::IsMember({"proxy", "lt", "standard", "hq", "4444", "4444xq"}));
    o->stats_json.add_to(*sub, "the frames encoded, codec, view and file size");
    o->quiet.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
