// Image sequences to movies: frames written by `pelage render --frames` through an
// OpenColorIO display transform to 8-bit RGB, piped as raw video to ffmpeg, which
// converts to Y'CbCr with the BT.709 matrix at limited range and encodes H.264 (MP4,
// MOV, MKV) or ProRes (MOV). The stream is tagged with what it holds: the matrix, the
// range and, for an sRGB or Rec.709 display, its primaries and transfer function. The
// movie is written to a temporary name and renamed into place.
#pragma once

#include <string>
#include <vector>

#include "renderer/image/color_management.h"
#include "renderer/image/frame_sequence.h"

namespace pelage::renderer {

struct MovieSettings {
    std::string codec = "h264";         // "h264" or "prores"
    int crf = 18;                       // H.264 quality: 0 lossless … 51 worst
    std::string prores_profile = "hq";  // proxy, lt, standard, hq, 4444, 4444xq
    double fps = 24;
};

// pelage::InputError naming -o for a container pelage does not write (.mp4, .mov and
// .mkv are written), naming --codec for a codec the container cannot hold (ProRes is
// MOV only) or an unknown codec, naming --prores-profile for an unknown profile.
void check_movie_settings(const std::string &output, const MovieSettings &s);

// ffmpeg's output arguments (after "-i -") for `s`, a display named `display` and a
// container with file extension `extension`: the conversion to Y'CbCr, the encoder
// and the colour tags.
std::vector<std::string> movie_encode_args(const MovieSettings &s,
                                           const std::string &display,
                                           const std::string &extension);

// The frame rate recorded in an EXR by `pelage render --frames` (pelage:fps, from the
// scene's animation.fps), or 0.
double recorded_fps(const std::string &exr);

// The OpenColorIO view an EXR was rendered for (pelage:view), or "".
std::string recorded_view(const std::string &exr);

// The ffmpeg executable on $PATH, or "" when there is none.
std::string find_ffmpeg();

// Encodes `frames` to `output` with `ffmpeg`. Frames must share one size (InputError
// otherwise); std::runtime_error with the end of ffmpeg's messages when ffmpeg fails
// or stops reading early.
void encode_movie(const std::vector<FrameFile> &frames, const std::string &output,
                  const MovieSettings &settings, const DisplayTransform &display,
                  const std::string &ffmpeg);

}  // namespace pelage::renderer
