// Point-to-triangle distances over a uniform grid of triangles, for the Hausdorff distance.
#include "drapelab/surface_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

namespace drapelab {
namespace {

// Cells along the longest side of the triangles' bounding box, at most: a surface of tiny triangles
// spread far apart (an exploded cloth) gets larger cells rather than billions of them.
constexpr double kMaxCellsPerSide = 1024.0;
// A triangle whose bounding box covers more cells than this is kept apart and tested by every
// query, so that one long sliver cannot fill millions of cells.
constexpr long long kMaxCellsPerTriangle = 64;
// A query point further than this many cells outside the bounding box goes straight to the loop
// over every triangle (its cell indices stay far inside an int and the hash key's 21 bits).
constexpr double kMaxReachCells = 65536.0;

// Triangles bucketed by the grid cells their bounding boxes overlap.
class TriangleGrid {
 public:
  // `x` must be finite (hausdorff_distance checks it).
  TriangleGrid(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xi& triangles,
               SurfaceDistanceWork* work)
      : x_(x), triangles_(triangles), work_(work) {
    low_ = x.rowwise().minCoeff();
    const Eigen::Vector3d high = x.rowwise().maxCoeff();
    double edges = 0.0;
    for (Eigen::Index t = 0; t < triangles.cols(); ++t)
      edges += (x.col(triangles(0, t)) - x.col(triangles(1, t))).norm();
    const double mean_edge =
        edges / static_cast<double>(std::max<Eigen::Index>(1, triangles.cols()));  // m
    const double extent = (high - low_).maxCoeff();                                // m
    cell_ = std::max(mean_edge, extent / kMaxCellsPerSide);
    if (!(cell_ > 0.0)) cell_ = 1.0;  // every vertex at one point: any cell will do
    last_cell_ = cell_index(high);
    for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
      Eigen::Vector3d lo = x.col(triangles(0, t)), hi = lo;
      for (int k = 1; k < 3; ++k) {
        lo = lo.cwiseMin(x.col(triangles(k, t)));
        hi = hi.cwiseMax(x.col(triangles(k, t)));
      }
      const Eigen::Vector3i from = cell_index(lo), to = cell_index(hi);
      const Eigen::Vector3i span = to - from + Eigen::Vector3i::Ones();
      if (static_cast<long long>(span.x()) * span.y() * span.z() > kMaxCellsPerTriangle) {
        large_.push_back(static_cast<int>(t));
        continue;
      }
      for (int i = from.x(); i <= to.x(); ++i)
        for (int j = from.y(); j <= to.y(); ++j)
          for (int k = from.z(); k <= to.z(); ++k)
            cells_[key(i, j, k)].push_back(static_cast<int>(t));
    }
  }

  // Distance from p to the nearest triangle: visits shells of cells around p until no unvisited
  // cell can hold anything nearer than the best found, or every occupied cell has been visited.
  // Stops early once the best is at most `enough` (the caller only needs to know it is no larger).
  // A search that would visit more than cell_budget() cells tests every triangle instead, so a
  // query costs at most cell_budget() cell visits and (kMaxCellsPerTriangle + 1) x T triangle
  // tests, whatever the points.
  double distance(const Eigen::Vector3d& p, double enough) const {
    if (work_) ++work_->queries;
    const Eigen::Vector3d local = (p - low_) / cell_;
    const double reach = kMaxReachCells;
    if (!((local.array() >= -reach).all() &&
          (local.array() <= last_cell_.cast<double>().array() + reach).all()))
      return every_triangle(p);
    const Eigen::Vector3i centre = cell_index(p);
    double best = std::numeric_limits<double>::infinity();
    for (int t : large_) best = std::min(best, triangle_distance(p, t));
    // Only cells inside the box of occupied cells are visited: offsets from the centre in [lo, hi].
    const Eigen::Vector3i lo = -centre, hi = last_cell_ - centre;
    const int first_ring = std::max({0, lo.maxCoeff(), (-hi).maxCoeff()});  // nearest box cell
    const int last_ring = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    const long long budget = cell_budget();
    long long visited = 0;
    for (int ring = first_ring; ring <= last_ring; ++ring) {
      for (int i = std::max(-ring, lo.x()); i <= std::min(ring, hi.x()); ++i)
        for (int j = std::max(-ring, lo.y()); j <= std::min(ring, hi.y()); ++j) {
          // The shell only: the whole k row on its sides, else its two faces along k.
          const bool side = std::abs(i) == ring || std::abs(j) == ring;
          for (int k = side ? std::max(-ring, lo.z()) : -ring; k <= std::min(ring, hi.z());
               k += side ? 1 : 2 * ring) {
            if (k < lo.z()) continue;
            if (++visited > budget) return every_triangle(p);
            if (work_) ++work_->cells;
            const auto found = cells_.find(key(centre.x() + i, centre.y() + j, centre.z() + k));
            if (found == cells_.end()) continue;
            for (int t : found->second) best = std::min(best, triangle_distance(p, t));
          }
        }
      if (best <= enough || best <= ring * cell_) return best;
    }
    return best;  // every occupied cell visited
  }

  long long cell_budget() const { return 64 + 8 * static_cast<long long>(triangles_.cols()); }

 private:
  double triangle_distance(const Eigen::Vector3d& p, int t) const {
    if (work_) ++work_->triangle_tests;
    return point_triangle_distance(p, x_.col(triangles_(0, t)), x_.col(triangles_(1, t)),
                                   x_.col(triangles_(2, t)));
  }

  double every_triangle(const Eigen::Vector3d& p) const {
    if (work_) ++work_->full_scans;
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index t = 0; t < triangles_.cols(); ++t)
      best = std::min(best, triangle_distance(p, static_cast<int>(t)));
    return best;
  }

  // The cell of a point within kMaxReachCells of the bounding box.
  Eigen::Vector3i cell_index(const Eigen::Vector3d& p) const {
    return ((p - low_) / cell_).array().floor().cast<int>();
  }
  // Cell indices lie in [-2^16 - 1, 2^10 + 2^16 + 1]: 21 bits each, offset to be non-negative.
  static long long key(int i, int j, int k) {
    constexpr long long offset = 1LL << 20;
    return ((static_cast<long long>(i) + offset) << 42) |
           ((static_cast<long long>(j) + offset) << 21) | (static_cast<long long>(k) + offset);
  }

  const Eigen::Matrix3Xd& x_;
  const Eigen::Matrix3Xi& triangles_;
  SurfaceDistanceWork* work_;
  Eigen::Vector3d low_ = Eigen::Vector3d::Zero();  // m, the vertices' bounding box's low corner
  Eigen::Vector3i last_cell_ = Eigen::Vector3i::Zero();  // the cell of its high corner
  double cell_ = 1.0;                                    // m
  std::vector<int> large_;  // triangles over more than kMaxCellsPerTriangle cells
  std::unordered_map<long long, std::vector<int>> cells_;
};

// Largest distance from the sample points of surface `from` to surface `to`. Node i is the same
// material point on both, so a sample's distance to its own counterpart on `to` bounds its distance
// to the surface from above: samples whose bound cannot beat the largest distance found so far are
// skipped, and the others are visited in decreasing order of their bound.
double directed_distance(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to,
                         const Eigen::Matrix3Xi& triangles, SurfaceDistanceWork* work) {
  const TriangleGrid grid(to, triangles, work);
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
                          const Eigen::Matrix3Xi& triangles, SurfaceDistanceWork* work) {
  // A non-finite coordinate has no distance; it would also break the sort of the samples below.
  if (!xa.allFinite() || !xb.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  if (triangles.cols() == 0) {  // vertex sets
    auto directed = [](const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to) {
      double worst = 0.0;
      for (Eigen::Index i = 0; i < from.cols(); ++i)
        worst = std::max(worst, (to.colwise() - from.col(i)).colwise().norm().minCoeff());
      return worst;
    };
    return std::max(directed(xa, xb), directed(xb, xa));
  }
  return std::max(directed_distance(xa, xb, triangles, work),
                  directed_distance(xb, xa, triangles, work));
}

}  // namespace drapelab
