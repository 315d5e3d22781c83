#include "renderer/image/movie.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace fs = std::filesystem;

std::vector<FrameFile> find_frame_sequence(const std::string &pattern,
                                           const std::string &field) {
    const fs::path p(pattern);
    const std::string name = p.filename().string();
    const size_t last = name.find_last_of('#');
    if (last == std::string::npos)
        throw InputError("", 0, field,
                         "\"" + pattern +
                             "\": expected a frame pattern such as "
                             "out.####.exr");
    size_t first = last;
    while (first > 0 && name[first - 1] == '#') --first;
    const std::string prefix = name.substr(0, first), suffix = name.substr(last + 1);
    const size_t width = last - first + 1;
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();

    // --- Every file prefix + digits (at least `width`) + suffix ---
    std::vector<FrameFile> frames;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string f = it->path().filename().string();
        if (f.size() < prefix.size() + suffix.size() + width ||
            f.compare(0, prefix.size(), prefix) != 0 ||
            f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string digits =
            f.substr(prefix.size(), f.size() - prefix.size() - suffix.size());
        if (digits.size() < width || digits.size() > 9 ||
            !std::all_of(digits.begin(), digits.end(), ::isdigit))
            continue;
        frames.push_back({std::atoi(digits.c_str()), (dir / f).string()});
    }
    if (frames.empty())
        throw InputError("", 0, field,
                         "\"" + pattern +
                             "\": no frames found (render them with "
                             "pelage render --frames)");
    std::sort(frames.begin(), frames.end(),
              [](const FrameFile &a, const FrameFile &b) { return a.frame < b.frame; });
    for (size_t i = 1; i < frames.size(); ++i) {
        if (frames[i].frame == frames[i - 1].frame)
            throw InputError("", 0, field,
                             "frame " + std::to_string(frames[i].frame) +
                                 " is there twice: " + frames[i - 1].path + ", " +
                                 frames[i].path);
        if (frames[i].frame != frames[i - 1].frame + 1) {
            const int a = frames[i - 1].frame + 1, b = frames[i].frame - 1;
            throw InputError(
                "", 0, field,
                "\"" + pattern + "\": frame" + (a == b ? " " : "s ") + std::to_string(a) +
                    (a == b ? "" : "-" + std::to_string(b)) +
                    " missing (the sequence has " + std::to_string(frames.front().frame) +
                    "-" + std::to_string(frames.back().frame) +
                    "; render them, e.g. with pelage render --resume)");
        }
    }
    return frames;
}

double recorded_fps(const std::string &exr) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) return 0;
    return double(in->spec().get_float_attribute("pelage:fps", 0.0f));
}

std::string find_ffmpeg() {
    const char *path = std::getenv("PATH");
    if (!path) return "";
    std::string all = path;
    size_t start = 0;
    while (start <= all.size()) {
        const size_t end = std::min(all.find(':', start), all.size());
        const std::string d = all.substr(start, end - start);
        if (!d.empty()) {
            const std::string f = (fs::path(d) / "ffmpeg").string();
            if (::access(f.c_str(), X_OK) == 0) return f;
        }
        start = end + 1;
    }
    return "";
}

namespace {

std::string shell_quote(const std::string &s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// The first three channels of an EXR as display-referred 8-bit RGB.
std::vector<unsigned char> read_display_rgb(const std::string &path, int *w, int *h,
                                            const DisplayTransform &display) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path, 0, "", "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec &spec = in->spec();
    *w = spec.width;
    *h = spec.height;
    if (spec.nchannels < 3) throw InputError(path, 0, "", "fewer than 3 channels");
    std::vector<float> rgb(size_t(spec.width) * spec.height * 3);
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, rgb.data()))
        throw InputError(path, 0, "", "cannot read pixels: " + in->geterror());
    display.apply_rgb(rgb.data(), size_t(spec.width) * spec.height);
    std::vector<unsigned char> bytes(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) {
        const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
        bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
    }
    return bytes;
}

}  // namespace

void encode_movie(const std::vector<FrameFile> &frames, const std::string &output,
                  double fps, const DisplayTransform &display,
                  const std::string &ffmpeg) {
    int w = 0, h = 0;
    std::vector<unsigned char> first =
        read_display_rgb(frames.front().path, &w, &h, display);
    const fs::path out(output);
    const std::string tmp =
        (out.parent_path() / ("." + out.stem().string() + ".tmp" +
                              std::to_string(getpid()) + out.extension().string()))
            .string();
    // H.264 in yuv420p needs even sizes: pad odd ones by one pixel.
    char cmd_args[256];
    std::snprintf(cmd_args, sizeof cmd_args,
                  " -y -loglevel error -f rawvideo -pix_fmt rgb24 -s %dx%d -r %.6g -i - "
                  "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p "
                  "-movflags +faststart ",
                  w, h, fps);
    const std::string cmd = shell_quote(ffmpeg) + cmd_args + shell_quote(tmp);
    FILE *pipe = ::popen(cmd.c_str(), "w");
    if (!pipe) throw std::runtime_error("cannot start ffmpeg: " + cmd);
    bool ok = true;
    std::string error;
    for (size_t i = 0; i < frames.size() && ok; ++i) {
        int fw = w, fh = h;
        std::vector<unsigned char> rgb;
        try {
            rgb = i == 0 ? std::move(first)
                         : read_display_rgb(frames[i].path, &fw, &fh, display);
        } catch (const std::exception &e) {
            ok = false;
            error = e.what();
            break;
        }
        if (fw != w || fh != h) {
            ok = false;
            error = frames[i].path + ": " + std::to_string(fw) + "x" +
                    std::to_string(fh) + ", the first frame is " + std::to_string(w) +
                    "x" + std::to_string(h);
            break;
        }
        if (std::fwrite(rgb.data(), 1, rgb.size(), pipe) != rgb.size()) {
            ok = false;
            error = "ffmpeg stopped reading frames";
        }
    }
    const int status = ::pclose(pipe);
    std::error_code ec;
    if (!ok || status != 0) {
        fs::remove(tmp, ec);
        if (!error.empty() && error.find("ffmpeg") == std::string::npos)
            throw InputError("", 0, "", error);
        throw std::runtime_error("ffmpeg failed (status " + std::to_string(status) + ")" +
                                 (error.empty() ? "" : ": " + error));
    }
    fs::rename(tmp, output, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(output +
                                 ": cannot move the movie into place: " + ec.message());
    }
}

}  // namespace pelage::renderer
