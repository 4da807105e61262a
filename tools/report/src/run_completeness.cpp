// Whether a run folder holds the whole run (run_completeness.hpp).
#include "drapelab/report/run_completeness.hpp"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/folder_lock.hpp"
#include "drapelab/run_folder/run_transaction.hpp"

namespace drapelab::report {

namespace fs = std::filesystem;

std::string whole_rows(const std::string& text, bool* cut) {
  const bool partial = !text.empty() && text.back() != '\n';
  if (cut) *cut = partial;
  if (!partial) return text;
  const auto newline = text.rfind('\n');
  return newline == std::string::npos ? std::string() : text.substr(0, newline + 1);
}

std::string frame_ranges(const std::vector<int>& frames) {
  std::string text;
  for (std::size_t k = 0; k < frames.size();) {
    std::size_t end = k;
    while (end + 1 < frames.size() && frames[end + 1] == frames[end] + 1) ++end;
    text += (text.empty() ? "" : ", ") + std::to_string(frames[k]) +
            (end > k ? "-" + std::to_string(frames[end]) : "");
    k = end + 1;
  }
  return text.empty() ? "none" : text;
}

bool RunCompleteness::incomplete() const { return state == "running" || !cut_files.empty(); }

std::vector<std::string> RunCompleteness::notices() const {
  std::vector<std::string> lines;
  if (state == "running")
    lines.push_back(live_writer.empty()
                        ? "the run is incomplete: summary.json says state \"running\" and no "
                          "run writes the folder any more, so its writer was killed"
                        : "the run is incomplete: it is still running (pid " + live_writer +
                              "); this is its staging folder, and its files move into place when "
                              "it ends");
  for (const auto& file : cut_files)
    lines.push_back(file +
                    " ends in the middle of a row (its writer was killed while writing); "
                    "the cut row is left out");
  if (interrupted()) lines.push_back("the run was interrupted (Ctrl-C) before its end");
  if (state == "write_failed")
    lines.push_back("the run stopped at a write error (disk full or permissions) before its end");
  if (lines.empty() && state != "finished" && !state.empty())
    lines.push_back("summary.json says state \"" + state + "\"");
  if (lines.empty()) return lines;
  for (const auto& solver : solvers) {
    std::string line = solver.name + ": frames " + frame_ranges(solver.frames) + " recorded";
    if (frames_planned >= 0) line += " of 0-" + std::to_string(frames_planned);
    if (!solver.missing.empty()) line += ", missing " + frame_ranges(solver.missing);
    if (!solver.status.empty() && solver.status != "ok")
      line += " (it stopped early: " + solver.status + ")";
    lines.push_back(line);
  }
  return lines;
}

namespace {

// The pid of the run writing `folder` when it is a live run's staging folder (DIR/.drapelab-run-PID
// while DIR's lock is held by PID); "" otherwise.
std::string live_writer_of(const fs::path& folder) {
  std::error_code error;
  const fs::path staging = fs::weakly_canonical(folder, error);
  const std::string name = staging.filename().string();
  const std::string prefix = run_folder::kStagingPrefix;
  if (error || name.rfind(prefix, 0) != 0) return "";
  const auto holder = run_folder::lock_holder(staging.parent_path());
  return holder && *holder == name.substr(prefix.size()) ? *holder : "";
}

}  // namespace

RunCompleteness inspect_run(const fs::path& folder) {
  RunCompleteness run;
  std::vector<std::string> order;
  std::map<std::string, std::string> status;
  if (const auto text = run_folder::read_file_bytes(folder / "summary.json")) {
    const auto summary = nlohmann::json::parse(*text, nullptr, false);
    if (summary.is_object()) {
      if (summary.contains("run") && summary["run"].is_object()) {
        const auto& r = summary["run"];
        if (r.contains("state") && r["state"].is_string()) run.state = r["state"];
        if (run.state == "running") run.live_writer = live_writer_of(folder);
        if (r.contains("frames_planned") && r["frames_planned"].is_number_integer())
          run.frames_planned = r["frames_planned"];
      }
      if (summary.contains("solvers") && summary["solvers"].is_object())
        for (const auto& [name, entry] : summary["solvers"].items()) {
          order.push_back(name);
          if (entry.is_object() && entry.contains("status") && entry["status"].is_string())
            status[name] = entry["status"];
        }
    }
  }
  std::map<std::string, std::set<int>> frames;
  for (const char* name : {"metrics.csv", "contacts.csv", "compare.csv"}) {
    const auto text = run_folder::read_file_bytes(folder / name);
    if (!text) continue;
    bool cut = false;
    const std::string whole = whole_rows(*text, &cut);
    if (cut) run.cut_files.push_back(name);
    if (std::string(name) != "metrics.csv") continue;
    const auto table = run_folder::parse_csv(whole);
    const auto solver_column = table.column("solver"), frame_column = table.column("frame");
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
      const auto frame = run_folder::parse_number(table.text(r, frame_column));
      const std::string& solver = table.text(r, solver_column);
      if (!frame) continue;
      if (std::find(order.begin(), order.end(), solver) == order.end()) order.push_back(solver);
      frames[solver].insert(static_cast<int>(*frame));
    }
  }
  for (const auto& name : order) {
    SolverFrameSpan span;
    span.name = name;
    span.status = status.count(name) ? status[name] : "";
    span.frames.assign(frames[name].begin(), frames[name].end());
    for (int f = 0; f <= run.frames_planned; ++f)
      if (!frames[name].count(f)) span.missing.push_back(f);
    run.solvers.push_back(std::move(span));
  }
  return run;
}

}  // namespace drapelab::report
