// The verbs of the drapelab command line, each a function from parsed arguments to an exit code.
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <string>
#include <vector>

#include "drapelab/sweep/arguments.hpp"

namespace drapelab::cli {

inline constexpr int kExitBadInput = 2;

// drapelab view ...: replaces this process with drapelab-view and the arguments after "view".
int view_verb(int argc, char** argv);

struct RunArguments {
  std::string scene;
  std::string out;
  std::vector<std::string> overrides;  // --set key.path=value
  std::string meshes;  // --meshes obj|pc2|both (shorthand for --set output.meshes=...)
  bool force = false;
  bool allow_start_inside = false;  // a cloth starting inside a collider is a warning, not an error
  bool quiet = false;               // problems only: no notes, no progress, no outcome
  bool no_progress = false;  // no progress lines (a sweep's runs, whose output is a log file)
};
void add_run_options(CLI::App& verb, RunArguments& arguments);
int run_verb(const RunArguments& arguments, const std::string& command_line,
             const std::atomic<bool>& interrupt);

struct ValidateArguments {
  std::string scene;
  std::vector<std::string> overrides;
  bool print_resolved = false;
  bool allow_start_inside = false;  // as for run
};
void add_validate_options(CLI::App& verb, ValidateArguments& arguments);
int validate_verb(const ValidateArguments& arguments);

struct CheckArguments {
  std::string scene;
  std::string golden;
  std::vector<std::string> overrides;  // with --update only
  std::string out;
  bool update = false;
  bool first_difference = false;  // stop the run at the end of the first window that differs
};
void add_check_options(CLI::App& verb, CheckArguments& arguments);
int check_verb(const CheckArguments& arguments, const std::atomic<bool>& interrupt);

// drapelab stability: the largest stable step of one solver, by bisection on steps per frame.
struct StabilityArguments {
  std::string scene;
  std::string solver;                  // default: the first spring_damper solver, else the first
  std::vector<std::string> overrides;  // --set key.path=value
  double duration = 0.0;               // s, 0 = the scene's
  double tolerance = 0.01;             // stop when (unstable dt - stable dt) / stable dt <= this
  double max_dt = 0.0;                 // s, the largest step tried; 0 = the frame period
  std::string json;                    // write the trials and the answer here
};
void add_stability_options(CLI::App& verb, StabilityArguments& arguments);
int stability_verb(const StabilityArguments& arguments, const std::atomic<bool>& interrupt);

// drapelab study: cost and accuracy of every integrator at several steps, against an RK4 reference.
struct StudyArguments {
  std::string scene;
  std::string solver;                    // a spring_damper solver; default the first one
  std::vector<std::string> overrides;    // --set key.path=value
  std::vector<std::string> integrators;  // default: all eight
  double dt = 0.0;                       // s, the base step; 0 = the solver's dt in the scene
  std::vector<double> factors{1.0, 2.0, 4.0, 8.0};  // steps tried: dt x factor
  std::string out;        // folder for study.csv and study.md; default out/SCENE-study
  double duration = 0.0;  // s, 0 = the scene's
};
void add_study_options(CLI::App& verb, StudyArguments& arguments);
int study_verb(const StudyArguments& arguments, const std::string& command_line,
               const std::atomic<bool>& interrupt);

void add_sweep_options(CLI::App& verb, sweep::SweepArguments& arguments);
int sweep_verb(const sweep::SweepArguments& arguments, const std::string& command_line,
               const std::atomic<bool>& interrupt);

// drapelab render: PNG images of every recorded frame of a run (a panel per solver), and a video.
struct RenderArguments {
  std::string run_dir;  // a run folder with point caches or per-frame OBJ files
  std::string out;      // default RUN_DIR/render
  std::string size;     // WxH pixels, all panels; default 480 x 480 per solver
  std::string camera;   // "eye=x,y,z;target=x,y,z;fov=deg", any subset
  std::string texture;  // PNG for the cloth; default a checker
  int every = 1;        // render frames 0, N, 2N, ...
};
void add_render_options(CLI::App& verb, RenderArguments& arguments);
int render_verb(const RenderArguments& arguments, const std::atomic<bool>& interrupt);

// drapelab report: one self-contained HTML page for a run folder or a sweep folder.
struct ReportArguments {
  std::string folder;  // a run folder or a sweep folder
  std::string out;     // the HTML file; default FOLDER/report.html
};
void add_report_options(CLI::App& verb, ReportArguments& arguments);
int report_verb(const ReportArguments& arguments);

// drapelab bench: every solver's cost on a fixed set of scenes and sizes, in one process run.
struct BenchArguments {
  bool quick = false;               // 33 x 33 only, 0.1 s per run
  std::string out;                  // folder for bench.csv and bench.md; default out/bench
  std::vector<int> sizes;           // particles per side; default 33, 65, 129, 257
  std::vector<std::string> scenes;  // scene files; default sphere_drape, table_drape, curtain
  double duration = 0.0;            // s per run; 0 = 0.5 (0.1 with --quick)
  int threads = 0;                  // threads for our solver's loops; 0 = every core
  int repeat = 1;                   // runs of every solver in every cell; the fastest is reported
  bool no_reference = false;        // skip the reference run (no rms_to_reference)
};
void add_bench_options(CLI::App& verb, BenchArguments& arguments);
int bench_verb(const BenchArguments& arguments, const std::atomic<bool>& interrupt);

}  // namespace drapelab::cli
