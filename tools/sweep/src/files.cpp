#include "drapelab/sweep/files.hpp"

#include <nlohmann/json.hpp>

#include "drapelab/run_folder/csv.hpp"

namespace drapelab::sweep {

using nlohmann::ordered_json;

std::string sweep_csv(const SweepPlan& plan,
                      const std::map<std::size_t, CombinationOutcome>& finished) {
  std::vector<std::string> header{"combination"};
  for (const auto& key : plan.keys()) header.push_back(key.key);
  for (const char* name : {"solver", "type", "status", "exit_code", "message"})
    header.emplace_back(name);
  for (const auto& name : sweep_final_metrics()) header.push_back(name);
  for (const auto& name : sweep_solver_measures()) header.push_back(name);
  header.emplace_back("run_folder");
  std::string text;
  for (std::size_t k = 0; k < header.size(); ++k)
    text += (k ? "," : "") + run_folder::csv_cell(header[k]);
  text += "\n";
  for (const auto& [index, outcome] : finished) {  // std::map: in combination order
    const auto values = plan.values(index);
    for (const auto& row : outcome.rows) {
      std::vector<std::string> cells{std::to_string(index)};
      for (const auto& value : values) cells.push_back(run_folder::csv_cell(value));
      cells.push_back(run_folder::csv_cell(row.solver));
      cells.push_back(run_folder::csv_cell(row.type));
      cells.push_back(row.status);
      cells.push_back(outcome.exit_code ? std::to_string(*outcome.exit_code) : "");
      cells.push_back(run_folder::csv_cell(row.message, true));
      for (const auto& measure : row.measures) cells.push_back(measure);
      cells.push_back(run_folder::csv_cell(outcome.folder));
      for (std::size_t k = 0; k < cells.size(); ++k) text += (k ? "," : "") + cells[k];
      text += "\n";
    }
  }
  return text;
}

const std::vector<std::string>& sweep_timing_columns() {
  static const std::vector<std::string> names = {"ms_per_step",
                                                 "wall_seconds_per_simulated_second"};
  return names;
}

std::string sweep_json(const SweepRecord& record, const SweepPlan& plan,
                       const std::map<std::size_t, CombinationOutcome>& finished) {
  ordered_json j;
  j["command"] = record.command;
  j["drapelab"] = record.executable;
  j["scene_file"] = record.scene_file;
  j["scene"] = record.scene_name;
  j["overrides"] = record.overrides;
  ordered_json varied = ordered_json::array();
  for (const auto& key : plan.keys()) varied.push_back({{"key", key.key}, {"values", key.values}});
  j["varied"] = varied;
  j["order"] = "combination index counts like an odometer: the last varied key changes fastest";
  j["jobs"] = record.jobs;
  j["engine"] = record.engine;
  if (record.engine == "slurm") j["slurm_job"] = record.job_id;
  j["state"] = record.state;
  std::size_t done = 0, ok = 0;
  ordered_json combinations = ordered_json::array();
  const bool waits = record.state == "running" || record.state == "submitted";
  const std::string waiting = waits ? "pending" : "not_run";
  for (std::size_t index = 0; index < plan.count(); ++index) {
    ordered_json c;
    c["index"] = index;
    ordered_json values = ordered_json::object();
    const auto chosen = plan.values(index);
    for (std::size_t k = 0; k < plan.keys().size(); ++k) values[plan.keys()[k].key] = chosen[k];
    c["values"] = values;
    const auto found = finished.find(index);
    if (found == finished.end()) {
      c["status"] = waiting;
      c["folder"] = nullptr;
    } else {
      const CombinationOutcome& outcome = found->second;
      ++done;
      ok += outcome.status == "ok";
      c["status"] = outcome.status;
      // Not "exit_code": sweep.csv's column of that name is not a varied key, and readers of the
      // folder (drapelab report) take strings named in sweep.json for varied keys.
      c["exit_status"] = outcome.exit_code ? ordered_json(*outcome.exit_code) : ordered_json();
      c["message"] = outcome.message;
      c["folder"] = outcome.folder.empty() ? ordered_json() : ordered_json(outcome.folder);
      c["wall_seconds"] = outcome.wall_seconds;
    }
    combinations.push_back(c);
  }
  j["combinations_total"] = plan.count();
  j["combinations_finished"] = done;
  j["combinations_ok"] = ok;
  j["combinations"] = combinations;
  // A path or command line that is not UTF-8 is written with U+FFFD, not refused.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace drapelab::sweep
