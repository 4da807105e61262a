// What a run tells a progress display while it steps (drapelab run's progress lines: the command
// line formats and prints them; the runner only reports).
#pragma once

#include <string>
#include <vector>

namespace drapelab::runner {

// One solver of a run, as its progress line shows it.
struct SolverProgress {
  std::string name;
  int frames_done = 0;             // frames stepped and recorded after frame 0
  int frames_total = 0;            // the scene's frame count
  double simulated_seconds = 0.0;  // s, the time of the last frame recorded
  double duration_seconds = 0.0;   // s, the scene's duration
  double wall_seconds = 0.0;       // s, spent stepping and measuring this solver
  std::string stopped;             // its status when it stopped early (unstable, error); else empty
};

// Told of a run's progress by run_scene.
class RunProgress {
 public:
  virtual ~RunProgress() = default;
  // After every recorded frame (once its rows are written), every solver in the scene's order.
  virtual void frame_recorded(const std::vector<SolverProgress>& solvers) = 0;
  // When the frames end (finished, stopped or interrupted), before the run's closing messages.
  virtual void frames_ended() = 0;
};

}  // namespace drapelab::runner
