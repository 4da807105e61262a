// What the runner keeps about each solver of a run, filled in by the frame loop (frame_loop.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/run_folder/point_cache.hpp"
#include "drapelab/runner/energy_audit.hpp"
#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"
#include "rest_measures.hpp"

namespace drapelab::runner {

struct SolverRun {
  std::unique_ptr<Solver> solver;
  const scene::SolverSpec* spec = nullptr;
  SolverStatus status =
      SolverStatus::ok;  // the solver's own, or unstable when a stretch check failed
  std::string message;
  StopCause stopped_by = StopCause::none;  // why it stopped before the end (interruption aside)
  int stopped_at_frame = -1;               // the frame at which it stopped unstable, -1 otherwise
  double wall_seconds = 0.0;               // s, stepping only
  std::int64_t steps = 0;
  int frames_recorded = 0;  // frames measured, frame 0 included
  std::optional<ClothMetrics> last_metrics;
  RestTracker rest;                     // settle time and rest jitter, from every measured frame
  std::unique_ptr<EnergyAudit> energy;  // built at the first measured frame
  std::unique_ptr<run_folder::Pc2Writer> point_cache;  // drapelab run with meshes: pc2

  bool running() const { return status == SolverStatus::ok; }
};

}  // namespace drapelab::runner
