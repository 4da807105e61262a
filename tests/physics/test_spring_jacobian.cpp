// The spring Jacobians implicit Euler assembles: the exact one against finite differences of the
// force, stretched and compressed, and the semidefinite form the solve uses.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "forces/spring_force.hpp"
#include "forces/spring_jacobian.hpp"

namespace drapelab {
namespace {

// Central differences of the spring force on particle 1 w.r.t. x1 (column by column), step eps (m
// or m/s).
template <typename Force>
Eigen::Matrix3d central_difference(const Force& force, const Eigen::Vector3d& at, double eps) {
  Eigen::Matrix3d jacobian;
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector3d plus = at, minus = at;
    plus[c] += eps;
    minus[c] -= eps;
    jacobian.col(c) = (force(plus) - force(minus)) / (2.0 * eps);
  }
  return jacobian;
}

double relative_error(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return (a - b).norm() / b.norm();
}

TEST(SpringJacobian, MatchesFiniteDifferencesStretchedAndCompressed) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double ks = 350.0, kd = 0.7;  // N/m, N*s/m
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Vector3d x1(u(random), u(random), u(random)), x2(u(random), u(random), u(random));
    const Eigen::Vector3d v1(u(random), u(random), u(random)), v2(u(random), u(random), u(random));
    // Alternate stretched and compressed springs.
    const double rest = (x1 - x2).norm() * (trial % 2 ? 1.3 : 0.7);
    const SpringJacobian j = spring_jacobian_exact(x1, x2, v1, v2, ks, kd, rest);
    const double eps = 1e-6 * (x1 - x2).norm();
    const Eigen::Matrix3d by_x1 = central_difference(
        [&](const Eigen::Vector3d& p) { return damped_spring_force(p, x2, v1, v2, ks, kd, rest); },
        x1, eps);
    const Eigen::Matrix3d by_x2 = central_difference(
        [&](const Eigen::Vector3d& p) { return damped_spring_force(x1, p, v1, v2, ks, kd, rest); },
        x2, eps);
    const Eigen::Matrix3d by_v1 = central_difference(
        [&](const Eigen::Vector3d& p) { return damped_spring_force(x1, x2, p, v2, ks, kd, rest); },
        v1, 1e-6);
    EXPECT_LT(relative_error(j.dforce_dx, by_x1), 1e-6) << "trial " << trial;
    EXPECT_LT(relative_error(-j.dforce_dx, by_x2), 1e-6) << "trial " << trial;
    EXPECT_LT(relative_error(j.dforce_dv, by_v1), 1e-6) << "trial " << trial;
  }
}

TEST(SpringJacobian, SolveFormIsTheElasticPartWhenStretchedAndSemidefiniteWhenCompressed) {
  const Eigen::Vector3d x1(0.3, 0.1, -0.2), x2(-0.1, 0.4, 0.25), zero = Eigen::Vector3d::Zero();
  const double length = (x1 - x2).norm();
  // Stretched, no damper: identical to the exact Jacobian.
  const SpringJacobian exact = spring_jacobian_exact(x1, x2, zero, zero, 200.0, 0.0, 0.8 * length);
  const SpringJacobian solve = spring_jacobian_for_solve(x1, x2, 200.0, 0.0, 0.8 * length);
  EXPECT_LT((exact.dforce_dx - solve.dforce_dx).norm(), 1e-12 * exact.dforce_dx.norm());
  // Compressed: the exact form has a positive eigenvalue (across the spring); the solve form none.
  const SpringJacobian compressed_exact =
      spring_jacobian_exact(x1, x2, zero, zero, 200.0, 0.0, 1.5 * length);
  const SpringJacobian compressed = spring_jacobian_for_solve(x1, x2, 200.0, 0.3, 1.5 * length);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(compressed_exact.dforce_dx)
                .eigenvalues()
                .maxCoeff(),
            1.0);
  EXPECT_LE(
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(compressed.dforce_dx).eigenvalues().maxCoeff(),
      1e-12);
  EXPECT_LE(
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(compressed.dforce_dv).eigenvalues().maxCoeff(),
      1e-12);
  EXPECT_LT((compressed.dforce_dx - compressed.dforce_dx.transpose()).norm(), 1e-12);
}

}  // namespace
}  // namespace drapelab
