// The per-frame tables of a run: metrics.csv, compare.csv and contacts.csv (docs/outputs.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/run_folder/csv.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::runner {

// Per-vertex differences between two solvers' states of the same model.
struct StateDifference {
  double rms_distance = 0.0;  // m, weighted by vertex area (uniform for a chain, which has no area)
  double max_distance = 0.0;  // m
  double hausdorff_distance = 0.0;  // m, between the triangle surfaces (sampled)
};
StateDifference compare_states(const ClothModel& model, const ClothState& a, const ClothState& b);

class FrameTables {
 public:
  // `bodies`: the scene has dynamic colliders, so bodies.csv is written too.
  FrameTables(const std::filesystem::path& folder, bool bodies);
  void add_metrics(const std::string& solver, int frame, double time, const ClothMetrics& m);
  void add_comparison(const std::string& solver_a, const std::string& solver_b, int frame,
                      double time, const StateDifference& difference);
  void add_contact(const std::string& solver, int frame, double time, const std::string& collider,
                   int contact_count, double normal_force, double friction_force,
                   double max_penetration);
  // bodies.csv: where one solver's copy of a dynamic collider is, and how it moves.
  void add_body(const std::string& solver, int frame, double time, const std::string& collider,
                const BodyState& body);
  void flush();   // at the end of each frame; throws run_folder::WriteError
  void commit();  // the frame's rows are all written
  // Cuts every table back to its last committed frame after a write error; false when a table
  // could not be cut.
  bool rollback() noexcept;

 private:
  run_folder::CsvWriter metrics_;
  run_folder::CsvWriter compare_;
  run_folder::CsvWriter contacts_;
  std::optional<run_folder::CsvWriter> bodies_;  // only with dynamic colliders
};

}  // namespace drapelab::runner
