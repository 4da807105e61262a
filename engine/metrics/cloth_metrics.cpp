// Per-frame metrics (docs/metrics.md, "Per frame (`metrics.csv`)") from (model, state) only.
#include "drapelab/cloth_metrics.hpp"

#include <algorithm>
#include <limits>

#include "metrics/projected_area.hpp"

namespace drapelab {

ClothMetrics compute_cloth_metrics(const ClothModel& model, const ClothState& state,
                                   const Eigen::Vector3d& gravity) {
  ClothMetrics m;
  const int count = model.particle_count();
  for (int i = 0; i < count; ++i) {
    m.kinetic_energy += 0.5 * model.mass[i] * state.v.col(i).squaredNorm();
    m.gravity_energy -= model.mass[i] * gravity.dot(state.x.col(i));
  }
  m.centroid = state.x * model.mass / model.total_mass();
  m.lowest_y = state.x.row(1).minCoeff();

  const SpringSet& s = model.springs;
  double stretch_sum = 0.0;
  std::size_t stretch_count = 0;
  double max_stretch = -std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < s.size(); ++e) {
    const double length = (state.x.col(s.v0[e]) - state.x.col(s.v1[e])).norm();
    const double extension = length - s.rest_length[e];
    m.spring_energy += 0.5 * s.ks[e] * extension * extension;
    if (s.kind[e] == SpringKind::stretch) {
      const double strain = length / s.rest_length[e] - 1.0;
      stretch_sum += strain;
      max_stretch = std::max(max_stretch, strain);
      ++stretch_count;
    }
  }
  if (stretch_count > 0) {
    m.max_stretch = max_stretch;
    m.mean_stretch = stretch_sum / static_cast<double>(stretch_count);
  }
  // Projected along gravity; without gravity, along y (up).
  const Eigen::Vector3d up =
      gravity.squaredNorm() > 0.0 ? Eigen::Vector3d(-gravity) : Eigen::Vector3d::UnitY();
  m.projected_area = projected_union_area(state.x, model.triangles, up);
  return m;
}

}  // namespace drapelab
