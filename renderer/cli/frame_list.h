// Frame lists as render-farm managers write them (Deadline, OpenCue, Blender's
// command line), and the frame-number tokens of sequence file names.
//   --frames: comma-separated items, each N, FIRST-LAST or FIRST-LASTxSTEP, e.g.
//   "1001-1120", "1,5,9", "1-100x5", "0-20x5,33". Strict: no spaces, signs or junk.
//   File names: a run of N '#' (N digits, "####"), printf's "%d" / "%0Nd", or Houdini's
//   "$F" / "$FN"; the frame number is zero-padded to N digits.
#pragma once

#include <string>
#include <vector>

namespace pelage::renderer::cli {

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

// True when `name` holds a frame-number token (see above).
bool has_frame_token(const std::string &name);

// `name` with its last frame-number token replaced by `frame`, zero-padded to the
// token's width: out.####.exr, out.%04d.exr and out.$F4.exr all give out.0007.exr for
// frame 7. A name without a token is returned unchanged.
std::string substitute_frame(const std::string &name, int frame);

}  // namespace pelage::renderer::cli
