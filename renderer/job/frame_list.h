// Frame lists as render-farm managers write them (Deadline, OpenCue, Blender's
// command line): comma-separated items, each N, FIRST-LAST or FIRST-LASTxSTEP, e.g.
// "1001-1120", "1,5,9", "1-100x5", "0-20x5,33". Strict: no spaces, signs or junk.
// The frame-number tokens of file names are renderer/image/frame_pattern.h's.
#pragma once

#include <string>
#include <vector>

namespace pelage::renderer {

// One item of a frame list: first..last (inclusive) every `step`-th frame.
struct FrameRange {
    int first = 0, last = 0, step = 1;
    std::string text;  // the item as written, for error messages
};

// Parses `spec`; items without an explicit step take `default_step` (the --step
// option). Throws pelage::InputError at field `flag` naming the offending item.
std::vector<FrameRange> parse_frame_ranges(const std::string &spec, int default_step = 1,
                                           const std::string &flag = "--frames");

// Every frame of the ranges, ascending, each once.
std::vector<int> expand_frames(const std::vector<FrameRange> &ranges);

}  // namespace pelage::renderer
