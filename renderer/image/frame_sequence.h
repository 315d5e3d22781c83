// The files of a rendered frame sequence on disk (cow.####.exr → cow.0000.exr,
// cow.0010.exr, …), checked complete: one step between all frames, no holes.
#pragma once

#include <string>
#include <vector>

namespace pelage::renderer {

struct FrameFile {
    int frame;
    std::string path;
};

struct FrameSequence {
    std::vector<FrameFile> frames;  // in frame order
    int step = 1;                   // between consecutive frames (1 for a single frame)
};

// The files matching `pattern`, whose file name holds a frame placeholder
// (renderer/image/frame_pattern.h: ####, %04d, $F4). The step is the most common gap
// between the frames found (`pelage render --step 10` writes 0, 10, 20, …).
// pelage::InputError (field `field`) when the pattern has no placeholder, no file
// matches, a frame is off the step, or frames are missing between the first and last
// (the message names them).
FrameSequence find_frame_sequence(const std::string &pattern, const std::string &field);

}  // namespace pelage::renderer
