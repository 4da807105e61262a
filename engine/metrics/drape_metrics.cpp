// Drape coefficient and node count on one raster grid (drape_metrics.hpp).
#include "drapelab/drape_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "metrics/projected_area.hpp"

namespace drapelab {
namespace {

Raster grid_around(const Eigen::Vector2d& center, double half_extent, int cells) {
  const double cell = 2.0 * half_extent / cells;
  return Raster(center - Eigen::Vector2d::Constant(half_extent), cell, cells, cells);
}

}  // namespace

std::vector<double> circular_smooth(const std::vector<double>& r, int width) {
  const int n = static_cast<int>(r.size());
  const int half = std::max(0, width / 2);
  std::vector<double> smoothed(r.size(), 0.0);
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int k = -half; k <= half; ++k) sum += r[static_cast<std::size_t>(((i + k) % n + n) % n)];
    smoothed[static_cast<std::size_t>(i)] = sum / (2 * half + 1);
  }
  return smoothed;
}

int count_outline_nodes(const std::vector<double>& r, double min_prominence) {
  const int n = static_cast<int>(r.size());
  if (n < 3) return 0;
  const auto [low, high] = std::minmax_element(r.begin(), r.end());
  const double needed = std::max(min_prominence, 0.1 * (*high - *low));
  auto at = [&](int i) { return r[static_cast<std::size_t>(((i % n) + n) % n)]; };
  int nodes = 0;
  for (int i = 0; i < n; ++i) {
    // A maximum, or the first sample of a flat top: higher than the last different value before it
    // and not lower than the next different value after it.
    if (at(i) == at(i - 1)) continue;
    int before = i - 1;
    if (at(before) > at(i)) continue;
    int after = i + 1;
    while (after < i + n && at(after) == at(i)) ++after;
    if (after == i + n || at(after) > at(i)) continue;
    // Walk each way to a higher value, tracking the lowest point on the way.
    double left_low = at(i), right_low = at(i);
    for (int k = i - 1; k > i - n && at(k) <= at(i); --k) left_low = std::min(left_low, at(k));
    for (int k = after; k < i + n && at(k) <= at(i); ++k) right_low = std::min(right_low, at(k));
    if (at(i) - std::max(left_low, right_low) > needed) ++nodes;
  }
  return nodes;
}

DrapeMeter::DrapeMeter(const ClothModel& model, const DrapeSupport& support,
                       const Eigen::Vector3d& up, DrapeSettings settings)
    : settings_(settings), up_(up) {
  const ProjectionPlane plane(up_);
  center_ = plane.project(support.center);
  const Eigen::Matrix2Xd rest = plane.project(model.rest_positions);
  double specimen_radius = support.radius;  // R_D, m
  for (Eigen::Index i = 0; i < rest.cols(); ++i)
    specimen_radius = std::max(specimen_radius, (rest.col(i) - center_).norm());
  half_extent_ = 1.1 * specimen_radius;
  Raster flat = grid_around(center_, half_extent_, settings_.cells_per_side);
  flat.fill_triangles(rest, model.triangles);
  flat_area_ = flat.covered_area();
  Raster disc = grid_around(center_, half_extent_, settings_.cells_per_side);
  for (int iy = 0; iy < disc.cells_y; ++iy)
    for (int ix = 0; ix < disc.cells_x; ++ix)
      if ((disc.centre(ix, iy) - center_).norm() <= support.radius)
        disc.covered[static_cast<std::size_t>(iy) * disc.cells_x + ix] = 1;
  support_area_ = disc.covered_area();
}

DrapeMeasure DrapeMeter::measure(const ClothModel& model, const Eigen::Matrix3Xd& positions) const {
  const ProjectionPlane plane(up_);
  Raster shadow = grid_around(center_, half_extent_, settings_.cells_per_side);
  shadow.fill_triangles(plane.project(positions), model.triangles);
  DrapeMeasure m;
  m.shadow_area = shadow.covered_area();
  m.flat_area = flat_area_;
  m.support_area = support_area_;
  const double span = flat_area_ - support_area_;
  m.coefficient = span > 0.0 ? (m.shadow_area - support_area_) / span : 0.0;

  // Outline r(theta): the farthest covered cell centre in each angular bin.
  const int bins = std::max(3, settings_.angle_bins);
  std::vector<double> outline(static_cast<std::size_t>(bins), 0.0);
  for (int iy = 0; iy < shadow.cells_y; ++iy)
    for (int ix = 0; ix < shadow.cells_x; ++ix) {
      if (!shadow.at(ix, iy)) continue;
      const Eigen::Vector2d d = shadow.centre(ix, iy) - center_;
      const double angle = std::atan2(d.y(), d.x()) + std::numbers::pi;  // [0, 2 pi]
      const int bin = std::min(bins - 1, static_cast<int>(angle / (2.0 * std::numbers::pi) * bins));
      outline[static_cast<std::size_t>(bin)] =
          std::max(outline[static_cast<std::size_t>(bin)], d.norm());
    }
  const int window =
      2 * static_cast<int>(std::lround(0.5 * settings_.smoothing_degrees * bins / 360.0)) + 1;
  m.outline = circular_smooth(outline, window);
  m.nodes = count_outline_nodes(m.outline, settings_.min_prominence);
  return m;
}

}  // namespace drapelab
