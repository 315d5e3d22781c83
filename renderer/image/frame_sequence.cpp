#include "renderer/image/frame_sequence.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "renderer/image/frame_pattern.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace fs = std::filesystem;

namespace {

// "frame 30", "frames 40-59", "frames 30-50 (step 10)".
std::string describe_frames(int a, int b, int step) {
    if (a == b) return "frame " + std::to_string(a);
    std::string s = "frames " + std::to_string(a) + "-" + std::to_string(b);
    if (step > 1) s += " (step " + std::to_string(step) + ")";
    return s;
}

}  // namespace

FrameSequence find_frame_sequence(const std::string &pattern, const std::string &field) {
    const fs::path p(pattern);
    const auto fp = parse_frame_pattern(p.filename().string());
    if (!fp)
        throw InputError("", 0, field,
                         "\"" + pattern +
                             "\": expected a frame pattern such as out.####.exr, "
                             "out.%04d.exr or out.$F4.exr");
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();

    FrameSequence seq;
    std::vector<FrameFile> &frames = seq.frames;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string f = it->path().filename().string();
        if (const auto n = match_frame(*fp, f))
            frames.push_back({*n, (p.parent_path() / f).string()});
    }
    if (frames.empty())
        throw InputError("", 0, field,
                         "\"" + pattern +
                             "\": no frames found (render them with "
                             "pelage render --frames)");
    std::sort(frames.begin(), frames.end(),
              [](const FrameFile &a, const FrameFile &b) { return a.frame < b.frame; });
    // The step: the most common gap (the smaller on a tie), so a hole shows as a larger
    // gap and a stray frame from another render as a frame off the step.
    std::map<int, size_t> gaps;
    for (size_t i = 1; i < frames.size(); ++i) {
        const int gap = frames[i].frame - frames[i - 1].frame;
        if (gap == 0)
            throw InputError("", 0, field,
                             "frame " + std::to_string(frames[i].frame) +
                                 " is there twice: " + frames[i - 1].path + ", " +
                                 frames[i].path);
        ++gaps[gap];
    }
    seq.step = 1;
    size_t most = 0;
    for (const auto &[gap, n] : gaps)
        if (n > most) seq.step = gap, most = n;
    const int step = seq.step;
    // The frames on the step: those sharing the most common remainder.
    std::map<int, size_t> remainders;
    for (const FrameFile &f : frames) ++remainders[f.frame % step];
    int on = frames.front().frame % step;
    for (const auto &[r, n] : remainders)
        if (n > remainders[on]) on = r;
    for (const FrameFile &f : frames)
        if (f.frame % step != on)
            throw InputError(
                "", 0, field,
                "\"" + pattern + "\": " + f.path + " (frame " + std::to_string(f.frame) +
                    ") is off the sequence's step of " + std::to_string(step) +
                    "; are two renders mixed in one folder?");
    const int first = frames.front().frame, last = frames.back().frame;
    const long long expected = (static_cast<long long>(last) - first) / step + 1;
    for (size_t i = 1; i < frames.size(); ++i) {
        if (frames[i].frame == frames[i - 1].frame + step) continue;
        const int a = frames[i - 1].frame + step, b = frames[i].frame - step;
        const long long missing = expected - static_cast<long long>(frames.size());
        const bool more = missing > (b - a) / step + 1;
        throw InputError("", 0, field,
                         "\"" + pattern + "\": " + describe_frames(a, b, step) +
                             " missing" +
                             (more ? " (" + std::to_string(missing) + " in all)" : "") +
                             " from the sequence " + std::to_string(first) + "-" +
                             std::to_string(last) +
                             (step > 1 ? ", step " + std::to_string(step) : "") +
                             "; render them, e.g. with pelage render --resume");
    }
    return seq;
}

}  // namespace pelage::renderer
