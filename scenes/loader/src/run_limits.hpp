// How long a run may be. The loader refuses scenes beyond these bounds so that frame and step
// counts fit an int and a slip of the finger (dt: 1e-13, frame_rate: 1e-300, duration: 4e7) is an
// error naming the key, not an overflow, a run of no frames or one that never ends.
#pragma once

#include <string>

#include "drapelab/scene/number_format.hpp"

namespace drapelab::scene {

inline constexpr double kMaxFrames = 1e7;  // recorded frames after frame 0 (duration x frame_rate)
inline constexpr double kMaxStepsPerFrame =
    1e7;  // solver steps per recorded frame (frame period / dt)

// The message for a solver step that gives more than kMaxStepsPerFrame steps per frame.
inline std::string too_many_steps_message(double frame_period, double dt, bool automatic) {
  return std::string(automatic ? "chosen automatically from the stable step is " : "is ") +
         format_number(dt) + " s, which gives " + format_number(frame_period / dt) +
         " steps per frame of " + format_number(frame_period) + " s; at most " +
         std::to_string(static_cast<long long>(kMaxStepsPerFrame)) +
         " steps per frame are allowed: use a larger dt (softer springs for an automatic one) or a "
         "higher frame_rate";
}

}  // namespace drapelab::scene
