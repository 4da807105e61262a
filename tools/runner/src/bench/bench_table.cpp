// drapelab bench's outputs (bench_table.hpp).
#include "drapelab/runner/bench_table.hpp"

#include <cstdio>
#include <sstream>

#include "drapelab/run_folder/files.hpp"

namespace drapelab::runner {
namespace {

std::string number(double value, const char* format = "%.4g") {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

bool measured(const BenchRow& row) { return row.status != "skipped"; }

// The rms distance to the reference, or an empty cell.
std::string rms_cell(const BenchRow& row, const char* format) {
  return row.rms_to_reference ? number(*row.rms_to_reference, format) : "";
}

// A count or a number where it was measured, or an empty cell.
std::string optional_cell(const std::optional<int>& value) {
  return value ? std::to_string(*value) : "";
}
std::string optional_cell(const std::optional<double>& value, const char* format) {
  return value ? number(*value, format) : "";
}

}  // namespace

std::string format_row(const BenchRow& row) {
  std::ostringstream line;
  line << row.scene << " " << row.size << "x" << row.size << " " << row.solver << ": "
       << row.status;
  if (measured(row))
    line << ", " << number(row.wall_per_simulated) << " wall s per simulated s, "
         << number(row.ms_per_step) << " ms per step, x" << number(row.cost_ratio, "%.3g")
         << " ours; second half " << number(row.second_half_wall_per_simulated)
         << " wall s per simulated s, x" << number(row.second_half_cost_ratio, "%.3g") << " ours";
  if (measured(row) && row.rms_to_reference)
    line << "; " << rms_cell(row, "%.3g") << " m rms to the reference";
  if (measured(row) && row.runs > 1)
    line << "; fastest of " << row.runs << " runs, the slowest x"
         << number(row.wall_spread, "%.3g");
  return line.str();
}

std::string markdown(const BenchTable& table) {
  std::ostringstream md;
  md << "Machine: " << table.machine << "\n\n"
     << "| scene | particles | solver | setting | dt (s) | status | wall s / sim s | ms / step | "
        "max stretch | "
        "max penetration (m) | self-intersections (max) | triangle penetration (m) | "
        "rms to reference (m) | cost / ours | wall s / sim s, 2nd half | "
        "cost / ours, 2nd half | "
        "runs | slowest / "
        "fastest |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchRow& r : table.rows) {
    md << "| " << r.scene << " | " << r.size << " x " << r.size << " | " << r.solver << " | "
       << r.setting << " | ";
    if (!measured(r)) {
      md << " | " << r.status << " | | | | | | | | | | | | |\n";
      continue;
    }
    md << number(r.dt) << " | " << r.status << " | " << number(r.wall_per_simulated) << " | "
       << number(r.ms_per_step) << " | " << number(r.max_stretch, "%.3g") << " | "
       << number(r.max_penetration, "%.3g") << " | " << optional_cell(r.self_intersections) << " | "
       << optional_cell(r.triangle_penetration, "%.3g") << " | " << rms_cell(r, "%.3g") << " | "
       << number(r.cost_ratio, "%.3g") << " | " << number(r.second_half_wall_per_simulated) << " | "
       << number(r.second_half_cost_ratio, "%.3g") << " | " << r.runs << " | "
       << number(r.wall_spread, "%.3g") << " |\n";
  }
  return md.str();
}

void write_bench_files(const std::filesystem::path& folder, const BenchTable& table) {
  std::filesystem::create_directories(folder);
  std::ostringstream csv;
  csv << "scene,size,particles,springs,solver,type,setting,dt,status,wall_seconds_per_simulated_"
         "second,"
         "ms_per_step,max_stretch,max_penetration,rms_to_reference,cost_ratio_to_ours,"
         "second_half_wall_seconds_per_simulated_second,second_half_cost_ratio_to_ours,runs,wall_"
         "spread,self_intersections,triangle_penetration\n";
  for (const BenchRow& r : table.rows) {
    csv << r.scene << "," << r.size << "," << r.particles << "," << r.springs << "," << r.solver
        << "," << r.type << ",\"" << r.setting << "\"," << (measured(r) ? number(r.dt, "%.9g") : "")
        << "," << r.status << ",";
    if (measured(r))
      csv << number(r.wall_per_simulated, "%.6g") << "," << number(r.ms_per_step, "%.6g") << ","
          << number(r.max_stretch, "%.6g") << "," << number(r.max_penetration, "%.6g") << ","
          << rms_cell(r, "%.6g") << "," << number(r.cost_ratio, "%.6g") << ","
          << number(r.second_half_wall_per_simulated, "%.6g") << ","
          << number(r.second_half_cost_ratio, "%.6g") << "," << r.runs << ","
          << number(r.wall_spread, "%.6g") << "," << optional_cell(r.self_intersections) << ","
          << optional_cell(r.triangle_penetration, "%.6g");
    else
      csv << ",,,,,,,,,,,";
    csv << "\n";
  }
  run_folder::write_file_atomically(folder / "bench.csv", csv.str());
  run_folder::write_file_atomically(folder / "bench.md", markdown(table));
}

}  // namespace drapelab::runner
