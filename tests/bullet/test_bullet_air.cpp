// Air in Bullet's two cloths: a sheet falling face-on reaches the terminal speed
// sqrt(2 m g / (rho C_d A)), in the classic cloth through Bullet's own two-sided lift-and-drag face
// model, in the deformable world through our force applied to its nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "drapelab/air.hpp"
#include "drapelab/bullet/bullet_deformable_solver.hpp"
#include "drapelab/bullet/bullet_softbody_solver.hpp"
#include "drapelab/grid_cloth.hpp"

namespace drapelab {
namespace {

TEST(BulletAir, AFaceOnSheetReachesItsTerminalSpeed) {
  GridClothSpec spec;
  spec.nx = spec.ny = 9;
  spec.size = {0.5, 0.5};
  spec.plane = GridPlane::xz;
  spec.center = {0.0, 10.0, 0.0};
  spec.areal_density = 0.08;  // kg/m^2: 20 g, each node's mass in proportion to its area
  spec.stretch = {200.0, 0.02};
  spec.shear = {20.0, 0.002};
  spec.bend = {2.0, 0.0002};
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  AirSettings air;
  air.enabled = true;
  air.density = 1.2;
  air.drag = 1.0;
  const double terminal = std::sqrt(2.0 * model->total_mass() * 9.81 / (1.2 * 1.0 * 0.25));  // m/s
  bullet::BulletSoftBodyOptions classic;
  classic.dt = 1e-4;
  classic.margin = classic.voxel_size = 0.01;
  classic.air = air;
  bullet::BulletDeformableOptions deformable;
  deformable.dt = 1e-4;
  deformable.margin = deformable.voxel_size = 0.01;
  deformable.air = air;
  const std::unique_ptr<Solver> solvers[] = {
      bullet::make_bullet_softbody_solver("classic", model, initial, {}, classic),
      bullet::make_bullet_deformable_solver("deformable", model, initial, {}, deformable)};
  for (const auto& solver : solvers) {
    SCOPED_TRACE(solver->name());
    for (int k = 0; k < 10000; ++k) solver->step(1e-4);  // 1 s, eight time constants v_t / g
    ASSERT_EQ(solver->status(), SolverStatus::ok) << solver->message();
    const double speed = -solver->state().v.row(1).mean();
    EXPECT_NEAR(speed / terminal, 1.0, 0.01);
    RecordProperty(solver->name() + "_terminal_over_theory", std::to_string(speed / terminal));
  }
}

}  // namespace
}  // namespace drapelab
