// Distances between cloth surfaces: point to triangle, and the Hausdorff distance of two shapes of
// one mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "drapelab/grid_cloth.hpp"
#include "drapelab/surface_distance.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

// A flat n x n sheet of 1 kg, `size` m square, centred at the origin.
GridClothSpec flat(int n, double size) {
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
