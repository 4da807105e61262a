// Drape metrics (docs/metrics.md, "Drape test"): the drape coefficient's limits, and the node count
// of shadow outlines with a known number of lobes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "drapelab/drape_metrics.hpp"
#include "drapelab/grid_cloth.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitY();

// A flat 0.3 m square specimen at height 0.5 m, 61 x 61 particles, over a support of radius 0.09 m.
ClothModel specimen() {
  return build_grid_cloth(fixtures::flat_sheet(61, 0.3, {0.0, 0.5, 0.0}, 0.05));
}

// Maps the square onto a star: the particle at angle theta and fraction f of the way from the
// centre to the square's edge goes to radius f R(theta), R(theta) = radius (1 + depth cos(lobes
// theta)), dropped below the table by how far it moved in.
Eigen::Matrix3Xd star_shape(const ClothModel& model, int lobes, double radius, double depth) {
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int i = 0; i < x.cols(); ++i) {
    const Eigen::Vector2d p(x(0, i), x(2, i));
    if (p.norm() == 0.0) continue;
    const double theta = std::atan2(p.y(), p.x());
    const double to_edge = 0.15 / std::max(std::abs(std::cos(theta)), std::abs(std::sin(theta)));
    const double target = p.norm() / to_edge * radius * (1.0 + depth * std::cos(lobes * theta));
    x(0, i) = target * std::cos(theta);
    x(2, i) = target * std::sin(theta);
    x(1, i) -= std::max(0.0, p.norm() - target);  // the hanging part drops
  }
  return x;
}

TEST(DrapeCoefficient, FlatSpecimenIsOne) {
  const ClothModel model = specimen();
  const DrapeMeter meter(model, {{0.0, 0.45, 0.0}, 0.09}, kUp);
  const DrapeMeasure m = meter.measure(model, model.rest_positions);
  EXPECT_DOUBLE_EQ(m.coefficient, 1.0);
  EXPECT_NEAR(m.flat_area, 0.09, 0.09 * 2e-3);                            // 0.3 m squared
  EXPECT_NEAR(m.support_area, std::numbers::pi * 0.0081, 0.0254 * 2e-3);  // pi R_d^2
  EXPECT_EQ(m.nodes, 4) << "a square's shadow has four corners";
}

TEST(DrapeCoefficient, LimpSpecimenHangingAtTheDiscEdgeIsNearZero) {
  const ClothModel model = specimen();
  const double support = 0.09;  // m
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int i = 0; i < x.cols(); ++i) {
    const Eigen::Vector2d p(x(0, i), x(2, i));
    if (p.norm() <= support) continue;
    const Eigen::Vector2d edge = p.normalized() * support;  // hangs straight down from the rim
    x(1, i) -= p.norm() - support;
    x(0, i) = edge.x();
    x(2, i) = edge.y();
  }
  const DrapeMeter meter(model, {{0.0, 0.45, 0.0}, support}, kUp);
  const DrapeMeasure m = meter.measure(model, x);
  EXPECT_NEAR(m.coefficient, 0.0, 0.01);
}

TEST(DrapeCoefficient, GrowsWithTheShadow) {
  const ClothModel model = specimen();
  const DrapeMeter meter(model, {{0.0, 0.45, 0.0}, 0.09}, kUp);
  double previous = 0.0;
  for (double radius : {0.1, 0.12, 0.14}) {
    const DrapeMeasure m = meter.measure(model, star_shape(model, 5, radius, 0.0));
    const double expected =
        (std::numbers::pi * radius * radius - m.support_area) / (m.flat_area - m.support_area);
    EXPECT_NEAR(m.coefficient, expected, 0.01);
    EXPECT_GT(m.coefficient, previous);
    previous = m.coefficient;
  }
}

TEST(DrapeNodes, ShadowsWithThreeToEightLobesCountTheirLobes) {
  const ClothModel model = specimen();
  const DrapeMeter meter(model, {{0.0, 0.45, 0.0}, 0.09}, kUp);
  for (int lobes = 3; lobes <= 8; ++lobes)
    EXPECT_EQ(meter.measure(model, star_shape(model, lobes, 0.12, 0.12)).nodes, lobes)
        << lobes << " lobes";
}

TEST(DrapeNodes, OutlineCountIgnoresRipplesBelowTheProminence) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> noise(-0.0004, 0.0004);  // m, well below 2 mm
  for (int lobes = 3; lobes <= 8; ++lobes) {
    std::vector<double> r(360);
    for (int k = 0; k < 360; ++k)
      r[k] = 0.12 + 0.015 * std::cos(lobes * k * std::numbers::pi / 180.0 + 0.3) + noise(random);
    EXPECT_EQ(count_outline_nodes(circular_smooth(r, 5), 0.002), lobes) << lobes;
  }
  // A circle (or ripples alone) has no node; a plateau counts once.
  EXPECT_EQ(count_outline_nodes(std::vector<double>(360, 0.1), 0.002), 0);
  std::vector<double> plateau(360, 0.1);
  for (int k = 100; k < 140; ++k) plateau[k] = 0.12;
  EXPECT_EQ(count_outline_nodes(plateau, 0.002), 1);
  // Two maxima, one too shallow: 0.1 (r_max - r_min) decides.
  std::vector<double> two(360, 0.10);
  for (int k = 0; k < 30; ++k) two[k] = 0.15;
  for (int k = 180; k < 190; ++k) two[k] = 0.103;
  EXPECT_EQ(count_outline_nodes(two, 0.002), 1);
}

}  // namespace
}  // namespace drapelab
