#include "drapelab/sweep/outcome.hpp"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/scene/number_format.hpp"

namespace drapelab::sweep {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// Messages go into one CSV cell and one progress line: newlines become spaces.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// A JSON value as a sweep.csv cell: numbers in the shortest form that reads back the same double,
// null and anything missing as an empty cell.
std::string cell(const ordered_json& value) {
  if (value.is_number_integer() || value.is_number_unsigned()) return value.dump();
  if (value.is_number_float()) return format_number(value.get<double>());
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  return {};
}

ordered_json member(const ordered_json& object, const std::string& key) {
  if (!object.is_object()) return nullptr;
  const auto found = object.find(key);
  return found == object.end() ? ordered_json() : *found;
}

std::vector<std::string> measures_of(const ordered_json& solver) {
  std::vector<std::string> cells;
  const ordered_json final_metrics = member(solver, "final");
  for (const auto& name : sweep_final_metrics()) cells.push_back(cell(member(final_metrics, name)));
  for (const auto& name : sweep_solver_measures()) cells.push_back(cell(member(solver, name)));
  return cells;
}

// One row without a solver, for a run that gave no per-solver results.
SweepRow whole_run_row(const std::string& status, const std::string& message) {
  SweepRow row;
  row.status = status;
  row.message = one_line(message);
  row.measures.assign(sweep_final_metrics().size() + sweep_solver_measures().size(), "");
  return row;
}

void settle(CombinationOutcome& outcome) {
  outcome.status = "ok";
  outcome.message.clear();
  for (const auto& row : outcome.rows) {
    if (row.status == "ok") continue;
    outcome.status = row.status;
    outcome.message = row.message;
    break;
  }
}

// The rows of a run that wrote summary.json; `interrupted` when the child exited with 130.
std::optional<std::vector<SweepRow>> rows_from_summary(const fs::path& summary_file,
                                                       bool interrupted) {
  std::error_code ec;
  if (!fs::is_regular_file(summary_file, ec)) return std::nullopt;
  const auto summary = ordered_json::parse(run_folder::read_file(summary_file), nullptr, false);
  if (summary.is_discarded() || !member(summary, "solvers").is_object()) return std::nullopt;
  const ordered_json run = member(summary, "run");
  std::vector<SweepRow> rows;
  for (const auto& [name, solver] : summary["solvers"].items()) {
    SweepRow row;
    row.solver = name;
    row.type = cell(member(solver, "type"));
    row.status = cell(member(solver, "status"));
    row.message = one_line(cell(member(solver, "message")));
    // A solver still ok when Ctrl-C stopped the run did not finish: say so.
    if (interrupted && row.status == "ok") {
      row.status = "interrupted";
      if (row.message.empty())
        row.message = "interrupted after " + cell(member(run, "frames_done")) + " of " +
                      cell(member(run, "frames_planned")) + " frames";
    }
    if (row.status.empty()) row.status = "error";
    row.measures = measures_of(solver);
    rows.push_back(std::move(row));
  }
  if (rows.empty()) return std::nullopt;
  return rows;
}

}  // namespace

const std::vector<std::string>& sweep_final_metrics() {
  static const std::vector<std::string> names = {
      "kinetic_energy", "max_stretch",    "mean_stretch",      "max_penetration",
      "min_clearance",  "projected_area", "drape_coefficient", "drape_nodes"};
  return names;
}

const std::vector<std::string>& sweep_solver_measures() {
  static const std::vector<std::string> names = {"settle_time", "rest_jitter", "ms_per_step",
                                                 "wall_seconds_per_simulated_second"};
  return names;
}

std::string first_error_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line)) {
    if (line.rfind("error: ", 0) == 0) return one_line(line.substr(7));
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  return one_line(last);
}

CombinationOutcome refused_outcome(std::size_t index, const std::string& error) {
  CombinationOutcome outcome;
  outcome.index = index;
  outcome.exit_code = runner::kExitBadInput;
  outcome.rows.push_back(whole_run_row("bad_input", error));
  settle(outcome);
  return outcome;
}

CombinationOutcome unstarted_outcome(std::size_t index, const std::string& folder,
                                     const std::string& error) {
  CombinationOutcome outcome;
  outcome.index = index;
  outcome.folder = folder;
  outcome.rows.push_back(whole_run_row("error", error));
  settle(outcome);
  return outcome;
}

CombinationOutcome silent_outcome(std::size_t index, const std::string& folder,
                                  const std::string& status, const std::string& message) {
  CombinationOutcome outcome;
  outcome.index = index;
  outcome.folder = folder;
  outcome.rows.push_back(whole_run_row(status, message));
  settle(outcome);
  return outcome;
}

CombinationOutcome finished_outcome(std::size_t index, const ChildExit& exit,
                                    const fs::path& run_dir, const fs::path& log,
                                    const std::string& folder, bool stopped_by_sweep) {
  CombinationOutcome outcome;
  outcome.index = index;
  outcome.folder = folder;
  const std::string log_name = log.filename().string();
  if (!exit.exited) {
    const std::string how = "terminated by " + describe_signal(exit.signal);
    if (stopped_by_sweep)
      outcome.rows.push_back(whole_run_row("interrupted", how + " when the sweep was interrupted"));
    else
      outcome.rows.push_back(whole_run_row("crashed", how + "; its output is in " + log_name));
    settle(outcome);
    return outcome;
  }
  outcome.exit_code = exit.code;
  const std::string first_error = first_error_line(log);
  switch (exit.code) {
    case runner::kExitBadInput:
      outcome.rows.push_back(whole_run_row("bad_input", first_error));
      break;
    case runner::kExitOk:
    case runner::kExitUnstable:
    case runner::kExitInterrupted: {
      const bool interrupted = exit.code == runner::kExitInterrupted;
      if (auto rows = rows_from_summary(run_dir / "summary.json", interrupted)) {
        outcome.rows = std::move(*rows);
        // Exit 1 with every solver ok would be a contradiction: keep it visible.
        if (exit.code == runner::kExitUnstable &&
            std::all_of(outcome.rows.begin(), outcome.rows.end(),
                        [](const SweepRow& r) { return r.status == "ok"; }))
          outcome.rows.push_back(
              whole_run_row("error", "exit code 1 with every solver ok: " + first_error));
      } else {
        outcome.rows.push_back(whole_run_row(interrupted ? "interrupted" : "error",
                                             "no readable summary.json in the run folder" +
                                                 (first_error.empty() ? "" : ": " + first_error)));
      }
      break;
    }
    default:
      outcome.rows.push_back(
          whole_run_row("error", "drapelab run exited with code " + std::to_string(exit.code) +
                                     (first_error.empty() ? "" : ": " + first_error) + " (see " +
                                     log_name + ")"));
      break;
  }
  settle(outcome);
  return outcome;
}

}  // namespace drapelab::sweep
