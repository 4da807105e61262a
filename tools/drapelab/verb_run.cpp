// drapelab run SCENE --out DIR: simulate and write the run folder (docs/outputs.md).
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "interrupt.hpp"
#include "progress/progress_display.hpp"
#include "progress/progress_line.hpp"
#include "scene_warnings.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

void add_run_options(CLI::App& verb, RunArguments& arguments) {
  verb.add_option("scene", arguments.scene, "Scene file (YAML)")->required();
  verb.add_option("--out,-o", arguments.out, "Output folder (created if missing)")->required();
  verb.add_option("--set", arguments.overrides,
                  "Override a key: key.path=value, validated like the file (list items by index: "
                  "solvers.0.dt=1e-4); may be repeated");
  verb.add_option("--meshes", arguments.meshes,
                  "Also write meshes: obj (per frame), pc2 (point cache) or both")
      ->check(CLI::IsMember({"none", "obj", "pc2", "both"}));
  verb.add_flag("--force", arguments.force,
                "Use a folder that holds a different run or other files: replaces only the files "
                "drapelab wrote there");
  verb.add_flag("--allow-start-inside", arguments.allow_start_inside,
                "Run a cloth that starts inside or through a collider, with a warning (without it, "
                "bad input: the contact pushes it out at once and the run blows up)");
  verb.add_flag("--quiet,-q", arguments.quiet,
                "Print only problems (warnings and errors): no notes, no progress, no summary");
  verb.add_flag("--no-progress", arguments.no_progress,
                "Print no progress lines (they go to stderr: redrawn in place on a terminal, "
                "else a line every 5 s)");
  verb.footer(
      "Example:\n  drapelab run scenes/curtain.yaml --out out/curtain --set "
      "cloth.resolution=[65,65]\n"
      "Exit codes: 0 every solver ok, 1 a solver became unstable, 2 bad input (nothing run), "
      "130 interrupted.");
}

namespace {

// The run's progress on stderr: a line per solver, redrawn in place on a terminal, else written
// every few seconds (progress_display.hpp).
class RunProgressLines final : public runner::RunProgress {
 public:
  explicit RunProgressLines(ProgressMode mode)
      : display_(mode, std::cerr, plain_progress_interval(), STDERR_FILENO) {}

  void frame_recorded(const std::vector<runner::SolverProgress>& solvers) override {
    if (display_.mode() == ProgressMode::none) return;
    std::size_t name_width = 0;
    for (const auto& solver : solvers) name_width = std::max(name_width, solver.name.size());
    std::vector<std::string> lines;
    for (const auto& solver : solvers) lines.push_back(format_solver_progress(solver, name_width));
    display_.update(lines);
  }
  void frames_ended() override { display_.clear(); }

 private:
  ProgressDisplay display_;
};

void print_outcome(const runner::RunResult& result, const std::filesystem::path& out) {
  for (const auto& solver : result.solvers) {
    std::ostringstream line;
    line.precision(4);
    line << "  " << solver.name << " (" << solver_type_name(solver.type)
         << "): " << solver_status_name(solver.status) << ", " << solver.steps << " steps, "
         << solver.ms_per_step() << " ms per step, " << solver.wall_seconds_per_simulated_second()
         << " s per simulated second";
    std::cout << line.str() << "\n";
  }
  std::cout << "outputs in " << out.string() << "/:\n";
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(out))
    if (!run_folder::is_bookkeeping_name(entry.path().filename().string()))
      names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  for (const auto& name : names)
    std::cout << "  " << name << (std::filesystem::is_directory(out / name) ? "/" : "") << "\n";
}

}  // namespace

int run_verb(const RunArguments& arguments, const std::string& command_line,
             const std::atomic<bool>& interrupt) {
  std::vector<std::string> overrides = arguments.overrides;
  if (!arguments.meshes.empty()) overrides.push_back("output.meshes=" + arguments.meshes);
  const auto loaded = scene::load_scene_file(
      arguments.scene, overrides,
      arguments.allow_start_inside ? scene::StartInside::warning : scene::StartInside::error);
  if (!loaded.ok()) {
    for (const auto& error : loaded.errors) std::cerr << "error: " << error << "\n";
    std::cerr << "nothing was run\n";
    return kExitBadInput;
  }
  if (!arguments.quiet)
    for (const auto& note : loaded.notes) std::cerr << "note: " << note << "\n";
  for (const auto& warning : loaded.warnings) std::cerr << "warning: " << warning << "\n";
  for (const auto& warning : scene_warnings(*loaded.scene, *loaded.model))
    std::cerr << "warning: " << warning << "\n";
  runner::RunOptions options;
  options.out_dir = arguments.out;
  options.force = arguments.force;
  options.scene_text = run_folder::read_file(arguments.scene);
  options.command_line = command_line;
  options.interrupt = &interrupt;
  options.model = loaded.model;
  options.quiet = arguments.quiet;
  RunProgressLines progress(
      progress_mode_for(STDERR_FILENO, !arguments.quiet && !arguments.no_progress));
  options.progress = &progress;
  if (!arguments.quiet)
    std::cout << "running " << loaded.scene->name << " (" << loaded.scene->frame_count()
              << " frames) into " << arguments.out << "\n";
  const PollingSection polling;  // Ctrl-C stops the run after its current step
  const runner::RunResult result = runner::run_scene(*loaded.scene, options, std::cerr);
  // In a passive scene a rise of the total energy is a problem of the method: said even with -q.
  for (const auto& solver : result.solvers)
    for (const auto& warning : solver.energy_warnings)
      std::cerr << "warning: solver " << solver.name << ": " << warning << "\n";
  if (!result.folder.empty() && !arguments.quiet) print_outcome(result, result.folder);
  return result.exit_code;
}

}  // namespace drapelab::cli
