// The Cusick drape test's measures (docs/metrics.md, "Drape test"): the drape coefficient
// DC = (A_s - A_d) / (A_D - A_d) and the number of nodes (folds) of the shadow's outline.
//
// A_s, the shadow, is the union of the cloth's triangles projected along gravity; A_D is the same
// for the rest (flat) cloth, A_d the support disc's area. All three are rasterised on one square
// grid of cells_per_side^2 cells over +-1.1 R_D around the support's centre, where R_D is the
// farthest projected rest particle from it, so rasterisation errors largely cancel in the ratio.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "drapelab/cloth_model.hpp"

namespace drapelab {

// The support disc: centre (m, any point on the support's axis) and radius (m), seen along gravity.
struct DrapeSupport {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

struct DrapeSettings {
  int cells_per_side = 1024;       // raster resolution over +-1.1 R_D
  int angle_bins = 360;            // outline samples r(theta), one per degree
  double smoothing_degrees = 5.0;  // circular moving-average window on r(theta)
  double min_prominence = 0.002;   // m; a node also needs 0.1 (r_max - r_min)
};

struct DrapeMeasure {
  double coefficient = 0.0;     // DC, 1 = flat, 0 = hangs limp
  int nodes = 0;                // outline maxima with enough prominence
  double shadow_area = 0.0;     // A_s, m^2
  double flat_area = 0.0;       // A_D, m^2
  double support_area = 0.0;    // A_d, m^2
  std::vector<double> outline;  // r(theta), m, smoothed, angle_bins samples from e1 towards e2
};

// Fixed per model and support: the grid and the rasterised A_D and A_d.
class DrapeMeter {
 public:
  DrapeMeter(const ClothModel& model, const DrapeSupport& support, const Eigen::Vector3d& up,
             DrapeSettings settings = {});
  DrapeMeasure measure(const ClothModel& model, const Eigen::Matrix3Xd& positions) const;
  double flat_area() const { return flat_area_; }
  double support_area() const { return support_area_; }

 private:
  DrapeSettings settings_;
  Eigen::Vector3d up_;
  Eigen::Vector2d center_;    // support centre in the projection plane (m)
  double half_extent_ = 0.0;  // m, 1.1 R_D
  double flat_area_ = 0.0;
  double support_area_ = 0.0;
};

// Counts the maxima of a closed curve r(theta) (equal angle steps) whose prominence exceeds
// max(min_prominence, 0.1 (r_max - r_min)). Prominence: the height of a maximum above the higher of
// the two lowest points met walking from it, each way round the circle, to a higher value (or all
// the way round for the highest). Plateaus count once.
int count_outline_nodes(const std::vector<double>& r, double min_prominence);

// Circular moving average of r over a window of `width` samples (odd; 1 leaves r unchanged).
std::vector<double> circular_smooth(const std::vector<double>& r, int width);

}  // namespace drapelab
