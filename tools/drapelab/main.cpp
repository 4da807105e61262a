// drapelab: the command line. Verbs: run, validate, check, stability, study, sweep, bench, render,
// report (one file each, verb_*.cpp; docs/cli.md). Exit codes: 0 ok, 1 a solver became unstable or
// failed, 2 bad input (nothing was run) or a file that could not be written, 3 an internal error (a
// bug), 130 interrupted (files hold the frames recorded so far).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>

#include "drapelab/run_folder/output_file.hpp"
#include "interrupt.hpp"
#include "unknown_verb.hpp"
#include "verbs.hpp"

namespace {

constexpr int kExitInternalError = 3;

}  // namespace

int main(int argc, char** argv) {
  // Every line reaches a pipe or a log as it is printed: stdout is otherwise fully buffered when it
  // is not a terminal, and a long run's first line ("running ...") would arrive only at its end,
  // after the progress lines and warnings on stderr (unbuffered).
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  CLI::App app{
      "drapelab: a cloth laboratory. Runs cloth solvers side by side on the same scene and "
      "records drape metrics frame by frame."};
  app.set_version_flag("--version", std::string("drapelab ") + DRAPELAB_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  drapelab run scenes/curtain.yaml --out out/curtain\n"
      "  drapelab validate scenes/curtain.yaml --set cloth.resolution=[65,65]\n"
      "  drapelab check scenes/sphere_drape.yaml --golden tests/golden/sphere_drape.json\n"
      "  drapelab stability scenes/curtain.yaml\n"
      "  drapelab study scenes/curtain.yaml --duration 0.5 --factors 1,4\n"
      "  drapelab sweep scenes/curtain.yaml --vary cloth.springs.bend.ks=1,10,100 --out "
      "out/bend-sweep\n"
      "  drapelab render out/sphere_drape --size 1280x480\n"
      "  drapelab report out/sphere_drape\n"
      "Run 'drapelab VERB --help' for a verb's options.");

  drapelab::cli::RunArguments run_arguments;
  CLI::App* run = app.add_subcommand("run", "Simulate a scene and write its run folder");
  drapelab::cli::add_run_options(*run, run_arguments);

  drapelab::cli::ValidateArguments validate_arguments;
  CLI::App* validate = app.add_subcommand("validate", "Check a scene file without running it");
  drapelab::cli::add_validate_options(*validate, validate_arguments);

  drapelab::cli::CheckArguments check_arguments;
  CLI::App* check = app.add_subcommand(
      "check", "Compare a run of a scene with its golden file (regression test)");
  drapelab::cli::add_check_options(*check, check_arguments);

  drapelab::cli::StabilityArguments stability_arguments;
  CLI::App* stability = app.add_subcommand(
      "stability", "Find the largest stable step of one solver of a scene (bisection)");
  drapelab::cli::add_stability_options(*stability, stability_arguments);

  drapelab::cli::BenchArguments bench_arguments;
  CLI::App* bench = app.add_subcommand(
      "bench", "Time every solver on fixed scenes and sizes (bench.csv, bench.md)");
  drapelab::cli::add_bench_options(*bench, bench_arguments);

  drapelab::cli::StudyArguments study_arguments;
  CLI::App* study = app.add_subcommand(
      "study", "Cost and accuracy of every integrator at several steps, against an RK4 reference");
  drapelab::cli::add_study_options(*study, study_arguments);

  drapelab::sweep::SweepArguments sweep_arguments;
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "Run a scene for every combination of varied keys, in parallel child processes (sweep.csv)");
  drapelab::cli::add_sweep_options(*sweep, sweep_arguments);

  drapelab::cli::RenderArguments render_arguments;
  CLI::App* render = app.add_subcommand(
      "render", "Render a run's frames as PNG images (a panel per solver) and a video");
  drapelab::cli::add_render_options(*render, render_arguments);

  drapelab::cli::ReportArguments report_arguments;
  CLI::App* report =
      app.add_subcommand("report", "Write one self-contained HTML page for a run or sweep folder");
  drapelab::cli::add_report_options(*report, report_arguments);

  // Listed for --help; its own program parses its options (drapelab view --help).
  app.add_subcommand("view",
                     "Play a scene live in a window and grab the cloth with the mouse "
                     "(drapelab view SCENE; options: drapelab view --help)")
      ->allow_extras();
  if (argc >= 2 && std::string(argv[1]) == "view") return drapelab::cli::view_verb(argc, argv);

  std::string command_line;
  for (int k = 0; k < argc; ++k) command_line += (k ? " " : "") + std::string(argv[k]);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A misspelt verb is named, with the nearest verb; CLI11 alone would say that one is missing.
    if (const auto unknown = drapelab::cli::unknown_verb_message(argc, argv, app)) {
      std::cerr << "error: " << *unknown << "\n";
      return drapelab::cli::kExitBadInput;
    }
    app.exit(e);
    return drapelab::cli::kExitBadInput;  // usage errors are bad input too
  }

  const std::atomic<bool>& interrupted = drapelab::cli::install_interrupt_handlers();
  // Every verb's failure ends here with a message and its exit code, never an abort.
  try {
    if (*run) return drapelab::cli::run_verb(run_arguments, command_line, interrupted);
    if (*check) return drapelab::cli::check_verb(check_arguments, interrupted);
    if (*stability) return drapelab::cli::stability_verb(stability_arguments, interrupted);
    if (*bench) return drapelab::cli::bench_verb(bench_arguments, interrupted);
    if (*study) return drapelab::cli::study_verb(study_arguments, command_line, interrupted);
    if (*sweep) return drapelab::cli::sweep_verb(sweep_arguments, command_line, interrupted);
    if (*render) return drapelab::cli::render_verb(render_arguments, interrupted);
    if (*report) return drapelab::cli::report_verb(report_arguments);
    return drapelab::cli::validate_verb(validate_arguments);
  } catch (const drapelab::run_folder::WriteError& error) {
    std::cerr << "error: " << error.what() << "\n";
    return drapelab::cli::kExitBadInput;
  } catch (const std::filesystem::filesystem_error& error) {
    std::cerr << "error: " << error.what() << "\n";
    return drapelab::cli::kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory; the scene needs more memory than this machine has (try a "
                 "coarser cloth: docs/cli.md, \"Limits\")\n";
    return drapelab::cli::kExitBadInput;
  } catch (const std::exception& error) {
    std::cerr << "internal error: " << error.what()
              << "\nthis is a bug in drapelab; please report it with the command line and the "
                 "scene file\n";
    return kExitInternalError;
  } catch (...) {
    std::cerr << "internal error: an unknown exception\nthis is a bug in drapelab; please report "
                 "it with the command line and the scene file\n";
    return kExitInternalError;
  }
}
