// What the runner keeps about each solver of a run.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/runner/mesh_output.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"
#include "rest_measures.hpp"

namespace drapelab::runner {

struct SolverRun {
  std::unique_ptr<Solver> solver;
  const scene::SolverSpec* spec = nullptr;
  SolverStatus status = SolverStatus::ok;  // the solver's own, or unstable when the runner saw a runaway
  std::string message;
  double wall_seconds = 0.0;               // s, stepping only
  std::int64_t steps = 0;
  int frames_recorded = 0;                 // rows written, frame 0 included
  std::optional<ClothMetrics> last_metrics;
  RestTracker rest;                        // settle time and rest jitter, from every recorded frame
  std::unique_ptr<Pc2Writer> point_cache;

  bool running() const { return status == SolverStatus::ok; }
};

}  // namespace drapelab::runner
