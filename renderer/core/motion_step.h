// Where a time in the shutter falls among a moving geometry's time steps: Embree's
// multi-segment motion blur spaces the steps evenly over [0, 1] and moves linearly from
// one to the next, and the shading of a hit must follow the same path.
#pragma once

#include <algorithm>
#include <cstddef>

namespace pelage::renderer {

// Segment i (between steps i and i + 1) of `segments`, and the fraction f into it.
struct MotionStep {
    size_t i;
    float f;
};

inline MotionStep motion_step(float time, size_t segments) {
    const float x = std::clamp(time, 0.0f, 1.0f) * float(segments);
    const size_t i = std::min(size_t(x), segments - 1);
    return {i, x - float(i)};
}

}  // namespace pelage::renderer
