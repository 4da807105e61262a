// drapelab sweep SCENE --vary key=v1,v2 [--vary ...] --out DIR: runs the scene once per
// combination of the varied values (their Cartesian product, in odometer order: sweep_plan.hpp),
// each as a `drapelab run` child process of its own into DIR/runs/NNN_key=value_..., up to --jobs
// at a time, and gathers every solver's outcome and final metrics into DIR/sweep.csv and
// DIR/sweep.json. Separate processes, not threads: a run that crashes or hangs takes only its own
// row with it, and every run folder is exactly what `drapelab run` writes.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/folder_lock.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/runner/sweep_children.hpp"
#include "drapelab/runner/sweep_files.hpp"
#include "drapelab/runner/sweep_outcome.hpp"
#include "drapelab/runner/sweep_plan.hpp"
#include "drapelab/runner/sweep_validation.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

using namespace drapelab::runner;  // the run pipeline: this file parses and prints

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMostCombinations = 10000;  // a guard against a product typed by mistake
// After Ctrl-C, how long the children get to stop after their current step before SIGKILL.
constexpr std::chrono::milliseconds kStopGrace{10000};
constexpr std::size_t kLongestShownMessage =
    200;  // characters of a failure shown on a progress line

// The files of a sweep folder that --force replaces (and only these), besides its runs.
const std::vector<std::string>& sweep_output_names() {
  static const std::vector<std::string> names = {"runs", "sweep.csv", "sweep.json",
                                                 "sweep.csv.partial", "sweep.json.partial"};
  return names;
}

// --force: removes a previous sweep's tables and every run folder in runs/ that drapelab wrote (by
// its manifest); anything else in the folder, runs/ included, stays.
std::optional<std::string> remove_previous_sweep(const fs::path& out) {
  std::error_code ec;
  for (const auto& name : sweep_output_names())
    if (name != "runs") fs::remove(out / name, ec);
  if (!fs::is_directory(out / "runs", ec)) return std::nullopt;
  for (const auto& entry : fs::directory_iterator(out / "runs", ec))
    if (entry.is_directory(ec))
      if (const auto problem = run_folder::remove_run_folder(entry.path())) return *problem;
  return std::nullopt;
}

// Whether `folder` holds anything but drapelab's lock and bookkeeping files.
bool holds_files(const fs::path& folder) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (!run_folder::is_bookkeeping_name(entry.path().filename().string())) return true;
  return false;
}

// Checks and prepares the sweep folder, and locks it for the sweep (one sweep per folder at a
// time); returns an error message when it may not be used.
std::optional<std::string> prepare_sweep_folder(const fs::path& out, bool force,
                                                std::unique_ptr<run_folder::FolderLock>& lock) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    return out.string() + " exists and is not a folder; choose another --out";
  fs::create_directories(out, ec);
  if (ec) return "cannot create the folder " + out.string() + ": " + ec.message();
  auto locked = run_folder::FolderLock::acquire(out);
  if (auto* refusal = std::get_if<std::string>(&locked)) return *refusal;
  lock = std::move(std::get<std::unique_ptr<run_folder::FolderLock>>(locked));
  if (holds_files(out)) {
    bool holds_sweep = false;
    for (const auto& name : sweep_output_names())
      holds_sweep = holds_sweep || fs::exists(out / name, ec);
    if (!force)
      return out.string() + (holds_sweep
                                 ? " holds a sweep already; add --force to replace it (its "
                                   "sweep.csv, sweep.json and the run folders drapelab wrote in "
                                   "runs/ are removed), or choose another --out"
                                 : " is not empty and holds no sweep; choose a new or empty --out "
                                   "folder, or add --force to write the sweep beside its files");
    if (const auto problem = remove_previous_sweep(out)) return *problem;
  }
  fs::create_directories(out / "runs", ec);
  if (ec || !fs::is_directory(out / "runs"))
    return "cannot create the folder " + (out / "runs").string() + (ec ? ": " + ec.message() : "");
  return std::nullopt;
}

std::string describe_values(const SweepPlan& plan, std::size_t index) {
  const auto values = plan.values(index);
  std::string text;
  for (std::size_t k = 0; k < values.size(); ++k)
    text += (k ? ", " : "") + plan.keys()[k].key + "=" + values[k];
  return text;
}

std::string shortened(const std::string& text) {
  return text.size() <= kLongestShownMessage ? text : text.substr(0, kLongestShownMessage) + "...";
}

// "[4/6] 003 cloth.springs.bend.ks=100, duration=0.5: ok (ours ok) in 1.2 s"
void print_progress(std::size_t done, const SweepPlan& plan, const CombinationOutcome& outcome) {
  std::ostringstream line;
  line << "[" << done << "/" << plan.count() << "] " << plan.index_label(outcome.index) << " "
       << describe_values(plan, outcome.index) << ": " << outcome.status;
  std::string solvers;
  for (const auto& row : outcome.rows)
    if (!row.solver.empty())
      solvers += (solvers.empty() ? "" : ", ") + row.solver + " " + row.status;
  if (!solvers.empty()) line << " (" << solvers << ")";
  if (outcome.wall_seconds > 0.0)
    line << " in " << std::setprecision(3) << outcome.wall_seconds << " s";
  if (!outcome.message.empty()) line << ": " << shortened(outcome.message);
  std::cout << line.str() << std::endl;  // flushed: a sweep can take hours
}

// The child currently running one combination.
struct RunningChild {
  std::size_t index = 0;
  pid_t pid = 0;
  std::chrono::steady_clock::time_point started;
};

class SweepFolder {
 public:
  SweepFolder(fs::path out, SweepRecord record, const SweepPlan& plan)
      : out_(std::move(out)), record_(std::move(record)), plan_(plan) {}

  std::string folder(std::size_t index) const { return "runs/" + plan_.folder_name(index); }
  fs::path run_dir(std::size_t index) const { return out_ / "runs" / plan_.folder_name(index); }
  fs::path log(std::size_t index) const {
    return out_ / "runs" / (plan_.folder_name(index) + ".log");
  }
  const std::map<std::size_t, CombinationOutcome>& finished() const { return finished_; }

  // Records a finished combination, prints its progress line and rewrites both files.
  void finish(CombinationOutcome outcome) {
    const std::size_t index = outcome.index;
    finished_[index] = std::move(outcome);
    print_progress(finished_.size(), plan_, finished_[index]);
    write();
  }

  void set_state(const std::string& state) {
    record_.state = state;
    write();
  }

  // Both files, replaced atomically: valid whenever the sweep stops.
  void write() const {
    try {
      run_folder::write_file_atomically(out_ / "sweep.csv", sweep_csv(plan_, finished_));
      run_folder::write_file_atomically(out_ / "sweep.json", sweep_json(record_, plan_, finished_));
    } catch (const std::exception& e) {
      std::cerr << "warning: " << e.what() << "; trying again after the next run\n";
    }
  }

 private:
  fs::path out_;
  SweepRecord record_;
  const SweepPlan& plan_;
  std::map<std::size_t, CombinationOutcome> finished_;
};

// The key of a "key=value" override.
std::string override_key(const std::string& text) { return text.substr(0, text.find('=')); }

}  // namespace

void add_sweep_options(CLI::App& verb, SweepArguments& arguments) {
  verb.add_option("scene", arguments.scene, "Scene file (YAML)")->required();
  verb.add_option(
          "--vary", arguments.varies,
          "A key and its values: key.path=v1,v2,... (YAML values as --set takes them; a value "
          "holding commas is a flow list in brackets: cloth.resolution=[5,5],[9,9]); may be "
          "repeated")
      ->required()
      ->allow_extra_args(
          false);  // one key per --vary: a scene path after it is not taken for a key
  verb.add_option("--out,-o", arguments.out,
                  "Sweep folder: sweep.csv, sweep.json and runs/ (created if missing)")
      ->required();
  verb.add_option("--jobs,-j", arguments.jobs, "Runs at a time (default: the number of cores)")
      ->check(CLI::PositiveNumber);
  verb.add_option(
          "--set", arguments.overrides,
          "Override a key in every run: key.path=value, validated like the file; may be repeated")
      ->allow_extra_args(false);
  verb.add_flag("--force", arguments.force,
                "Replace a sweep already in the folder (its runs/, sweep.csv, sweep.json)");
  verb.footer(
      "Runs every combination of the varied values, the last --vary key changing fastest, each as "
      "its own "
      "'drapelab run' into DIR/runs/NNN_key=value_...; every combination is validated first.\n"
      "Example:\n  drapelab sweep scenes/curtain.yaml --vary cloth.springs.bend.ks=1,10,100 --set "
      "duration=0.5 "
      "--out out/bend-sweep\n"
      "Exit codes: 0 every run ok, 1 a run failed (it is a row of sweep.csv), 2 bad arguments or "
      "an unknown "
      "key (nothing run), 130 interrupted (sweep.csv holds the runs finished).");
}

int sweep_verb(const SweepArguments& arguments, const std::string& command_line,
               const std::atomic<bool>& interrupt) {
  // 1. The arguments, before any scene is read.
  std::vector<VariedKey> keys;
  std::set<std::string> seen;
  for (const auto& text : arguments.varies) {
    std::string problem;
    auto varied = parse_vary(text, &problem);
    if (!varied) {
      std::cerr << "error: " << problem << "\nnothing was run\n";
      return kExitBadInput;
    }
    if (!seen.insert(varied->key).second) {
      std::cerr << "error: --vary " << varied->key
                << " is given twice; list all its values in one --vary\n"
                << "nothing was run\n";
      return kExitBadInput;
    }
    keys.push_back(std::move(*varied));
  }
  for (const auto& text : arguments.overrides) {
    if (seen.count(override_key(text))) {
      std::cerr << "error: " << override_key(text) << " is both --set and --vary; drop the --set\n"
                << "nothing was run\n";
      return kExitBadInput;
    }
  }
  const SweepPlan plan(std::move(keys));
  if (plan.count() > kMostCombinations) {
    std::cerr << "error: the --vary options make more than " << kMostCombinations
              << " combinations; split the sweep\nnothing was run\n";
    return kExitBadInput;
  }
  const int jobs = arguments.jobs > 0
                       ? arguments.jobs
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  // 2. Every combination loaded in-process: an unknown key stops here, before anything runs.
  const SweepValidation validation = validate_sweep(arguments.scene, arguments.overrides, plan);
  if (!validation.ok()) {
    for (const auto& error : validation.base_errors) std::cerr << "error: " << error << "\n";
    for (const auto& error : validation.key_errors) std::cerr << "error: " << error << "\n";
    std::cerr << "nothing was run\n";
    return kExitBadInput;
  }
  const PollingSection polling;  // Ctrl-C: the children stop, and sweep.csv keeps the finished runs
  const fs::path out = arguments.out;
  std::unique_ptr<run_folder::FolderLock> lock;  // held until the sweep ends
  if (const auto problem = prepare_sweep_folder(out, arguments.force, lock)) {
    std::cerr << "error: " << *problem << "\nnothing was run\n";
    return kExitBadInput;
  }

  SweepRecord record;
  record.command = command_line;
  record.executable = own_executable_path();
  record.scene_file = arguments.scene;
  record.scene_name = validation.scene_name;
  record.overrides = arguments.overrides;
  record.jobs = jobs;
  record.state = "running";
  SweepFolder folder(out, record, plan);
  std::size_t refused = 0;
  for (const auto& error : validation.combination_errors) refused += error.has_value();
  std::cout << "sweep of " << validation.scene_name << " (" << arguments.scene
            << "): " << plan.count() << " combination" << (plan.count() == 1 ? "" : "s") << " of";
  for (const auto& key : plan.keys())
    std::cout << " " << key.key << " (" << key.values.size() << ")";
  std::cout << ", up to " << jobs << " at a time";
  if (refused) std::cout << "; " << refused << " refused by validation (bad_input rows)";
  std::cout << std::endl;
  folder.write();

  // 3. The runs: refused combinations are rows at once; the others are started in order.
  std::vector<std::size_t> queue;
  for (std::size_t index = 0; index < plan.count(); ++index) {
    if (const auto& error = validation.combination_errors[index])
      folder.finish(refused_outcome(index, *error));
    else
      queue.push_back(index);
  }
  std::size_t next = 0;
  std::vector<RunningChild> running;
  while ((next < queue.size() || !running.empty()) && !interrupt.load()) {
    while (static_cast<int>(running.size()) < jobs && next < queue.size() && !interrupt.load()) {
      const std::size_t index = queue[next++];
      // --force: a run folder left in runs/ (files of someone else's, an older sweep's run) is
      // written beside; a run replaces only drapelab's own files.
      std::vector<std::string> child{
          "drapelab", "run", arguments.scene, "--out", folder.run_dir(index).string(), "--force"};
      std::vector<std::string> overrides = arguments.overrides;
      const auto varied = plan.overrides(index);
      overrides.insert(overrides.end(), varied.begin(), varied.end());
      for (const auto& text : overrides) {
        child.emplace_back("--set");
        child.push_back(text);
      }
      std::string problem;
      const auto pid = spawn_child("/proc/self/exe", child, folder.log(index), &problem);
      if (!pid) {
        folder.finish(unstarted_outcome(index, folder.folder(index), problem));
        continue;
      }
      running.push_back({index, *pid, std::chrono::steady_clock::now()});
    }
    bool any_ended = false;
    for (auto it = running.begin(); it != running.end();) {
      const auto ended = poll_child(it->pid);
      if (!ended) {
        ++it;
        continue;
      }
      auto outcome = finished_outcome(it->index, *ended, folder.run_dir(it->index),
                                      folder.log(it->index), folder.folder(it->index), false);
      outcome.wall_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - it->started).count();
      folder.finish(std::move(outcome));
      it = running.erase(it);
      any_ended = true;
    }
    if (!any_ended) std::this_thread::sleep_for(kChildPollPeriod);
  }

  if (interrupt.load()) {
    // Ctrl-C: stop the children (they keep their files valid), record them, and stop.
    std::vector<pid_t> pids;
    for (const auto& child : running) pids.push_back(child.pid);
    const auto ends = stop_children(pids, kStopGrace);
    for (std::size_t k = 0; k < running.size(); ++k) {
      auto outcome =
          finished_outcome(running[k].index, ends[k], folder.run_dir(running[k].index),
                           folder.log(running[k].index), folder.folder(running[k].index), true);
      outcome.wall_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - running[k].started)
              .count();
      folder.finish(std::move(outcome));
    }
    folder.set_state("interrupted");
    std::cerr << "interrupted; " << (out / "sweep.csv").string() << " holds the "
              << folder.finished().size() << " of " << plan.count() << " combinations finished\n";
    return runner::kExitInterrupted;
  }

  folder.set_state("complete");
  std::map<std::string, std::size_t> tally;
  for (const auto& [index, outcome] : folder.finished()) ++tally[outcome.status];
  std::cout << plan.count() << " combination" << (plan.count() == 1 ? "" : "s") << ":";
  bool first = true;
  for (const auto& [status, count] : tally) {
    std::cout << (first ? " " : ", ") << count << " " << status;
    first = false;
  }
  std::cout << "\ntable: " << (out / "sweep.csv").string() << "\n";
  return tally.size() == 1 && tally.count("ok") ? runner::kExitOk : runner::kExitUnstable;
}

}  // namespace drapelab::cli
