// Distances between cloth surfaces: point to triangle, and the Hausdorff distance of two shapes of
// one mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "drapelab/grid_cloth.hpp"
#include "drapelab/surface_distance.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

// A flat n x n sheet of 1 kg, `size` m square, centred at the origin.
GridClothSpec flat_sheet(int n, double size) {
  return fixtures::flat_sheet(n, size, Eigen::Vector3d::Zero(), 1.0);
}

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
  GridClothSpec spec = flat_sheet(11, 1.0);
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
  GridClothSpec spec = flat_sheet(1, 1.0);
  spec.ny = 4;
  const ClothModel model = build_grid_cloth(spec);
  Eigen::Matrix3Xd moved = model.rest_positions;
  moved(0, 3) += 0.5;
  EXPECT_NEAR(hausdorff_distance(model.rest_positions, moved, model.triangles), 0.5, 1e-12);
}

// Each query of the Hausdorff distance costs at most 64 + 8 T cell visits and 65 T triangle tests
// (surface_distance.hpp), whatever the positions: the work counters prove it on the inputs that
// used to loop for ever (a tiny cloth blown up to 1e10 m, a cloth collapsed to a point) and on NaN.
void expect_bounded_work(const Eigen::Matrix3Xd& xa, const Eigen::Matrix3Xd& xb,
                         const Eigen::Matrix3Xi& triangles, double expected) {
  SurfaceDistanceWork work;
  const double d = hausdorff_distance(xa, xb, triangles, &work);
  if (std::isnan(expected))
    EXPECT_TRUE(std::isnan(d));
  else
    EXPECT_NEAR(d, expected, 1e-9 * std::max(1.0, expected));
  const long long t = triangles.cols();
  EXPECT_LE(work.queries, 2 * 8 * t);  // at most one per sample of both directions
  EXPECT_LE(work.cells, work.queries * (64 + 8 * t));
  EXPECT_LE(work.triangle_tests, work.queries * 65 * t + 2 * t);
}

TEST(SurfaceDistance, EveryQueryEndsAfterABoundedAmountOfWork) {
  // 17 x 17 particles over 10 micrometres: cells of 0.6 micrometre.
  const ClothModel model = build_grid_cloth(flat_sheet(17, 1e-5));
  const Eigen::Matrix3Xd& x = model.rest_positions;
  Eigen::Matrix3Xd exploded = x * 1e15;  // 1e10 m across
  exploded.row(1).array() += 1e10;
  const double far = hausdorff_distance(x, exploded, model.triangles);
  EXPECT_GT(far, 1e10);
  expect_bounded_work(x, exploded, model.triangles, far);
  // Every particle of one surface at one point: degenerate triangles.
  const Eigen::Matrix3Xd point = Eigen::Matrix3Xd::Zero(3, x.cols());
  expect_bounded_work(x, point, model.triangles,
                      (x.colwise().norm()).maxCoeff());  // the farthest corner from the origin
  // One particle far away: a long sliver fills no grid cells, the rest stay fine.
  Eigen::Matrix3Xd spike = x;
  spike(1, 100) = 1e6;
  expect_bounded_work(x, spike, model.triangles, hausdorff_distance(x, spike, model.triangles));
  Eigen::Matrix3Xd nan = x;
  nan(0, 7) = std::nan("");
  expect_bounded_work(x, nan, model.triangles, std::nan(""));
  expect_bounded_work(nan, x, model.triangles, std::nan(""));
}

TEST(SurfaceDistance, AQueryPastItsCellBudgetTestsEveryTriangle) {
  // Two tiny triangles 1 km apart: cells of about 1 m, all empty between them. Moved to the middle,
  // each sample is 500 m from both, past the budget of 64 + 8 x 2 cells: every triangle is tested.
  Eigen::Matrix3Xd apart(3, 6), middle(3, 6);
  apart << 0, 1e-3, 0, 1000, 1000.001, 1000,  //
      0, 0, 0, 0, 0, 0,                       //
      0, 0, 1e-3, 0, 0, 1e-3;
  middle = apart;
  middle.row(0).array() = apart.row(0).array() - apart.row(0).array().floor() + 500.0;
  Eigen::Matrix3Xi triangles(3, 2);
  triangles << 0, 3, 1, 4, 2, 5;
  SurfaceDistanceWork work;
  EXPECT_NEAR(hausdorff_distance(apart, middle, triangles, &work), 500.0, 2e-3);
  EXPECT_GT(work.full_scans, 0);
  EXPECT_LE(work.cells, work.queries * (64 + 8 * 2));
}

}  // namespace
}  // namespace drapelab
