// drapelab run: steps every solver of a scene in lock-step, frame by frame, and writes the run folder.
#pragma once

#include <atomic>
#include <filesystem>
#include <iosfwd>
#include <string>

#include "drapelab/scene/scene.hpp"

namespace drapelab::runner {

struct RunOptions {
  std::filesystem::path out_dir;
  bool force = false;                          // replace a previous run in out_dir
  std::string scene_text;                      // the scene file as given, copied to scene.yaml
  std::string command_line;                    // recorded in summary.json
  const std::atomic<bool>* interrupt = nullptr;  // set by Ctrl-C: stop after the current step
};

// Exit codes of shared/outputs.md.
inline constexpr int kExitOk = 0;           // every solver ok
inline constexpr int kExitUnstable = 1;     // a solver became unstable or failed
inline constexpr int kExitBadInput = 2;     // bad input: nothing was run
inline constexpr int kExitInterrupted = 130;  // Ctrl-C: files hold every frame recorded so far

// Runs the scene; progress and problems go to `log`. Returns an exit code above.
int run_scene(const scene::Scene& scene, const RunOptions& options, std::ostream& log);

}  // namespace drapelab::runner
