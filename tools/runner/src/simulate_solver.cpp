// The frame loop of run_scene for a single solver, with nothing written: step a frame, measure it,
// apply the stretch checks, hand the frame to the caller.
#include "drapelab/runner/simulate_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "drapelab/collision_metrics.hpp"
#include "drapelab/scene/number_format.hpp"
#include "solver_factory.hpp"

namespace drapelab::runner {
namespace {

using Clock = std::chrono::steady_clock;

bool interrupted(const SimulationOptions& options) {
  return options.interrupt && options.interrupt->load(std::memory_order_relaxed);
}

// The metrics run_scene records for a frame: cloth metrics, plus clearance when there are
// colliders.
ClothMetrics measure(const scene::Scene& scene, const SceneSetup& setup, const ClothState& state,
                     double time) {
  ClothMetrics metrics = frame_metrics(setup, scene, state);
  if (setup.contacts) {
    const CollisionMetrics collisions =
        compute_collision_metrics(*setup.model, state, *setup.contacts, time);
    metrics.min_clearance = collisions.min_clearance;
    metrics.max_penetration = collisions.max_penetration;
    metrics.contact_count = collisions.contact_count;
  }
  return metrics;
}

// Which stretch check refuses a measured frame (none when it passes); a NaN stretch is refused too.
StopCause stretch_check(const scene::SolverSpec& spec, const ClothMetrics& metrics,
                        double stretch_limit) {
  if (!(metrics.max_stretch <= spec.runaway_stretch)) return StopCause::runaway_stretch;
  if (!(metrics.max_stretch < stretch_limit)) return StopCause::stretch_limit;
  return StopCause::none;
}

}  // namespace

double SimulationResult::second_half_wall_seconds_per_simulated_second(double frame_period) const {
  const int last = static_cast<int>(stepping_seconds_at_frame.size()) - 1;
  if (last < 2) return 0.0;
  const int middle = last / 2;
  return (stepping_seconds_at_frame[last] - stepping_seconds_at_frame[middle]) / ((last - middle) * frame_period);
}

SimulationResult simulate_solver(const scene::Scene& scene, const scene::SolverSpec& spec,
                                 const SceneSetup& setup, const SimulationOptions& options) {
  SimulationResult result;
  result.dt = spec.dt;
  const auto solver = make_solver(scene, spec, setup.model, setup.initial, setup.contacts);
  for (int frame = 0; frame <= scene.frame_count(); ++frame) {
    if (frame > 0) {
      const auto start = Clock::now();
      for (int s = 0; s < spec.steps_per_frame; ++s) {
        solver->step(spec.dt);
        ++result.steps;
        if (solver->status() != SolverStatus::ok || interrupted(options)) break;
      }
      result.wall_seconds += std::chrono::duration<double>(Clock::now() - start).count();
    }
    if (solver->status() != SolverStatus::ok) {
      result.status = solver->status();
      result.message = solver->message();
      result.stopped_by = StopCause::solver;
      result.stopped_at_frame = frame;
      break;
    }
    if (frame > 0 && interrupted(options)) {  // a partly stepped frame is not measured
      result.stopped_by = StopCause::interrupted;
      break;
    }
    const double time = frame / scene.frame_rate;  // s
    result.final_metrics = measure(scene, setup, solver->state(), time);
    // The first frame sets it (a sheet under compression has a negative max stretch); a NaN state
    // must not read as stable, so NaN sticks.
    const double stretch = result.final_metrics.max_stretch;
    if (frame == 0 || std::isnan(stretch))
      result.max_stretch = stretch;
    else if (!std::isnan(result.max_stretch))
      result.max_stretch = std::max(result.max_stretch, stretch);
    const StopCause cause = stretch_check(spec, result.final_metrics, options.stretch_limit);
    if (cause != StopCause::none) {
      const bool runaway = cause == StopCause::runaway_stretch;
      result.status = SolverStatus::unstable;
      result.message =
          describe_most_stretched_spring(*setup.model, solver->state()) +
          (runaway ? " (more than runaway_stretch = " + format_number(spec.runaway_stretch)
                   : " (at least the stretch limit " + format_number(options.stretch_limit)) +
          ") at frame " + std::to_string(frame) + ", step " + std::to_string(result.steps);
      result.stopped_by = cause;
      result.stopped_at_frame = frame;
      break;
    }
    ++result.frames_recorded;
    result.stepping_seconds_at_frame.push_back(result.wall_seconds);
    if (options.on_frame) options.on_frame(frame, solver->state(), result.final_metrics);
  }
  result.final_state = solver->state();
  result.counters = solver->counters();
  return result;
}

}  // namespace drapelab::runner
