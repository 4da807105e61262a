// vbd's offset self-contact keeps the cloth from crossing itself at every frame, at vbd's own step
// and whatever the self-contact stiffness: a strip twisted into a rope by its two ends (scenes/
// twist.yaml) at its stiffness and at 10 and 100 times it, a sheet thrown at 20 m/s onto another
// held by its corners, and a sheet crumpled between two closing plates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "drapelab/contact_model.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/self_intersections.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/sheets.hpp"
#include "layered_cloth.hpp"
#include "scene_audit.hpp"
#include "self_collision/self_contact.hpp"

namespace drapelab {
namespace {

using Audit = fixtures::SceneAudit;
using fixtures::audit_scene;

// scenes/twist.yaml's first solver: ours, vbd at its own step.
Audit twist(const std::vector<std::string>& overrides) {
  return audit_scene(scene::load_scene_file(
      std::filesystem::path(DRAPELAB_SOURCE_DIR) / "scenes" / "twist.yaml", overrides));
}

// The strip at `stiffness` (N/m) for `duration` s: no crossing at any frame, and its layers press
// on each other (it is wound tight enough for the guarantee to matter).
void expect_twist_never_crosses(double stiffness, double duration) {
  SCOPED_TRACE("self-contact stiffness " + std::to_string(stiffness) + " N/m, " +
               std::to_string(duration) + " s");
  const Audit audit = twist({"cloth.self_collision.stiffness=" + std::to_string(stiffness),
                             "duration=" + std::to_string(duration)});
  EXPECT_EQ(audit.result.status, SolverStatus::ok) << audit.result.message;
  EXPECT_EQ(audit.frames, static_cast<int>(std::lround(duration * 30.0)) + 1);
  EXPECT_EQ(audit.most_crossings, 0);
  double contacts = 0.0;
  for (const auto& [name, value] : audit.result.counters)
    if (name == "self_contacts_last") contacts = value;
  EXPECT_GT(contacts, 20.0);
}

// The full scene, 1.5 s, at its stiffness and at 10 and 100 times it: over a minute of CPU (label
// slow).
TEST(IntersectionFree, TheTwistedStripNeverCrossesItselfAtAnyStiffness) {
  for (const double stiffness : {500.0, 5000.0, 50000.0})
    expect_twist_never_crosses(stiffness, 1.5);
}

// Its CI-sized twin: 0.8 s, wound past where the penalty method's layers began to cross (0.6 s),
// at the scene's stiffness and 100 times it.
TEST(IntersectionFreeCi, TheTwistedStripNeverCrossesItself) {
  for (const double stiffness : {500.0, 50000.0}) expect_twist_never_crosses(stiffness, 0.8);
}

// Two 21 x 21 sheets, 0.4 m square, in one cloth: the lower held at its four corners, the upper
// 5 cm above it thrown down at 20 m/s. Each step the upper sheet would move 17 cm, three times the
// gap: it must land on the lower sheet and carry it down, never pass through it.
TEST(IntersectionFree, ASheetThrownAt20MetresPerSecondOntoAnotherLandsOnIt) {
  GridClothSpec lower = fixtures::flat_sheet(21, 0.4, {0.0, 1.0, 0.0}, 0.04);
  GridClothSpec upper = fixtures::flat_sheet(21, 0.4, {0.005, 1.05, 0.005}, 0.04);
  lower.pins = {PinNamed{"corners"}};
  lower.thickness = upper.thickness = 0.003;
  auto model = std::make_shared<const ClothModel>(fixtures::stacked_cloth({lower, upper}));
  SpringDamperSettings settings;
  settings.integrator = Integrator::vbd;
  settings.air_damping = 0.1;
  settings.self_collision.enabled = true;
  settings.self_collision.thickness = 0.003;
  settings.self_collision.stiffness = 1000.0;
  ClothState start{model->rest_positions, Eigen::Matrix3Xd::Zero(3, model->particle_count())};
  const int per_sheet = 21 * 21;
  start.v.rightCols(per_sheet).row(1).setConstant(-20.0);  // m/s, down onto the lower sheet
  SpringDamperSolver solver("ours", model, start, settings);
  const SelfIntersectionCounter audit(model->triangles);
  int most = 0;
  fixtures::run_frames(solver, 0.3, 1.0 / 120.0, 1.0 / 120.0, [&](const ClothState& state) {
    most = std::max(most, audit.count(state.x));
  });
  ASSERT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  EXPECT_EQ(most, 0);
  EXPECT_GT(solver.self_contact_stats()->contacts_total, 0);
  // Every upper particle is still above the lower sheet's middle particle's height band: the
  // upper sheet's mean stays above the lower's.
  const Eigen::Matrix3Xd& x = solver.state().x;
  EXPECT_GT(x.rightCols(per_sheet).row(1).mean(), x.leftCols(per_sheet).row(1).mean());
}

// A sheet on a floor between two upright plates that close from 0.5 m to 0.16 m apart in 1 s:
// the sheet buckles and folds into layers pressed together.
const std::string kCrumple = R"(name: crumple_test
duration: 1.4
frame_rate: 30
cloth:
  shape: grid
  size: [0.4, 0.4]
  resolution: [25, 25]
  plane: xz
  center: [0, 0.004, 0]
  mass: 0.04
  thickness: 0.003
  perturbation: 0.002
  springs:
    stretch: {ks: 600, kd: 0.01}
    shear:   {ks: 60,  kd: 0.005}
    bend:    {ks: 0.2, kd: 0.0002}
  air_damping: 0.5
  self_collision: {enabled: true, thickness: 0.003, stiffness: 1000, damping: 0.002, friction: 0.3}
colliders:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 1, 0], friction: 0.4}
  - name: left
    type: box
    half_extents: [0.02, 0.1, 0.3]
    motion:
      keyframes:
        - {t: 0.0, center: [-0.25, 0.1, 0]}
        - {t: 1.0, center: [-0.08, 0.1, 0]}
  - name: right
    type: box
    half_extents: [0.02, 0.1, 0.3]
    motion:
      keyframes:
        - {t: 0.0, center: [0.25, 0.1, 0]}
        - {t: 1.0, center: [0.08, 0.1, 0]}
contact: {stiffness: 3000, damping: 0.2, friction: 0.4}
solvers:
  - {name: ours, type: spring_damper, integrator: vbd}
)";

TEST(IntersectionFree, ASheetCrumpledBetweenClosingPlatesNeverCrossesItself) {
  const Audit audit = audit_scene(scene::load_scene_text(kCrumple, "crumple_test.yaml", {}));
  EXPECT_EQ(audit.result.status, SolverStatus::ok) << audit.result.message;
  EXPECT_EQ(audit.frames, 43);
  EXPECT_EQ(audit.most_crossings, 0);
}

}  // namespace
}  // namespace drapelab
