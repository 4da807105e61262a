// The sweep folder while a sweep runs or is collected: preparing it (its lock, --force), and the
// finished combinations, printed as progress lines and written to sweep.csv and sweep.json after
// each one. Shared by the local and the Slurm engines.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "drapelab/run_folder/folder_lock.hpp"
#include "drapelab/sweep/files.hpp"
#include "drapelab/sweep/outcome.hpp"
#include "drapelab/sweep/plan.hpp"
#include "progress/progress_display.hpp"

namespace drapelab::sweep {

// Checks and prepares the sweep folder, and locks it for the sweep (one sweep per folder at a
// time); returns an error message when it may not be used.
std::optional<std::string> prepare_sweep_folder(const std::filesystem::path& out, bool force,
                                                std::unique_ptr<run_folder::FolderLock>& lock);

// "cloth.springs.bend.ks=100, duration=0.5"
std::string describe_values(const SweepPlan& plan, std::size_t index);

class SweepFolder {
 public:
  SweepFolder(std::filesystem::path out, SweepRecord record, const SweepPlan& plan)
      : out_(std::move(out)), record_(std::move(record)), plan_(plan) {}

  const std::filesystem::path& out() const { return out_; }
  const SweepRecord& record() const { return record_; }
  SweepRecord& record() { return record_; }
  std::string folder(std::size_t index) const { return "runs/" + plan_.folder_name(index); }
  std::filesystem::path run_dir(std::size_t index) const {
    return out_ / "runs" / plan_.folder_name(index);
  }
  std::filesystem::path log(std::size_t index) const {
    return out_ / "runs" / (plan_.folder_name(index) + ".log");
  }
  const std::map<std::size_t, CombinationOutcome>& finished() const { return finished_; }
  bool is_finished(std::size_t index) const { return finished_.count(index) > 0; }

  // Records a finished combination, prints its line and rewrites both files.
  void finish(CombinationOutcome outcome);
  // Records one already known (collecting a sweep again): no progress line, no rewrite.
  void restore(CombinationOutcome outcome);
  void set_state(const std::string& state);
  // Both files, replaced atomically: valid whenever the sweep stops.
  void write() const;

  // The progress line on stderr (runs done of total, docs/cli.md "Progress"), its clock started
  // now: the combinations finished so far took none of its time.
  void start_progress(cli::ProgressMode mode);
  // Shows the line when it is due; `running`: the runs in progress, when the engine knows them.
  void show_progress(std::optional<std::size_t> running);
  // Erases the line from a terminal before other output; the next show_progress draws it again.
  void clear_progress() const;

 private:
  std::filesystem::path out_;
  SweepRecord record_;
  const SweepPlan& plan_;
  std::map<std::size_t, CombinationOutcome> finished_;
  std::unique_ptr<cli::ProgressDisplay> progress_;  // none until start_progress
  cli::ProgressDisplay::Clock::time_point progress_start_;
  std::size_t finished_at_progress_start_ = 0;
};

// The closing lines of a sweep ("4 combinations: 3 ok, 1 unstable", the table's path) and its exit
// code: 0 when every combination is ok, else 1.
int print_tally(const SweepFolder& folder, const SweepPlan& plan);

}  // namespace drapelab::sweep
