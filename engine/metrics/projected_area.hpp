// Area of the union of triangles projected on a plane, by rasterisation: folds overlap, so summing
// triangle areas would count them twice (docs/metrics.md, "Projected area").
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace drapelab {

struct ProjectedAreaSettings {
  int cells_per_side = 1024;  // raster resolution over the projected bounding box
};

// An orthonormal basis (e1, e2) of the plane normal to `up` (any non-zero vector), so that
// (e1, e2, up) is right-handed.
struct ProjectionPlane {
  explicit ProjectionPlane(const Eigen::Vector3d& up);
  Eigen::Vector2d project(const Eigen::Vector3d& p) const { return {e1.dot(p), e2.dot(p)}; }
  Eigen::Matrix2Xd project(const Eigen::Matrix3Xd& points) const;
  Eigen::Vector3d e1, e2;
};

// A square-cell raster: cell (ix, iy) has its centre at low + ((ix + 1/2) cell, (iy + 1/2) cell).
struct Raster {
  Eigen::Vector2d low = Eigen::Vector2d::Zero();  // m
  double cell = 0.0;                              // m
  int cells_x = 0, cells_y = 0;
  std::vector<std::uint8_t> covered;  // row-major, 1 = the centre lies in some triangle

  Raster(const Eigen::Vector2d& low_corner, double cell_size, int nx, int ny);
  Eigen::Vector2d centre(int ix, int iy) const {
    return low + Eigen::Vector2d(ix + 0.5, iy + 0.5) * cell;
  }
  bool at(int ix, int iy) const {
    return covered[static_cast<std::size_t>(iy) * cells_x + ix] != 0;
  }
  // Covered cells times the cell area (m^2).
  double covered_area() const;
  // Marks every cell whose centre lies in one of the triangles (2-D points, m).
  void fill_triangles(const Eigen::Matrix2Xd& points, const Eigen::Matrix3Xi& triangles);
};

// Projects the triangles of `positions` (m, 3 x N) on the plane normal to `up` and returns the area
// (m^2) of the cells whose centre lies in at least one triangle, on a raster over their bounding
// box. The error is at most about (outline length) x (cell size). Zero when there are no triangles.
double projected_union_area(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles,
                            const Eigen::Vector3d& up, const ProjectedAreaSettings& settings = {});

}  // namespace drapelab
