// summary.json: per solver status, steps, cost and final metrics, plus what the run was.
#pragma once

#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "solver_run.hpp"

namespace drapelab::runner {

struct RunInfo {
  std::string state;  // running | finished | interrupted
  std::string command_line;
  int frames_planned = 0;  // after frame 0
  int frames_done = 0;
};

// What summary.json records of one solver's run, for run_scene's result.
SolverOutcome outcome_of(const SolverRun& run);

std::string summary_json(const scene::Scene& scene, const ClothModel& model,
                         const std::vector<SolverRun>& runs, const RunInfo& info);

}  // namespace drapelab::runner
