// The tables of `drapelab study`: study.csv (every number, shortest round-trip form) and study.md
// (a markdown table with three significant digits, ready for a README). Columns: docs/cli.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/integrators.hpp"

namespace drapelab::runner {

// One (integrator, step) of the study.
struct StudyRow {
  Integrator integrator = Integrator::symplectic_euler;
  double factor = 1.0;  // the step is the base dt x factor
  double dt = 0.0;      // s
  int steps_per_frame = 0;
  std::string status;                // ok, unstable or error (solver_status_name)
  std::optional<double> stopped_at;  // s, simulated time at which an unstable run stopped
  double wall_seconds_per_simulated_second = 0.0;  // over the steps taken
  double ms_per_step = 0.0;
  int force_evaluations_per_step = 0;
  double max_stretch = 0.0;  // max over the recorded frames
  // Against the reference, empty unless ok (m). rms over all particles at a frame; final = last
  // frame.
  std::optional<double> error_rms_final, error_rms_max, error_max_distance;
  std::optional<double> cg_iterations_mean;  // implicit_euler only
};

// What the rows were measured against: the same scene with rk4 at base dt / 16.
struct StudyReference {
  double dt = 0.0;  // s
  int steps_per_frame = 0;
  std::int64_t steps = 0;
  double wall_seconds = 0.0;
  double wall_seconds_per_simulated_second = 0.0;
  double ms_per_step = 0.0;
};

struct StudyHeader {
  std::string scene, solver, command;
  double duration = 0.0;      // s
  double frame_period = 0.0;  // s
  double base_dt = 0.0;       // s
  StudyReference reference;
};

const std::vector<std::string>& study_csv_columns();
std::string study_csv(const std::vector<StudyRow>& rows);
std::string study_markdown(const StudyHeader& header, const std::vector<StudyRow>& rows);

}  // namespace drapelab::runner
