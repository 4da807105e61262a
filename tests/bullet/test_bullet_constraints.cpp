// Distance constraints in Bullet's two cloths: a hard chain holds its lengths while it swings (the
// bridge projects the nodes after every substep), and a soft constraint's static sag is Hooke's
// (its force kicks the nodes before every substep).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/grid_cloth.hpp"
#include "fixtures/chains.hpp"
#include "fixtures/constraint_ends.hpp"

namespace drapelab {
namespace {

// `count` beads of 20 g, the first pinned, with no spring force.
std::shared_ptr<const ClothModel> beads(int count) {
  return std::make_shared<const ClothModel>(build_grid_cloth(fixtures::beads(count, 0.02, true)));
}

using fixtures::particle_end;

// Both Bullet cloths for `model` from `initial`, with `constraints`.
std::unique_ptr<Solver> make(SolverType type, std::shared_ptr<const ClothModel> model,
                             const ClothState& initial,
                             std::shared_ptr<const DistanceConstraints> constraints) {
  if (type == SolverType::bullet_softbody) {
    bullet::BulletSoftBodyOptions options;
    options.dt = 1e-4;
    options.margin = options.voxel_size = 0.005;
    options.constraints = std::move(constraints);
    return bullet::make_bullet_softbody_solver("classic", std::move(model), initial, {}, options);
  }
  bullet::BulletDeformableOptions options;
  options.dt = 1e-4;
  options.margin = options.voxel_size = 0.005;
  options.constraints = std::move(constraints);
  return bullet::make_bullet_deformable_solver("deformable", std::move(model), initial, {},
                                               options);
}

// Four free beads on 10 cm hard links below a pinned one, the chain released horizontal.
TEST(BulletConstraints, HardChainHoldsItsLengthsWhileItSwings) {
  const int n = 5;
  auto model = beads(n);
  ClothState initial;
  initial.x.resize(3, n);
  initial.v = Eigen::Matrix3Xd::Zero(3, n);
  for (int i = 0; i < n; ++i) initial.x.col(i) = Eigen::Vector3d(0.1 * i, 1.0, 0.0);
  auto constraints = std::make_shared<DistanceConstraints>();
  for (int i = 1; i < n; ++i) {
    DistanceConstraint link;
    link.a = i;
    link.b = particle_end(i - 1);
    link.length = 0.1;
    constraints->list.push_back(link);
  }
  for (SolverType type : {SolverType::bullet_softbody, SolverType::bullet_deformable}) {
    SCOPED_TRACE(solver_type_name(type));
    const auto solver = make(type, model, initial, constraints);
    double worst = 0.0, lowest = 1.0;
    for (int k = 0; k < 8000; ++k) {  // 0.8 s
      solver->step(1e-4);
      ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
      worst = std::max(worst, constraints->largest_error(solver->state().time, solver->state().x));
      lowest = std::min(lowest, solver->state().x.row(1).minCoeff());
    }
    EXPECT_LE(worst, 1e-6);
    EXPECT_LT(lowest, 0.7);  // m: it swung down
  }
}

// A bead on a 20 N/m soft constraint below the pinned one settles m g / k below its length.
TEST(BulletConstraints, SoftConstraintSagIsHookes) {
  auto model = beads(2);
  ClothState initial;
  initial.x.resize(3, 2);
  initial.v = Eigen::Matrix3Xd::Zero(3, 2);
  initial.x.col(0) = Eigen::Vector3d(0.0, 1.0, 0.0);
  initial.x.col(1) = Eigen::Vector3d(0.0, 0.7, 0.0);
  auto constraints = std::make_shared<DistanceConstraints>();
  DistanceConstraint spring;
  spring.a = 1;
  spring.b = particle_end(0);
  spring.length = 0.3;
  spring.mode = ConstraintMode::soft;
  spring.stiffness = 20.0;
  spring.damping = 0.2;
  constraints->list.push_back(spring);
  const double sag = 0.02 * 9.81 / 20.0;  // m
  for (SolverType type : {SolverType::bullet_softbody, SolverType::bullet_deformable}) {
    SCOPED_TRACE(solver_type_name(type));
    const auto solver = make(type, model, initial, constraints);
    for (int k = 0; k < 30000; ++k) solver->step(1e-4);  // 3 s: the bob decays as e^-5t
    ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
    const double extension = 1.0 - solver->state().x(1, 1) - 0.3;
    EXPECT_NEAR(extension / sag, 1.0, 1e-3) << "extension " << extension << " m";
  }
}

}  // namespace
}  // namespace drapelab
