// drapelab study SCENE: cost and accuracy of the integrators of a spring_damper solver. For each
// integrator and each step h = dt x factor, runs the scene in-process and measures its cost, its
// stability (as in `drapelab stability`: status ok and max stretch below 1 at every recorded frame)
// and its distance from a reference: the same scene with rk4 at dt / 16.
#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/runner/run_scene.hpp"
#include "drapelab/runner/simulate_solver.hpp"
#include "drapelab/runner/study_report.hpp"
#include "drapelab/runner/trial_scene.hpp"
#include "drapelab/scene/number_format.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

using namespace drapelab::runner;  // the run pipeline: this file parses and prints

namespace fs = std::filesystem;

namespace {

constexpr double kStabilityStretchLimit =
    1.0;  // the stability verb's criterion: a spring at twice its rest length
constexpr int kReferenceRefinement = 16;  // the reference's step is the base dt / 16

// "a,b" arrives as one item or several (CLI11's delimiter); names may carry spaces after commas.
std::optional<std::vector<Integrator>> parse_integrator_list(
    const std::vector<std::string>& names) {
  if (names.empty()) return all_integrators();
  std::vector<Integrator> list;
  for (std::string name : names) {
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    const auto integrator = parse_integrator(name);
    if (!integrator) {
      std::string expected;
      for (const auto& known : integrator_names())
        expected += (expected.empty() ? "" : ", ") + known;
      std::cerr << "error: --integrators: unknown integrator '" << name
                << "'; expected one of: " << expected << "\n";
      return std::nullopt;
    }
    list.push_back(*integrator);
  }
  return list;
}

// Distances of a run's frames from the reference's frames (m).
struct ErrorTracker {
  const std::vector<Eigen::Matrix3Xd>* reference = nullptr;  // positions at every recorded frame
  double rms_final = 0.0, rms_max = 0.0, max_distance = 0.0;

  void add(int frame, const ClothState& state) {
    const Eigen::Matrix3Xd& x_ref = (*reference)[static_cast<std::size_t>(frame)];
    const Eigen::VectorXd squared = (state.x - x_ref).colwise().squaredNorm().transpose();
    rms_final = std::sqrt(squared.mean());  // over all particles, pins (error 0) included
    rms_max = std::max(rms_max, rms_final);
    max_distance = std::max(max_distance, std::sqrt(squared.maxCoeff()));
  }
};

// The command as typed, with the program's path shortened to its name (the table is for a README).
std::string shown_command(const std::string& command_line) {
  const auto space = command_line.find(' ');
  return "drapelab" + (space == std::string::npos ? std::string() : command_line.substr(space));
}

}  // namespace

void add_study_options(CLI::App& verb, StudyArguments& arguments) {
  verb.add_option("scene", arguments.scene, "Scene file (YAML)")->required();
  verb.add_option("--solver", arguments.solver,
                  "The spring_damper solver to study (default: the first one)");
  verb.add_option("--set", arguments.overrides,
                  "Override a key: key.path=value, validated like the file; may be repeated");
  verb.add_option("--integrators", arguments.integrators,
                  "Comma-separated integrators (default: all eight)")
      ->delimiter(',');
  verb.add_option("--dt", arguments.dt, "Base step, s (default: the solver's dt in the scene)")
      ->check(CLI::PositiveNumber);
  verb.add_option("--factors", arguments.factors, "Comma-separated multiples of dt to run at")
      ->capture_default_str()
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  verb.add_option("--out,-o", arguments.out,
                  "Folder for study.csv and study.md (default: out/SCENE-study)");
  verb.add_option("--duration", arguments.duration,
                  "Simulated seconds (default: the scene's duration)")
      ->check(CLI::PositiveNumber);
  verb.footer(
      "Each run is compared with a reference, the scene with rk4 at dt / 16, at every recorded "
      "frame. Steps "
      "that do not divide the frame period are skipped.\n"
      "Example:\n  drapelab study scenes/curtain.yaml --duration 0.5 --factors 1,4\n"
      "Exit codes: 0 done (unstable runs are rows), 1 the reference is unstable, 2 bad input, 130 "
      "interrupted.");
}

int study_verb(const StudyArguments& arguments, const std::string& command_line,
               const std::atomic<bool>& interrupt) {
  std::shared_ptr<const ClothModel> model;  // the loader's, so the cloth is built once
  const auto scene =
      load_trial_scene(arguments.scene, arguments.overrides, arguments.duration, &model);
  if (!scene) return kExitBadInput;
  const PollingSection polling;  // the trials stop at Ctrl-C
  std::string problem;
  const auto index = choose_solver(*scene, arguments.solver, true, &problem);
  if (!index) {
    std::cerr << "error: " << problem << "\n";
    return kExitBadInput;
  }
  const auto integrators = parse_integrator_list(arguments.integrators);
  if (!integrators) return kExitBadInput;
  const scene::SolverSpec& spec = scene->solvers[*index];
  const double frame_period = scene->frame_period();  // s
  const double base_dt = arguments.dt > 0.0 ? arguments.dt : spec.dt;
  const auto base_steps = whole_steps_per_frame(frame_period, base_dt);
  if (!base_steps) {
    std::cerr << "error: --dt " << format_number(base_dt)
              << " s must divide the frame period 1/frame_rate = " << format_number(frame_period)
              << " s into whole steps (at most one frame); try --dt "
              << format_number(frame_period / std::max(1.0, std::ceil(frame_period / base_dt)))
              << "\n";
    return kExitBadInput;
  }
  std::vector<std::pair<double, int>> steps;  // (factor, steps per frame)
  for (const double factor : arguments.factors) {
    if (const auto k = whole_steps_per_frame(frame_period, base_dt * factor)) {
      steps.emplace_back(factor, *k);
      continue;
    }
    std::cout << "factor " << format_number(factor)
              << " skipped: h = " << format_number(base_dt * factor)
              << " s does not divide the frame period " << format_number(frame_period)
              << " s into whole steps (" << format_number(frame_period / (base_dt * factor))
              << " steps per frame)\n";
  }
  if (steps.empty()) {
    std::cerr << "error: no factor gives a step that divides the frame period; nothing was run\n";
    return kExitBadInput;
  }
  const fs::path out =
      arguments.out.empty() ? fs::path("out") / (scene->name + "-study") : fs::path(arguments.out);
  std::error_code made;
  fs::create_directories(out, made);
  if (made || !fs::is_directory(out)) {
    std::cerr << "error: cannot create the folder " << out.string()
              << (made ? ": " + made.message() : "") << "\n";
    return kExitBadInput;
  }

  const runner::SceneSetup setup = runner::build_scene_setup(*scene, model);
  runner::SimulationOptions options;
  options.stretch_limit = kStabilityStretchLimit;
  options.interrupt = &interrupt;

  // The reference: rk4 at a sixteenth of the base step, its positions kept at every recorded frame.
  scene::SolverSpec reference_spec =
      with_steps_per_frame(spec, frame_period, *base_steps * kReferenceRefinement);
  reference_spec.integrator = Integrator::rk4;
  std::vector<Eigen::Matrix3Xd> reference_frames;
  std::cout << "study of solver '" << spec.name << "' in scene " << scene->name << ": "
            << integrators->size() << " integrators x " << steps.size() << " steps, "
            << format_number(scene->duration)
            << " s each; reference: rk4 at h = " << format_number(reference_spec.dt) << " s ..."
            << std::endl;
  runner::SimulationOptions reference_options = options;
  reference_options.on_frame = [&](int, const ClothState& state, const ClothMetrics&) {
    reference_frames.push_back(state.x);
  };
  const auto reference = runner::simulate_solver(*scene, reference_spec, setup, reference_options);
  if (reference.interrupted()) return runner::kExitInterrupted;
  if (reference.status != SolverStatus::ok) {
    std::cerr
        << "error: the reference (rk4 at h = " << format_number(reference_spec.dt) << " s) is "
        << solver_status_name(reference.status) << ": " << reference.message
        << "\nnothing to measure errors against; try a smaller --dt or a shorter --duration\n";
    return runner::kExitUnstable;
  }
  StudyHeader header;
  header.scene = scene->name;
  header.solver = spec.name;
  header.command = shown_command(command_line);
  header.duration = scene->duration;
  header.frame_period = frame_period;
  header.base_dt = base_dt;
  header.reference = {reference_spec.dt,
                      reference_spec.steps_per_frame,
                      reference.steps,
                      reference.wall_seconds,
                      reference.wall_seconds_per_simulated_second(),
                      reference.ms_per_step()};
  std::cout << "reference: " << reference.steps << " steps in " << std::setprecision(3)
            << reference.wall_seconds << " s (" << reference.wall_seconds_per_simulated_second()
            << " s per simulated s)" << std::endl;

  std::vector<StudyRow> rows;
  for (const Integrator integrator : *integrators) {
    for (const auto& [factor, steps_per_frame] : steps) {
      scene::SolverSpec trial_spec = with_steps_per_frame(spec, frame_period, steps_per_frame);
      trial_spec.integrator = integrator;
      ErrorTracker errors{&reference_frames};
      runner::SimulationOptions trial_options = options;
      trial_options.on_frame = [&errors](int frame, const ClothState& state, const ClothMetrics&) {
        errors.add(frame, state);
      };
      const auto result = runner::simulate_solver(*scene, trial_spec, setup, trial_options);
      if (result.interrupted()) {
        std::cerr << "interrupted; " << (out / "study.csv").string() << " holds the " << rows.size()
                  << " rows measured so far\n";
        return runner::kExitInterrupted;
      }
      StudyRow row;
      row.integrator = integrator;
      row.factor = factor;
      row.dt = trial_spec.dt;
      row.steps_per_frame = steps_per_frame;
      row.status = solver_status_name(result.status);
      row.wall_seconds_per_simulated_second = result.wall_seconds_per_simulated_second();
      row.ms_per_step = result.ms_per_step();
      row.force_evaluations_per_step = force_evaluations_per_step(integrator);
      row.max_stretch = result.max_stretch;
      if (result.status == SolverStatus::ok) {
        row.error_rms_final = errors.rms_final;
        row.error_rms_max = errors.rms_max;
        row.error_max_distance = errors.max_distance;
      } else {
        row.stopped_at = result.final_state.time;
      }
      if (integrator == Integrator::implicit_euler)
        row.cg_iterations_mean = result.counter("cg_iterations_mean");
      rows.push_back(row);
      std::ostringstream line;
      line << "  " << integrator_name(integrator) << " h = " << format_number(row.dt)
           << " s: " << row.status;
      if (row.error_rms_final)
        line << ", final rms error " << format_number(*row.error_rms_final) << " m";
      if (!result.message.empty())
        line << " (" << result.message.substr(0, result.message.find(". Try:")) << ")";
      std::cout << line.str() << std::endl;
      // Rewritten after every row, so the files are whole whenever the study stops.
      run_folder::write_file_atomically(out / "study.csv", study_csv(rows));
      run_folder::write_file_atomically(out / "study.md", study_markdown(header, rows));
    }
  }
  std::cout << "\n"
            << study_markdown(header, rows) << "\nwritten: " << (out / "study.csv").string() << ", "
            << (out / "study.md").string() << "\n";
  return runner::kExitOk;
}

}  // namespace drapelab::cli
