// A sweep's runs as one Slurm job array: the task script that runs one combination per array task,
// sbatch to submit it, squeue to see which tasks remain, scancel to cancel, and the status file
// each task leaves. Slurm's commands are run as programs (found on PATH), so drapelab needs no
// Slurm library and works with any Slurm whose sbatch, squeue and scancel take these options.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "drapelab/sweep/children.hpp"

namespace drapelab::sweep {

// What a program run to completion printed (stdout and stderr together) and how it ended.
struct CommandOutput {
  bool started = false;  // false: not found or not executable (`text` says why)
  int exit_code = -1;    // -1 when a signal ended it
  std::string text;
};
CommandOutput run_command(const std::vector<std::string>& arguments);

// The first of Slurm's commands (sbatch, squeue, scancel) that is not an executable on PATH.
std::optional<std::string> missing_slurm_command();

// The sbatch options of `drapelab sweep --engine slurm`.
struct SlurmOptions {
  std::string partition;           // --partition; empty: the cluster's default
  std::string time_limit;          // --time, per task (Slurm's forms: "30", "2:00:00", ...)
  int cpus_per_task = 1;           // --cpus-per-task; also the task's OMP_NUM_THREADS
  int most_running = 0;            // the array's "%N" throttle; 0: no limit
  std::vector<std::string> extra;  // more sbatch arguments, passed as given
};

// One array task: its combination and the command it runs (arguments[0] is the program).
struct SlurmTask {
  std::size_t index = 0;
  std::vector<std::string> arguments;
  std::filesystem::path log;  // the run's output, as for a local sweep
};

// The sweep folder's slurm/ files.
std::filesystem::path slurm_folder(const std::filesystem::path& sweep);
std::filesystem::path task_script_path(const std::filesystem::path& sweep);
std::filesystem::path task_status_path(const std::filesystem::path& sweep, std::size_t index);

// The bash script every array task runs: it picks its command by SLURM_ARRAY_TASK_ID, runs it from
// `workdir` (the directory the sweep was started in, so relative paths mean the same), and writes
// its status file (exit code, start and end times) once the command has ended, also when Slurm
// stopped it with SIGTERM (scancel, the time limit).
std::string task_script(const std::filesystem::path& sweep, const std::filesystem::path& workdir,
                        const std::vector<SlurmTask>& tasks);

// "0-3,5,7-9": the array indices, as sbatch --array takes them.
std::string array_ranges(const std::vector<std::size_t>& indices);

// sbatch's arguments for the array (without the "sbatch" program itself).
std::vector<std::string> sbatch_arguments(const SlurmOptions& options, const std::string& job_name,
                                          const std::filesystem::path& sweep,
                                          const std::vector<std::size_t>& indices);

// Submits; returns the job id, or nothing with `error` holding sbatch's own message.
std::optional<std::string> submit_array(const std::vector<std::string>& sbatch_args,
                                        std::string* error);

// The array indices of `job_id` still pending or running; nothing when squeue failed (`error`).
std::optional<std::set<std::size_t>> queued_tasks(const std::string& job_id, std::string* error);

// Cancels every task of the job; false with `error` when scancel failed.
bool cancel_job(const std::string& job_id, std::string* error);

// What a task's status file says.
struct TaskEnd {
  ChildExit exit;                 // the command's end: an exit code, or the signal that ended it
  double wall_seconds = 0.0;      // s, from the command's start to its end
  bool stopped_by_slurm = false;  // SIGTERM reached the task (scancel or the time limit)
};
// Reads a task's status file; nothing while it is missing or incomplete.
std::optional<TaskEnd> read_task_end(const std::filesystem::path& status_file);

}  // namespace drapelab::sweep
