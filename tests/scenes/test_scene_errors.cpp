// Every validation rule of the scene format (docs/scene-reference.md) that a bad scene breaks, one
// table row per case: the edit of the base scene (base_scene.hpp), and the error it must cause, with
// the display file name, the 1-based line, the key path and the expected-value wording. Bad --set
// overrides: test_scene_overrides.cpp; several errors of one scene: test_scene_loader.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base_scene.hpp"
#include "fixtures/scene_cases.hpp"

namespace {

using namespace drapelab::fixtures;  // fixtures/scene_cases.hpp
using namespace drapelab::loader_tests;  // base_scene.hpp

// Line 34 of the base scene, the solver's dt, removed: the step is then chosen by the loader.
const TextEdit kNoDt = remove_lines(34, 34);

// A solver with adaptive substeps and `integrator` (which must be symplectic Euler), on line 34.
SceneEdit adaptive_with(const std::string& integrator) {
  return {kNoDt, replace_line(33, "    integrator: " + integrator), append_text("    adaptive_substeps: true\n")};
}

// Implicit options appended on line 35 to a solver using `integrator`.
SceneEdit implicit_options(const std::string& integrator, const std::string& options) {
  return {replace_line(33, "    integrator: " + integrator), append_text("    implicit: " + options + "\n")};
}

std::vector<BadScene> bad_scenes() {
  return {
      // Required keys
      {"MissingNameIsReportedAtTheTopMap", remove_lines(2, 2), 2, "name", {"is required", "[a-z0-9_-]+"}},
      {"MissingDuration", remove_lines(3, 3), 2, "duration", {"is required", "> 0"}},
      {"MissingCloth", remove_lines(7, 25), 2, "cloth", {"is required", "map"}},
      {"MissingResolutionIsReportedAtTheClothMap", remove_lines(10, 10), 8, "cloth.resolution",
       {"is required", "[33, 33]"}},
      {"MissingMassAndArealDensity", remove_lines(13, 13), 8, "cloth.mass", {"is required", "areal_density"}},
      {"EmptySolversList", {remove_lines(31, 34), replace_line(30, "solvers: []")}, 30, "solvers",
       {"must be a non-empty list of solvers"}},
      {"SolverEntryNotAMap", {remove_lines(32, 34), replace_line(31, "  - spring_damper")}, 31, "solvers.0",
       {"must be a map of keys", "'spring_damper'"}},

      // Names
      {"NameMustMatchThePattern", replace_line(2, "name: Bad Name"), 2, "name",
       {"must use only a-z, 0-9, _ and -", "got 'Bad Name'"}},
      {"NameMustBeText", replace_line(2, "name: [a, b]"), 2, "name", {"must be text", "a list"}},
      {"SolverNameMustMatchThePattern", replace_line(31, "  - name: Ours!"), 31, "solvers.0.name",
       {"must use only a-z, 0-9, _ and -", "'Ours!'"}},

      // Numbers: not numbers, not finite, out of range
      {"DurationNotANumber", replace_line(3, "duration: abc"), 3, "duration",
       {"must be a number (> 0)", "got 'abc'"}},
      {"DurationAList", replace_line(3, "duration: [1, 2]"), 3, "duration", {"must be a number", "a list"}},
      {"DurationMustBePositive_Zero", replace_line(3, "duration: 0"), 3, "duration", {"must be > 0, got 0"}},
      {"DurationMustBePositive_Negative", replace_line(3, "duration: -1"), 3, "duration", {"must be > 0, got -1"}},
      {"NonFiniteNumbersAreRefused_Infinity", replace_line(3, "duration: inf"), 3, "duration",
       {"must be finite", "'inf'"}},
      {"NonFiniteNumbersAreRefused_NaN", replace_line(3, "duration: nan"), 3, "duration",
       {"must be finite", "'nan'"}},
      {"NonFiniteNumbersAreRefused_SpringConstant", replace_line(18, "    stretch: {ks: inf, kd: 0.1}"), 18,
       "cloth.springs.stretch.ks", {"must be finite"}},
      {"NonFiniteNumbersAreRefused_ListItem", replace_line(5, "gravity: [0, nan, 0]"), 5, "gravity.1",
       {"must be finite"}},
      {"FrameRateMustBePositive_Zero", replace_line(4, "frame_rate: 0"), 4, "frame_rate", {"must be > 0, got 0"}},
      {"FrameRateMustBePositive_Negative", replace_line(4, "frame_rate: -30"), 4, "frame_rate",
       {"must be > 0, got -30"}},
      {"SeedMustBeANonNegativeWholeNumber_Negative", replace_line(6, "seed: -1"), 6, "seed",
       {"must be >= 0, got -1"}},
      {"SeedMustBeANonNegativeWholeNumber_Fraction", replace_line(6, "seed: 1.5"), 6, "seed",
       {"must be a whole number", "'1.5'"}},
      {"StretchKsMustBePositive_Negative", replace_line(18, "    stretch: {ks: -3, kd: 0.1}"), 18,
       "cloth.springs.stretch.ks", {"must be > 0, got -3"}},
      {"StretchKsMustBePositive_Zero", replace_line(18, "    stretch: {ks: 0, kd: 0.1}"), 18,
       "cloth.springs.stretch.ks", {"must be > 0, got 0"}},
      {"ShearAndBendKsMustBeNonNegative_Shear", replace_line(19, "    shear: {ks: -1, kd: 0.05}"), 19,
       "cloth.springs.shear.ks", {"must be >= 0, got -1"}},
      {"ShearAndBendKsMustBeNonNegative_Bend", replace_line(20, "    bend: {ks: -5, kd: 0.01}"), 20,
       "cloth.springs.bend.ks", {"must be >= 0, got -5"}},
      {"SpringDampingMustBeNonNegative_Stretch", replace_line(18, "    stretch: {ks: 500, kd: -0.1}"), 18,
       "cloth.springs.stretch.kd", {"must be >= 0, got -0.1"}},
      {"SpringDampingMustBeNonNegative_Shear", replace_line(19, "    shear: {ks: 50, kd: -1}"), 19,
       "cloth.springs.shear.kd", {"must be >= 0"}},
      {"SpringDampingMustBeNonNegative_Bend", replace_line(20, "    bend: {ks: 5, kd: -2}"), 20,
       "cloth.springs.bend.kd", {"must be >= 0"}},
      {"SpringsMustBeMaps_OneKind", replace_line(18, "    stretch: 500"), 18, "cloth.springs.stretch",
       {"must be a map of keys", "'500'"}},
      {"SpringsMustBeMaps_AllKinds", {remove_lines(18, 20), replace_line(17, "  springs: stiff")}, 17,
       "cloth.springs", {"must be a map of keys", "'stiff'"}},
      {"ThicknessMustBePositive", replace_line(14, "  thickness: 0"), 14, "cloth.thickness",
       {"must be > 0, got 0"}},
      {"PerturbationMustBeNonNegative", replace_line(15, "  perturbation: -0.001"), 15, "cloth.perturbation",
       {"must be >= 0, got -0.001"}},
      {"AirDampingMustBeNonNegative", replace_line(16, "  air_damping: -1"), 16, "cloth.air_damping",
       {"must be >= 0, got -1"}},
      {"MassAndArealDensityMustBePositive_Mass", replace_line(13, "  mass: 0"), 13, "cloth.mass",
       {"must be > 0, got 0"}},
      {"MassAndArealDensityMustBePositive_MassNotANumber", replace_line(13, "  mass: heavy"), 13, "cloth.mass",
       {"must be a number", "'heavy'"}},
      {"MassAndArealDensityMustBePositive_ArealDensity", replace_line(13, "  areal_density: -1"), 13,
       "cloth.areal_density", {"must be > 0, got -1"}},
      {"ContactValuesAreChecked_Stiffness", replace_line(27, "  stiffness: 0"), 27, "contact.stiffness",
       {"must be > 0, got 0"}},
      {"ContactValuesAreChecked_Damping", replace_line(28, "  damping: -4"), 28, "contact.damping",
       {"must be >= 0, got -4"}},
      {"ContactValuesAreChecked_Friction", replace_line(29, "  friction: -0.2"), 29, "contact.friction",
       {"must be >= 0, got -0.2"}},
      {"ContactValuesAreChecked_FrictionNotANumber", replace_line(29, "  friction: grippy"), 29,
       "contact.friction", {"must be a number", "'grippy'"}},
      {"SizeValuesMustBePositive_Depth", replace_line(9, "  size: [1.0, 0]"), 9, "cloth.size.1",
       {"must be > 0, got 0"}},
      {"SizeValuesMustBePositive_Width", replace_line(9, "  size: [-1, 0.5]"), 9, "cloth.size.0",
       {"must be > 0, got -1"}},
      {"SolverNumbersAreChecked_DtZero", replace_line(34, "    dt: 0"), 34, "solvers.0.dt", {"must be > 0, got 0"}},
      {"SolverNumbersAreChecked_DtNotANumber", replace_line(34, "    dt: fast"), 34, "solvers.0.dt",
       {"must be a number", "'fast'"}},
      {"SolverNumbersAreChecked_MaxSpeed", insert_lines(34, "    max_speed: -1"), 35, "solvers.0.max_speed",
       {"must be > 0, got -1"}},
      {"SolverNumbersAreChecked_RunawayStretch", insert_lines(34, "    runaway_stretch: 0"), 35,
       "solvers.0.runaway_stretch", {"must be > 0, got 0"}},
      {"SolverNumbersAreChecked_RoundDt", insert_lines(34, "    round_dt: yes please"), 35, "solvers.0.round_dt",
       {"must be true or false"}},

      // List shapes
      {"GravityMustHaveThreeNumbers_Two", replace_line(5, "gravity: [0, -9.81]"), 5, "gravity",
       {"must be a list of 3 numbers, got a list of 2"}},
      {"GravityMustHaveThreeNumbers_Four", replace_line(5, "gravity: [0, -9.81, 0, 1]"), 5, "gravity",
       {"must be a list of 3 numbers, got a list of 4"}},
      {"GravityMustHaveThreeNumbers_One", replace_line(5, "gravity: -9.81"), 5, "gravity",
       {"must be a list of 3 numbers, got '-9.81'"}},
      {"GravityMustHaveThreeNumbers_NotANumber", replace_line(5, "gravity: [0, down, 0]"), 5, "gravity.1",
       {"must be a number", "'down'"}},
      {"SizeMustHaveTwoNumbers_One", replace_line(9, "  size: [1.0]"), 9, "cloth.size",
       {"must be a list of 2 numbers, got a list of 1"}},
      {"SizeMustHaveTwoNumbers_Three", replace_line(9, "  size: [1, 1, 1]"), 9, "cloth.size",
       {"must be a list of 2 numbers, got a list of 3"}},
      {"CenterMustHaveThreeNumbers", replace_line(12, "  center: [0, 1]"), 12, "cloth.center",
       {"must be a list of 3 numbers, got a list of 2"}},
      {"ResolutionMustHaveTwoWholeNumbers_One", replace_line(10, "  resolution: [5]"), 10, "cloth.resolution",
       {"must be a list of 2 whole numbers, got a list of 1"}},
      {"ResolutionMustHaveTwoWholeNumbers_Three", replace_line(10, "  resolution: [5, 4, 3]"), 10,
       "cloth.resolution", {"must be a list of 2 whole numbers, got a list of 3"}},
      {"ResolutionMustHaveTwoWholeNumbers_NotAList", replace_line(10, "  resolution: 33"), 10, "cloth.resolution",
       {"must be a list of 2 whole numbers"}},
      {"ResolutionMustBeWholeNumbers_Fraction", replace_line(10, "  resolution: [5.5, 4]"), 10,
       "cloth.resolution.0", {"must be a whole number", "'5.5'"}},
      {"ResolutionMustBeWholeNumbers_Word", replace_line(10, "  resolution: [5, many]"), 10, "cloth.resolution.1",
       {"must be a whole number", "'many'"}},
      {"ResolutionMustBeAtLeastOne", replace_line(10, "  resolution: [0, 4]"), 10, "cloth.resolution.0",
       {"must be >= 1", "got 0"}},
      // The pins are removed so that only the resolution is wrong.
      {"ResolutionOneByOneIsNotACloth", {remove_lines(21, 25), replace_line(10, "  resolution: [1, 1]")}, 10,
       "cloth.resolution", {"must give at least 2 particles", "[1, 1]"}},

      // Mass and density
      {"MassAndArealDensityTogetherAreRefused", insert_lines(13, "  areal_density: 0.3"), 14,
       "cloth.areal_density", {"cannot be given together with cloth.mass"}},
      {"ArealDensityOnAChainIsRefused",
       {replace_line(10, "  resolution: [1, 4]"), replace_line(13, "  areal_density: 0.2")}, 13,
       "cloth.areal_density", {"needs a two-dimensional cloth", "chain", "cloth.mass"}},

      // Unknown and duplicate keys
      {"UnknownTopKeySuggestsTheNearest", replace_line(3, "durration: 0.5"), 3, "durration",
       {"is not a known key", "did you mean duration?"}},
      // ...and the real key is then missing, reported too.
      {"UnknownTopKeyLeavesTheKnownOneMissing", replace_line(3, "durration: 0.5"), 2, "duration",
       {"is required"}},
      {"UnknownClothKeySuggestsTheNearest", replace_line(9, "  sise: [1.0, 0.5]"), 9, "cloth.sise",
       {"is not a known key", "did you mean cloth.size?"}},
      {"UnknownSpringKeySuggestsTheNearest", replace_line(18, "    strech: {ks: 500, kd: 0.1}"), 18,
       "cloth.springs.strech", {"is not a known key", "did you mean cloth.springs.stretch?"}},
      {"UnknownSpringParameterSuggestsTheNearest", replace_line(18, "    stretch: {ks: 500, kdd: 0.1}"), 18,
       "cloth.springs.stretch.kdd", {"is not a known key", "did you mean cloth.springs.stretch.kd?"}},
      {"UnknownSolverKeySuggestsTheNearest", replace_line(33, "    integrater: symplectic_euler"), 33,
       "solvers.0.integrater", {"is not a known key", "did you mean solvers.0.integrator?"}},
      {"UnknownKeyFarFromAnyListsTheValidKeys", insert_lines(6, "colour: red"), 7, "colour",
       {"is not a known key", "valid keys here:", "duration", "cloth"}},
      {"DuplicateKeysAreRefused", replace_line(4, "duration: 1.0"), 4, "duration", {"appears twice"}},
      {"DuplicateNestedKeysAreRefused", insert_lines(14, "  thickness: 0.003"), 15, "cloth.thickness",
       {"appears twice"}},

      // Choices
      {"UnknownPlaneSuggestsTheNearest", replace_line(11, "  plane: yz"), 11, "cloth.plane",
       {"must be one of xz | xy", "got 'yz'", "did you mean 'xz'?"}},
      {"UnknownIntegratorSuggestsTheNearest", replace_line(33, "    integrator: symplectic_eulr"), 33,
       "solvers.0.integrator",
       {"must be one of", "explicit_euler", "got 'symplectic_eulr'", "did you mean 'symplectic_euler'?"}},
      {"UnknownShapeSuggestsTheNearest", replace_line(8, "  shape: gird"), 8, "cloth.shape",
       {"must be one of grid | disc | mesh", "got 'gird'", "did you mean 'grid'?"}},
      {"UnknownSolverTypeSuggestsTheNearest", replace_line(32, "    type: spring-damper"), 32, "solvers.0.type",
       {"must be one of", "got 'spring-damper'", "did you mean 'spring_damper'?"}},
      {"UnknownMeshOutputSuggestsTheNearest", append_text("output:\n  meshes: bothh\n"), 36, "output.meshes",
       {"must be one of none | obj | pc2 | both", "got 'bothh'", "did you mean 'both'?"}},
      // A horizontal (xz) sheet has no y edges; a vertical (xy) one no z edges (its ball pin, placed for
      // the horizontal sheet, removed).
      {"PinSetNamesFollowThePlane_Horizontal", replace_line(22, "    - edge_min_y"), 22, "cloth.pins.0",
       {"must be one of", "edge_min_z", "got 'edge_min_y'", "did you mean"}},
      {"PinSetNamesFollowThePlane_Vertical",
       {replace_line(11, "  plane: xy"), remove_lines(25, 25), replace_line(22, "    - edge_max_z")}, 22,
       "cloth.pins.0", {"must be one of", "edge_max_y", "got 'edge_max_z'"}},

      // Pins
      {"GridCoordinatePinOutOfRange_Column", replace_line(23, "    - [5, 0]"), 23, "cloth.pins.1",
       {"selects no particle", "[5, 0] is outside the 5 x 4 grid"}},
      {"GridCoordinatePinOutOfRange_Row", replace_line(23, "    - [0, 4]"), 23, "cloth.pins.1",
       {"selects no particle", "[0, 4]"}},
      {"GridCoordinatePinOutOfRange_Negative", replace_line(23, "    - [-1, 0]"), 23, "cloth.pins.1.0",
       {"must be >= 0"}},
      {"GridCoordinatePinOutOfRange_ThreeNumbers", replace_line(23, "    - [1, 2, 3]"), 23, "cloth.pins.1",
       {"must be a list of 2 whole numbers, got a list of 3"}},
      {"IndexPinOutOfRange_Above", replace_line(24, "    - {index: 20}"), 24, "cloth.pins.2",
       {"selects no particle", "particle index 20 is outside 0..19"}},
      {"IndexPinOutOfRange_Negative", replace_line(24, "    - {index: -1}"), 24, "cloth.pins.2.index",
       {"must be >= 0"}},
      {"BallPinSelectingNothing", replace_line(25, "    - {within: {center: [5, 5, 5], radius: 0.1}}"), 25,
       "cloth.pins.3", {"selects no particle", "no particle lies within the ball"}},
      {"BallPinValuesAreChecked_ZeroRadius", replace_line(25, "    - {within: {center: [0, 1, 0], radius: 0}}"),
       25, "cloth.pins.3.within.radius", {"must be > 0, got 0"}},
      {"BallPinValuesAreChecked_NoRadius", replace_line(25, "    - {within: {center: [0, 1, 0]}}"), 25,
       "cloth.pins.3.within.radius", {"is required"}},
      {"BallPinValuesAreChecked_NoCenter", replace_line(25, "    - {within: {radius: 0.2}}"), 25,
       "cloth.pins.3.within.center", {"is required"}},
      {"BallPinValuesAreChecked_ShortCenter", replace_line(25, "    - {within: {center: [0, 1], radius: 0.2}}"), 25,
       "cloth.pins.3.within.center", {"must be a list of 3 numbers"}},
      {"PinMapNeedsExactlyOneOfIndexAndWithin_Both",
       replace_line(24, "    - {index: 2, within: {center: [0, 1, 0], radius: 0.2}}"), 24, "cloth.pins.2",
       {"must have exactly one of index or within"}},
      {"PinMapNeedsExactlyOneOfIndexAndWithin_Neither", replace_line(24, "    - {}"), 24, "cloth.pins.2",
       {"must have exactly one of index or within"}},
      {"PinMapNeedsExactlyOneOfIndexAndWithin_Misspelt", replace_line(24, "    - {indx: 2}"), 24,
       "cloth.pins.2.indx", {"is not a known key", "did you mean cloth.pins.2.index?"}},
      {"PinsMustBeAList", {remove_lines(22, 25), replace_line(21, "  pins: corners")}, 21, "cloth.pins",
       {"must be a list of pin selectors"}},
      {"EmptyPinSelector", replace_line(22, "    - ~"), 22, "cloth.pins.0", {"must be a pin selector", "got nothing"}},
      // yaml-cpp marks an empty value ("duration:" or a bare "-") at the NEXT token; the error still
      // names the line of the key or item itself (and never a line past the end of the file).
      {"EmptyValueIsReportedOnItsOwnLine_Duration", replace_line(3, "duration:"), 3, "duration",
       {"must be a number", "got nothing"}},
      {"EmptyValueIsReportedOnItsOwnLine_LastLine", replace_line(34, "    dt:"), 34, "solvers.0.dt",
       {"must be a number", "got nothing"}},
      {"EmptyValueIsReportedOnItsOwnLine_ListItem", replace_line(22, "    -"), 22, "cloth.pins.0",
       {"must be a pin selector"}},

      // Solver types and their options
      {"BulletDeformableTakesNoIterations",
       {replace_line(32, "    type: bullet_deformable"), replace_line(33, "    iterations: 4")}, 33,
       "solvers.0.iterations", {"is not a known key"}},
      {"BulletSoftBodyRefusesAnIntegrator", replace_line(32, "    type: bullet_softbody"), 33,
       "solvers.0.integrator", {"is not a known key"}},
      {"BulletSoftBodyLinkStiffnessIsAFraction",
       {replace_line(32, "    type: bullet_softbody"), replace_line(33, "    kLST: {bend: 1.5}")}, 33,
       "solvers.0.kLST.bend", {"must be >= 0 and <= 1"}},
      {"BulletKeysOnOurSolverAreUnknown_Iterations", insert_lines(34, "    iterations: 4"), 35,
       "solvers.0.iterations", {"is not a known key"}},
      {"BulletKeysOnOurSolverAreUnknown_Margin", insert_lines(34, "    margin: 0.01"), 35, "solvers.0.margin",
       {"is not a known key"}},
      {"BulletKeysOnOurSolverAreUnknown_VoxelSize", insert_lines(34, "    voxel_size: 0.1"), 35,
       "solvers.0.voxel_size", {"is not a known key"}},
      {"ImplicitOptionsAreChecked_Tolerance", implicit_options("implicit_euler", "{tolerance: 0}"), 35,
       "solvers.0.implicit.tolerance", {"must be > 0"}},
      {"ImplicitOptionsAreChecked_MaxIterations", implicit_options("implicit_euler", "{max_iterations: 0}"), 35,
       "solvers.0.implicit.max_iterations", {"must be >= 1"}},
      {"ImplicitOptionsAreChecked_MisspeltKey", implicit_options("implicit_euler", "{tolerence: 1e-3}"), 35,
       "solvers.0.implicit.tolerence", {"is not a known key", "did you mean", "tolerance"}},
      {"ImplicitOptionsAreChecked_OnlyForImplicitEuler", implicit_options("rk4", "{tolerance: 1e-3}"), 35,
       "solvers.0.implicit", {"applies only to integrator: implicit_euler", "rk4"}},
      {"AdaptiveSubstepsNeedSymplecticEuler_ExplicitEuler", adaptive_with("explicit_euler"), 34,
       "solvers.0.adaptive_substeps", {"needs integrator symplectic_euler", "explicit_euler"}},
      {"AdaptiveSubstepsNeedSymplecticEuler_Midpoint", adaptive_with("midpoint"), 34, "solvers.0.adaptive_substeps",
       {"needs integrator symplectic_euler", "midpoint"}},
      {"AdaptiveSubstepsNeedSymplecticEuler_Rk4", adaptive_with("rk4"), 34, "solvers.0.adaptive_substeps",
       {"needs integrator symplectic_euler", "rk4"}},
      {"AdaptiveSubstepsNeedSymplecticEuler_Verlet", adaptive_with("verlet"), 34, "solvers.0.adaptive_substeps",
       {"needs integrator symplectic_euler", "verlet"}},
      {"AdaptiveSubstepsNeedSymplecticEuler_Leapfrog", adaptive_with("leapfrog"), 34, "solvers.0.adaptive_substeps",
       {"needs integrator symplectic_euler", "leapfrog"}},
      {"AdaptiveSubstepsNeedSymplecticEuler_ImplicitEuler", adaptive_with("implicit_euler"), 34,
       "solvers.0.adaptive_substeps", {"needs integrator symplectic_euler", "implicit_euler"}},
      {"AdaptiveSubstepsMustBeTrueOrFalse", {kNoDt, append_text("    adaptive_substeps: 3\n")}, 34,
       "solvers.0.adaptive_substeps", {}},

      // Solvers, steps and frames
      {"DuplicateSolverNamesAreRefused", append_text("  - name: ours\n    dt: 0.001041666666666666667\n"), 35,
       "solvers.1.name", {"'ours' is already used", "unique"}},
      // Two solvers without names are both named after their type.
      {"DefaultSolverNamesCollideToo",
       {remove_lines(31, 34), replace_line(30, "solvers: [{type: spring_damper}, {type: spring_damper}]")}, 30,
       "solvers.1.name", {"'spring_damper' is already used"}},
      {"DtThatDoesNotDivideTheFramePeriodIsRefused", replace_line(34, "    dt: 0.001"), 34, "solvers.0.dt",
       {"must divide the frame period", "round_dt", "got 0.001", "try dt = "}},
      {"DtLargerThanTheFramePeriodIsRefused", replace_line(34, "    dt: 0.05"), 34, "solvers.0.dt",
       {"must not exceed the frame period", "got 0.05"}},
      {"DurationTimesFrameRateMustBeWhole", replace_line(3, "duration: 0.51"), 3, "duration",
       {"times frame_rate must be a whole number of frames", "30.6"}},
      // The frame rate can make it fractional too; the error sits on duration.
      {"DurationTimesFrameRateMustBeWhole_ByTheFrameRate",
       {replace_line(4, "frame_rate: 25"), replace_line(34, "    dt: 0.001")}, 3, "duration",
       {"times frame_rate must be a whole number of frames", "12.5"}},
      // Run-length bounds (run_limits.hpp): at most 10^7 steps per frame and from 1 to 10^7 frames,
      // checked before any count is cast to int.
      {"StepsPerFrameAboveTenMillionAreRefused", replace_line(34, "    dt: 1e-13"), 34, "solvers.0.dt",
       {"is 1e-13 s", "166666666666.6666", "steps per frame", "at most 10000000 steps per frame"}},
      // Springs so stiff that the stable step is about 1e-11 s; no dt: the error sits on the solver entry.
      {"AutomaticStepAboveTenMillionPerFrameIsRefusedAtTheSolver",
       {kNoDt, replace_line(18, "    stretch: {ks: 1e16, kd: 0}")}, 31, "solvers.0.dt",
       {"chosen automatically", "steps per frame", "softer springs"}},
      {"FrameCountMustBeFromOneToTenMillion_TooFew", replace_line(4, "frame_rate: 1e-300"), 4, "frame_rate",
       {"(frames per second) times duration must give at least 1 frame", "0.5 s x 1e-300 /s"}},
      // Without a frame_rate key the error sits on duration.
      {"FrameCountMustBeFromOneToTenMillion_TooFewByDefaultRate",
       {whole_scene(kMinimal), replace_line(2, "duration: 1e-300")}, 2, "duration",
       {"times frame_rate must give from 1 to 10000000 frames", "6e-299"}},
      {"FrameCountMustBeFromOneToTenMillion_TooMany", replace_line(3, "duration: 4e7"), 3, "duration",
       {"times frame_rate must give from 1 to 10000000 frames", "2.4e+09"}},

      // Whole-file problems (line 0: the file as a whole)
      {"YamlSyntaxErrorReportsItsLine_Bracket", replace_line(9, "  size: [1.0, 0.5]]"), 9, "", {"not valid YAML"}},
      {"YamlSyntaxErrorReportsItsLine_Indentation", replace_line(14, "   thickness: 0.004"), 14, "",
       {"not valid YAML"}},
      {"EmptyFileIsAnError", whole_scene(""), 0, "", {"the scene is empty", "name", "duration", "cloth", "solvers"}},
      {"EmptyFileIsAnError_OnlyAComment", whole_scene("# only a comment\n"), 0, "", {"the scene is empty"}},
      {"TopLevelMustBeAMap_Text", whole_scene("just some words\n"), 1, "",
       {"must be a map of keys", "'just some words'"}},
      {"TopLevelMustBeAMap_List", whole_scene("- a\n- b\n"), 1, "", {"must be a map of keys", "a list"}},
  };
}

class SceneErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneErrors, NamesTheLineTheKeyAndTheExpectedValue) {
  const BadScene& row = GetParam();
  const std::string location = row.line == 0 ? std::string(kName) : at(row.line);
  EXPECT_TRUE(HasKeyedError(load(row.edit.apply(kBase)), location, row.key, row.wording));
}

INSTANTIATE_TEST_SUITE_P(SceneLoader, SceneErrors, ::testing::ValuesIn(bad_scenes()), RowName());

}  // namespace
