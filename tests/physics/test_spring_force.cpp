// The damped spring kernel: the formula, Newton's third law, energy gradient, and that damping
// never adds energy.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "forces/spring_force.hpp"

namespace drapelab {
namespace {

TEST(SpringForce, MatchesTheFormulaForChosenValues) {
  // x1 - x2 = (3, 4, 0): length 5, direction (0.6, 0.8, 0). Rest 4, ks 10: elastic 10 N.
  // v1 - v2 = (1, 2, 3): closing speed (1, 2, 3).(0.6, 0.8, 0) = 2.2 m/s; kd 0.5: viscous 1.1 N.
  const Eigen::Vector3d x1(4, 6, 1), x2(1, 2, 1), v1(1, 1, 1), v2(0, -1, -2);
  const Eigen::Vector3d f1 = damped_spring_force(x1, x2, v1, v2, 10.0, 0.5, 4.0);
  const Eigen::Vector3d expected = -(10.0 + 1.1) * Eigen::Vector3d(0.6, 0.8, 0.0);
  EXPECT_NEAR((f1 - expected).norm(), 0.0, 1e-12);
}

TEST(SpringForce, SecondParticleGetsTheOppositeForce) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector3d x1(u(random), u(random), u(random)), x2(u(random), u(random), u(random));
    const Eigen::Vector3d v1(u(random), u(random), u(random)), v2(u(random), u(random), u(random));
    const double ks = 100 * (u(random) + 1.5), kd = u(random) + 1.0, rest = 0.5 * (u(random) + 1.5);
    const Eigen::Vector3d f1 = damped_spring_force(x1, x2, v1, v2, ks, kd, rest);
    const Eigen::Vector3d f2 = damped_spring_force(x2, x1, v2, v1, ks, kd, rest);
    EXPECT_NEAR((f1 + f2).norm(), 0.0, 1e-12 * f1.norm() + 1e-15);
    // Central force: parallel to x1 - x2.
    EXPECT_NEAR(f1.cross(x1 - x2).norm(), 0.0, 1e-12 * f1.norm() * (x1 - x2).norm() + 1e-15);
  }
}

TEST(SpringForce, ElasticForceIsMinusTheEnergyGradient) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d x1(u(random), u(random), u(random)), x2(u(random), u(random), u(random));
    const double ks = 50.0 * (u(random) + 2.0), rest = 0.3 * (u(random) + 2.0);
    const Eigen::Vector3d force = damped_spring_force(x1, x2, zero, zero, ks, 0.0, rest);
    Eigen::Vector3d gradient;
    const double step = 1e-6;  // m, central differences: error O(step^2)
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d plus = x1, minus = x1;
      plus[c] += step;
      minus[c] -= step;
      gradient[c] =
          (spring_energy(plus, x2, ks, rest) - spring_energy(minus, x2, ks, rest)) / (2 * step);
    }
    EXPECT_LT((force + gradient).norm(), 1e-6 * (1.0 + force.norm()));
  }
}

TEST(SpringForce, DampingNeverAddsEnergy) {
  // The viscous part's power on the pair, f1.v1 + f2.v2 = f1.(v1 - v2), is never positive.
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector3d x1(u(random), u(random), u(random)), x2(u(random), u(random), u(random));
    const Eigen::Vector3d v1(u(random), u(random), u(random)), v2(u(random), u(random), u(random));
    const double rest = (x1 - x2).norm();  // at rest length the force is purely viscous
    const Eigen::Vector3d f1 =
        damped_spring_force(x1, x2, v1, v2, 1000.0, 2.0 * (u(random) + 1.0), rest);
    EXPECT_LE(f1.dot(v1 - v2), 1e-12);
  }
}

TEST(SpringForce, ZeroLengthSpringExertsNoForceInsteadOfNaN) {
  const Eigen::Vector3d p(1, 2, 3), v(1, 0, 0);
  const Eigen::Vector3d f = damped_spring_force(p, p, v, -v, 100.0, 1.0, 0.1);
  EXPECT_TRUE(f.allFinite());
  EXPECT_EQ(f.norm(), 0.0);
}

TEST(SpringForce, EnergyIsHalfKTimesExtensionSquared) {
  EXPECT_DOUBLE_EQ(spring_energy(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1.5, 0), 200.0, 1.0),
                   0.5 * 200.0 * 0.25);
}

}  // namespace
}  // namespace drapelab
