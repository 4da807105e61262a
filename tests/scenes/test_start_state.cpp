// Where the cloth starts (docs/scene-reference.md, "Where the cloth starts"): a cloth that starts
// inside or through a collider, and a self-collision thickness the cloth's edges break, are errors
// at the key that causes them; a start in contact that is meant (resting within the thickness, a
// pin carried inside a body) loads. One table row per case of the reliability review (issue 41).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fixtures/scene_cases.hpp"
#include "fixtures/scene_text.hpp"

namespace {

using namespace drapelab::fixtures;  // fixtures/scene_cases.hpp, scene_text.hpp
using drapelab::scene::LoadResult;
using drapelab::scene::StartInside;

constexpr const char* kFile = "start.yaml";

// A level 1 m sheet of 11 x 11 particles (0.1 m apart) 1 m above a floor. Line numbers matter.
const std::string kSheet =
    "name: start\n"                        //  1
    "duration: 0.1\n"                      //  2
    "cloth:\n"                             //  3
    "  resolution: [11, 11]\n"             //  4
    "  size: [1, 1]\n"                     //  5
    "  center: [0, 1, 0]\n"                //  6
    "  mass: 0.1\n"                        //  7
    "  thickness: 0.004\n"                 //  8
    "colliders:\n"                         //  9
    "  - name: floor\n"                    // 10
    "    type: plane\n"                    // 11
    "    point: [0, 0, 0]\n"               // 12
    "    normal: [0, 1, 0]\n"              // 13
    "solvers: [{type: spring_damper}]\n";  // 14

LoadResult load_start(const std::string& text, StartInside start = StartInside::error) {
  return drapelab::scene::load_scene_text(text, kFile, {}, start);
}

std::vector<BadScene> bad_starts() {
  const std::string cloth_at = "The cloth (start.yaml:3) starts ";
  return {
      {"PlaneNormalPointingDownUnderAFallingSheet",
       replace_line(13, "    normal: [0, -1, 0]"),
       10,
       "colliders.0",
       {"(plane 'floor': a half-space, solid where y > 0, the side its normal [0, -1, 0] points "
        "away from)",
        "holds 121 of the cloth's 121 free particles at t = 0",
        "particle 0 (grid i=0, j=0), 1 m inside", cloth_at + "inside it",
        "turn the plane's normal towards the cloth", "--allow-start-inside"}},
      {"PlaneTurnedNinetyDegreesThroughTheSheet",
       insert_lines(13, "    rotation: [0, 0, 90]"),
       10,
       "colliders.0",
       // Turned about z, the normal +y becomes -x: x > 0 is solid, the five columns right of the
       // middle one (which lies on the plane, outside the solid).
       {"(plane 'floor': a half-space, solid where x > 0, the side its normal [-1, 0, 0] points "
        "away from)",
        "holds 55 of the cloth's 121 free particles", "0.5 m inside", cloth_at + "inside it"}},
      {"DrapeSupportBallLargerThanTheCloth",
       {remove_lines(10, 13),
        insert_lines(9, "  - {name: ball, type: sphere, center: [0, 0.5, 0], radius: 1.5}")},
       10,
       "colliders.0",
       {"(sphere 'ball' of radius 1.5 m at [0, 0.5, 0])", "holds 121 of the cloth's 121",
        "particle 60 (grid i=5, j=5), 1 m inside", cloth_at + "inside it"}},
      {"FlagCentreAtTheFloor_NegativeZero",
       {replace_line(6, "  center: [0, -0.0, 0]\n  plane: xy")},
       11,
       "colliders.0",
       // The row at y = 0 lies on the floor, outside its solid; the five rows below are inside.
       {"(plane 'floor': a half-space, solid where y < 0, the side its normal [0, 1, 0] points "
        "away from)",
        "holds 55 of the cloth's 121", "0.5 m inside"}},
      {"FlagCentreAtTheFloor_Subnormal",
       {replace_line(6, "  center: [0, 1e-320, 0]\n  plane: xy")},
       11,
       "colliders.0",
       {"(plane 'floor': a half-space, solid where y < 0", "holds 55 of the cloth's 121"}},
      {"PoleThroughTheSheetBetweenParticles",
       {remove_lines(10, 13),
        insert_lines(9,
                     "  - {name: pole, type: cylinder, center: [0.05, 1, 0.05], radius: 0.01, "
                     "height: 2}")},
       10,
       "colliders.0",
       // The pole stands in a cell's middle, 0.07 m from its corners: it crosses the cell's two
       // triangles and holds no particle.
       {"(cylinder 'pole' of radius 0.01 m and height 2 m at [0.05, 1, 0.05])",
        "at t = 0 crosses 2 triangles whose corners lie outside it", cloth_at + "through it"}},
      {"ColliderCarriedByItsParentOntoTheSheet",
       {remove_lines(10, 13),
        insert_lines(9,
                     "  - {name: body, type: box, center: [5, 1, 0], half_extents: [0.1, 0.1, "
                     "0.1]}\n"
                     "  - {name: hand, type: sphere, parent: body, center: [-5, 0, 0], radius: "
                     "0.1}")},
       11,
       "colliders.1",
       // Its parent puts the hand at [0, 1, 0]: the sheet's middle particle is inside; its four
       // neighbours, 0.1 m away, are on its surface.
       {"(sphere 'hand' of radius 0.1 m at [0, 1, 0])", "holds 1 of the cloth's 121",
        "particle 60 (grid i=5, j=5), 0.1 m inside"}},
      {"SelfCollisionThicknessAboveTheEdge",
       insert_lines(8, "  self_collision: {thickness: 0.2}"),
       9,
       "cloth.self_collision.thickness",
       {"must be below 0.7 of the cloth's shortest rest edge (0.7 x 0.1 m = 0.07 m), got 0.2 m",
        "pushes the flat cloth's neighbouring parts apart at rest"}},
      {"SelfCollisionThicknessOfOneMetre",
       insert_lines(8, "  self_collision:\n    enabled: true\n    thickness: 1"),
       11,
       "cloth.self_collision.thickness",
       {"must be below 0.7 of the cloth's shortest rest edge", "got 1 m"}},
      {"SelfCollisionTakingTheClothsThickness",
       {replace_line(8, "  thickness: 0.2"), insert_lines(8, "  self_collision: {enabled: true}")},
       9,
       "cloth.self_collision",
       {"takes the cloth's thickness, 0.2 m, which must be below 0.7 of the cloth's shortest "
        "rest edge"}},
  };
}

class BadStarts : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadStarts, AreErrorsAtTheKeyThatCausesThem) {
  const BadScene& row = GetParam();
  EXPECT_TRUE(HasKeyedError(load_start(row.edit.apply(kSheet)), at_line(kFile, row.line), row.key,
                            row.wording));
}

INSTANTIATE_TEST_SUITE_P(StartState, BadStarts, ::testing::ValuesIn(bad_starts()), RowName());

// A start in contact that is meant, as a scene of a cloth laid on something is written.
struct MeantStart {
  std::string name;
  SceneEdit edit;
};

void PrintTo(const MeantStart& row, std::ostream* out) { *out << row.name << ": " << row.edit; }

std::vector<MeantStart> meant_starts() {
  return {
      {"TheSheetAsGiven", {}},
      {"RestingExactlyAtTheThickness", replace_line(6, "  center: [0, 0.004, 0]")},
      {"RestingWithinTheThickness", replace_line(6, "  center: [0, 0.001, 0]")},
      {"LyingOnTheSurface", replace_line(6, "  center: [0, 0, 0]")},
      {"RestingOnATiltedPlaneAtTheThickness",
       // The sheet and the plane turned alike about the same line: 0.004 m apart everywhere.
       {replace_line(6, "  center: [0, 0.004, 0]\n  rotation: [20, 0, 0]"),
        insert_lines(13, "    rotation: [20, 0, 0]")}},
      {"PinnedInsideABodyItIsAttachedTo",
       {insert_lines(8, "  pins: [{within: {center: [0, 1, 0], radius: 0.12}, attach: hand}]"),
        insert_lines(14, "  - {name: hand, type: sphere, center: [0, 1, 0], radius: 0.1}")}},
      {"PinnedInsideABodyCarriedByItsParent",
       {insert_lines(8, "  pins: [{within: {center: [0, 1, 0], radius: 0.12}, attach: hand}]"),
        insert_lines(14,
                     "  - {name: body, type: box, center: [5, 1, 0], half_extents: [0.1, 0.1, "
                     "0.1]}\n"
                     "  - {name: hand, type: sphere, parent: body, center: [-5, 0, 0], radius: "
                     "0.1}")}},
      {"SelfCollisionThicknessBelowTheEdge",
       insert_lines(8, "  self_collision: {thickness: 0.069}")},
  };
}

class MeantStarts : public ::testing::TestWithParam<MeantStart> {};

TEST_P(MeantStarts, Load) { EXPECT_LOADS(load_start(GetParam().edit.apply(kSheet))); }

INSTANTIATE_TEST_SUITE_P(StartState, MeantStarts, ::testing::ValuesIn(meant_starts()), RowName());

TEST(StartState, AllowedAStartInsideIsAWarningAtTheCollider) {
  const std::string text = with_line(kSheet, 13, "    normal: [0, -1, 0]");
  const LoadResult allowed = load_start(text, StartInside::warning);
  ASSERT_LOADS(allowed);
  ASSERT_EQ(allowed.warnings.size(), 1u);
  const std::string& warning = allowed.warnings.front();
  EXPECT_EQ(warning.rfind(at_line(kFile, 10) + " colliders.0 (plane 'floor'", 0), 0u) << warning;
  EXPECT_NE(warning.find("it runs anyway (--allow-start-inside)"), std::string::npos) << warning;
  // Without the permission, the same text is an error and there is no warning.
  const LoadResult refused = load_start(text);
  EXPECT_FALSE(refused.ok());
  EXPECT_TRUE(refused.warnings.empty());
}

TEST(StartState, EveryCollidersStartIsReported) {
  const std::string text =
      with_line(kSheet, 13,
                "    normal: [0, -1, 0]\n"
                "  - {name: ball, type: sphere, center: [0, 1, 0], radius: 0.25}");
  const LoadResult result = load_start(text);
  EXPECT_TRUE(HasKeyedError(result, at_line(kFile, 10), "colliders.0", {"(plane 'floor'"}));
  EXPECT_TRUE(HasKeyedError(result, at_line(kFile, 14), "colliders.1",
                            {"(sphere 'ball' of radius 0.25 m at [0, 1, 0])",
                             "holds 21 of the cloth's 121 free particles"}));
}

}  // namespace
