// One solver of a scene simulated in-process, without an output folder: what the stability and
// study verbs run many times with different steps and integrators. The solver is built by the same
// factory from the same setup and runs through the same frame loop as in run_scene (same per-frame
// metrics, same checks), so a trial here behaves like that solver in `drapelab run`.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/runner/scene_setup.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::runner {

struct SimulationOptions {
  // A recorded frame whose max stretch (ClothMetrics::max_stretch, |x_a - x_b| / L - 1 over stretch
  // springs) is not below this stops the run as unstable. The scene's runaway_stretch applies too,
  // as in run_scene; infinity leaves it alone.
  double stretch_limit = std::numeric_limits<double>::infinity();
  const std::atomic<bool>* interrupt = nullptr;  // Ctrl-C: stop after the current step
  // Called at every recorded frame that passed the checks (frame 0 = the initial state), in order.
  std::function<void(int frame, const ClothState& state, const ClothMetrics& metrics)> on_frame;
};

// Why a simulation ended before its duration.
enum class StopCause {
  none,             // ran to the end
  solver,           // the solver's own status left ok (non-finite state, runaway speed, ...)
  runaway_stretch,  // the scene's runaway_stretch, as in run_scene
  stretch_limit,    // SimulationOptions::stretch_limit
  interrupted,      // options.interrupt was set (the status stays ok)
};

struct SimulationResult {
  SolverStatus status = SolverStatus::ok;  // the solver's own, or unstable from the stretch checks
  std::string message;  // why not ok: the solver's message or the stretched spring
  StopCause stopped_by = StopCause::none;
  int frames_recorded = 0;    // frames that passed, frame 0 included
  int stopped_at_frame = -1;  // the frame at which the run stopped unstable, -1 otherwise
  double max_stretch = 0.0;   // max over the measured frames (the failing one included)
  double wall_seconds = 0.0;  // s, stepping only (no metrics), as in summary.json
  // s: wall_seconds when each recorded frame was reached (frame 0: 0), for the cost of part of a
  // run.
  std::vector<double> stepping_seconds_at_frame;
  std::int64_t steps = 0;
  double dt = 0.0;                                       // s, the step used
  ClothState final_state;                                // at the last step taken
  ClothMetrics final_metrics;                            // at the last frame measured
  std::vector<std::pair<std::string, double>> counters;  // Solver::counters() at the end

  bool interrupted() const { return stopped_by == StopCause::interrupted; }
  double simulated_seconds() const { return static_cast<double>(steps) * dt; }
  // A counter of Solver::counters() by name; nothing when the solver does not report it.
  std::optional<double> counter(const std::string& name) const {
    for (const auto& [key, value] : counters)
      if (key == name) return value;
    return std::nullopt;
  }
  double ms_per_step() const {
    return steps > 0 ? 1e3 * wall_seconds / static_cast<double>(steps) : 0.0;
  }
  double wall_seconds_per_simulated_second() const {
    return simulated_seconds() > 0.0 ? wall_seconds / simulated_seconds() : 0.0;
  }
  // Stepping wall seconds per simulated second over the second half of the recorded frames (from
  // frame K / 2 to the last, K), where a run that starts in free fall has settled into its
  // contacts; 0 with fewer than three frames. frame_period in s.
  double second_half_wall_seconds_per_simulated_second(double frame_period) const;
};

// Runs `spec` (a solver of `scene`, possibly with its dt, steps_per_frame or integrator changed;
// steps_per_frame x dt must be the frame period) for scene.duration, from `setup` (built from
// `scene`).
SimulationResult simulate_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                 const SceneSetup& setup, const SimulationOptions& options = {});

}  // namespace drapelab::runner
