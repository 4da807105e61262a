// Distances between two states of the same cloth seen as triangle surfaces (docs/metrics.md,
// "Comparison between solvers (`compare.csv`)").
#pragma once

#include <Eigen/Core>

namespace drapelab {

// Closest distance (m) from point p to triangle (a, b, c).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// What the distance queries of hausdorff_distance did: each query visits at most 64 + 8 T grid
// cells and tests at most 65 T triangles (T triangles), whatever the positions (huge, degenerate).
struct SurfaceDistanceWork {
  long long queries = 0;         // point-to-surface queries
  long long cells = 0;           // grid cells visited
  long long triangle_tests = 0;  // point-triangle distances computed
  long long full_scans = 0;      // queries answered by testing every triangle
};

// Symmetric Hausdorff distance (m) between the surfaces {xa, triangles} and {xb, triangles}: the
// largest distance from a point of either surface to the other surface, sampled at every vertex,
// the third points of every edge and every triangle centroid, point-to-triangle.
// Without triangles (a chain) the surfaces are the vertex sets. NaN when a coordinate is not
// finite. `work`, when given, receives the counts of the queries.
double hausdorff_distance(const Eigen::Matrix3Xd& xa, const Eigen::Matrix3Xd& xb,
                          const Eigen::Matrix3Xi& triangles, SurfaceDistanceWork* work = nullptr);

}  // namespace drapelab
