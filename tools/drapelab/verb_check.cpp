// drapelab check SCENE --golden FILE [--update]: the regression test of collision response. Runs
// the scene with the overrides recorded in the golden file and compares its key metrics at the
// recorded frames, within the file's tolerances. --update records a new golden file and prints what
// changed.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <optional>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/runner/golden.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/scene/scene_loader.hpp"
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
                  "With --update: override a key for the recorded run (kept in the golden file)");
  verb.add_option("--out,-o", arguments.out,
                  "Keep the run's folder here (default: a temporary folder, removed)");
  verb.footer(
      "Examples:\n"
      "  drapelab check scenes/sphere_drape.yaml --golden tests/golden/sphere_drape.json\n"
      "  drapelab check my_scene.yaml --golden my_scene.golden.json --update --set duration=1\n"
      "Exit codes: 0 every value within tolerance (or the file written), 1 a value differs from "
      "the "
      "golden file, 2 bad input.");
}

namespace {

// A run folder: the --out folder, or a fresh temporary one removed when this goes out of scope.
class RunFolder {
 public:
  explicit RunFolder(const std::string& out) {
    if (!out.empty()) {
      path_ = out;
      return;
    }
    path_ = fs::temp_directory_path() / ("drapelab-check-" + std::to_string(::getpid()));
    temporary_ = true;
    fs::remove_all(path_);
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

// Runs the scene; returns the run's exit code, or nothing when the scene is bad input.
std::optional<int> run_for_check(const CheckArguments& arguments,
                                 const std::vector<std::string>& overrides, const fs::path& folder,
                                 const std::atomic<bool>& interrupt, scene::Scene* loaded) {
  const auto result = scene::load_scene_file(arguments.scene, overrides);
  if (!result.ok()) {
    for (const auto& error : result.errors) std::cerr << "error: " << error << "\n";
    return std::nullopt;
  }
  *loaded = *result.scene;
  runner::RunOptions options;
  options.out_dir = folder;
  options.force = true;
  options.scene_text = run_folder::read_file(arguments.scene);
  options.command_line = "drapelab check " + arguments.scene;
  options.interrupt = &interrupt;
  options.model = result.model;
  return runner::run_scene(*result.scene, options, std::cerr).exit_code;
}

int update_golden(const CheckArguments& arguments, const std::atomic<bool>& interrupt) {
  std::optional<runner::Golden> previous;
  if (fs::exists(arguments.golden))
    previous = runner::golden_from_json(run_folder::read_file(arguments.golden), nullptr);
  RunFolder folder(arguments.out);
  scene::Scene scene;
  const auto code = run_for_check(arguments, arguments.overrides, folder.path(), interrupt, &scene);
  if (!code) return kExitBadInput;
  if (*code == runner::kExitInterrupted) return *code;
  runner::Golden golden;
  golden.scene = scene.name;
  golden.overrides = arguments.overrides;
  if (previous) golden.tolerance = previous->tolerance;  // tolerances are kept across updates
  golden.frames =
      runner::read_golden_values(folder.path(), runner::golden_frames(scene.frame_count()));
  if (previous) {
    const auto changes = runner::compare_golden(*previous, golden.frames);
    std::cout << arguments.golden << ": "
              << (changes.empty() ? "no value changed beyond the tolerance"
                                  : std::to_string(changes.size()) + " values changed:")
              << "\n";
    for (const auto& change : changes)
      std::cout << "  " << runner::describe_difference(change) << "\n";
  } else {
    std::cout << arguments.golden << ": new golden file\n";
  }
  fs::create_directories(fs::absolute(arguments.golden).parent_path());
  run_folder::write_file_atomically(arguments.golden, runner::golden_to_json(golden));
  if (*code != runner::kExitOk)
    std::cout << "note: the recorded run did not end ok (exit " << *code << ")\n";
  return runner::kExitOk;
}

}  // namespace

int check_verb(const CheckArguments& arguments, const std::atomic<bool>& interrupt) {
  if (arguments.update) return update_golden(arguments, interrupt);
  if (!arguments.overrides.empty()) {
    std::cerr << "error: --set goes with --update: the golden file fixes the overrides of the run "
                 "it checks\n";
    return kExitBadInput;
  }
  if (!fs::exists(arguments.golden)) {
    std::cerr << "error: " << arguments.golden
              << ": no such golden file; record one with\n  drapelab check " << arguments.scene
              << " --golden " << arguments.golden << " --update\n";
    return kExitBadInput;
  }
  std::string problem;
  const auto golden = runner::golden_from_json(run_folder::read_file(arguments.golden), &problem);
  if (!golden) {
    std::cerr << "error: " << arguments.golden << ": " << problem << "\n";
    return kExitBadInput;
  }
  RunFolder folder(arguments.out);
  scene::Scene scene;
  const auto code = run_for_check(arguments, golden->overrides, folder.path(), interrupt, &scene);
  if (!code) return kExitBadInput;
  if (*code == runner::kExitInterrupted) return *code;
  if (scene.name != golden->scene) {
    std::cerr << "error: " << arguments.golden << " records scene '" << golden->scene << "', but "
              << arguments.scene << " is scene '" << scene.name << "'\n";
    return kExitBadInput;
  }
  std::vector<int> frames;
  for (const auto& [frame, rows] : golden->frames) frames.push_back(frame);
  const auto differences =
      runner::compare_golden(*golden, runner::read_golden_values(folder.path(), frames));
  std::size_t values = 0;
  for (const auto& [frame, rows] : golden->frames)
    for (const auto& [row, columns] : rows) values += columns.size();
  if (differences.empty()) {
    std::cout << arguments.scene << ": " << values << " values at " << frames.size()
              << " frames match " << arguments.golden << "\n";
    return runner::kExitOk;
  }
  std::cout << arguments.scene << ": " << differences.size() << " of " << values
            << " values differ from " << arguments.golden << " (tolerance: relative "
            << golden->tolerance.relative << ", absolute " << golden->tolerance.absolute
            << ", counts " << golden->tolerance.count << "):\n";
  for (const auto& difference : differences)
    std::cout << "  " << runner::describe_difference(difference) << "\n";
  std::cout << "If the change is intended, record it with tools/update-golden.sh (or --update) and "
               "review "
               "the diff of the golden file.\n";
  return runner::kExitUnstable;
}

}  // namespace drapelab::cli
