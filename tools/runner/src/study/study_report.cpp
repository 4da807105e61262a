#include "drapelab/runner/study_report.hpp"

#include <cstdio>
#include <sstream>

#include "drapelab/scene/number_format.hpp"

namespace drapelab::runner {
namespace {

std::string exact(const std::optional<double>& value) {
  return value ? format_number(*value) : std::string();
}

std::string short_number(const std::optional<double>& value, const char* format = "%.3g") {
  if (!value) return {};
  char text[32];
  std::snprintf(text, sizeof text, format, *value);
  return text;
}

}  // namespace

const std::vector<std::string>& study_csv_columns() {
  static const std::vector<std::string> columns = {"integrator",
                                                   "factor",
                                                   "dt",
                                                   "steps_per_frame",
                                                   "status",
                                                   "stopped_at",
                                                   "wall_seconds_per_simulated_second",
                                                   "ms_per_step",
                                                   "force_evaluations_per_step",
                                                   "max_stretch",
                                                   "error_rms_final",
                                                   "error_rms_max",
                                                   "error_max_distance",
                                                   "cg_iterations_mean"};
  return columns;
}

std::string study_csv(const std::vector<StudyRow>& rows) {
  std::ostringstream out;
  const auto& columns = study_csv_columns();
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << "\n";
  for (const auto& r : rows) {
    out << integrator_name(r.integrator) << ',' << format_number(r.factor) << ','
        << format_number(r.dt) << ',' << r.steps_per_frame << ',' << r.status << ','
        << exact(r.stopped_at) << ',' << format_number(r.wall_seconds_per_simulated_second) << ','
        << format_number(r.ms_per_step) << ',' << r.force_evaluations_per_step << ','
        << format_number(r.max_stretch) << ',' << exact(r.error_rms_final) << ','
        << exact(r.error_rms_max) << ',' << exact(r.error_max_distance) << ','
        << exact(r.cg_iterations_mean) << "\n";
  }
  return out.str();
}

std::string study_markdown(const StudyHeader& header, const std::vector<StudyRow>& rows) {
  std::ostringstream out;
  const StudyReference& ref = header.reference;
  out << "Scene `" << header.scene << "`, solver `" << header.solver << "`, "
      << format_number(header.duration) << " s simulated, base step "
      << short_number(header.base_dt, "%.4g") << " s (`" << header.command << "`).\n"
      << "Errors are distances (m) from the reference, rk4 at h = " << short_number(ref.dt, "%.4g")
      << " s (" << ref.steps_per_frame << " steps per frame), which cost "
      << short_number(ref.wall_seconds) << " s wall ("
      << short_number(ref.wall_seconds_per_simulated_second) << " s per simulated s, "
      << short_number(ref.ms_per_step) << " ms per step).\n\n";
  out << "| integrator | h (s) | steps/frame | status | wall s / sim s | ms / step | force evals / "
         "step | max stretch "
         "| rms error, final (m) | rms error, max (m) | max distance (m) | CG iterations |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    std::string status = r.status;
    if (r.stopped_at) status += " at " + short_number(r.stopped_at) + " s";
    out << "| " << integrator_name(r.integrator) << " | " << short_number(r.dt) << " | "
        << r.steps_per_frame << " | " << status << " | "
        << short_number(r.wall_seconds_per_simulated_second) << " | " << short_number(r.ms_per_step)
        << " | " << r.force_evaluations_per_step << " | " << short_number(r.max_stretch) << " | "
        << short_number(r.error_rms_final) << " | " << short_number(r.error_rms_max) << " | "
        << short_number(r.error_max_distance) << " | " << short_number(r.cg_iterations_mean, "%.1f")
        << " |\n";
  }
  return out.str();
}

}  // namespace drapelab::runner
