#include "drapelab/sweep/folder.hpp"

#include <unistd.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/run_transaction.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "progress/progress_line.hpp"

namespace drapelab::sweep {

using namespace drapelab::runner;
using namespace drapelab::cli;  // the progress line
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kLongestShownMessage =
    200;  // characters of a failure shown on a progress line

// The files of a sweep folder that --force replaces (and only these), besides its runs.
const std::vector<std::string>& sweep_output_names() {
  static const std::vector<std::string> names = {
      "runs", "sweep.csv", "sweep.json", "sweep.csv.partial", "sweep.json.partial", "slurm"};
  return names;
}

// --force: removes a previous sweep's tables and every run folder in runs/ that drapelab wrote (by
// its manifest); anything else in the folder, runs/ included, stays.
std::optional<std::string> remove_previous_sweep(const fs::path& out) {
  std::error_code ec;
  for (const auto& name : sweep_output_names())
    if (name == "slurm")
      fs::remove_all(out / name, ec);  // the job array's script and status files: all drapelab's
    else if (name != "runs")
      fs::remove(out / name, ec);
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

}  // namespace

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

namespace {

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

}  // namespace

void SweepFolder::finish(CombinationOutcome outcome) {
  const std::size_t index = outcome.index;
  finished_[index] = std::move(outcome);
  clear_progress();
  print_progress(finished_.size(), plan_, finished_[index]);
  write();
}

void SweepFolder::restore(CombinationOutcome outcome) {
  const std::size_t index = outcome.index;
  finished_[index] = std::move(outcome);
}

void SweepFolder::set_state(const std::string& state) {
  clear_progress();  // the sweep ends or stops waiting: its closing lines follow
  record_.state = state;
  write();
}

void SweepFolder::start_progress(cli::ProgressMode mode) {
  progress_ =
      std::make_unique<ProgressDisplay>(mode, std::cerr, plain_progress_interval(), STDERR_FILENO);
  progress_start_ = ProgressDisplay::Clock::now();
  finished_at_progress_start_ = finished_.size();
}

void SweepFolder::show_progress(std::optional<std::size_t> running) {
  if (!progress_ || progress_->mode() == cli::ProgressMode::none) return;
  SweepProgress sweep;
  sweep.done = finished_.size();
  sweep.total = plan_.count();
  sweep.ran = finished_.size() - finished_at_progress_start_;
  sweep.running = running;
  sweep.wall_seconds =
      std::chrono::duration<double>(ProgressDisplay::Clock::now() - progress_start_).count();
  progress_->update({format_sweep_progress(sweep)});
}

void SweepFolder::clear_progress() const {
  if (progress_) progress_->clear();
}

void SweepFolder::write() const {
  try {
    run_folder::write_file_atomically(out_ / "sweep.csv", sweep_csv(plan_, finished_));
    run_folder::write_file_atomically(out_ / "sweep.json", sweep_json(record_, plan_, finished_));
  } catch (const std::exception& e) {
    clear_progress();
    std::cerr << "warning: " << e.what() << "; trying again after the next run\n";
  }
}

int print_tally(const SweepFolder& folder, const SweepPlan& plan) {
  std::map<std::string, std::size_t> tally;
  for (const auto& [index, outcome] : folder.finished()) ++tally[outcome.status];
  std::cout << plan.count() << " combination" << (plan.count() == 1 ? "" : "s") << ":";
  bool first = true;
  for (const auto& [status, count] : tally) {
    std::cout << (first ? " " : ", ") << count << " " << status;
    first = false;
  }
  std::cout << "\ntable: " << (folder.out() / "sweep.csv").string() << "\n";
  return tally.size() == 1 && tally.count("ok") ? kExitOk : kExitUnstable;
}

}  // namespace drapelab::sweep
