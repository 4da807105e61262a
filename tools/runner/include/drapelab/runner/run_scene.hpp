// drapelab run: steps every solver of a scene in lock-step, frame by frame, and writes the run
// folder.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/runner/run_progress.hpp"
#include "drapelab/scene/scene.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::runner {

struct RunOptions {
  std::filesystem::path out_dir;
  bool force = false;                            // replace a previous run in out_dir
  std::string scene_text;                        // the scene file as given, copied to scene.yaml
  std::string command_line;                      // recorded in summary.json
  const std::atomic<bool>* interrupt = nullptr;  // set by Ctrl-C: stop after the current step
  std::shared_ptr<const ClothModel> model;  // the loader's cloth (built from the scene when null)
  RunProgress* progress = nullptr;          // told of every recorded frame, when given
  bool quiet = false;                       // print problems only: no notes (drapelab run -q)
};

// Exit codes (docs/outputs.md, "Exit codes").
inline constexpr int kExitOk = 0;             // every solver ok
inline constexpr int kExitUnstable = 1;       // a solver became unstable or failed
inline constexpr int kExitBadInput = 2;       // bad input (nothing run), or a file not written
inline constexpr int kExitInterrupted = 130;  // Ctrl-C: files hold every frame recorded so far

// What one solver did in a run, as summary.json records it.
struct SolverOutcome {
  std::string name;
  SolverType type = SolverType::spring_damper;
  SolverStatus status = SolverStatus::ok;
  std::string message;  // why not ok: which particle, which step, what to try
  std::int64_t steps = 0;
  double dt = 0.0;            // s
  int frames_recorded = 0;    // rows in metrics.csv, frame 0 included
  double wall_seconds = 0.0;  // s, stepping only
  // The energy audit's warnings, one line each: "frame 9 (t = 0.15 s): the total energy rose by
  // 0.14 J; likely cause: ..." (energy_audit.hpp).
  std::vector<std::string> energy_warnings;

  double ms_per_step() const {
    return steps > 0 ? 1e3 * wall_seconds / static_cast<double>(steps) : 0.0;
  }
  double wall_seconds_per_simulated_second() const {
    const double simulated = static_cast<double>(steps) * dt;  // s
    return simulated > 0.0 ? wall_seconds / simulated : 0.0;
  }
};

struct RunResult {
  int exit_code = kExitOk;  // one of the codes above
  // finished | interrupted | write_failed; empty when refused (bad input)
  std::string state;
  int frames_done = 0;                 // the last frame recorded
  std::filesystem::path folder;        // where the run's files are (empty when refused)
  std::vector<SolverOutcome> solvers;  // in the scene's order
};

// Runs the scene into options.out_dir; notes and problems go to `log`, progress to
// options.progress.
RunResult run_scene(const scene::Scene& scene, const RunOptions& options, std::ostream& log);

}  // namespace drapelab::runner
