#include "drapelab/runner/metric_columns.hpp"

namespace drapelab::runner {
namespace {

template <typename T>
std::optional<double> as_double(const std::optional<T>& value) {
  if (!value) return std::nullopt;
  return static_cast<double>(*value);
}

}  // namespace

const std::vector<MetricColumn>& metric_columns() {
  using M = const ClothMetrics&;
  static const std::vector<MetricColumn> columns = {
      {"kinetic_energy", [](M m) -> std::optional<double> { return m.kinetic_energy; }},
      {"gravity_energy", [](M m) -> std::optional<double> { return m.gravity_energy; }},
      {"spring_energy", [](M m) -> std::optional<double> { return m.spring_energy; }},
      {"max_stretch", [](M m) -> std::optional<double> { return m.max_stretch; }},
      {"mean_stretch", [](M m) -> std::optional<double> { return m.mean_stretch; }},
      {"min_clearance", [](M m) { return m.min_clearance; }},
      {"max_penetration", [](M m) { return m.max_penetration; }},
      {"contact_count", [](M m) { return as_double(m.contact_count); }},
      {"centroid_x", [](M m) -> std::optional<double> { return m.centroid.x(); }},
      {"centroid_y", [](M m) -> std::optional<double> { return m.centroid.y(); }},
      {"centroid_z", [](M m) -> std::optional<double> { return m.centroid.z(); }},
      {"lowest_y", [](M m) -> std::optional<double> { return m.lowest_y; }},
      {"projected_area", [](M m) -> std::optional<double> { return m.projected_area; }},
      {"drape_coefficient", [](M m) { return m.drape_coefficient; }},
      {"drape_nodes", [](M m) { return as_double(m.drape_nodes); }},
      {"self_intersections", [](M m) { return as_double(m.self_intersections); }},
      {"triangle_penetration", [](M m) { return m.triangle_penetration; }},
      {"constraint_error", [](M m) { return m.constraint_error; }},
      {"elastic_energy", [](M m) { return m.elastic_energy; }},
      {"contact_energy", [](M m) { return m.contact_energy; }},
      {"constraint_energy", [](M m) { return m.constraint_energy; }},
      {"total_energy", [](M m) { return m.total_energy; }},
      {"external_work", [](M m) { return m.external_work; }},
      {"dissipated", [](M m) { return m.dissipated; }},
      {"energy_error", [](M m) { return m.energy_error; }},
      {"self_contact_energy", [](M m) { return m.self_contact_energy; }},
  };
  return columns;
}

}  // namespace drapelab::runner
