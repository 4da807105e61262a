// drapelab check SCENE --golden FILE [--update]: the regression test of collision response. Runs
// the scene with the overrides recorded in the golden file and compares the means of its metrics
// over the file's windows of frames, each within its own tolerance. --update records a new golden
// file from a run whose every solver is ok, measuring the tolerances with a probe run, and prints
// what changed.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <utility>
#include <vector>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "drapelab/runner/golden.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

namespace fs = std::filesystem;

void add_check_options(CLI::App& verb, CheckArguments& arguments) {
  verb.add_option("scene", arguments.scene, "Scene file (YAML)")->required();
  verb.add_option("--golden,-g", arguments.golden,
                  "Golden file (JSON) to compare with, or to write with --update")
      ->required();
  verb.add_flag("--update", arguments.update,
                "Run the scene and record its metrics as the new golden file");
  verb.add_option("--set", arguments.overrides,
                  "Override a key. With --update: for the recorded run (kept in the golden file); "
                  "without: on top of the golden file's overrides, to see whether the golden file "
                  "notices the change");
  verb.add_option("--out,-o", arguments.out,
                  "Keep the run's folder here (default: a temporary folder, removed)");
  verb.add_flag("--first-difference", arguments.first_difference,
                "Stop the run at the end of the first window with a value that differs, and "
                "compare the windows up to it (a quicker answer to whether a change is noticed)")
      ->excludes("--update");
  verb.footer(
      "Examples:\n"
      "  drapelab check scenes/sphere_drape.yaml --golden tests/golden/sphere_drape.json\n"
      "  drapelab check scenes/sphere_drape.yaml --golden tests/golden/sphere_drape.json "
      "--set contact.stiffness=1100\n"
      "  drapelab check my_scene.yaml --golden my_scene.golden.json --update --set duration=1\n"
      "Exit codes: 0 every value within tolerance (or the file written), 1 a value differs from "
      "the golden file, or our solver's total energy rose in a passive scene (energy audit), or "
      "--update refused a run whose solvers are not all ok, 2 bad input "
      "(the scene; a golden file that is missing, unreadable, a folder, or compares nothing; a "
      "golden path that cannot be written), 130 interrupted.");
}

namespace {

// A run folder: the --out folder, or a fresh temporary one removed when this goes out of scope.
class RunFolder {
 public:
  RunFolder(const std::string& out, const std::string& purpose) {
    if (!out.empty()) {
      path_ = out;
      return;
    }
    path_ = fs::temp_directory_path() /
            ("drapelab-check-" + purpose + "-" + std::to_string(::getpid()));
    temporary_ = true;
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ~RunFolder() {
    std::error_code ignored;
    if (temporary_) fs::remove_all(path_, ignored);
  }
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  bool temporary_ = false;
};

struct CheckRun {
  scene::Scene scene;
  runner::RunResult result;
};

// The golden file's windows that end at or before `frame`.
runner::Golden windows_up_to(const runner::Golden& golden, int frame) {
  runner::Golden first = golden;
  first.windows.erase(first.windows.upper_bound(frame), first.windows.end());
  return first;
}

// --first-difference: at the end of each of the golden file's windows, compares the windows so far
// from the files the run has written, and stops the run at the first one with a difference. The
// run stops through the flag it polls, which also takes Ctrl-C (at the end of the frame).
class FirstDifference final : public runner::RunProgress {
 public:
  FirstDifference(const runner::Golden& golden, fs::path staging,
                  const std::atomic<bool>& interrupt)
      : golden_(golden), staging_(std::move(staging)), interrupt_(interrupt) {}

  void frame_recorded(const std::vector<runner::SolverProgress>& solvers) override {
    if (interrupt_.load(std::memory_order_relaxed)) stop_ = true;
    int frame = 0;
    for (const auto& solver : solvers) frame = std::max(frame, solver.frames_done);
    if (!golden_.windows.contains(frame) || stop_) return;
    const runner::Golden so_far = windows_up_to(golden_, frame);
    std::vector<int> ends;
    for (const auto& [end, rows] : so_far.windows) ends.push_back(end);
    if (runner::compare_golden(so_far,
                               runner::window_means(runner::read_run_values(staging_), ends))
            .empty())
      return;
    stopped_at_ = frame;
    stop_ = true;
  }
  void frames_ended() override {}

  const std::atomic<bool>& stop() const { return stop_; }
  // The end of the window that stopped the run; nullopt when the run went on to its end.
  std::optional<int> stopped_at() const { return stopped_at_; }

 private:
  const runner::Golden& golden_;
  fs::path staging_;  // where the running run writes (run_transaction.hpp)
  const std::atomic<bool>& interrupt_;
  std::atomic<bool> stop_ = false;
  std::optional<int> stopped_at_;
};

// Runs the scene with `overrides`; nothing when the scene is bad input (the errors are printed).
// With `first_difference`, the run polls its stop flag instead of `interrupt`.
std::optional<CheckRun> run_for_check(const CheckArguments& arguments,
                                      const std::vector<std::string>& overrides,
                                      const fs::path& folder, const std::atomic<bool>& interrupt,
                                      FirstDifference* first_difference = nullptr) {
  const auto loaded = scene::load_scene_file(arguments.scene, overrides);
  if (!loaded.ok()) {
    for (const auto& error : loaded.errors) std::cerr << "error: " << error << "\n";
    return std::nullopt;
  }
  CheckRun run;
  run.scene = *loaded.scene;
  runner::RunOptions options;
  options.out_dir = folder;
  options.force = true;
  options.scene_text = run_folder::read_file(arguments.scene);
  options.command_line = "drapelab check " + arguments.scene;
  options.interrupt = first_difference ? &first_difference->stop() : &interrupt;
  options.progress = first_difference;
  options.model = loaded.model;
  const PollingSection polling;  // Ctrl-C stops the run after its current step
  run.result = runner::run_scene(*loaded.scene, options, std::cerr);
  if (run.result.folder.empty()) run.result.folder = folder;
  return run;
}

// The solvers of a run that did not end ok, one line each.
std::string solver_problems(const runner::RunResult& result) {
  std::string lines;
  for (const auto& solver : result.solvers)
    if (solver.status != SolverStatus::ok)
      lines += "  " + solver.name + ": " + solver_status_name(solver.status) +
               (solver.message.empty() ? "" : ": " + solver.message) + "\n";
  if (lines.empty()) lines = "  the run ended in state '" + result.state + "'\n";
  return lines;
}

// Refuses a golden path that cannot take a file: a folder, or a folder that cannot be created or
// written. Checked before the run, so a bad path costs no simulation. Returns the problem.
std::optional<std::string> golden_path_problem(const fs::path& golden) {
  std::error_code ec;
  if (fs::is_directory(golden, ec))
    return golden.string() + " is a folder; --golden takes a file, e.g. " +
           (golden / "scene.json").string();
  const fs::path folder = fs::absolute(golden, ec).parent_path();
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder))
    return "cannot create the folder " + folder.string() + " for " + golden.string() +
           (ec ? " (" + ec.message() + ")" : "");
  const fs::path trial = folder / (".drapelab-check-write-test-" + std::to_string(::getpid()));
  {
    std::ofstream file(trial);
    if (!file) return "cannot write in " + folder.string() + " (it is not writable)";
  }
  fs::remove(trial, ec);
  if (fs::exists(golden) && ::access(golden.c_str(), W_OK) != 0)
    return golden.string() + " is not writable";
  return std::nullopt;
}

// The overrides of the probe run: gravity changed by `probe` of itself (golden.hpp, GoldenRule).
std::vector<std::string> probe_overrides(const std::vector<std::string>& overrides,
                                         const scene::Scene& scene, double probe) {
  std::vector<std::string> probed = overrides;
  const Eigen::Vector3d g = scene.gravity * (1.0 + probe);
  probed.push_back("gravity=[" + format_number(g.x()) + ", " + format_number(g.y()) + ", " +
                   format_number(g.z()) + "]");
  return probed;
}

int update_golden(const CheckArguments& arguments, const std::atomic<bool>& interrupt) {
  if (const auto problem = golden_path_problem(arguments.golden)) {
    std::cerr << "error: " << *problem << "\nnothing was run\n";
    return kExitBadInput;
  }
  std::optional<runner::Golden> previous;
  if (fs::exists(arguments.golden)) {
    std::string problem;
    previous = runner::golden_from_json(run_folder::read_file(arguments.golden), &problem);
    if (!previous)
      std::cout << "note: the previous " << arguments.golden << " " << problem
                << "; it is replaced without a comparison\n";
  }
  RunFolder folder(arguments.out, "run");
  const auto run = run_for_check(arguments, arguments.overrides, folder.path(), interrupt);
  if (!run) return kExitBadInput;
  if (run->result.exit_code == runner::kExitInterrupted) return runner::kExitInterrupted;
  if (run->result.exit_code != runner::kExitOk) {
    std::cerr << "error: not recorded: --update records only a run whose every solver is ok, and "
                 "this one is not:\n"
              << solver_problems(run->result) << arguments.golden << " is left as it was\n";
    return run->result.exit_code == runner::kExitBadInput ? kExitBadInput : runner::kExitUnstable;
  }
  runner::Golden golden;
  golden.scene = run->scene.name;
  golden.overrides = arguments.overrides;
  if (run->scene.gravity.norm() == 0.0) {
    std::cerr << "error: " << arguments.scene << " has no gravity, which the probe runs that "
              << "measure the tolerances changes; give the scene a gravity\n";
    return kExitBadInput;
  }
  // The probe runs: the same scene with gravity changed by +probe and -probe of itself.
  std::vector<std::map<int, runner::GoldenRows>> probes;
  const auto ends = runner::golden_window_ends(run->scene.frame_count(), golden.rule.windows);
  for (const double sign : {1.0, -1.0}) {
    RunFolder probe_folder("", "probe");
    const auto probe = run_for_check(
        arguments, probe_overrides(arguments.overrides, run->scene, sign * golden.rule.probe),
        probe_folder.path(), interrupt);
    if (!probe) return kExitBadInput;
    if (probe->result.exit_code == runner::kExitInterrupted) return runner::kExitInterrupted;
    if (probe->result.exit_code != runner::kExitOk) {
      std::cerr << "error: not recorded: a probe run (gravity changed by "
                << sign * golden.rule.probe
                << " of itself) did not end ok, so a rounding difference decides this run:\n"
                << solver_problems(probe->result) << arguments.golden << " is left as it was\n";
      return runner::kExitUnstable;
    }
    probes.push_back(runner::window_means(runner::read_run_values(probe->result.folder), ends));
  }
  const auto frames = runner::read_run_values(run->result.folder);
  golden.windows = runner::window_means(frames, ends);
  golden.scale = runner::golden_scales(frames);
  golden.relative = runner::golden_relative(golden.rule, golden.scale, golden.windows, probes);
  if (golden.value_count() == 0) {
    std::cerr << "error: not recorded: the run wrote no values to compare ("
              << run->result.folder.string() << ")\n";
    return runner::kExitUnstable;
  }
  if (previous) {
    const auto changes = runner::compare_golden(*previous, golden.windows);
    std::cout << arguments.golden << ": "
              << (changes.empty() ? "no value changed beyond the tolerance"
                                  : std::to_string(changes.size()) + " values changed:")
              << "\n";
    for (const auto& change : changes)
      std::cout << "  " << runner::describe_difference(change) << "\n";
  } else {
    std::cout << arguments.golden << ": new golden file\n";
  }
  if (const auto problem =
          runner::write_golden_file(arguments.golden, runner::golden_to_json(golden))) {
    std::cerr << "error: " << *problem << "\n";
    return kExitBadInput;
  }
  std::cout << "wrote " << arguments.golden << ": " << golden.value_count() << " values at "
            << golden.windows.size() << " windows\n";
  return runner::kExitOk;
}

int compare_with_golden(const CheckArguments& arguments, const std::atomic<bool>& interrupt) {
  std::error_code ec;
  if (fs::is_directory(arguments.golden, ec)) {
    std::cerr << "error: " << arguments.golden << " is a folder; --golden takes a golden file\n";
    return kExitBadInput;
  }
  if (!fs::exists(arguments.golden)) {
    std::cerr << "error: " << arguments.golden
              << ": no such golden file; record one with\n  drapelab check " << arguments.scene
              << " --golden " << arguments.golden << " --update\n";
    return kExitBadInput;
  }
  const auto text = run_folder::read_file_bytes(arguments.golden);
  if (!text) {
    std::cerr << "error: " << arguments.golden << " cannot be read\n";
    return kExitBadInput;
  }
  std::string problem;
  const auto golden = runner::golden_from_json(*text, &problem);
  if (!golden) {
    std::cerr << "error: " << arguments.golden << " " << problem << "\n";
    return kExitBadInput;
  }
  // Overrides given here go after the file's own: the way to ask whether the golden file notices a
  // change of the scene (a contact parameter, say).
  std::vector<std::string> overrides = golden->overrides;
  overrides.insert(overrides.end(), arguments.overrides.begin(), arguments.overrides.end());
  RunFolder folder(arguments.out, "run");
  std::optional<FirstDifference> first_difference;
  if (arguments.first_difference)
    first_difference.emplace(
        *golden, folder.path() / (run_folder::kStagingPrefix + std::to_string(::getpid())),
        interrupt);
  const auto run = run_for_check(arguments, overrides, folder.path(), interrupt,
                                 first_difference ? &*first_difference : nullptr);
  if (!run) return kExitBadInput;
  const std::optional<int> stopped_at =
      first_difference ? first_difference->stopped_at() : std::nullopt;
  if (run->result.exit_code == runner::kExitInterrupted && !stopped_at)
    return runner::kExitInterrupted;
  if (run->scene.name != golden->scene) {
    std::cerr << "error: " << arguments.golden << " records scene '" << golden->scene << "', but "
              << arguments.scene << " is scene '" << run->scene.name << "'\n";
    return kExitBadInput;
  }
  const runner::Golden compared = stopped_at ? windows_up_to(*golden, *stopped_at) : *golden;
  std::vector<int> ends;
  for (const auto& [frame, rows] : compared.windows) ends.push_back(frame);
  const auto differences = runner::compare_golden(
      compared, runner::window_means(runner::read_run_values(run->result.folder), ends));
  const std::string extra = arguments.overrides.empty()
                                ? ""
                                : " (with " + std::to_string(arguments.overrides.size()) +
                                      " extra override(s) given here)";
  if (stopped_at)
    std::cout << "note: --first-difference stopped the run at frame " << *stopped_at
              << ", the end of the first window that differs\n";
  else if (run->result.exit_code != runner::kExitOk)
    std::cout << "note: the run did not end ok:\n" << solver_problems(run->result);
  // The energy audit: in a passive scene our solver must not gain energy; Bullet's cloths are
  // reported, not held to it (their methods are not ours to change).
  bool energy_gained = false;
  for (const auto& solver : run->result.solvers)
    for (const auto& warning : solver.energy_warnings) {
      const bool ours = solver.type == SolverType::spring_damper;
      energy_gained = energy_gained || ours;
      std::cout << (ours ? "energy: " : "note: ") << solver.name << ": " << warning << "\n";
    }
  if (energy_gained) {
    std::cout << arguments.scene << extra
              << ": our solver gained energy in a passive scene (the energy audit above)\n";
    return runner::kExitUnstable;
  }
  if (differences.empty()) {
    std::cout << arguments.scene << extra << ": " << golden->value_count() << " values at "
              << ends.size() << " windows match " << arguments.golden << "\n";
    return runner::kExitOk;
  }
  std::cout << arguments.scene << extra << ": " << differences.size() << " of "
            << compared.value_count() << " values differ from " << arguments.golden << ":\n";
  for (const auto& difference : differences)
    std::cout << "  " << runner::describe_difference(difference) << "\n";
  std::cout << "If the change is intended, record it with tools/update-golden.sh (or --update) and "
               "review the diff of the golden file.\n";
  return runner::kExitUnstable;
}

}  // namespace

int check_verb(const CheckArguments& arguments, const std::atomic<bool>& interrupt) {
  // Any failure below the verb is reported, never an abort: reading a run's files is the verb's
  // own work (exit 1), and running out of memory is a failure of this run (exit 1).
  try {
    return arguments.update ? update_golden(arguments, interrupt)
                            : compare_with_golden(arguments, interrupt);
  } catch (const std::bad_alloc&) {
    std::cerr << "error: drapelab check ran out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
  }
  return runner::kExitUnstable;
}

}  // namespace drapelab::cli
