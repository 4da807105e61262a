// The Slurm engine: the combinations become one job array (sbatch --array), each task one
// `drapelab run` into the sweep folder, which every node must see at the same path (a shared
// filesystem). The sweep then waits, reading the status file each task leaves as it ends and asking
// squeue which tasks remain, and writes sweep.csv and sweep.json as a local sweep does. With
// --detach it returns once the array is submitted, and `drapelab sweep --collect DIR` waits later
// from what slurm/submission.json records.
#include <sys/stat.h>

#include <chrono>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/sweep/engines.hpp"
#include "drapelab/sweep/slurm_job.hpp"

namespace drapelab::sweep {

using namespace drapelab::runner;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::ordered_json;

namespace {

constexpr auto kStatusPollPeriod = std::chrono::milliseconds(250);  // status files: cheap reads
constexpr auto kQueuePollPeriod = std::chrono::seconds(2);          // squeue asks the controller
// A task gone from the queue without a status file is lost only after this long (--lost-after):
// on a shared filesystem a file written on a compute node may take a few seconds to be seen here.
constexpr double kDefaultLostAfter = 30.0;  // s

Clock::duration lost_after_duration(double seconds) {
  return std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(seconds > 0.0 ? seconds : kDefaultLostAfter));
}
// After scancel: the longest wait for the tasks to leave the queue (Slurm sends SIGTERM, then
// SIGKILL after its KillWait, 30 s by default), and then for their last status files.
constexpr auto kCancelWait = std::chrono::seconds(90);
constexpr auto kCancelSettle = std::chrono::seconds(5);

// What --collect needs to wait for a sweep submitted earlier: slurm/submission.json.
struct Submission {
  std::string job_id;
  std::vector<std::size_t> indices;  // the combinations submitted (the array's indices)
};

fs::path submission_path(const fs::path& sweep) { return slurm_folder(sweep) / "submission.json"; }

std::string submission_json(const SweepRecord& record, const SweepPlan& plan,
                            const std::vector<std::size_t>& indices,
                            const std::map<std::size_t, CombinationOutcome>& refused) {
  ordered_json j;
  j["job_id"] = record.job_id;
  j["indices"] = indices;
  ordered_json varied = ordered_json::array();
  for (const auto& key : plan.keys()) varied.push_back({{"key", key.key}, {"values", key.values}});
  j["varied"] = varied;
  ordered_json refusals = ordered_json::object();
  for (const auto& [index, outcome] : refused)
    refusals[std::to_string(index)] = outcome.rows.front().message;
  j["refused"] = refusals;
  j["record"] = {{"command", record.command},       {"executable", record.executable},
                 {"scene_file", record.scene_file}, {"scene_name", record.scene_name},
                 {"overrides", record.overrides},   {"jobs", record.jobs}};
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

// How one task ended, as a row; `cancelled`: the sweep cancelled the array (Ctrl-C).
CombinationOutcome task_outcome(const SweepFolder& folder, std::size_t index, const TaskEnd& end,
                                bool cancelled) {
  CombinationOutcome outcome =
      finished_outcome(index, end.exit, folder.run_dir(index), folder.log(index),
                       folder.folder(index), cancelled || end.stopped_by_slurm);
  outcome.wall_seconds = end.wall_seconds;
  if (end.stopped_by_slurm && !cancelled) {
    const std::string why = " (Slurm stopped the task: its time limit, or scancel)";
    for (auto& row : outcome.rows)
      if (row.status == "interrupted") row.message += why;
    if (outcome.status == "interrupted") outcome.message += why;
  }
  return outcome;
}

// Waits on one submitted array.
class ArrayWatch {
 public:
  ArrayWatch(SweepFolder& folder, Submission submission, Clock::duration lost_after)
      : folder_(folder), submission_(std::move(submission)), lost_after_(lost_after) {}

  bool all_finished() const {
    for (const std::size_t index : submission_.indices)
      if (!folder_.is_finished(index)) return false;
    return true;
  }

  // Records every task whose status file has appeared.
  void collect_ended(bool cancelled) {
    for (const std::size_t index : submission_.indices) {
      if (folder_.is_finished(index)) continue;
      if (const auto end = read_task_end(task_status_path(folder_.out(), index)))
        folder_.finish(task_outcome(folder_, index, *end, cancelled));
    }
  }

  // Asks squeue which tasks remain; false when it could not say. Tasks gone from the queue for
  // lost_after without a status file are rows with status lost.
  bool check_queue() {
    std::string problem;
    const auto queued = queued_tasks(submission_.job_id, &problem);
    if (!queued) {
      if (!warned_) {
        folder_.clear_progress();
        std::cerr << "warning: " << problem << "; trying again\n";
      }
      warned_ = true;
      return false;
    }
    queue_empty_ = true;
    const auto now = Clock::now();
    for (const std::size_t index : submission_.indices) {
      if (folder_.is_finished(index)) continue;
      if (queued->count(index)) {
        queue_empty_ = false;
        gone_since_.erase(index);
      } else {
        gone_since_.emplace(index, now);
      }
    }
    for (const auto& [index, since] : gone_since_) {
      if (folder_.is_finished(index) || now - since < lost_after_) continue;
      if (const auto end = read_task_end(task_status_path(folder_.out(), index))) continue;
      folder_.finish(silent_outcome(
          index, folder_.folder(index), "lost",
          "the Slurm task left the queue without a status: cancelled from outside before it "
          "started, a node failure, or SIGKILL after its time limit; see slurm/task_" +
              std::to_string(index) + ".out"));
    }
    return true;
  }

  // Waits until every task has ended, or until `interrupt`. True when all ended.
  bool wait(const std::atomic<bool>& interrupt) {
    auto next_queue_check = Clock::now();
    while (true) {
      collect_ended(false);
      if (all_finished()) return true;
      if (interrupt.load()) return false;
      if (Clock::now() >= next_queue_check) {
        check_queue();
        next_queue_check = Clock::now() + kQueuePollPeriod;
      }
      folder_.show_progress(std::nullopt);  // queued and running tasks are not told apart
      std::this_thread::sleep_for(kStatusPollPeriod);
    }
  }

  // After Ctrl-C: scancel, then the tasks' last status files; the tasks that never wrote one were
  // cancelled before they could run (or stop).
  void cancel() {
    std::string problem;
    folder_.clear_progress();
    std::cerr << "cancelling Slurm job " << submission_.job_id << " (scancel)\n";
    if (!cancel_job(submission_.job_id, &problem)) std::cerr << "warning: " << problem << "\n";
    const auto give_up = Clock::now() + kCancelWait;
    std::optional<Clock::time_point> emptied;
    while (Clock::now() < give_up) {
      collect_ended(true);
      if (all_finished()) return;
      if (check_queue() && queue_empty_ && !emptied) emptied = Clock::now();
      if (emptied && Clock::now() - *emptied >= kCancelSettle) break;
      std::this_thread::sleep_for(kQueuePollPeriod / 4);
    }
    for (const std::size_t index : submission_.indices)
      if (!folder_.is_finished(index))
        folder_.finish(silent_outcome(index, folder_.folder(index), "cancelled",
                                      "cancelled by the sweep's Ctrl-C (scancel " +
                                          submission_.job_id + ") before the run could end"));
  }

 private:
  SweepFolder& folder_;
  Submission submission_;
  Clock::duration lost_after_;
  std::map<std::size_t, Clock::time_point> gone_since_;
  bool queue_empty_ = false;
  bool warned_ = false;
};

// Waits for the array and closes the sweep; shared by a sweep that waits and by --collect.
int wait_and_close(SweepFolder& folder, const SweepPlan& plan, Submission submission,
                   double lost_after, const std::atomic<bool>& interrupt,
                   bool cancel_on_interrupt) {
  const std::string job_id = submission.job_id;
  ArrayWatch watch(folder, std::move(submission), lost_after_duration(lost_after));
  if (watch.wait(interrupt)) {
    folder.set_state("complete");
    return print_tally(folder, plan);
  }
  if (cancel_on_interrupt) {
    watch.cancel();
    folder.set_state("interrupted");
    std::cerr << "interrupted; " << (folder.out() / "sweep.csv").string() << " holds every "
              << "combination, those cancelled included\n";
  } else {
    folder.set_state("submitted");
    std::cerr << "stopped waiting; Slurm job " << job_id << " goes on. Collect it again with "
              << "drapelab sweep --collect " << folder.out().string() << ", or cancel it with "
              << "scancel " << job_id << "\n";
  }
  return kExitInterrupted;
}

// Removes what a sweep whose submission failed wrote, so that nothing half-made stays.
void discard_sweep(const fs::path& out) {
  std::error_code ec;
  fs::remove_all(slurm_folder(out), ec);
  fs::remove(out / "sweep.csv", ec);
  fs::remove(out / "sweep.json", ec);
}

}  // namespace

int run_slurm_sweep(SweepStart& start) {
  SweepFolder& folder = start.folder;
  const std::vector<std::size_t> indices = combinations_to_run(start);
  if (indices.empty()) {  // every combination refused: nothing to submit
    folder.set_state("complete");
    return print_tally(folder, start.plan);
  }
  const fs::path sweep = fs::absolute(folder.out());
  const std::string program = folder.record().executable;
  std::vector<SlurmTask> tasks;
  for (const std::size_t index : indices)
    tasks.push_back({index, run_arguments(start, index, program), folder.log(index)});
  const auto& a = start.arguments;
  SlurmOptions options;
  options.partition = a.partition;
  options.time_limit = a.time_limit;
  options.cpus_per_task = a.cpus_per_task > 0 ? a.cpus_per_task : 1;
  options.most_running = folder.record().jobs;
  options.extra = a.sbatch_args;
  const std::vector<std::string> sbatch_args =
      sbatch_arguments(options, "drapelab-" + folder.record().scene_name, sweep, indices);
  try {
    fs::create_directories(slurm_folder(sweep) / "status");
    run_folder::write_file_atomically(task_script_path(sweep),
                                      task_script(sweep, fs::current_path(), tasks));
    ::chmod(task_script_path(sweep).c_str(), 0755);
  } catch (const std::exception& e) {
    discard_sweep(folder.out());
    std::cerr << "error: cannot write the job's script: " << e.what() << "\nnothing was run\n";
    return kExitBadInput;
  }
  std::string problem;
  const auto job_id = submit_array(sbatch_args, &problem);
  if (!job_id) {
    discard_sweep(folder.out());
    std::cerr << "error: " << problem << "\nnothing was run\n";
    return kExitBadInput;
  }
  folder.record().job_id = *job_id;
  folder.record().state = a.detach ? "submitted" : "running";
  try {
    run_folder::write_file_atomically(
        submission_path(sweep),
        submission_json(folder.record(), start.plan, indices, folder.finished()));
  } catch (const std::exception& e) {
    std::cerr << "warning: " << e.what() << "; --collect cannot gather this sweep\n";
  }
  folder.write();
  std::cout << "submitted Slurm job " << *job_id << ": " << indices.size() << " task"
            << (indices.size() == 1 ? "" : "s") << " (array " << array_ranges(indices) << ")"
            << std::endl;
  if (a.detach) {
    std::cout << "collect it with: drapelab sweep --collect " << folder.out().string() << "\n";
    return kExitOk;
  }
  return wait_and_close(folder, start.plan, {*job_id, indices}, a.lost_after, start.interrupt,
                        true);
}

namespace {

// slurm/submission.json as drapelab wrote it; `problem` says why not when it is missing or is not
// a submission (job_id, indices, varied, record).
std::optional<ordered_json> read_submission(const fs::path& out, std::string* problem) {
  const auto text = run_folder::read_file_bytes(submission_path(out));
  if (!text) {
    *problem = submission_path(out).string() + " is missing";
    return std::nullopt;
  }
  auto j = ordered_json::parse(*text, nullptr, false);
  if (j.is_discarded() || !j.contains("job_id") || !j["job_id"].is_string() ||
      !j.contains("indices") || !j.contains("varied") || !j.contains("record")) {
    *problem = submission_path(out).string() +
               " is not a submission drapelab wrote (job_id, indices, varied, record)";
    return std::nullopt;
  }
  return j;
}

}  // namespace

std::optional<std::string> queued_slurm_job(const fs::path& out) {
  std::string problem;
  const auto j = read_submission(out, &problem);
  if (!j) return std::nullopt;
  const std::string job_id = (*j)["job_id"].get<std::string>();
  const auto queued = missing_slurm_command() ? std::nullopt : queued_tasks(job_id, &problem);
  if (!queued || queued->empty()) return std::nullopt;
  return out.string() + " holds Slurm job " + job_id + ", which still has " +
         std::to_string(queued->size()) + " task" + (queued->size() == 1 ? "" : "s") +
         " queued or running; cancel it (scancel " + job_id +
         ") or wait for it (drapelab sweep --collect " + out.string() + ") before --force";
}

int collect_slurm_sweep(const std::string& out_text, double lost_after, cli::ProgressMode progress,
                        const std::atomic<bool>& interrupt) {
  const fs::path out = out_text;
  std::string problem;
  const auto submission_file = read_submission(out, &problem);
  if (!submission_file) {
    std::cerr << "error: " << problem << ": --collect gathers a sweep submitted with --engine "
              << "slurm into " << out_text << "\n";
    return kExitBadInput;
  }
  const ordered_json& j = *submission_file;
  std::vector<VariedKey> keys;
  for (const auto& key : j["varied"])
    keys.push_back({key["key"].get<std::string>(), key["values"].get<std::vector<std::string>>()});
  const SweepPlan plan(std::move(keys));
  auto locked = run_folder::FolderLock::acquire(out);
  if (auto* refusal = std::get_if<std::string>(&locked)) {
    std::cerr << "error: " << *refusal << "\n";
    return kExitBadInput;
  }
  const auto& r = j["record"];
  SweepRecord record;
  record.command = r.value("command", "");
  record.executable = r.value("executable", "");
  record.scene_file = r.value("scene_file", "");
  record.scene_name = r.value("scene_name", "");
  record.overrides = r.value("overrides", std::vector<std::string>{});
  record.jobs = r.value("jobs", 0);
  record.engine = "slurm";
  record.job_id = j["job_id"].get<std::string>();
  record.state = "running";
  SweepFolder folder(out, record, plan);
  for (const auto& [index, message] : j["refused"].items())
    folder.restore(refused_outcome(std::stoul(index), message.get<std::string>()));
  const Submission submission{record.job_id, j["indices"].get<std::vector<std::size_t>>()};
  std::cout << "collecting Slurm job " << record.job_id << " (" << submission.indices.size()
            << " tasks) into " << out.string() << std::endl;
  folder.start_progress(progress);
  return wait_and_close(folder, plan, submission, lost_after, interrupt, false);
}

}  // namespace drapelab::sweep
