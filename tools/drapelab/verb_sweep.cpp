// drapelab sweep SCENE --vary key=v1,v2 [--vary ...] --out DIR: runs the scene once per
// combination of the varied values (their Cartesian product, in odometer order:
// drapelab/sweep/plan.hpp), each as a `drapelab run` of its own into DIR/runs/NNN_key=value_...,
// and gathers every solver's outcome and final metrics into DIR/sweep.csv and DIR/sweep.json. The
// runs are child processes of this one (--engine local, tools/sweep/src/local_engine.cpp) or the
// tasks of one Slurm job array (--engine slurm, tools/sweep/src/slurm_engine.cpp); this file
// parses, validates and prepares the folder.
#include <unistd.h>

#include <iostream>
#include <set>
#include <thread>

#include "drapelab/runner/run_scene.hpp"
#include "drapelab/sweep/children.hpp"
#include "drapelab/sweep/engines.hpp"
#include "drapelab/sweep/plan.hpp"
#include "drapelab/sweep/slurm_job.hpp"
#include "drapelab/sweep/validation.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

using namespace drapelab::runner;  // the run pipeline and the sweep: this file parses and prints
using namespace drapelab::sweep;

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMostCombinations = 10000;  // a guard against a product typed by mistake

// The key of a "key=value" override.
std::string override_key(const std::string& text) { return text.substr(0, text.find('=')); }

int refuse(const std::string& problem) {
  std::cerr << "error: " << problem << "\nnothing was run\n";
  return kExitBadInput;
}

// The arguments that belong together: a new sweep or --collect; Slurm's options with slurm only.
std::optional<std::string> check_argument_set(const SweepArguments& a) {
  const bool submission_options = !a.partition.empty() || !a.time_limit.empty() ||
                                  a.cpus_per_task > 0 || !a.sbatch_args.empty() || a.detach;
  if (!a.collect.empty()) {
    if (!a.scene.empty() || !a.varies.empty() || !a.out.empty() || !a.overrides.empty() ||
        a.force || a.engine != "local" || submission_options)
      return "--collect DIR takes no other option but --lost-after and --no-progress: it gathers "
             "the sweep already submitted into DIR";
    return std::nullopt;
  }
  if (a.scene.empty()) return "a scene file is required (or --collect DIR)";
  if (a.varies.empty()) return "--vary key.path=v1,v2,... is required";
  if (a.out.empty()) return "--out DIR is required: the sweep folder";
  if (a.engine != "slurm" && (submission_options || a.lost_after > 0.0))
    return "--partition, --time, --cpus-per-task, --sbatch-arg, --detach and --lost-after need "
           "--engine slurm";
  return std::nullopt;
}

}  // namespace

void add_sweep_options(CLI::App& verb, SweepArguments& arguments) {
  verb.add_option("scene", arguments.scene, "Scene file (YAML)");
  verb.add_option(
          "--vary", arguments.varies,
          "A key and its values: key.path=v1,v2,... (YAML values as --set takes them; a value "
          "holding commas is a flow list in brackets: cloth.resolution=[5,5],[9,9]); may be "
          "repeated")
      ->allow_extra_args(
          false);  // one key per --vary: a scene path after it is not taken for a key
  verb.add_option("--out,-o", arguments.out,
                  "Sweep folder: sweep.csv, sweep.json and runs/ (created if missing)");
  verb.add_option("--jobs,-j", arguments.jobs,
                  "Runs at a time (default: the number of cores; with --engine slurm: tasks "
                  "running at once, default no limit)")
      ->check(CLI::PositiveNumber);
  verb.add_option(
          "--set", arguments.overrides,
          "Override a key in every run: key.path=value, validated like the file; may be repeated")
      ->allow_extra_args(false);
  verb.add_flag("--force", arguments.force,
                "Replace a sweep already in the folder (its runs/, sweep.csv, sweep.json)");
  verb.add_option("--engine", arguments.engine,
                  "local: child processes on this machine (default); slurm: one Slurm job array "
                  "(sbatch), a task per combination")
      ->check(CLI::IsMember({"local", "slurm"}));
  verb.add_flag("--detach", arguments.detach,
                "slurm: return once the job array is submitted; gather it later with --collect");
  verb.add_option("--collect", arguments.collect,
                  "Wait for the Slurm sweep submitted into DIR and write its sweep.csv and "
                  "sweep.json (Ctrl-C stops waiting; the job goes on)");
  verb.add_option("--partition", arguments.partition, "slurm: the partition (sbatch --partition)");
  verb.add_option("--time", arguments.time_limit,
                  "slurm: each task's time limit, as sbatch --time takes it (30, 1:30:00, ...)");
  verb.add_option("--cpus-per-task", arguments.cpus_per_task,
                  "slurm: CPUs per task (default 1); each run's OpenMP threads")
      ->check(CLI::PositiveNumber);
  verb.add_option("--sbatch-arg", arguments.sbatch_args,
                  "slurm: one more sbatch argument, passed as given (--sbatch-arg=--mem=2G); may "
                  "be repeated")
      ->allow_extra_args(false);
  verb.add_option("--lost-after", arguments.lost_after,
                  "slurm: seconds a task may be gone from the queue without its status file "
                  "before its row is lost (default 30; more for a slow shared filesystem)")
      ->check(CLI::PositiveNumber);
  verb.add_flag("--no-progress", arguments.no_progress,
                "Print no progress line (runs done of total, on stderr: redrawn in place on a "
                "terminal, else a line every 5 s)");
  verb.footer(
      "Runs every combination of the varied values, the last --vary key changing fastest, each as "
      "its own 'drapelab run' into DIR/runs/NNN_key=value_...; every combination is validated "
      "first.\n"
      "Example:\n  drapelab sweep scenes/curtain.yaml --vary cloth.springs.bend.ks=1,10,100 --set "
      "duration=0.5 --out out/bend-sweep\n"
      "On a Slurm cluster (DIR, the scene and drapelab on a shared filesystem):\n"
      "  drapelab sweep scenes/cusick.yaml --vary cloth.springs.bend.ks=0.5,1,2,4 --out "
      "out/bend --engine slurm --partition short --time 30\n"
      "Exit codes: 0 every run ok (or submitted, with --detach), 1 a run failed (it is a row of "
      "sweep.csv), 2 bad arguments, an unknown key or a refused submission (nothing run), 130 "
      "interrupted (sweep.csv holds the runs finished).");
}

int sweep_verb(const SweepArguments& arguments, const std::string& command_line,
               const std::atomic<bool>& interrupt) {
  if (const auto problem = check_argument_set(arguments)) return refuse(*problem);
  if (!arguments.collect.empty()) {
    const PollingSection polling;  // Ctrl-C stops waiting; the job goes on
    return collect_slurm_sweep(arguments.collect, arguments.lost_after,
                               progress_mode_for(STDERR_FILENO, !arguments.no_progress), interrupt);
  }

  // 1. The arguments, before any scene is read.
  std::vector<VariedKey> keys;
  std::set<std::string> seen;
  for (const auto& text : arguments.varies) {
    std::string problem;
    auto varied = parse_vary(text, &problem);
    if (!varied) return refuse(problem);
    if (!seen.insert(varied->key).second)
      return refuse("--vary " + varied->key + " is given twice; list all its values in one --vary");
    keys.push_back(std::move(*varied));
  }
  for (const auto& text : arguments.overrides)
    if (seen.count(override_key(text)))
      return refuse(override_key(text) + " is both --set and --vary; drop the --set");
  const SweepPlan plan(std::move(keys));
  if (plan.count() > kMostCombinations)
    return refuse("the --vary options make more than " + std::to_string(kMostCombinations) +
                  " combinations; split the sweep");
  const bool slurm = arguments.engine == "slurm";
  const int jobs = arguments.jobs > 0 ? arguments.jobs
                   : slurm            ? 0
                           : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  if (slurm)
    if (const auto missing = missing_slurm_command())
      return refuse("--engine slurm needs Slurm's " + *missing +
                    " on PATH (run the sweep on a machine that submits Slurm jobs)");

  // 2. Every combination loaded in-process: an unknown key stops here, before anything runs.
  const SweepValidation validation = validate_sweep(arguments.scene, arguments.overrides, plan);
  if (!validation.ok()) {
    for (const auto& error : validation.base_errors) std::cerr << "error: " << error << "\n";
    for (const auto& error : validation.key_errors) std::cerr << "error: " << error << "\n";
    std::cerr << "nothing was run\n";
    return kExitBadInput;
  }
  const PollingSection polling;  // Ctrl-C: the runs stop, and sweep.csv keeps the finished ones
  const fs::path out = arguments.out;
  if (arguments.force)
    if (const auto problem = queued_slurm_job(out)) return refuse(*problem);
  std::unique_ptr<run_folder::FolderLock> lock;  // held until the sweep ends
  if (const auto problem = prepare_sweep_folder(out, arguments.force, lock))
    return refuse(*problem);

  SweepRecord record;
  record.command = command_line;
  record.executable = own_executable_path();
  record.scene_file = arguments.scene;
  record.scene_name = validation.scene_name;
  record.overrides = arguments.overrides;
  record.jobs = jobs;
  record.engine = arguments.engine;
  record.state = "running";
  SweepFolder folder(out, record, plan);
  std::size_t refused = 0;
  for (const auto& error : validation.combination_errors) refused += error.has_value();
  std::cout << "sweep of " << validation.scene_name << " (" << arguments.scene
            << "): " << plan.count() << " combination" << (plan.count() == 1 ? "" : "s") << " of";
  for (const auto& key : plan.keys())
    std::cout << " " << key.key << " (" << key.values.size() << ")";
  if (slurm)
    std::cout << ", as a Slurm job array"
              << (jobs > 0 ? " of up to " + std::to_string(jobs) + " tasks at a time" : "");
  else
    std::cout << ", up to " << jobs << " at a time";
  if (refused) std::cout << "; " << refused << " refused by validation (bad_input rows)";
  std::cout << std::endl;
  folder.write();

  // 3. Refused combinations are rows at once; the engine runs the others.
  for (std::size_t index = 0; index < plan.count(); ++index)
    if (const auto& error = validation.combination_errors[index])
      folder.finish(refused_outcome(index, *error));
  folder.start_progress(progress_mode_for(STDERR_FILENO, !arguments.no_progress));
  SweepStart start{arguments, plan, validation, folder, interrupt};
  return slurm ? run_slurm_sweep(start) : run_local_sweep(start);
}

}  // namespace drapelab::cli
