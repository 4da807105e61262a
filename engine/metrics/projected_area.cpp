// Union area of projected triangles by rasterisation on a square-cell grid.
#include "metrics/projected_area.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace drapelab {
namespace {

// Twice the signed area of (a, b, p): positive when p is left of a->b.
double edge_function(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

}  // namespace

ProjectionPlane::ProjectionPlane(const Eigen::Vector3d& up) {
  const Eigen::Vector3d n = up.normalized();
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e1 = n.cross(helper).normalized();
  e2 = n.cross(e1);
}

Eigen::Matrix2Xd ProjectionPlane::project(const Eigen::Matrix3Xd& points) const {
  Eigen::Matrix2Xd projected(2, points.cols());
  projected.row(0) = e1.transpose() * points;
  projected.row(1) = e2.transpose() * points;
  return projected;
}

Raster::Raster(const Eigen::Vector2d& low_corner, double cell_size, int nx, int ny)
    : low(low_corner),
      cell(cell_size),
      cells_x(nx),
      cells_y(ny),
      covered(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0) {}

double Raster::covered_area() const {
  return static_cast<double>(std::count(covered.begin(), covered.end(), 1)) * cell * cell;
}

// Scanline fill: for each cell row, the triangle's span along the row's centre line.
void Raster::fill_triangles(const Eigen::Matrix2Xd& points, const Eigen::Matrix3Xi& triangles) {
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const Eigen::Vector2d a = points.col(triangles(0, t));
    const Eigen::Vector2d b = points.col(triangles(1, t));
    const Eigen::Vector2d c = points.col(triangles(2, t));
    if (edge_function(a, b, c) == 0.0) continue;  // degenerate: no area
    const double t_low = std::min({a.y(), b.y(), c.y()}), t_high = std::max({a.y(), b.y(), c.y()});
    const int y0 = std::max(0, static_cast<int>(std::ceil((t_low - low.y()) / cell - 0.5)));
    const int y1 =
        std::min(cells_y - 1, static_cast<int>(std::floor((t_high - low.y()) / cell - 0.5)));
    const Eigen::Vector2d corners[3] = {a, b, c};
    for (int iy = y0; iy <= y1; ++iy) {
      const double y = low.y() + (iy + 0.5) * cell;  // m, the row's centre line
      double span_low = std::numeric_limits<double>::infinity(), span_high = -span_low;
      for (int e = 0; e < 3; ++e) {
        const Eigen::Vector2d& p = corners[e];
        const Eigen::Vector2d& q = corners[(e + 1) % 3];
        if ((p.y() > y) == (q.y() > y) && p.y() != y && q.y() != y)
          continue;            // edge misses the line
        if (p.y() == q.y()) {  // edge along the line
          span_low = std::min({span_low, p.x(), q.x()});
          span_high = std::max({span_high, p.x(), q.x()});
          continue;
        }
        const double x = p.x() + (y - p.y()) / (q.y() - p.y()) * (q.x() - p.x());
        span_low = std::min(span_low, x);
        span_high = std::max(span_high, x);
      }
      if (span_low > span_high) continue;
      // Cells whose centre low.x + (ix + 1/2) cell lies in [span_low, span_high].
      const int x0 = std::max(0, static_cast<int>(std::ceil((span_low - low.x()) / cell - 0.5)));
      const int x1 =
          std::min(cells_x - 1, static_cast<int>(std::floor((span_high - low.x()) / cell - 0.5)));
      if (x0 <= x1)
        std::fill(covered.begin() + static_cast<std::ptrdiff_t>(iy) * cells_x + x0,
                  covered.begin() + static_cast<std::ptrdiff_t>(iy) * cells_x + x1 + 1, 1);
    }
  }
}

double projected_union_area(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles,
                            const Eigen::Vector3d& up, const ProjectedAreaSettings& settings) {
  if (triangles.cols() == 0 || positions.cols() == 0) return 0.0;
  const Eigen::Matrix2Xd projected = ProjectionPlane(up).project(positions);
  const Eigen::Vector2d low = projected.rowwise().minCoeff();
  const Eigen::Vector2d high = projected.rowwise().maxCoeff();
  const double extent = (high - low).maxCoeff();
  if (!(extent > 0.0)) return 0.0;
  const int cells = std::max(1, settings.cells_per_side);
  const double cell = extent / cells;  // m, square cells covering the longer side
  const int cells_x = std::max(1, static_cast<int>(std::ceil((high.x() - low.x()) / cell)));
  const int cells_y = std::max(1, static_cast<int>(std::ceil((high.y() - low.y()) / cell)));
  Raster raster(low, cell, cells_x, cells_y);
  raster.fill_triangles(projected, triangles);
  return raster.covered_area();
}

}  // namespace drapelab
