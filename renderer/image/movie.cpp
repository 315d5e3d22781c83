#include "renderer/image/movie.h"

#include <OpenImageIO/imageio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
    for (char &c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

const char *const prores_profiles[] = {"proxy", "lt", "standard", "hq", "4444", "4444xq"};

int prores_profile_index(const std::string &name) {
    for (int i = 0; i < 6; ++i)
        if (name == prores_profiles[i]) return i;
    return -1;
}

}  // namespace

void check_movie_settings(const std::string &output, const MovieSettings &s) {
    const std::string ext = lower(fs::path(output).extension().string());
    if (ext != ".mp4" && ext != ".mov" && ext != ".mkv")
        throw InputError("", 0, "-o",
                         "\"" + output +
                             "\": pelage movie writes .mp4, .mov or .mkv (for a GIF or "
                             "another format, convert the .mp4 with ffmpeg)");
    if (s.codec != "h264" && s.codec != "prores")
        throw InputError("", 0, "--codec",
                         "\"" + s.codec + "\": expected h264 or prores");
    if (s.codec == "prores" && ext != ".mov")
        throw InputError(
            "", 0, "--codec",
            "ProRes is written in QuickTime (.mov) only, not \"" + output + "\"");
    if (prores_profile_index(s.prores_profile) < 0)
        throw InputError("", 0, "--prores-profile",
                         "\"" + s.prores_profile +
                             "\": expected proxy, lt, standard, hq, 4444 or 4444xq");
    if (s.crf < 0 || s.crf > 51)
        throw InputError("", 0, "--crf", std::to_string(s.crf) + ": expected 0-51");
}

std::vector<std::string> movie_encode_args(const MovieSettings &s,
                                           const std::string &display,
                                           const std::string &extension) {
    const bool prores = s.codec == "prores";
    const int profile = prores_profile_index(s.prores_profile);
    const bool full_chroma = prores && profile >= 4;
    const std::string pix_fmt = !prores       ? "yuv420p"
                                : full_chroma ? "yuv444p10le"
                                              : "yuv422p10le";
    // Primaries and transfer function only for a display whose encoding is known.
    const std::string d = lower(display);
    std::string primaries, trc;
    if (d.find("srgb") != std::string::npos)
        primaries = "bt709", trc = "iec61966-2-1";
    else if (d.find("709") != std::string::npos || d.find("1886") != std::string::npos)
        primaries = "bt709", trc = "bt709";
    // The pixels are display-referred R'G'B'; the scale filter converts them with the
    // BT.709 matrix to limited range, and setparams marks the frames so (ProRes takes
    // its tags from the frames, H.264 and the container from the options below).
    // Subsampled chroma needs even sizes: odd ones are padded by one pixel.
    std::string vf = full_chroma ? "" : "pad=ceil(iw/2)*2:ceil(ih/2)*2,";
    vf += "scale=out_color_matrix=bt709:out_range=tv,format=" + pix_fmt +
          ",setparams=range=tv:colorspace=bt709";
    if (!trc.empty()) vf += ":color_primaries=" + primaries + ":color_trc=" + trc;
    std::vector<std::string> a = {"-vf", vf};
    if (prores)
        a.insert(a.end(), {"-c:v", "prores_ks", "-profile:v", std::to_string(profile),
                           "-vendor", "apl0"});
    else
        a.insert(a.end(), {"-c:v", "libx264", "-crf", std::to_string(s.crf)});
    a.insert(a.end(),
             {"-pix_fmt", pix_fmt, "-color_range", "tv", "-colorspace", "bt709"});
    if (!trc.empty())
        a.insert(a.end(), {"-color_primaries", primaries, "-color_trc", trc});
    const std::string ext = lower(extension);
    if (ext == ".mp4" || ext == ".mov")
        a.insert(a.end(), {"-movflags", "+faststart+write_colr"});
    return a;
}

double recorded_fps(const std::string &exr) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) return 0;
    return double(in->spec().get_float_attribute("pelage:fps", 0.0f));
}

std::string recorded_view(const std::string &exr) {
    auto in = OIIO::ImageInput::open(exr);
    if (!in) return "";
    return in->spec().get_string_attribute("pelage:view");
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

// The last few lines of ffmpeg's messages, for the error report.
std::string tail_of(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)),
                     std::istreambuf_iterator<char>());
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
        text.pop_back();
    size_t from = text.size();
    for (int lines = 0; lines < 8 && from > 0; ++lines) {
        const size_t nl = text.rfind('\n', from - 1);
        from = nl == std::string::npos ? 0 : nl;
    }
    if (text.size() - from > 2000) from = text.size() - 2000;
    while (from < text.size() && text[from] == '\n') ++from;
    return text.substr(from);
}

// While alive, writing to a pipe whose reader is gone fails with EPIPE instead of
// killing the process, so an ffmpeg that exits early is reported, not a silent 141.
class IgnoreSigpipe {
  public:
    IgnoreSigpipe() : m_previous(std::signal(SIGPIPE, SIG_IGN)) {}
    ~IgnoreSigpipe() { std::signal(SIGPIPE, m_previous); }
    IgnoreSigpipe(const IgnoreSigpipe &) = delete;
    IgnoreSigpipe &operator=(const IgnoreSigpipe &) = delete;

  private:
    void (*m_previous)(int);
};

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
                  const MovieSettings &settings, const DisplayTransform &display,
                  const std::string &ffmpeg) {
    check_movie_settings(output, settings);
    int w = 0, h = 0;
    std::vector<unsigned char> first =
        read_display_rgb(frames.front().path, &w, &h, display);
    const fs::path out(output);
    const std::string tag = ".tmp" + std::to_string(getpid());
    const std::string tmp =
        (out.parent_path() / ("." + out.stem().string() + tag + out.extension().string()))
            .string();
    const std::string log =
        (fs::temp_directory_path() / ("pelage-movie" + tag + ".log")).string();
    char input[160];
    std::snprintf(input, sizeof input,
                  " -y -nostdin -loglevel error -f rawvideo -pix_fmt rgb24 -s %dx%d -r "
                  "%.6g -i -",
                  w, h, settings.fps);
    std::string cmd = shell_quote(ffmpeg) + input;
    for (const std::string &a :
         movie_encode_args(settings, display.display(), out.extension().string()))
        cmd += " " + shell_quote(a);
    cmd += " " + shell_quote(tmp) + " 2>" + shell_quote(log);
    FILE *pipe = ::popen(cmd.c_str(), "w");
    if (!pipe) throw std::runtime_error("cannot start ffmpeg: " + cmd);
    bool ok = true, input_error = false;
    std::string error;
    int status = 0;
    {
        const IgnoreSigpipe no_sigpipe;  // after popen: ffmpeg keeps the default action
        for (size_t i = 0; i < frames.size() && ok; ++i) {
            int fw = w, fh = h;
            std::vector<unsigned char> rgb;
            try {
                rgb = i == 0 ? std::move(first)
                             : read_display_rgb(frames[i].path, &fw, &fh, display);
            } catch (const std::exception &e) {
                ok = false;
                input_error = true;
                error = e.what();
                break;
            }
            if (fw != w || fh != h) {
                ok = false;
                input_error = true;
                error = frames[i].path + ": " + std::to_string(fw) + "x" +
                        std::to_string(fh) + ", the first frame is " + std::to_string(w) +
                        "x" + std::to_string(h);
                break;
            }
            if (std::fwrite(rgb.data(), 1, rgb.size(), pipe) != rgb.size()) {
                ok = false;
                error =
                    "ffmpeg stopped reading at frame " + std::to_string(frames[i].frame);
            }
        }
        status = ::pclose(pipe);  // flushes: may hit EPIPE too
    }
    const std::string messages = tail_of(log);
    std::error_code ec;
    fs::remove(log, ec);
    if (!ok || status != 0) {
        fs::remove(tmp, ec);
        if (input_error) throw InputError("", 0, "", error);
        std::string why = "ffmpeg failed";
        if (WIFEXITED(status))
            why += " (exit " + std::to_string(WEXITSTATUS(status)) + ")";
        else if (WIFSIGNALED(status))
            why += " (signal " + std::to_string(WTERMSIG(status)) + ")";
        if (!error.empty()) why += "; " + error;
        throw std::runtime_error(
            why + (messages.empty() ? std::string(", no message") : ":\n" + messages));
    }
    fs::rename(tmp, output, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(output +
                                 ": cannot move the movie into place: " + ec.message());
    }
}

}  // namespace pelage::renderer
