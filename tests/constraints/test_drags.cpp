// Drags (interactions:, and the viewer's mouse): a particle pulled by a spring of rest length 0
// toward a moving target. In zero gravity a free sheet's momentum changes by the drag's impulse
// alone while it pulls, not at all before its first keyframe (the run is the undragged run bit for
// bit) or after its release, and the sheet follows the target; under every integrator.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "drapelab/distance_constraints.hpp"
#include "drapelab/drag_track.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

constexpr int kCentre = 12;         // the middle particle of a 5 x 5 sheet
constexpr double kStiffness = 2.0;  // N/m
constexpr double kStep = 1e-4;      // s
constexpr double kPressed = 0.05;   // s: the first keyframe
constexpr double kReleased = 0.5;   // s: the last keyframe

std::shared_ptr<const DistanceConstraints> drag_of_centre(const Eigen::Vector3d& start) {
  auto track = std::make_shared<DragTrack>();
  track->particle = kCentre;
  track->stiffness = kStiffness;
  track->damping = 0.01;
  // Pulled 0.3 m sideways and up, along a straight path over 0.45 s.
  track->keyframes = {{kPressed, start}, {kReleased, start + Eigen::Vector3d(0.3, 0.2, 0.0)}};
  auto constraints = std::make_shared<DistanceConstraints>();
  DistanceConstraint drag;
  drag.a = kCentre;
  drag.b.kind = ConstraintEnd::Kind::drag;
  drag.b.drag = track;
  drag.length = 0.0;
  drag.mode = ConstraintMode::soft;
  drag.stiffness = kStiffness;
  drag.damping = 0.01;
  constraints->list.push_back(drag);
  return constraints;
}

Eigen::Vector3d momentum(const ClothModel& model, const ClothState& state) {
  return state.v * model.mass;
}

TEST(Drags, MomentumChangesByTheDragsImpulseOnly) {
  const GridClothSpec spec =
      fixtures::flat_sheet(5, 0.4, Eigen::Vector3d(0.0, 1.0, 0.0), /*mass=*/0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  for (Integrator integrator : all_integrators()) {
    SCOPED_TRACE(integrator_name(integrator));
    SpringDamperSettings settings;
    settings.integrator = integrator;
    settings.gravity = Eigen::Vector3d::Zero();
    SpringDamperSolver free("free", model, initial, settings);
    settings.constraints = drag_of_centre(initial.x.col(kCentre));
    SpringDamperSolver dragged("dragged", model, initial, settings);
    const DistanceConstraint& drag = settings.constraints->list.front();
    Eigen::Vector3d impulse = Eigen::Vector3d::Zero();  // N*s: the drag's, step by step
    double worst_during = 0.0, worst_after = 0.0;       // N*s
    Eigen::Vector3d released_momentum = Eigen::Vector3d::Zero(), after_release = released_momentum;
    const int steps = static_cast<int>(0.8 / kStep + 0.5);
    for (int k = 0; k < steps; ++k) {
      const double t = dragged.state().time;
      if (k * kStep < kPressed - 0.5 * kStep) {
        free.step(kStep);
        dragged.step(kStep);
        ASSERT_TRUE(free.state().x == dragged.state().x) << "step " << k;  // bit for bit
        continue;
      }
      // The drag's force at the step's start (what the explicit Euler pair applies).
      Eigen::Matrix3Xd force = Eigen::Matrix3Xd::Zero(3, model->particle_count());
      settings.constraints->add_soft_forces(t, dragged.state().x, dragged.state().v, force,
                                            nullptr);
      dragged.step(kStep);
      ASSERT_EQ(dragged.status(), SolverStatus::ok) << dragged.message();
      const Eigen::Vector3d p = momentum(*model, dragged.state());
      if (DistanceConstraints::acts(drag, t)) {
        impulse += kStep * force.col(kCentre);
        worst_during = std::max(worst_during, (p - impulse).norm());
        released_momentum = p;
      } else if (t > kReleased + 1.5 * kStep) {
        // From the second step after release: the two-level schemes (Verlet, leapfrog) finish
        // the last pulled step's force in the first.
        worst_after = std::max(worst_after, (p - after_release).norm());
      } else {
        after_release = p;
      }
    }
    // The sheet's internal forces cancel: after release its momentum is constant, to rounding
    // for the explicit schemes and to the linear solve's tolerance for the implicit ones; while
    // pulled, the Euler pair's is the sum of the drag's start-of-step impulses exactly, the other
    // schemes' within their own evaluation points of the force (measured 2 to 3e-4 of it).
    const bool implicit = integrator == Integrator::implicit_euler || integrator == Integrator::vbd;
    EXPECT_LT(worst_after / impulse.norm(), implicit ? 1e-6 : 1e-10);
    const bool explicit_pair =
        integrator == Integrator::symplectic_euler || integrator == Integrator::explicit_euler;
    EXPECT_LT(worst_during / impulse.norm(), explicit_pair ? 1e-12 : 1e-2);
    // The sheet followed the target: its centre moved toward where the drag let go.
    const Eigen::Vector3d centre_of_mass = dragged.state().x * model->mass / model->total_mass();
    const Eigen::Vector3d start_of_mass = initial.x * model->mass / model->total_mass();
    EXPECT_GT((centre_of_mass - start_of_mass).dot(Eigen::Vector3d(0.3, 0.2, 0.0).normalized()),
              0.05);
    RecordProperty(std::string(integrator_name(integrator)) + "_impulse_error",
                   std::to_string(worst_during / impulse.norm()));
  }
}

}  // namespace
}  // namespace drapelab
