// drapelab stability SCENE: the largest step for which one solver of the scene stays stable for the
// whole duration. Stable = the solver's status stays ok and the max stretch (docs/metrics.md: over
// stretch springs, |x_a - x_b| / L - 1) stays below 1 at every recorded frame. Steps are
// frame_period / k for whole k (a scene's step must divide the frame period), so the search bisects
// on k (step_search.hpp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "drapelab/runner/run_scene.hpp"
#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/runner/step_search.hpp"
#include "drapelab/runner/trial_scene.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/stability.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

using namespace drapelab::runner;  // the run pipeline: this file parses and prints

namespace {

constexpr double kStretchLimit =
    1.0;  // a stretch spring at twice its rest length: the state has blown up
constexpr int kMostStepsPerFrame = 1000000;  // the smallest step tried is frame_period / 1e6

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

struct Trial {
  int steps_per_frame = 0;
  double dt = 0.0;  // s
  bool stable = false;
  runner::SimulationResult result;
};

std::string steps_per_frame_text(int k) {
  return std::to_string(k) + (k == 1 ? " step" : " steps") + " per frame";
}

// One table cell: why a trial is not stable, in a few words (the full message goes to the JSON
// file).
std::string why_not(const Trial& trial) {
  const runner::SimulationResult& r = trial.result;
  const std::string at = "t = " + short_number(r.final_state.time) + " s";
  switch (r.stopped_by) {
    case runner::StopCause::solver:
      return std::string("solver ") + solver_status_name(r.status) + " after " +
             std::to_string(r.steps) + " steps (" + at + ")";
    case runner::StopCause::runaway_stretch:
    case runner::StopCause::stretch_limit:
      return "max stretch " + short_number(r.final_metrics.max_stretch) + " at frame " +
             std::to_string(r.stopped_at_frame) + " (" + at + ")";
    case runner::StopCause::interrupted:
      return "interrupted";
    case runner::StopCause::none:
      break;
  }
  return {};
}

void print_trial(std::size_t number, const Trial& trial) {
  char line[160];
  std::snprintf(line, sizeof line, "%5zu  %-12s %11d  %-9s %-12s ", number,
                short_number(trial.dt).c_str(), trial.steps_per_frame,
                trial.stable ? "stable" : "unstable",
                short_number(trial.result.max_stretch).c_str());
  std::cout << line << why_not(trial) << std::endl;  // flushed: the search can take minutes
}

nlohmann::ordered_json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json();
}

nlohmann::ordered_json trial_json(const Trial& trial) {
  const runner::SimulationResult& r = trial.result;
  return {{"dt", trial.dt},
          {"steps_per_frame", trial.steps_per_frame},
          {"stable", trial.stable},
          {"status", solver_status_name(r.status)},
          {"message", r.message},
          {"max_stretch", number_or_null(r.max_stretch)},
          {"frames_recorded", r.frames_recorded},
          {"steps", r.steps},
          {"simulated_seconds", r.final_state.time},
          {"wall_seconds", r.wall_seconds}};
}

// The smallest k whose step frame_period / k does not exceed max_dt (s).
int smallest_steps_per_frame(double frame_period, double max_dt) {
  const double ratio = frame_period / max_dt;
  const double whole = std::round(ratio);
  if (std::abs(ratio - whole) <= 1e-9 * ratio) return std::max(1, static_cast<int>(whole));
  return std::max(1, static_cast<int>(std::ceil(ratio)));
}

}  // namespace

void add_stability_options(CLI::App& verb, StabilityArguments& arguments) {
  verb.add_option("scene", arguments.scene, "Scene file (YAML)")->required();
  verb.add_option(
      "--solver", arguments.solver,
      "The solver to test, by name (default: the first spring_damper solver, else the first)");
  verb.add_option("--set", arguments.overrides,
                  "Override a key: key.path=value, validated like the file; may be repeated");
  verb.add_option("--duration", arguments.duration,
                  "Simulated seconds of each trial (default: the scene's duration)")
      ->check(CLI::PositiveNumber);
  verb.add_option("--tolerance", arguments.tolerance,
                  "Stop bisecting once (smallest unstable dt - largest stable dt) / largest stable "
                  "dt is at most "
                  "this (0: bisect to neighbouring steps per frame)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb.add_option("--max-dt", arguments.max_dt, "Largest step tried, s (default: the frame period)")
      ->check(CLI::PositiveNumber);
  verb.add_option("--json", arguments.json,
                  "Also write the trials and the answer to this JSON file");
  verb.footer(
      "Stable: the solver's status stays ok and max stretch (|x_a - x_b| / L - 1 over stretch "
      "springs) stays "
      "below 1 at every recorded frame. Steps are frame_period / k for whole k.\n"
      "Example:\n  drapelab stability scenes/curtain.yaml --set "
      "solvers.0.integrator=implicit_euler\n"
      "Exit codes: 0 found, 1 even frame_period / 1e6 is unstable, 2 bad input, 130 interrupted.");
}

int stability_verb(const StabilityArguments& arguments, const std::atomic<bool>& interrupt) {
  std::shared_ptr<const ClothModel> model;  // the loader's, so the cloth is built once
  const auto scene =
      load_trial_scene(arguments.scene, arguments.overrides, arguments.duration, &model);
  if (!scene) return kExitBadInput;
  const PollingSection polling;  // the trials stop at Ctrl-C
  std::string problem;
  const auto index = choose_solver(*scene, arguments.solver, false, &problem);
  if (!index) {
    std::cerr << "error: " << problem << "\n";
    return kExitBadInput;
  }
  const scene::SolverSpec& spec = scene->solvers[*index];
  const double frame_period = scene->frame_period();  // s
  StepSearchLimits limits;
  limits.largest_k = kMostStepsPerFrame;
  limits.tolerance = arguments.tolerance;
  limits.smallest_k =
      arguments.max_dt > 0.0 ? smallest_steps_per_frame(frame_period, arguments.max_dt) : 1;
  if (limits.smallest_k > limits.largest_k) {
    std::cerr << "error: --max-dt " << format_number(arguments.max_dt)
              << " s is below the smallest step tried, "
              << "frame_period / 1e6 = " << format_number(frame_period / kMostStepsPerFrame)
              << " s\n";
    return kExitBadInput;
  }

  if (!arguments.json.empty()) {
    const auto folder = std::filesystem::absolute(arguments.json).parent_path();
    if (!std::filesystem::is_directory(folder)) {
      std::cerr << "error: --json " << arguments.json << ": no folder " << folder.string()
                << "; nothing was run\n";
      return kExitBadInput;
    }
  }

  const runner::SceneSetup setup = runner::build_scene_setup(*scene, model);
  std::string described = solver_type_name(spec.type);
  if (spec.type == SolverType::spring_damper)
    described += ", " + std::string(integrator_name(spec.integrator));
  std::cout << "stability of solver '" << spec.name << "' (" << described << ") in scene "
            << scene->name << ": " << format_number(scene->duration)
            << " s per trial, frame period " << short_number(frame_period)
            << " s; stable = status ok and max stretch < " << format_number(kStretchLimit)
            << " at every frame\n";
  double estimate =
      std::numeric_limits<double>::quiet_NaN();  // s, stability.hpp's sufficient bound
  if (spec.type == SolverType::spring_damper) {
    estimate = stable_step_estimate(*setup.model, scene->cloth.air_damping, scene->contact_rates(),
                                    spec.integrator);
    std::cout << "stable step estimate (stability.hpp, sufficient): "
              << (std::isinf(estimate) ? std::string("none (no bound for this integrator)")
                                       : short_number(estimate) + " s")
              << "\n";
  }
  std::cout << "trial  dt (s)       steps/frame  result    max stretch  why not\n";

  std::vector<Trial> trials;
  auto trial = [&](int k) -> std::optional<bool> {
    Trial t;
    t.steps_per_frame = k;
    t.dt = frame_period / k;
    runner::SimulationOptions options;
    options.stretch_limit = kStretchLimit;
    options.interrupt = &interrupt;
    t.result = runner::simulate_solver(*scene, with_steps_per_frame(spec, frame_period, k), setup,
                                       options);
    if (t.result.interrupted()) return std::nullopt;
    t.stable = t.result.status == SolverStatus::ok;
    trials.push_back(t);
    print_trial(trials.size(), t);
    return t.stable;
  };
  const StepSearchOutcome outcome = search_largest_stable_step(spec.steps_per_frame, limits, trial);
  if (outcome.stopped) {
    std::cerr << "interrupted after " << trials.size() << " trials\n";
    return runner::kExitInterrupted;
  }

  if (outcome.stable_k) {
    std::cout << "largest stable dt: " << format_number(frame_period / *outcome.stable_k) << " s ("
              << steps_per_frame_text(*outcome.stable_k) << "); smallest unstable: ";
    if (outcome.unstable_k)
      std::cout << format_number(frame_period / *outcome.unstable_k) << " s ("
                << steps_per_frame_text(*outcome.unstable_k) << ")\n";
    else
      std::cout << "none up to the largest step tried, "
                << format_number(frame_period / limits.smallest_k) << " s\n";
  } else {
    std::cout << "no stable step: even frame_period / " << limits.largest_k << " = "
              << format_number(frame_period / limits.largest_k) << " s is unstable\n";
  }

  if (!arguments.json.empty()) {
    nlohmann::ordered_json j;
    j["scene"] = scene->name;
    j["solver"] = spec.name;
    j["type"] = solver_type_name(spec.type);
    if (spec.type == SolverType::spring_damper) j["integrator"] = integrator_name(spec.integrator);
    j["duration"] = scene->duration;
    j["frame_period"] = frame_period;
    j["stretch_limit"] = kStretchLimit;
    j["tolerance"] = arguments.tolerance;
    j["max_dt"] = frame_period / limits.smallest_k;
    j["stable_step_estimate"] = number_or_null(estimate);
    j["largest_stable_dt"] =
        outcome.stable_k ? nlohmann::ordered_json(frame_period / *outcome.stable_k) : nullptr;
    j["largest_stable_steps_per_frame"] =
        outcome.stable_k ? nlohmann::ordered_json(*outcome.stable_k) : nullptr;
    j["smallest_unstable_dt"] =
        outcome.unstable_k ? nlohmann::ordered_json(frame_period / *outcome.unstable_k) : nullptr;
    j["smallest_unstable_steps_per_frame"] =
        outcome.unstable_k ? nlohmann::ordered_json(*outcome.unstable_k) : nullptr;
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const auto& t : trials) list.push_back(trial_json(t));
    j["trials"] = list;
    std::ofstream out(arguments.json);
    out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    if (!out) {
      std::cerr << "error: cannot write " << arguments.json << "\n";
      return kExitBadInput;
    }
  }
  return outcome.stable_k ? runner::kExitOk : runner::kExitUnstable;
}

}  // namespace drapelab::cli
