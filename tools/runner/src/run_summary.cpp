#include "run_summary.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"

namespace drapelab::runner {
namespace {

using nlohmann::ordered_json;

// JSON has no infinity or NaN; such values become null.
ordered_json number_or_null(double value) {
  return std::isfinite(value) ? ordered_json(value) : ordered_json();
}

ordered_json metrics_json(const ClothMetrics& m) {
  ordered_json j;
  j["kinetic_energy"] = number_or_null(m.kinetic_energy);
  j["gravity_energy"] = number_or_null(m.gravity_energy);
  j["spring_energy"] = number_or_null(m.spring_energy);
  j["max_stretch"] = number_or_null(m.max_stretch);
  j["mean_stretch"] = number_or_null(m.mean_stretch);
  j["min_clearance"] = m.min_clearance ? ordered_json(*m.min_clearance) : ordered_json();
  j["max_penetration"] = m.max_penetration ? ordered_json(*m.max_penetration) : ordered_json();
  j["contact_count"] = m.contact_count ? ordered_json(*m.contact_count) : ordered_json();
  j["centroid"] = {number_or_null(m.centroid.x()), number_or_null(m.centroid.y()),
                   number_or_null(m.centroid.z())};
  j["lowest_y"] = number_or_null(m.lowest_y);
  j["projected_area"] = number_or_null(m.projected_area);
  j["drape_coefficient"] =
      m.drape_coefficient ? ordered_json(*m.drape_coefficient) : ordered_json();
  j["drape_nodes"] = m.drape_nodes ? ordered_json(*m.drape_nodes) : ordered_json();
  j["self_intersections"] =
      m.self_intersections ? ordered_json(*m.self_intersections) : ordered_json();
  j["triangle_penetration"] =
      m.triangle_penetration ? ordered_json(*m.triangle_penetration) : ordered_json();
  j["constraint_error"] = m.constraint_error ? ordered_json(*m.constraint_error) : ordered_json();
  for (const auto& [key, value] : {std::pair{"elastic_energy", m.elastic_energy},
                                   {"contact_energy", m.contact_energy},
                                   {"constraint_energy", m.constraint_energy},
                                   {"total_energy", m.total_energy}})
    j[key] = value ? ordered_json(*value) : ordered_json();
  return j;
}

ordered_json solver_json(const SolverRun& run) {
  const SolverOutcome outcome = outcome_of(run);
  ordered_json j;
  j["type"] = solver_type_name(run.spec->type);
  j["status"] = solver_status_name(run.status);
  j["message"] = run.message;
  if (run.spec->type == SolverType::spring_damper)
    j["integrator"] = integrator_name(run.spec->integrator);
  j["dt"] = run.spec->dt;
  j["steps_per_frame"] = run.spec->steps_per_frame;
  if (!run.spec->note.empty()) j["note"] = run.spec->note;
  j["steps"] = run.steps;
  j["frames_recorded"] = run.frames_recorded;
  j["wall_seconds"] = run.wall_seconds;
  j["ms_per_step"] = outcome.ms_per_step();
  j["wall_seconds_per_simulated_second"] = outcome.wall_seconds_per_simulated_second();
  const auto phases = run.solver->phase_seconds();
  if (!phases.empty()) {
    ordered_json timings = ordered_json::object();
    for (const auto& [phase, seconds] : phases) timings[phase] = seconds;
    j["phase_seconds"] = timings;
  }
  const auto counters = run.solver->counters();
  if (!counters.empty()) {
    ordered_json counts = ordered_json::object();
    for (const auto& [counter, value] : counters) counts[counter] = value;
    j["integrator_statistics"] = counts;
  }
  const auto settle = run.rest.settle_time();
  const auto jitter = run.rest.rest_jitter();
  j["settle_time"] = settle ? ordered_json(*settle) : ordered_json();
  j["rest_jitter"] = jitter ? ordered_json(*jitter) : ordered_json();
  j["final"] = run.last_metrics ? metrics_json(*run.last_metrics) : ordered_json::object();
  if (run.energy) {
    const EnergyAudit& audit = *run.energy;
    j["energy_audit"] = {{"passive", audit.passive()},
                         {"tolerance_J", audit.tolerance()},
                         {"worst_rise_J", audit.worst_rise()}};
    ordered_json warnings = ordered_json::array();
    for (const EnergyWarning& w : audit.warnings())
      warnings.push_back(
          {{"frame", w.frame}, {"time", w.time}, {"rise_J", w.rise}, {"cause", w.cause}});
    j["energy_warnings"] = warnings;
  }
  return j;
}

}  // namespace

SolverOutcome outcome_of(const SolverRun& run) {
  SolverOutcome outcome;
  outcome.name = run.spec->name;
  outcome.type = run.spec->type;
  outcome.status = run.status;
  outcome.message = run.message;
  outcome.steps = run.steps;
  outcome.dt = run.spec->dt;
  outcome.frames_recorded = run.frames_recorded;
  outcome.wall_seconds = run.wall_seconds;
  if (run.energy)
    for (const EnergyWarning& w : run.energy->warnings()) {
      std::ostringstream line;  // three figures for people; summary.json keeps every digit
      line.precision(3);
      line << "frame " << w.frame << " (t = " << w.time << " s): the total energy rose by "
           << w.rise << " J; likely cause: " << w.cause;
      outcome.energy_warnings.push_back(line.str());
    }
  return outcome;
}

std::string summary_json(const scene::Scene& scene, const ClothModel& model,
                         const std::vector<SolverRun>& runs, const RunInfo& info) {
  ordered_json j;
  j["scene"] = scene.name;
  j["drapelab_version"] = DRAPELAB_VERSION;
  j["scene_file"] = scene.source.string();
  j["command"] = info.command_line;
  j["run"] = {{"state", info.state},
              {"duration", scene.duration},
              {"frame_rate", scene.frame_rate},
              {"frames_planned", info.frames_planned},
              {"frames_done", info.frames_done}};
  j["model"] = {
      {"particles", model.particle_count()},
      {"pinned", (model.inverse_mass.array() == 0.0).count()},
      {"triangles", model.triangles.cols()},
      {"springs",
       {{"stretch", model.springs.count(SpringKind::stretch)},
        {"shear", model.springs.count(SpringKind::shear)},
        {"bend", model.springs.count(SpringKind::bend)}}},
      {"total_mass", model.total_mass()},
      {"rest_area", model.rest_area()},
      {"stable_symplectic_step",
       number_or_null(stable_step_estimate(model, scene.cloth.air_damping, scene.contact_rates(),
                                           Integrator::symplectic_euler))}};
  ordered_json solvers = ordered_json::object();
  for (const auto& run : runs) solvers[run.spec->name] = solver_json(run);
  j["solvers"] = solvers;
  // A path or command line that is not UTF-8 is written with U+FFFD, not refused.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace drapelab::runner
