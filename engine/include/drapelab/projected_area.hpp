// Area of the union of triangles projected on a plane, by rasterisation: folds overlap, so summing
// triangle areas would count them twice (metrics.md).
#pragma once

#include <Eigen/Core>

namespace drapelab {

struct ProjectedAreaSettings {
  int cells_per_side = 1024;  // raster resolution over the projected bounding box
};

// Projects the triangles of `positions` (m, 3 x N) on the plane normal to `up` (any non-zero vector)
// and returns the area (m^2) of the cells whose centre lies in at least one triangle. The error is at
// most about (outline length) x (cell size). Zero when there are no triangles.
double projected_union_area(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles,
                            const Eigen::Vector3d& up, const ProjectedAreaSettings& settings = {});

}  // namespace drapelab
