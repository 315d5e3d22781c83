#include "renderer/job/render_plan.h"

#include <cctype>
#include <filesystem>

#include "renderer/image/frame_pattern.h"
#include "renderer/job/frame_list.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const std::string &path) {
    std::string e = fs::path(path).extension().string();
    for (char &c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

// The scene's preview when -o moves the render: beside it, named after it, so that
// outputs never land where the scene file says while the EXR goes elsewhere.
// "out.exr" → "out_preview.png"; "out.####.exr" → "out_preview.####.png".
std::string preview_beside(const std::string &output, const std::string &extension) {
    const fs::path out(output);
    std::string stem = out.stem().string(), token;
    if (const size_t dot = stem.rfind('.');
        dot != std::string::npos && has_frame_token(stem.substr(dot + 1))) {
        token = stem.substr(dot);
        stem.resize(dot);
    }
    return (out.parent_path() / (stem + "_preview" + token + extension)).string();
}

// The frames --frames (and --step) ask for, each inside the animation.
std::vector<int> requested_frames(const RenderJob &o, const AnimationDesc &anim,
                                  const std::string &scene_path) {
    if (!anim.present)
        throw InputError(
            scene_path, 0, "--frames",
            "\"" + o.frames + "\": the scene is a still (it has no \"animation\" block)");
    const long long first = anim.first_frame, last = first + anim.frames - 1;
    const std::vector<FrameRange> ranges = parse_frame_ranges(o.frames, o.step);
    for (const FrameRange &r : ranges)
        if (r.first < first || r.last > last)
            throw InputError(scene_path, 0, "animation.frames",
                             "--frames " + r.text +
                                 " is outside the animation's frames " +
                                 std::to_string(first) + "-" + std::to_string(last));
    return expand_frames(ranges);
}

}  // namespace

RenderPlan plan_render(const RenderJob &o, SceneDesc &desc) {
    if (o.spp > 0) desc.film.spp = o.spp;
    if (o.noise_threshold >= 0) desc.film.noise_threshold = float(o.noise_threshold);
    if (o.denoise) desc.film.denoise = true;
    if (o.width > 0 && o.height > 0) {
        desc.film.width = o.width;
        desc.film.height = o.height;
    }
    if (!o.view.empty()) desc.film.view = o.view;
    if (o.cryptomatte) desc.film.cryptomatte = {"*"};
    RenderPlan plan;
    plan.output = !o.output.empty() ? o.output : desc.film.output;
    const std::string &output = plan.output;
    if (output.empty())
        throw InputError(desc.path, 0, "film.output",
                         "no output file: give -o OUT.exr or set film.output");
    if (lower_extension(output) != ".exr")
        throw InputError("", 0, "-o",
                         "\"" + output + "\": the render is written as OpenEXR (.exr)");
    if (!o.tile.empty()) {
        plan.tile = parse_tile(o.tile);
        tile_rows(*plan.tile, desc.film.height, &plan.tile_y0, &plan.tile_y1);
        if (!o.frames.empty())
            throw InputError("", 0, "--tile",
                             "tiles split a still: give --tile or --frames, not both");
        if (o.output.empty())
            throw InputError("", 0, "--tile",
                             "give -o naming this tile's file (pelage merge joins them)");
        if (!o.preview.empty())
            throw InputError("", 0, "--preview",
                             "a tile has no preview: preview the merged image");
    }
    plan.preview = plan.tile            ? ""
                   : !o.preview.empty() ? o.preview
                   : !o.output.empty() && !desc.film.preview.empty()
                       ? preview_beside(o.output, lower_extension(desc.film.preview))
                       : desc.film.preview;
    const std::string &preview = plan.preview;
    if (!preview.empty()) {
        const std::string e = lower_extension(preview);
        if (e != ".png" && e != ".jpg" && e != ".jpeg")
            throw InputError("", 0, "--preview",
                             "\"" + preview + "\": expected a .png or .jpg file");
        plan.display.emplace(desc.film.view, "");  // checks the view now
    }

    // --frames LIST [--step N], or the still (an animation's first frame).
    plan.animated = !o.frames.empty();
    plan.frames = plan.animated ? requested_frames(o, desc.animation, desc.path)
                                : std::vector<int>{desc.animation.first_frame};
    if (plan.frames.size() > 1 && !has_frame_token(output))
        throw InputError("", 0, "-o",
                         "\"" + output +
                             "\": several frames need a frame number in the file name: "
                             "#### (4 digits), %04d or $F4");
    if (plan.frames.size() > 1 && !preview.empty() && !has_frame_token(preview))
        throw InputError("", 0, "--preview",
                         "\"" + preview +
                             "\": several frames need a frame number in the name: "
                             "####, %04d or $F4");
    if (o.resume && !plan.animated && !plan.tile)
        throw InputError("", 0, "--resume",
                         "resumes a frame range or a tile: give --frames or --tile too");

    std::vector<std::pair<std::string, std::string>> files = {{"-o", output},
                                                              {"--preview", preview}};
    files.insert(files.end(), o.other_outputs.begin(), o.other_outputs.end());
    for (const auto &[flag, file] : files) {
        if (file.empty()) continue;
        const fs::path dir = fs::absolute(fs::path(file)).parent_path();
        if (!fs::is_directory(dir))
            throw InputError(
                "", 0, flag,
                "\"" + file + "\": folder " + dir.string() + " does not exist");
    }
    return plan;
}

}  // namespace pelage::renderer
