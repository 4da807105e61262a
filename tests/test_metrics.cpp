// Per-frame metrics: energies, stretch, centroid, and the projected (union) area.
#include <gtest/gtest.h>

#include <cmath>

#include "drapelab/cloth_metrics.hpp"
#include "drapelab/grid_cloth.hpp"
#include "metrics/projected_area.hpp"

namespace drapelab {
namespace {

GridClothSpec flat(int n, double size) {
  GridClothSpec spec;
  spec.nx = n;
  spec.ny = n;
  spec.size = {size, size};
  spec.center = {0.0, 0.0, 0.0};
  spec.mass = 1.0;
  return spec;
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
  const double area = projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitY());
  // Rasterisation error is at most about perimeter x cell size = 3.2 m x 0.8/1024 m.
  EXPECT_NEAR(area, 0.64, 3.2 * 0.8 / 1024);
}

TEST(ProjectedArea, FoldedSheetCountsOverlapOnce) {
  // Fold the 1 m square sheet along x = 0: the half at x > 0 is mirrored onto the other, 1 cm above.
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
  EXPECT_LT(projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitY()), 1e-2);
  // Seen along z it is the full square.
  EXPECT_NEAR(projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitZ()), 1.0, 4.0 / 1024);
}

TEST(ProjectedArea, TiltedDiscOfTrianglesShrinksByTheCosine) {
  const ClothModel model = build_grid_cloth(flat(17, 1.0));
  const double angle = 0.6;  // rad, rotation about x
  Eigen::Matrix3d rotation;
  rotation << 1, 0, 0, 0, std::cos(angle), -std::sin(angle), 0, std::sin(angle), std::cos(angle);
  const Eigen::Matrix3Xd x = rotation * model.rest_positions;
  EXPECT_NEAR(projected_union_area(x, model.triangles, Eigen::Vector3d::UnitY()), std::cos(angle), 4.0 / 1024);
}

TEST(ProjectedArea, AChainHasNoArea) {
  GridClothSpec spec = flat(1, 1.0);
  spec.ny = 5;
  const ClothModel model = build_grid_cloth(spec);
  EXPECT_EQ(projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitY()), 0.0);
}

}  // namespace
}  // namespace drapelab

#include <random>

#include "drapelab/surface_distance.hpp"

namespace drapelab {
namespace {

TEST(SurfaceDistance, PointTriangleDistanceMatchesDenseSampling) {
  std::mt19937_64 random(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a(u(random), u(random), u(random)), b(u(random), u(random), u(random)),
        c(u(random), u(random), u(random)), p(2 * u(random), 2 * u(random), 2 * u(random));
    double sampled = std::numeric_limits<double>::infinity();
    const int n = 200;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        sampled = std::min(sampled, (p - (a + s * (b - a) + t * (c - a))).norm());
      }
    const double exact = point_triangle_distance(p, a, b, c);
    EXPECT_LE(exact, sampled + 1e-12);
    EXPECT_NEAR(exact, sampled, 0.02 * ((b - a).norm() + (c - a).norm()) / n * 10);
  }
}

TEST(SurfaceDistance, HausdorffOfShiftedFoldedAndEqualSurfaces) {
  GridClothSpec spec = flat(11, 1.0);
  const ClothModel model = build_grid_cloth(spec);
  const Eigen::Matrix3Xd& x = model.rest_positions;
  EXPECT_EQ(hausdorff_distance(x, x, model.triangles), 0.0);
  Eigen::Matrix3Xd lifted = x;
  lifted.row(1).array() += 0.03;  // the whole sheet 3 cm higher
  EXPECT_NEAR(hausdorff_distance(x, lifted, model.triangles), 0.03, 1e-12);
  // Slid within its own plane by a third of a cell, the surfaces overlap except at two strips:
  // the Hausdorff distance is the slide (at the edges), while every vertex moved by it too.
  Eigen::Matrix3Xd slid = x;
  slid.row(0).array() += 0.1 / 3;
  EXPECT_NEAR(hausdorff_distance(x, slid, model.triangles), 0.1 / 3, 1e-12);
  // A corner lifted 0.2 m: the worst point is that corner; the flat sheet is within 0.2 m of it.
  Eigen::Matrix3Xd corner = x;
  corner(1, 0) += 0.2;
  const double d = hausdorff_distance(x, corner, model.triangles);
  EXPECT_GT(d, 0.05);
  EXPECT_LE(d, 0.2 + 1e-12);
}

TEST(SurfaceDistance, AChainUsesItsVertexSets) {
  GridClothSpec spec = flat(1, 1.0);
  spec.ny = 4;
  const ClothModel model = build_grid_cloth(spec);
  Eigen::Matrix3Xd moved = model.rest_positions;
  moved(0, 3) += 0.5;
  EXPECT_NEAR(hausdorff_distance(model.rest_positions, moved, model.triangles), 0.5, 1e-12);
}

}  // namespace
}  // namespace drapelab
