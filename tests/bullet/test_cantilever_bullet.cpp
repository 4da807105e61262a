// docs/validation.md, "The Peirce cantilever", for Bullet's two cloths: the bending length
// c = O / 2 at which the strip of scenes/cantilever.yaml droops 41.5 degrees over the ledge, with
// about 5 mm particles. Both run the springs derived from the cotton preset's continuum (bend
// springs whose energy grows as the fourth power of the hinge angle), each at its automatic step
// (the classic cloth's where its stiffness mapping holds, ks w h^2 = 0.1). Measured and recorded;
// asserted only what must hold: the search ends, c is finite and positive, and the strip hangs
// from its pins without stretching (it did not fall). About 30 s in Release.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "fixtures/cantilever_run.hpp"
#include "fixtures/measured.hpp"

namespace drapelab {
namespace {

std::string number(double value) { return fixtures::measured(value, 5); }

void measure(const std::string& solver) {
  fixtures::CantileverSetup setup;
  setup.scene_file = std::string(DRAPELAB_SOURCE_DIR) + "/scenes/cantilever.yaml";
  setup.solver = solver;
  setup.spacing = 0.005;
  const fixtures::CantileverResult r =
      fixtures::measure_cantilever(setup, fixtures::simulate_strip);
  testing::Test::RecordProperty("expected_c_m", number(r.expected_bending_length));
  testing::Test::RecordProperty("c_m", number(r.bending_length));
  testing::Test::RecordProperty("peirce_c_m", number(r.peirce_bending_length));
  testing::Test::RecordProperty("c_over_expected",
                                number(r.bending_length / r.expected_bending_length));
  testing::Test::RecordProperty("converged", r.converged ? "yes" : "no");
  testing::Test::RecordProperty("overhang_m", number(r.overhang));
  testing::Test::RecordProperty("angle_deg", number(r.angle_deg));
  testing::Test::RecordProperty("spacing_m", number(r.spacing));
  testing::Test::RecordProperty("settle_deg", number(r.settle_deg));
  std::string runs;  // overhang (m) and angle (deg) of every run, in order
  for (const fixtures::CantileverRun& run : r.runs)
    runs += (runs.empty() ? "" : " ") + number(run.overhang) + ":" + number(run.angle_deg);
  testing::Test::RecordProperty("runs", runs);

  // Every run stayed ok (a run's error is the only error a search that ran out of runs does not
  // have), and the strip hangs from the ledge: below the edge, above the vertical, as long as it
  // is.
  ASSERT_FALSE(r.runs.empty());
  for (const fixtures::CantileverRun& run : r.runs) EXPECT_TRUE(run.error.empty()) << run.error;
  EXPECT_TRUE(std::isfinite(r.bending_length));
  EXPECT_GT(r.bending_length, 0.0);
  EXPECT_GT(r.angle_deg, 0.0);
  EXPECT_LT(r.angle_deg, 90.0);
  EXPECT_GT(r.chord_ratio, 0.5);
  EXPECT_LT(r.chord_ratio, 1.05);
}

TEST(BulletCantilever, ClassicClothBendingLengthIsMeasured) { measure("bullet_classic"); }

TEST(BulletCantilever, DeformableClothBendingLengthIsMeasured) { measure("bullet_deformable"); }

}  // namespace
}  // namespace drapelab
