// Per-frame metrics: energies, stretch, centroid, and the projected (union) area.
#include <gtest/gtest.h>

#include <cmath>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/grid_cloth.hpp"
#include "fixtures/sheets.hpp"
#include "metrics/projected_area.hpp"

namespace drapelab {
namespace {

// A flat n x n sheet of 1 kg, `size` m square, centred at the origin.
GridClothSpec flat(int n, double size) {
  return fixtures::flat_sheet(n, size, Eigen::Vector3d::Zero(), 1.0);
}

TEST(Metrics, RestStateHasNoSpringEnergyOrStretch) {
  const ClothModel model = build_grid_cloth(flat(5, 1.0));
  ClothState state = initial_grid_state(model, GridClothSpec{}, 0.0, 0);
  state.x.row(1).array() += 2.0;  // lift the sheet 2 m
  const ClothMetrics m = compute_cloth_metrics(model, state, {0, -9.81, 0});
  EXPECT_EQ(m.kinetic_energy, 0.0);
  EXPECT_NEAR(m.gravity_energy, 1.0 * 9.81 * 2.0, 1e-12);
  EXPECT_NEAR(m.spring_energy, 0.0, 1e-20);
  EXPECT_NEAR(m.max_stretch, 0.0, 1e-15);
  EXPECT_NEAR(m.mean_stretch, 0.0, 1e-15);
  EXPECT_NEAR((m.centroid - Eigen::Vector3d(0, 2, 0)).norm(), 0.0, 1e-14);
  EXPECT_DOUBLE_EQ(m.lowest_y, 2.0);
  EXPECT_FALSE(m.min_clearance.has_value());
  EXPECT_FALSE(m.drape_coefficient.has_value());
}

TEST(Metrics, UniformScalingStretchesEverySpring) {
  const ClothModel model = build_grid_cloth(flat(4, 1.0));
  ClothState state = initial_grid_state(model, GridClothSpec{}, 0.0, 0);
  state.x *= 1.1;  // every spring 10 % longer
  state.v.setConstant(2.0);
  const ClothMetrics m = compute_cloth_metrics(model, state, {0, -9.81, 0});
  EXPECT_NEAR(m.max_stretch, 0.1, 1e-12);
  EXPECT_NEAR(m.mean_stretch, 0.1, 1e-12);
  EXPECT_NEAR(m.kinetic_energy, 0.5 * 1.0 * 12.0, 1e-12);  // |v|^2 = 12 m^2/s^2
  double expected = 0.0;
  for (std::size_t e = 0; e < model.springs.size(); ++e)
    expected += 0.5 * model.springs.ks[e] * std::pow(0.1 * model.springs.rest_length[e], 2);
  EXPECT_NEAR(m.spring_energy, expected, 1e-12 * expected);
}

TEST(ProjectedArea, FlatSquareIsItsArea) {
  const ClothModel model = build_grid_cloth(flat(11, 0.8));
  const double area =
      projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitY());
  // Rasterisation error is at most about perimeter x cell size = 3.2 m x 0.8/1024 m.
  EXPECT_NEAR(area, 0.64, 3.2 * 0.8 / 1024);
}

TEST(ProjectedArea, FoldedSheetCountsOverlapOnce) {
  // Fold the 1 m square sheet along x = 0: the half at x > 0 is mirrored onto the other, 1 cm
  // above.
  const ClothModel model = build_grid_cloth(flat(21, 1.0));
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int i = 0; i < x.cols(); ++i)
    if (x(0, i) > 0.0) {
      x(0, i) = -x(0, i);
      x(1, i) = 0.01;
    }
  const double area = projected_union_area(x, model.triangles, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(area, 0.5, 4.0 / 1024);  // the union, not the sum of triangle areas (1.0)
}

TEST(ProjectedArea, VerticalSheetProjectsToALine) {
  GridClothSpec spec = flat(9, 1.0);
  spec.plane = GridPlane::xy;
  const ClothModel model = build_grid_cloth(spec);
  EXPECT_LT(projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitY()),
            1e-2);
  // Seen along z it is the full square.
  EXPECT_NEAR(projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitZ()),
              1.0, 4.0 / 1024);
}

TEST(ProjectedArea, TiltedDiscOfTrianglesShrinksByTheCosine) {
  const ClothModel model = build_grid_cloth(flat(17, 1.0));
  const double angle = 0.6;  // rad, rotation about x
  Eigen::Matrix3d rotation;
  rotation << 1, 0, 0, 0, std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle);
  const Eigen::Matrix3Xd x = rotation * model.rest_positions;
  EXPECT_NEAR(projected_union_area(x, model.triangles, Eigen::Vector3d::UnitY()), std::cos(angle),
              4.0 / 1024);
}

TEST(ProjectedArea, AChainHasNoArea) {
  GridClothSpec spec = flat(1, 1.0);
  spec.ny = 5;
  const ClothModel model = build_grid_cloth(spec);
  EXPECT_EQ(projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitY()),
            0.0);
}

}  // namespace
}  // namespace drapelab
