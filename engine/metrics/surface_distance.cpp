// Point-to-triangle distances over a uniform grid of triangles, for the Hausdorff distance.
#include "drapelab/surface_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

namespace drapelab {
namespace {

// Triangles bucketed by the grid cells their bounding boxes overlap.
class TriangleGrid {
 public:
  TriangleGrid(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xi& triangles)
      : x_(x), triangles_(triangles) {
    double edges = 0.0;
    for (Eigen::Index t = 0; t < triangles.cols(); ++t)
      edges += (x.col(triangles(0, t)) - x.col(triangles(1, t))).norm();
    cell_ = std::max(edges / static_cast<double>(std::max<Eigen::Index>(1, triangles.cols())),
                     1e-9);  // m, one edge
    for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
      Eigen::Vector3d low = x.col(triangles(0, t)), high = low;
      for (int k = 1; k < 3; ++k) {
        low = low.cwiseMin(x.col(triangles(k, t)));
        high = high.cwiseMax(x.col(triangles(k, t)));
      }
      const Eigen::Vector3i from = cell_of(low), to = cell_of(high);
      for (int i = from.x(); i <= to.x(); ++i)
        for (int j = from.y(); j <= to.y(); ++j)
          for (int k = from.z(); k <= to.z(); ++k)
            cells_[key(i, j, k)].push_back(static_cast<int>(t));
    }
  }

  // Distance from p to the nearest triangle: visits shells of cells around p until no unvisited
  // cell can hold anything nearer than the best found. Stops early once the best is at most
  // `enough` (the caller only needs to know it is no larger).
  double distance(const Eigen::Vector3d& p, double enough) const {
    const Eigen::Vector3i centre = cell_of(p);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 0;; ++ring) {
      for (int i = -ring; i <= ring; ++i)
        for (int j = -ring; j <= ring; ++j)
          for (int k = -ring; k <= ring; ++k) {
            if (std::max({std::abs(i), std::abs(j), std::abs(k)}) != ring)
              continue;  // the shell only
            const auto found = cells_.find(key(centre.x() + i, centre.y() + j, centre.z() + k));
            if (found == cells_.end()) continue;
            for (int t : found->second)
              best = std::min(best, point_triangle_distance(p, x_.col(triangles_(0, t)),
                                                            x_.col(triangles_(1, t)),
                                                            x_.col(triangles_(2, t))));
          }
      if (best <= enough || best <= ring * cell_ || ring > 1000000) return best;
    }
  }

 private:
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const {
    return (p / cell_).array().floor().cast<int>();
  }
  static long long key(int i, int j, int k) {
    return (static_cast<long long>(i) * 73856093LL) ^ (static_cast<long long>(j) * 19349663LL) ^
           (static_cast<long long>(k) * 83492791LL);
  }

  const Eigen::Matrix3Xd& x_;
  const Eigen::Matrix3Xi& triangles_;
  double cell_ = 1.0;  // m
  std::unordered_map<long long, std::vector<int>> cells_;
};

// Largest distance from the sample points of surface `from` to surface `to`. Node i is the same
// material point on both, so a sample's distance to its own counterpart on `to` bounds its distance
// to the surface from above: samples whose bound cannot beat the largest distance found so far are
// skipped, and the others are visited in decreasing order of their bound.
double directed_distance(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to,
                         const Eigen::Matrix3Xi& triangles) {
  const TriangleGrid grid(to, triangles);
  // Barycentric weights of the samples: vertices, edge third points, centroid.
  static const double kWeights[8][3] = {
      {1, 0, 0},           {2. / 3, 1. / 3, 0}, {1. / 3, 2. / 3, 0}, {0, 2. / 3, 1. / 3},
      {0, 1. / 3, 2. / 3}, {1. / 3, 0, 2. / 3}, {2. / 3, 0, 1. / 3}, {1. / 3, 1. / 3, 1. / 3}};
  struct Sample {
    Eigen::Vector3d point;
    double bound;  // m, distance to the same material point on `to`
  };
  std::vector<Sample> samples;
  samples.reserve(static_cast<std::size_t>(triangles.cols()) * 8);
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    for (const auto& w : kWeights) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero(), q = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        p += w[k] * from.col(triangles(k, t));
        q += w[k] * to.col(triangles(k, t));
      }
      samples.push_back({p, (p - q).norm()});
    }
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.bound > b.bound; });
  double worst = 0.0;
  for (const auto& sample : samples) {
    if (sample.bound <= worst) break;  // sorted: no later sample can beat it
    worst = std::max(worst, grid.distance(sample.point, worst));
  }
  return worst;
}

}  // namespace

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // The closest point lies in one of the triangle's Voronoi regions: a vertex, an edge or the face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();  // vertex a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();  // edge ab
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)  // edge bc
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denominator = va + vb + vc;
  if (denominator == 0.0)
    return std::min({ap.norm(), bp.norm(), cp.norm()});  // degenerate triangle
  const double v = vb / denominator, w = vc / denominator;
  return (p - (a + ab * v + ac * w)).norm();  // inside the face
}

double hausdorff_distance(const Eigen::Matrix3Xd& xa, const Eigen::Matrix3Xd& xb,
                          const Eigen::Matrix3Xi& triangles) {
  if (triangles.cols() == 0) {  // vertex sets
    auto directed = [](const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to) {
      double worst = 0.0;
      for (Eigen::Index i = 0; i < from.cols(); ++i)
        worst = std::max(worst, (to.colwise() - from.col(i)).colwise().norm().minCoeff());
      return worst;
    };
    return std::max(directed(xa, xb), directed(xb, xa));
  }
  return std::max(directed_distance(xa, xb, triangles), directed_distance(xb, xa, triangles));
}

}  // namespace drapelab
