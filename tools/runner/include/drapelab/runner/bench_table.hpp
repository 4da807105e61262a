// drapelab bench's table: rows, CSV and markdown.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::runner {

struct BenchRow {
  std::string scene;
  int size = 0;  // particles per side
  int particles = 0;
  long long springs = 0;
  std::string solver, type;
  std::string setting;              // integrator, iterations, or why it was skipped
  double dt = 0.0;                  // s
  std::string status;               // ok | unstable | error | skipped
  double wall_per_simulated = 0.0;  // wall s per simulated s
  double ms_per_step = 0.0;
  double max_stretch = 0.0;      // over every frame
  double max_penetration = 0.0;  // m, over every frame
  // m: the root-mean-square distance between this row's particle positions and the reference run's
  // at the final frame, particles matched by index; nothing when either run did not end ok or
  // there is no reference run.
  std::optional<double> rms_to_reference;
  double cost_ratio = 0.0;  // wall_per_simulated / ours (same scene and size)
  // The same two over the run's second half (SimulationResult::second_half_...): the steady cost,
  // once the sheet has landed and Bullet's classic cloth has built most of its distance cache.
  double second_half_wall_per_simulated = 0.0;
  double second_half_cost_ratio = 0.0;
  // The most self-intersections (crossing edge-triangle pairs) of one frame, and the deepest
  // triangle penetration of a collider (m), over every frame; nothing where not measured.
  std::optional<int> self_intersections;
  std::optional<double> triangle_penetration;
  int runs = 0;              // runs of this setting (--repeat); the row is the fastest
  double wall_spread = 1.0;  // the slowest run's wall time over the fastest's
};

struct BenchTable {
  std::string machine;
  std::vector<BenchRow> rows;
};

std::string format_row(const BenchRow& row);  // one line for the console
std::string markdown(const BenchTable& table);
// bench.csv and bench.md in `folder`, each written atomically.
void write_bench_files(const std::filesystem::path& folder, const BenchTable& table);

}  // namespace drapelab::runner
