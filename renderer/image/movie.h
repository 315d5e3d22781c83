// Image sequences to movies: out.####.exr frames (written by `pelage render --frames`)
// through an OpenColorIO display transform to 8-bit RGB, piped as raw video to ffmpeg
// (H.264, yuv420p). The movie is written to a temporary name and renamed into place.
#pragma once

#include <string>
#include <vector>

#include "renderer/image/color_management.h"

namespace pelage::renderer {

struct FrameFile {
    int frame;
    std::string path;
};

// The files matching `pattern` (a run of '#' stands for a zero-padded frame number of at
// least that width), in frame order. pelage::InputError (field `field`) when the
// pattern has no '#', no file matches, or frames are missing between the first and last.
std::vector<FrameFile> find_frame_sequence(const std::string &pattern,
                                           const std::string &field);

// The frame rate recorded in an EXR by `pelage render --frames` (pelage:fps, from the
// scene's animation.fps), or 0.
double recorded_fps(const std::string &exr);

// The ffmpeg executable on $PATH, or "" when there is none.
std::string find_ffmpeg();

// Encodes `frames` at `fps` to `output` with `ffmpeg`. Frames must share one size
// (InputError otherwise); std::runtime_error when ffmpeg fails.
void encode_movie(const std::vector<FrameFile> &frames, const std::string &output,
                  double fps, const DisplayTransform &display, const std::string &ffmpeg);

}  // namespace pelage::renderer
