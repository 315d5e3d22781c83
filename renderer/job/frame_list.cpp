#include "renderer/job/frame_list.h"

#include <algorithm>
#include <climits>
#include <cstddef>

#include "sim/core/input_error.h"

namespace pelage::renderer {

namespace {

// Reads the digits at s[*i...] into *value; false when there are none or they overflow
// an int.
bool read_number(const std::string &s, size_t *i, int *value) {
    const size_t start = *i;
    long long v = 0;
    while (*i < s.size() && s[*i] >= '0' && s[*i] <= '9') {
        v = 10 * v + (s[*i] - '0');
        if (v > INT_MAX) return false;
        ++*i;
    }
    *value = int(v);
    return *i > start;
}

}  // namespace

std::vector<FrameRange> parse_frame_ranges(const std::string &spec, int default_step,
                                           const std::string &flag) {
    auto fail = [&](const std::string &item, const std::string &why) {
        throw InputError("", 0, flag,
                         "\"" + item + "\" in \"" + spec + "\": " + why +
                             " (expected frames like 1001-1120, 1,5,9, 1-100x5 or "
                             "0-20x5,33)");
    };
    if (spec.empty()) fail(spec, "no frames");
    std::vector<FrameRange> ranges;
    size_t begin = 0;
    while (true) {
        const size_t comma = spec.find(',', begin);
        const std::string item =
            spec.substr(begin, comma == std::string::npos ? comma : comma - begin);
        if (item.empty()) fail(item, "an empty item");
        FrameRange r;
        r.text = item;
        r.step = default_step;
        size_t i = 0;
        if (!read_number(item, &i, &r.first))
            fail(item, i < item.size() && item[i] >= '0' && item[i] <= '9'
                           ? "a frame number too large"
                           : "not a frame number (frames are whole numbers >= 0)");
        r.last = r.first;
        if (i < item.size() && item[i] == '-') {
            ++i;
            if (!read_number(item, &i, &r.last))
                fail(item, i < item.size() && item[i] >= '0' && item[i] <= '9'
                               ? "a frame number too large"
                               : "a range needs a last frame >= 0");
            if (r.last < r.first) fail(item, "the range runs backwards");
            if (i < item.size() && item[i] == 'x') {
                ++i;
                if (default_step != 1)
                    fail(item, "a step in both --step and the frame list");
                if (!read_number(item, &i, &r.step) || r.step < 1)
                    fail(item, "a step must be a whole number >= 1");
            }
        }
        if (i != item.size()) fail(item, "unexpected \"" + item.substr(i) + "\"");
        ranges.push_back(r);
        if (comma == std::string::npos) break;
        begin = comma + 1;
    }
    return ranges;
}

std::vector<int> expand_frames(const std::vector<FrameRange> &ranges) {
    std::vector<int> frames;
    for (const FrameRange &r : ranges)
        for (long long f = r.first; f <= r.last; f += r.step) frames.push_back(int(f));
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

}  // namespace pelage::renderer
