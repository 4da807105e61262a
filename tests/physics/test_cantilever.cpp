// docs/validation.md, "The Peirce cantilever": a cotton strip pinned on a ledge
// (scenes/cantilever.yaml) droops over its edge; the overhang O at which the chord from the edge to
// the tip makes 41.5 degrees gives the bending length c = O / 2, which for an inextensible strip is
// (B / W)^(1/3). Our solver by implicit Euler at 1/120 s (the scene's ours_implicit: it rests at
// the exact statics of the model; vbd at 1/120 s does not come to rest on this strip,
// docs/validation.md), on a short strip (two pinned cells behind the edge: the rest of the ledge's
// part changes nothing). Label `drape` with the other full drape runs: about 15 s in Release.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "fixtures/cantilever_run.hpp"
#include "fixtures/measured.hpp"

namespace drapelab {
namespace {

std::string number(double value) { return fixtures::measured(value, 5); }

fixtures::CantileverSetup strip(const std::string& solver, double spacing) {
  fixtures::CantileverSetup setup;
  setup.scene_file = std::string(DRAPELAB_SOURCE_DIR) + "/scenes/cantilever.yaml";
  setup.solver = solver;
  setup.spacing = spacing;
  return setup;
}

// Records c, Peirce's c, O, the angle and the spacing under `prefix`.
void record(const std::string& prefix, const fixtures::CantileverResult& r) {
  testing::Test::RecordProperty(prefix + "_c_m", number(r.bending_length));
  testing::Test::RecordProperty(prefix + "_peirce_c_m", number(r.peirce_bending_length));
  testing::Test::RecordProperty(prefix + "_c_over_expected",
                                number(r.bending_length / r.expected_bending_length));
  testing::Test::RecordProperty(prefix + "_converged", r.converged ? "yes" : "no");
  testing::Test::RecordProperty(prefix + "_overhang_m", number(r.overhang));
  testing::Test::RecordProperty(prefix + "_angle_deg", number(r.angle_deg));
  testing::Test::RecordProperty(prefix + "_spacing_m", number(r.spacing));
  testing::Test::RecordProperty(prefix + "_width_m", number(r.width));
  std::string runs;  // overhang (m) and angle (deg) of every run, in order
  for (const fixtures::CantileverRun& run : r.runs)
    runs += (runs.empty() ? "" : " ") + number(run.overhang) + ":" + number(run.angle_deg);
  testing::Test::RecordProperty(prefix + "_runs", runs);
}

// The measurement itself: converged to the angle, at rest, and the strip whole.
void expect_measured(const fixtures::CantileverResult& r) {
  EXPECT_TRUE(r.converged) << r.error;
  EXPECT_NEAR(r.angle_deg, fixtures::kPeirceAngleDeg, 0.2);
  EXPECT_LT(r.settle_deg, 0.05) << "the tip still moves at the end of the run";
  EXPECT_GT(r.chord_ratio, 0.8);
  EXPECT_LT(r.chord_ratio, 1.01);
}

TEST(Cantilever, PeircesFormulaAgreesWithHalfTheOverhangAtFortyOnePointFiveDegrees) {
  const double theta = fixtures::kPeirceAngleDeg * std::acos(-1.0) / 180.0;
  const double ratio = fixtures::peirce_bending_length(1.0, theta);
  EXPECT_NEAR(ratio, 0.5, 0.01);  // 0.5093
  RecordProperty("peirce_c_over_overhang", number(ratio));
}

// Two spacings near 5 mm and 2.5 mm (the search keeps a whole number of square cells over the
// edge, so the spacing it ends at is recorded). The bending length must be the fabric's within 5 %
// at both: measured 0.992 of (B / W)^(1/3) at 4.9 mm and 1.000 at 2.5 mm. Two properties of the
// model make it so (docs/validation.md): the hinges on the ledge's edge count only their free
// triangle (a clamped edge), which makes the clamp second order in the spacing, and the continuum
// grid turns its diagonal every row, so the strip cannot lower its bending energy by twisting. The
// search stops within 0.2 degree of 41.5, about 0.3 % of c: the finer strip may not be further off
// than the coarser by more than that.
TEST(Cantilever, ContinuumBendingLengthIsTheFabricsWithinFivePercentAtTwoSpacings) {
  std::string error;
  const double expected = fixtures::expected_bending_length(strip("ours_implicit", 0.005), &error);
  ASSERT_TRUE(error.empty()) << error;
  RecordProperty("expected_c_m", number(expected));  // 0.019867
  double coarse_error = 0.0;
  for (const double spacing : {0.005, 0.0025}) {
    SCOPED_TRACE("spacing " + number(spacing) + " m");
    const fixtures::CantileverResult r =
        fixtures::measure_cantilever(strip("ours_implicit", spacing), fixtures::simulate_strip);
    const bool coarse = spacing > 0.004;
    const std::string prefix = std::string("continuum_") + (coarse ? "coarse" : "fine");
    record(prefix, r);
    expect_measured(r);
    EXPECT_NEAR(r.spacing, spacing, 0.1 * spacing);
    // Peirce's general relation at the measured angle is within 2 % of O / 2 near 41.5 degrees.
    EXPECT_NEAR(r.peirce_bending_length, r.bending_length, 0.025 * r.bending_length);
    const double relative = std::fabs(1.0 - r.bending_length / expected);
    RecordProperty(prefix + "_error", number(relative));
    EXPECT_LT(relative, 0.05) << "c " << r.bending_length << " m against " << expected << " m";
    if (coarse)
      coarse_error = relative;
    else
      EXPECT_LT(relative, coarse_error + 0.005) << "the finer strip must not be further off";
  }
}

// The spring network of the same cotton preset: recorded, not asserted. Its bend springs store
// energy as the fourth power of the hinge angle, so its bending length depends on the spacing and
// the search may end at a spacing further from the one asked for (recorded beside c).
TEST(Cantilever, SpringsBendingLengthIsMeasured) {
  for (const double spacing : {0.005, 0.0025}) {
    SCOPED_TRACE("spacing " + number(spacing) + " m");
    const fixtures::CantileverResult r =
        fixtures::measure_cantilever(strip("ours_springs", spacing), fixtures::simulate_strip);
    record(std::string("springs_") + (spacing > 0.004 ? "coarse" : "fine"), r);
    EXPECT_TRUE(r.error.empty() || r.converged) << r.error;
  }
}

}  // namespace
}  // namespace drapelab
