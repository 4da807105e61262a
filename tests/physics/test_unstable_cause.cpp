// What an unstable run's message says acted in its last step (integrators/unstable_cause.hpp):
// each kind of contact with the colliders or particles involved, from what the step's force
// evaluation saw. End to end, through a run: tests/cli/test_hostile_scenes_cli.cpp.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "drapelab/grid_cloth.hpp"
#include "fixtures/sheets.hpp"
#include "integrators/unstable_cause.hpp"

namespace drapelab {
namespace {

Collider plane_named(const std::string& name) {
  Collider c;
  c.name = name;
  c.shape = ColliderShape::plane;
  return c;
}

Collider box_named(const std::string& name) {
  Collider c;
  c.name = name;
  c.shape = ColliderShape::box;
  return c;
}

class UnstableCause : public ::testing::Test {
 protected:
  // A 5 x 5 sheet of thickness 0.004 m.
  ClothModel model = [] {
    GridClothSpec spec = fixtures::flat_sheet(5, 1.0, Eigen::Vector3d(0, 1, 0), 0.1);
    spec.thickness = 0.004;
    return build_grid_cloth(spec);
  }();
  ContactModel colliders{{plane_named("floor"), box_named("table")}, {}, 0.004};
  std::vector<ColliderContactTotals> totals = std::vector<ColliderContactTotals>(2);
  std::vector<EdgeContactTotals> edges = std::vector<EdgeContactTotals>(2);
};

TEST_F(UnstableCause, NothingButSpringsGravityAndAirSaysNothing) {
  EXPECT_EQ(unstable_step_cause(model, {}, 3), "");
  StepContactsSeen seen;
  seen.colliders = &colliders;
  seen.totals = &totals;  // no collider touched
  seen.self_contacts = 0;
  EXPECT_EQ(unstable_step_cause(model, seen, 3), "");
}

TEST_F(UnstableCause, NamesEachColliderTouchedAndWhetherItHoldsParticlesInside) {
  totals[0].contact_count = 25;
  totals[0].max_depth = 1.004;
  totals[1].contact_count = 7;  // 4 particles and 3 edge contacts
  totals[1].max_depth = 0.001;
  edges[1].contact_count = 3;
  StepContactsSeen seen;
  seen.colliders = &colliders;
  seen.totals = &totals;
  seen.edge_totals = &edges;
  EXPECT_EQ(
      unstable_step_cause(model, seen, 3),
      " In that step: collider contacts with plane 'floor' (25 particles, the deepest 1.004 m "
      "into its contact, deeper than the cloth's thickness 0.004 m: inside the collider) "
      "and box 'table' (4 particles and 3 edge contacts, the deepest 0.001 m into its "
      "contact).");
}

TEST_F(UnstableCause, NamesSelfContactsAndTheConstraintsAndDragsOnTheParticle) {
  DistanceConstraints constraints;
  DistanceConstraint soft;
  soft.a = 3;
  soft.mode = ConstraintMode::soft;
  DistanceConstraint rope;  // between particles 7 and 3: ends on 3 too
  rope.a = 7;
  rope.b.kind = ConstraintEnd::Kind::particle;
  rope.b.particle = 3;
  rope.mode = ConstraintMode::rope;
  DistanceConstraint elsewhere;  // on particle 9 only
  elsewhere.a = 9;
  DistanceConstraint drag;  // the scene's drags follow its constraints
  drag.b.kind = ConstraintEnd::Kind::drag;
  auto track = std::make_shared<DragTrack>();
  track->particle = 3;
  drag.b.drag = track;
  constraints.list = {soft, elsewhere, rope, drag};
  StepContactsSeen seen;
  seen.self_contacts = 12;
  seen.constraints = &constraints;
  EXPECT_EQ(unstable_step_cause(model, seen, 3),
            " In that step: 12 self-contacts and particle 3 is an end of constraints.0 (soft), "
            "constraints.2 (rope) and interactions.0 (a drag).");
  EXPECT_EQ(unstable_step_cause(model, seen, 9),
            " In that step: 12 self-contacts and particle 9 is an end of constraints.1 (hard).");
}

}  // namespace
}  // namespace drapelab
