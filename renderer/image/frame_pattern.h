// Frame-number placeholders in file names, as renderers and compositors write them:
//   a run of N '#'    N digits, zero-padded     cow.####.exr  -> cow.0007.exr
//   %0Nd, %d          N digits, or unpadded     cow.%04d.exr  -> cow.0007.exr
//   $FN, $F           N digits, or unpadded     cow.$F4.exr   -> cow.0007.exr
// A frame that needs more digits than the width gets them (frame 12345 of #### is
// 12345). The last placeholder in the text is the frame number; any other is literal.
// N is read whole ($F04 is 4 digits) and must be 1 to 10: a text whose last placeholder
// is wider, or 0 wide (%00d, $F0), has none. This is the one parser of these tokens:
// `pelage render` writes names with it and `pelage movie` reads them back with it.
#pragma once

#include <optional>
#include <string>

namespace pelage::renderer {

struct FramePattern {
    std::string head, tail;  // the text before and after the placeholder
    std::string token;       // the placeholder as written, e.g. "####" or "%04d"
    int width = 1;           // minimum number of digits (1 = unpadded)
};

// The last placeholder in `text`, or nullopt when there is none (or its width is
// above 10 digits).
std::optional<FramePattern> parse_frame_pattern(const std::string &text);

// head + `frame` (>= 0) zero-padded to the width + tail.
std::string format_frame(const FramePattern &p, int frame);

// The frame number `text` names under `p`, or nullopt when `text` is not a name
// format_frame would write (other text, no digits, a superfluous leading zero, a
// number beyond int).
std::optional<int> match_frame(const FramePattern &p, const std::string &text);

// True when `name` holds a placeholder parse_frame_pattern accepts.
bool has_frame_token(const std::string &name);

// `name` with its placeholder replaced by `frame` (format_frame): out.####.exr,
// out.%04d.exr and out.$F4.exr all give out.0007.exr for frame 7. A name without a
// placeholder is returned unchanged.
std::string substitute_frame(const std::string &name, int frame);

}  // namespace pelage::renderer
