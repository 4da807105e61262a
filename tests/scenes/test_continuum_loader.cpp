// cloth.model: continuum in scene files (docs/scene-reference.md, "cloth.continuum"): the keys and
// their defaults, the material presets' continuum parameters, the springs derived from them for
// the Bullet cloths and the metrics, every shape, and every error, each naming its key. The
// resolved.yaml round trip of a continuum cloth: test_resolved_scene.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "drapelab/continuum.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "fixtures/scene_cases.hpp"
#include "fixtures/scene_text.hpp"

namespace drapelab {
namespace {

namespace fs = std::filesystem;
using namespace fixtures;  // fixtures/scene_text.hpp, fixtures/scene_cases.hpp

constexpr const char* kContinuumFile = "continuum.yaml";

scene::LoadResult load_continuum(const std::string& text,
                                 const std::vector<std::string>& overrides = {}) {
  return scene::load_scene_text(text, kContinuumFile, overrides);
}
std::string continuum_at(int line) { return at_line(kContinuumFile, line); }

// A 5 x 4 sheet of the continuum model with every key of cloth.continuum. Its particle spacing is
// the smaller cell side, 0.4 / 4 = 0.1 m. Line numbers matter for the error tests.
const std::string kSheet =
    "name: membrane\n"                                                     //  1
    "duration: 0.1\n"                                                      //  2
    "cloth:\n"                                                             //  3
    "  size: [0.4, 0.6]\n"                                                 //  4
    "  resolution: [5, 4]\n"                                               //  5
    "  mass: 0.1\n"                                                        //  6
    "  model: continuum\n"                                                 //  7
    "  continuum:\n"                                                       //  8
    "    stretch_modulus: 500\n"                                           //  9
    "    poisson: 0.25\n"                                                  // 10
    "    bending_rigidity: 2.0e-5\n"                                       // 11
    "    damping: 0.02\n"                                                  // 12
    "  pins: [corners]\n"                                                  // 13
    "solvers:\n"                                                           // 14
    "  - {name: ours, type: spring_damper, dt: 0.0010416666666666667}\n";  // 15

constexpr double kSheetSpacing = 0.1;  // m

// The bend spring's ks of docs/materials.md, "How they become springs": 16 B / (spacing^2 0.3^2).
double bend_ks(double bending_rigidity, double spacing) {
  return 16.0 * bending_rigidity / (spacing * spacing * 0.3 * 0.3);
}

// The springs of a continuum cloth are derived from its parameters at its particle spacing; with a
// material preset the shear springs keep the preset's own G (`preset_shear`, N/m).
void ExpectDerivedSprings(const GridClothSpec& cloth, double spacing,
                          std::optional<double> preset_shear = std::nullopt) {
  ASSERT_TRUE(cloth.continuum);
  const ContinuumParams& c = *cloth.continuum;
  EXPECT_DOUBLE_EQ(cloth.stretch.ks, c.stretch_modulus);
  EXPECT_DOUBLE_EQ(cloth.shear.ks,
                   preset_shear.value_or(c.stretch_modulus / (2.0 * (1.0 + c.poisson))));
  // The spacing to rounding: a mesh's mean edge is summed edge by edge.
  const double bend = bend_ks(c.bending_rigidity, spacing);
  EXPECT_NEAR(cloth.bend.ks, bend, 1e-12 * bend);
  EXPECT_DOUBLE_EQ(cloth.stretch.kd, c.damping * cloth.stretch.ks);
  if (!preset_shear) {
    EXPECT_DOUBLE_EQ(cloth.shear.kd, c.damping * cloth.shear.ks);
  }
  EXPECT_DOUBLE_EQ(cloth.bend.kd, c.damping * cloth.bend.ks);
}

// ---------------------------------------------------------------------------------------------
// Keys, defaults, derived springs

TEST(ContinuumLoader, KeysAreReadAndTheModelGetsItsElements) {
  const auto result = load_continuum(kSheet);
  ASSERT_LOADS(result);
  const GridClothSpec& cloth = result.scene->cloth.grid;
  ASSERT_TRUE(cloth.continuum);
  EXPECT_EQ(cloth.continuum->stretch_modulus, 500.0);
  EXPECT_EQ(cloth.continuum->poisson, 0.25);
  EXPECT_EQ(cloth.continuum->bending_rigidity, 2.0e-5);
  EXPECT_EQ(cloth.continuum->damping, 0.02);
  ExpectDerivedSprings(cloth, kSheetSpacing);
  EXPECT_DOUBLE_EQ(cloth.shear.ks, 200.0);  // 500 / (2 x 1.25)
  // The loader's model carries the elements: 24 triangles, and a hinge on each of the
  // 4 x 4 + 5 x 3 + 12 - 2 x (4 + 3) = 29 interior edges.
  ASSERT_TRUE(result.model);
  ASSERT_TRUE(result.model->continuum);
  EXPECT_EQ(result.model->continuum->triangle_count(), 24u);
  EXPECT_EQ(result.model->continuum->hinge_count(), 29u);
  EXPECT_EQ(result.model->continuum->params.poisson, 0.25);
  EXPECT_GT(result.model->springs.size(), 0u) << "the springs stay for the Bullet cloths";
}

TEST(ContinuumLoader, SpringsIsTheDefaultModel) {
  const std::string springs = with_line(without_lines(kSheet, 8, 12), 7, "  model: springs");
  for (const std::string& text : {springs, without_lines(kSheet, 7, 12)}) {
    const auto result = load_continuum(text);
    ASSERT_LOADS(result);
    EXPECT_FALSE(result.scene->cloth.grid.continuum);
    EXPECT_FALSE(result.model->continuum);
    EXPECT_EQ(result.scene->cloth.grid.stretch.ks, 2000.0);  // the springs' own defaults
  }
}

TEST(ContinuumLoader, OmittedKeysTakeTheDefaults) {
  const ContinuumParams defaults;
  const auto bare = load_continuum(without_lines(kSheet, 8, 12));  // model: continuum alone
  ASSERT_LOADS(bare);
  ASSERT_TRUE(bare.scene->cloth.grid.continuum);
  const ContinuumParams& c = *bare.scene->cloth.grid.continuum;
  EXPECT_EQ(c.stretch_modulus, defaults.stretch_modulus);
  EXPECT_EQ(c.poisson, defaults.poisson);
  EXPECT_EQ(c.bending_rigidity, defaults.bending_rigidity);
  EXPECT_EQ(c.damping, defaults.damping);
  ExpectDerivedSprings(bare.scene->cloth.grid, kSheetSpacing);

  // One key given: the others keep their defaults.
  const auto one =
      load_continuum(without_lines(without_lines(kSheet, 11, 12), 9, 9));  // poisson only
  ASSERT_LOADS(one);
  const ContinuumParams& p = *one.scene->cloth.grid.continuum;
  EXPECT_EQ(p.poisson, 0.25);
  EXPECT_EQ(p.stretch_modulus, defaults.stretch_modulus);
  EXPECT_EQ(p.bending_rigidity, defaults.bending_rigidity);
  EXPECT_EQ(p.damping, defaults.damping);
}

TEST(ContinuumLoader, RangeBoundsLoad) {
  const auto zero =
      load_continuum(kSheet, {"cloth.continuum.poisson=0", "cloth.continuum.bending_rigidity=0",
                              "cloth.continuum.damping=0"});
  ASSERT_LOADS(zero);
  EXPECT_EQ(zero.scene->cloth.grid.continuum->poisson, 0.0);
  EXPECT_EQ(zero.scene->cloth.grid.bend.ks, 0.0);
  EXPECT_EQ(zero.scene->cloth.grid.stretch.kd, 0.0);
  EXPECT_LOADS(load_continuum(kSheet, {"cloth.continuum.poisson=0.499"}));
}

// ---------------------------------------------------------------------------------------------
// Material presets

TEST(ContinuumLoader, MaterialGivesTheContinuumParameters) {
  // material: cotton and no cloth.continuum: tensile 1000 N/m, nu 0.3, B 1e-5 N m, beta 5e-5 s.
  const std::string cotton = with_line(without_lines(kSheet, 8, 12), 6, "  material: cotton");
  const auto result = load_continuum(cotton);
  ASSERT_LOADS(result);
  const GridClothSpec& cloth = result.scene->cloth.grid;
  ASSERT_TRUE(cloth.continuum);
  EXPECT_EQ(cloth.continuum->stretch_modulus, 1000.0);
  EXPECT_EQ(cloth.continuum->poisson, 0.3);
  EXPECT_EQ(cloth.continuum->bending_rigidity, 1.0e-5);
  EXPECT_EQ(cloth.continuum->damping, 5e-5);
  // The preset's shear rigidity G (55 N/m) stays the shear springs' (for the Bullet cloths and a
  // solver with model: springs): the isotropic membrane's own shear modulus, 1000 / 2.6 N/m, is
  // far above what a woven fabric has.
  ExpectDerivedSprings(cloth, kSheetSpacing, 55.0);
  // The rest of the preset as with springs.
  ASSERT_TRUE(cloth.areal_density);
  EXPECT_EQ(*cloth.areal_density, 0.13);
  EXPECT_EQ(cloth.thickness, 0.0003);
  EXPECT_EQ(result.scene->cloth.air_damping, 1.0);
}

TEST(ContinuumLoader, EveryPresetHasAWovenOrLeatherPoissonRatio) {
  const std::vector<std::pair<std::string, double>> expected = {
      {"silk", 0.35}, {"cotton", 0.3}, {"denim", 0.2}, {"leather", 0.4}};
  for (const auto& [name, poisson] : expected) {
    const auto result =
        load_continuum(with_line(without_lines(kSheet, 8, 12), 6, "  material: " + name));
    ASSERT_LOADS(result);
    EXPECT_EQ(result.scene->cloth.grid.continuum->poisson, poisson) << name;
    EXPECT_GE(poisson, 0.2) << name;
    EXPECT_LE(poisson, 0.4) << name;
  }
}

TEST(ContinuumLoader, ExplicitKeysWinOverTheMaterialKeyByKey) {
  // cloth.continuum gives poisson and damping; the preset (denim) gives the other two.
  const std::string text =
      with_line(without_lines(without_lines(kSheet, 11, 11), 9, 9), 6, "  material: denim");
  const auto result = load_continuum(text);
  ASSERT_LOADS(result);
  const ContinuumParams& c = *result.scene->cloth.grid.continuum;
  EXPECT_EQ(c.stretch_modulus, 2000.0);
  EXPECT_EQ(c.bending_rigidity, 1.0e-4);
  EXPECT_EQ(c.poisson, 0.25);
  EXPECT_EQ(c.damping, 0.02);
  ExpectDerivedSprings(result.scene->cloth.grid, kSheetSpacing, 170.0);  // denim's G
  EXPECT_EQ(*result.scene->cloth.grid.areal_density, 0.4);
  // mass replaces the preset's density, as with springs.
  const auto massive = load_continuum(insert_after(text, 6, "  mass: 0.3"));
  ASSERT_LOADS(massive);
  EXPECT_FALSE(massive.scene->cloth.grid.areal_density);
}

TEST(ContinuumLoader, MaterialWithTheSpringModelIsUnchanged) {
  const std::string text =
      with_line(without_lines(kSheet, 7, 12), 6, "  material: cotton");  // no model: springs
  const auto result = load_continuum(text);
  ASSERT_LOADS(result);
  const GridClothSpec& cloth = result.scene->cloth.grid;
  EXPECT_FALSE(cloth.continuum);
  EXPECT_EQ(cloth.stretch.ks, 1000.0);
  EXPECT_EQ(cloth.shear.ks, 55.0);  // the preset's G
  EXPECT_DOUBLE_EQ(cloth.bend.ks, bend_ks(1.0e-5, kSheetSpacing));
  EXPECT_DOUBLE_EQ(cloth.bend.kd, 5e-5 * cloth.bend.ks);
}

// ---------------------------------------------------------------------------------------------
// Every shape

const std::string kContinuumDisc =
    "name: disc\n"
    "duration: 0.1\n"
    "cloth:\n"
    "  shape: disc\n"
    "  radius: 0.15\n"
    "  rings: 10\n"
    "  material: cotton\n"
    "  model: continuum\n"
    "  continuum: {bending_rigidity: 3.0e-5}\n"
    "  pins: [center]\n"
    "solvers: [{type: spring_damper, dt: 0.0010416666666666667}]\n";

// solvers.N.model: a spring solver on a continuum cloth runs its springs, and a continuum solver on
// a springs cloth runs the elements of cloth.continuum; the Bullet cloths always run the springs.
TEST(ContinuumLoader, EachOfOurSolversMayRunEitherModel) {
  const std::string both = with_line(
      kSheet, 15,
      "  - {name: ours, type: spring_damper, dt: 0.0010416666666666667}\n"
      "  - {name: ours_springs, type: spring_damper, model: springs, dt: 0.0010416666666666667}\n"
      "  - {name: classic, type: bullet_softbody}");
  const auto on_continuum = load_continuum(both);
  ASSERT_LOADS(on_continuum);
  const auto& solvers = on_continuum.scene->solvers;
  EXPECT_TRUE(solvers[0].continuum);
  EXPECT_FALSE(solvers[1].continuum);
  const auto model = std::make_shared<const ClothModel>(*on_continuum.model);
  EXPECT_EQ(scene::cloth_for_solver(*on_continuum.scene, solvers[0], model), model);
  EXPECT_FALSE(scene::cloth_for_solver(*on_continuum.scene, solvers[1], model)->uses_continuum());
  EXPECT_FALSE(scene::cloth_for_solver(*on_continuum.scene, solvers[2], model)->uses_continuum());

  // A springs cloth whose cloth.continuum serves one solver.
  const std::string springs_cloth =
      with_line(with_line(kSheet, 7, "  model: springs"), 15,
                "  - {name: ours, type: spring_damper, dt: 0.0010416666666666667}\n"
                "  - {name: ours_continuum, type: spring_damper, model: continuum, dt: "
                "0.0010416666666666667}");
  const auto on_springs = load_continuum(springs_cloth);
  ASSERT_LOADS(on_springs);
  EXPECT_FALSE(on_springs.model->uses_continuum());
  const auto& mixed = on_springs.scene->solvers;
  EXPECT_FALSE(mixed[0].continuum);
  ASSERT_TRUE(mixed[1].continuum);
  const auto plain = std::make_shared<const ClothModel>(*on_springs.model);
  const auto elements = scene::cloth_for_solver(*on_springs.scene, mixed[1], plain);
  ASSERT_TRUE(elements->uses_continuum());
  EXPECT_EQ(elements->continuum->params.stretch_modulus, 500.0);
  EXPECT_EQ(elements->continuum->params.poisson, 0.25);
  // The resolved scene keeps both and loads back the same.
  const auto again = load_continuum(scene::resolved_scene_yaml(*on_springs.scene));
  ASSERT_LOADS(again);
  EXPECT_TRUE(again.scene->solvers[1].continuum);
  EXPECT_EQ(again.scene->cloth.continuum.bending_rigidity, 2.0e-5);
}

TEST(ContinuumLoader, AnUnusedContinuumBlockOnASpringsClothIsNoted) {
  const auto result = load_continuum(with_line(kSheet, 7, "  model: springs"));
  ASSERT_LOADS(result);
  EXPECT_FALSE(result.model->uses_continuum());
  bool noted = false;
  for (const std::string& note : result.notes)
    noted = noted || note.find("cloth.continuum acts on no solver") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(ContinuumLoader, DiscCarriesTheElementsAndSpringsAtItsRingSpacing) {
  const auto result = load_continuum(kContinuumDisc);
  ASSERT_LOADS(result);
  const GridClothSpec& cloth = result.scene->cloth.grid;
  ASSERT_TRUE(cloth.continuum);
  EXPECT_EQ(cloth.continuum->bending_rigidity, 3.0e-5);
  EXPECT_EQ(cloth.continuum->stretch_modulus, 1000.0);  // cotton's
  ExpectDerivedSprings(cloth, 0.15 / 10, 55.0);         // cotton's G
  ASSERT_TRUE(result.model->continuum);
  EXPECT_EQ(result.model->continuum->triangle_count(),
            static_cast<std::size_t>(result.model->triangles.cols()));
  EXPECT_GT(result.model->continuum->hinge_count(), result.model->continuum->triangle_count());
}

class ContinuumMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("drapelab_continuum_" + std::to_string(::getpid()));
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(folder_ / name) << text;
    return folder_ / name;
  }
  fs::path folder_;
};

TEST_F(ContinuumMesh, MeshCarriesTheElementsAndSpringsAtItsMeanEdge) {
  // A 2 m square fanned about its centre, scaled to 1 m: four triangles, four interior edges.
  write("square.obj",
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n");
  const auto result = scene::load_scene_file(
      write("cape.yaml",
            "name: cape\n"
            "duration: 0.1\n"
            "cloth:\n"
            "  shape: mesh\n"
            "  path: square.obj\n"
            "  scale: 0.5\n"
            "  mass: 0.1\n"
            "  model: continuum\n"
            "solvers: [{type: spring_damper, dt: 0.0010416666666666667}]\n"));
  ASSERT_LOADS(result);
  // Mean edge: 4 sides of 1 m and 4 half-diagonals of sqrt(0.5) m, each side in one triangle and
  // each half-diagonal in two: (4 x 1 + 8 x sqrt(0.5)) / 12.
  ExpectDerivedSprings(result.scene->cloth.grid, (4.0 + 8.0 * std::sqrt(0.5)) / 12.0);
  ASSERT_TRUE(result.model->continuum);
  EXPECT_EQ(result.model->continuum->triangle_count(), 4u);
  EXPECT_EQ(result.model->continuum->hinge_count(), 4u);
}

// ---------------------------------------------------------------------------------------------
// Errors

// Line 15 of the sheet, the solver, with adaptive substeps (and no dt: they choose it).
const TextEdit kAdaptive =
    replace_line(15, "  - {name: ours, type: spring_damper, adaptive_substeps: true}");

std::vector<BadScene> bad_continuum_scenes() {
  return {
      // The model and its keys
      {"ModelMustBeSpringsOrContinuum",
       replace_line(7, "  model: membrane"),
       7,
       "cloth.model",
       {"must be one of", "springs", "continuum"}},
      {"SpringsWithTheContinuumModelAreRefused",
       insert_lines(12, "  springs:\n    stretch: {ks: 500, kd: 0.1}"),
       13,
       "cloth.springs",
       {"cannot be given with model: continuum", "derived from cloth.continuum"}},
      {"ContinuumMustBeAMap",
       {remove_lines(9, 12), replace_line(8, "  continuum: stiff")},
       8,
       "cloth.continuum",
       {"must be a map of keys", "'stiff'"}},
      {"UnknownContinuumKeySuggestsTheNearest",
       replace_line(10, "    poison: 0.25"),
       10,
       "cloth.continuum.poison",
       {"is not a known key", "did you mean cloth.continuum.poisson?"}},
      {"ChainCannotBeAContinuum",
       replace_line(5, "  resolution: [1, 4]"),
       7,
       "cloth.model",
       {"is continuum, which needs a two-dimensional cloth", "[1, 4] is a chain",
        "model: springs"}},
      {"ChainAlongXCannotBeAContinuumEither",
       replace_line(5, "  resolution: [5, 1]"),
       7,
       "cloth.model",
       {"is continuum, which needs a two-dimensional cloth", "[5, 1] is a chain"}},

      // Ranges
      {"StretchModulusMustBePositive",
       replace_line(9, "    stretch_modulus: 0"),
       9,
       "cloth.continuum.stretch_modulus",
       {"must be > 0, got 0", "(the range is > 0 and <= 1e+12)"}},
      {"StretchModulusHasAnUpperBound",
       replace_line(9, "    stretch_modulus: 1e13"),
       9,
       "cloth.continuum.stretch_modulus",
       {"must be <= 1e+12, got 1e13"}},
      {"StretchModulusMustBeANumber",
       replace_line(9, "    stretch_modulus: stiff"),
       9,
       "cloth.continuum.stretch_modulus",
       {"must be a number (> 0 and <= 1e+12), got 'stiff'"}},
      {"StretchModulusMustBeFinite",
       replace_line(9, "    stretch_modulus: inf"),
       9,
       "cloth.continuum.stretch_modulus",
       {"must be finite"}},
      {"PoissonMustBeNonNegative",
       replace_line(10, "    poisson: -0.1"),
       10,
       "cloth.continuum.poisson",
       {"must be >= 0, got -0.1", "(the range is >= 0 and < 0.5)"}},
      {"PoissonMustBeBelowOneHalf",
       replace_line(10, "    poisson: 0.5"),
       10,
       "cloth.continuum.poisson",
       {"must be < 0.5, got 0.5", "(the range is >= 0 and < 0.5)"}},
      {"BendingRigidityMustBeNonNegative",
       replace_line(11, "    bending_rigidity: -1e-5"),
       11,
       "cloth.continuum.bending_rigidity",
       {"must be >= 0, got -1e-5", "(the range is >= 0 and <= 1000)"}},
      {"BendingRigidityHasAnUpperBound",
       replace_line(11, "    bending_rigidity: 1e308"),
       11,
       "cloth.continuum.bending_rigidity",
       {"must be <= 1000, got 1e308"}},
      {"DampingMustBeNonNegative",
       replace_line(12, "    damping: -0.01"),
       12,
       "cloth.continuum.damping",
       {"must be >= 0, got -0.01", "(the range is >= 0 and <= 10)"}},
      {"DampingHasAnUpperBound",
       replace_line(12, "    damping: 11"),
       12,
       "cloth.continuum.damping",
       {"must be <= 10, got 11"}},

      // Solvers
      {"AdaptiveSubstepsNeedTheSprings",
       kAdaptive,
       15,
       "solvers.0.adaptive_substeps",
       {"cannot be used with the continuum model", "built from the springs"}},
  };
}

class ContinuumErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(ContinuumErrors, NamesTheLineTheKeyAndTheExpectedValue) {
  const BadScene& row = GetParam();
  EXPECT_TRUE(HasKeyedError(load_continuum(row.edit.apply(kSheet)), continuum_at(row.line), row.key,
                            row.wording));
}

INSTANTIATE_TEST_SUITE_P(ContinuumLoader, ContinuumErrors,
                         ::testing::ValuesIn(bad_continuum_scenes()), RowName());

TEST(ContinuumLoader, ErrorsInOverridesNameTheOverride) {
  EXPECT_TRUE(HasKeyedError(load_continuum(kSheet, {"cloth.continuum.poisson=0.7"}),
                            at_override(kContinuumFile, "cloth.continuum.poisson=0.7"),
                            "cloth.continuum.poisson", {"must be < 0.5, got 0.7"}));
  // Switching a spring cloth to the continuum model with --set names the springs.
  const std::string springs = with_line(without_lines(kSheet, 7, 12), 6,
                                        "  mass: 0.1\n  springs: {stretch: {ks: 500, kd: 0.1}}");
  ASSERT_LOADS(load_continuum(springs));
  const auto switched = load_continuum(springs, {"cloth.model=continuum"});
  EXPECT_TRUE(HasKeyedError(switched, continuum_at(7), "cloth.springs",
                            {"cannot be given with model: continuum"}));
  EXPECT_LOADS(load_continuum(without_lines(springs, 7, 7), {"cloth.model=continuum"}))
      << "without the springs the override loads";
}

TEST(ContinuumLoader, AdaptiveSubstepsAreFineWithTheSpringModelAndBulletWithTheContinuum) {
  EXPECT_LOADS(load_continuum(SceneEdit{kAdaptive, remove_lines(7, 12)}.apply(kSheet)));
  // The Bullet cloths take the derived springs.
  EXPECT_LOADS(
      load_continuum(with_line(kSheet, 15,
                               "  - {name: ours, type: spring_damper, dt: 0.0010416666666666667}\n"
                               "  - {type: bullet_softbody}\n"
                               "  - {type: bullet_deformable}")));
  // An integrator other than symplectic Euler with adaptive substeps names the integrator.
  EXPECT_TRUE(HasKeyedError(
      load_continuum(with_line(
          kSheet, 15, "  - {type: spring_damper, integrator: verlet, adaptive_substeps: true}")),
      continuum_at(15), "solvers.0.adaptive_substeps", {"needs integrator symplectic_euler"}));
}

TEST(ContinuumLoader, EveryIntegratorLoadsWithTheContinuum) {
  for (const char* integrator : {"symplectic_euler", "explicit_euler", "midpoint", "rk4", "verlet",
                                 "leapfrog", "implicit_euler", "vbd"})
    EXPECT_LOADS(load_continuum(with_line(
        kSheet, 15, std::string("  - {type: spring_damper, integrator: ") + integrator + "}")))
        << integrator;
}

}  // namespace
}  // namespace drapelab
