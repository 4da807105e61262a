// Hostile scene input: every one is refused with a located error instead of a crash, a hang, an
// allocation of gigabytes, or a run that reports ok with inf or nan in its metrics
// (docs/scene-reference.md, "Limits").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base_scene.hpp"
#include "drapelab/cloth_limits.hpp"
#include "fixtures/scene_text.hpp"

namespace {

namespace fs = std::filesystem;
using namespace drapelab::fixtures;      // fixtures/scene_text.hpp
using namespace drapelab::loader_tests;  // base_scene.hpp
using drapelab::scene::load_scene_file;

// A folder of its own under the system's temporary folder, removed afterwards.
class TempFolder {
 public:
  explicit TempFolder(const std::string& name)
      : path_(fs::temp_directory_path() / ("drapelab_hostile_" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() { fs::remove_all(path_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return path_ / name;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// A unit square in the xz plane, two triangles (m).
const std::string kSquareMesh =
    "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 0 0.5\nv -0.5 0 0.5\nf 1 2 3\nf 1 3 4\n";

// A mesh cloth of the square, its scale and centre given (lines 3 to 7).
std::string mesh_scene(const std::string& scale, const std::string& center) {
  return "name: mesh\n"          // 1
         "duration: 0.1\n"       // 2
         "cloth:\n"              // 3
         "  shape: mesh\n"       // 4
         "  path: square.obj\n"  // 5
         "  scale: " +
         scale +
         "\n"  // 6
         "  center: " +
         center +
         "\n"                                   // 7
         "  mass: 0.1\n"                        // 8
         "solvers: [{type: spring_damper}]\n";  // 9
}

// ---------------------------------------------------------------------------------------------
// 1. Names: a plain loop, at most 64 characters

TEST(HostileInputs, AFiftyThousandCharacterNameIsRefusedWithoutOverflowingTheStack) {
  const std::string set = "name=" + std::string(50000, 'a');
  const auto result = load(kBase, {set});
  // The override is shown cut, with its length.
  EXPECT_TRUE(HasError(result, at_set("name=" + std::string(165, 'a') + "... (50011 characters)"),
                       {"name", "at most 64 characters", "50000"}));
}

TEST(HostileInputs, SolverAndColliderNamesAreBoundedToo) {
  const std::string long_name(65, 'b');
  EXPECT_TRUE(HasError(load(kBase, {"solvers.0.name=" + long_name}),
                       at_set("solvers.0.name=" + long_name),
                       {"solvers.0.name", "at most 64 characters", "65"}));
  const std::string collider =
      "colliders=[{name: " + long_name + ", type: sphere, center: [0, 0, 0], radius: 0.1}]";
  EXPECT_TRUE(HasError(load(kBase, {collider}), at_set(collider),
                       {"colliders.0.name", "at most 64 characters"}));
  EXPECT_LOADS(load(kBase, {"name=" + std::string(64, 'c')}));
}

// ---------------------------------------------------------------------------------------------
// 2. Builders' exceptions and the lengths behind them

TEST(HostileInputs, ADiscFarAwayIsALocatedErrorNotAnAbort) {
  const auto result = load(kMinimal, {"cloth={shape: disc, center: [1e16, 1, 0], mass: 0.1}"});
  EXPECT_TRUE(HasError(result, at_set("cloth={shape: disc, center: [1e16, 1, 0], mass: 0.1}"),
                       {"cloth.center.0", "<= 10000", "1e16"}));
}

TEST(HostileInputs, AMeshScaledToNothingOrFarAwayIsALocatedError) {
  const TempFolder folder("mesh_scale");
  folder.write("square.obj", kSquareMesh);
  // Out of the scale's range.
  const auto tiny = load_scene_file(folder.write("a.yaml", mesh_scene("1e-150", "[0, 1, 0]")));
  EXPECT_TRUE(
      HasError(tiny, folder.path().string() + "/a.yaml:6:", {"cloth.scale", ">= 1e-06", "1e-150"}));
  // In range, but the placed mesh is 1 micrometre across: smaller than any cloth may be.
  const auto small = load_scene_file(folder.write("b.yaml", mesh_scene("1e-6", "[0, 1, 0]")));
  EXPECT_TRUE(HasError(small, folder.path().string() + "/b.yaml:5:",
                       {"cloth.path", "scaled by 1e-06", "its size", ">= 0.001"}));
  const auto far = load_scene_file(folder.write("c.yaml", mesh_scene("1", "[1e16, 0, 0]")));
  EXPECT_TRUE(HasError(far, folder.path().string() + "/c.yaml:7:", {"cloth.center.0", "1e16"}));
  EXPECT_LOADS(load_scene_file(folder.write("d.yaml", mesh_scene("0.5", "[0, 1, 0]"))));
}

// ---------------------------------------------------------------------------------------------
// 3. UTF-8 only

TEST(HostileInputs, SceneTextThatIsNotUtf8IsRefusedWithItsLine) {
  const auto result = load(with_line(kBase, 3, "description: caf\xe9\nduration: 0.5"));
  EXPECT_TRUE(HasError(result, at(3), {"is not UTF-8 text", "0xe9"}));
  const auto truncated = load(kBase + "# \xe2\x82");
  EXPECT_TRUE(HasError(truncated, at(35), {"is not UTF-8 text", "ends inside"}));
  EXPECT_LOADS(load(with_line(kBase, 3, "description: caf\xc3\xa9 \xe2\x82\xac\nduration: 0.5")));
}

TEST(HostileInputs, OverridesThatAreNotUtf8AreRefused) {
  const auto result = load(kBase, {"description=\xff\xfe"});
  EXPECT_TRUE(HasError(result, at_set("description=\\xff\\xfe"), {"is not UTF-8 text", "0xff"}));
}

// ---------------------------------------------------------------------------------------------
// 4. Collider sizes and centres

TEST(HostileInputs, ColliderSizesAndCentresHaveFiniteRanges) {
  const std::string box =
      "colliders=[{name: b, type: box, center: [0, 0, 0], "
      "half_extents: [1e308, 1, 1]}]";
  EXPECT_TRUE(HasError(load(kBase, {box}), at_set(box),
                       {"colliders.0.half_extents.0", ">= 1e-06 and <= 10000", "1e308"}));
  const std::string far = "colliders=[{name: s, type: sphere, center: [1e308, 0, 0], radius: 1}]";
  EXPECT_TRUE(HasError(load(kBase, {far}), at_set(far),
                       {"colliders.0.center.0", ">= -10000 and <= 10000"}));
  const std::string axis =
      "colliders=[{name: c, type: cylinder, center: [0, 0, 0], radius: 1, "
      "height: 1, axis: [1e300, 1e300, 0]}]";
  EXPECT_TRUE(HasError(load(kBase, {axis}), at_set(axis), {"colliders.0.axis.0"}));
}

// ---------------------------------------------------------------------------------------------
// 5. Cloth size and gravity (the Hausdorff distance's own bound: test_surface_distance.cpp)

TEST(HostileInputs, AMicroscopicClothOrCrushingGravityIsRefused) {
  EXPECT_TRUE(HasError(load(kBase, {"cloth.size=[1e-5,1e-5]"}), at_set("cloth.size=[1e-5,1e-5]"),
                       {"cloth.size.0", ">= 0.001"}));
  EXPECT_TRUE(HasError(load(kBase, {"gravity=[0,-1e10,0]"}), at_set("gravity=[0,-1e10,0]"),
                       {"gravity.1", "<= 1000"}));
  // Each component in range, the magnitude not.
  EXPECT_TRUE(HasError(load(kBase, {"gravity=[600,-600,600]"}), at_set("gravity=[600,-600,600]"),
                       {"gravity", "magnitude of at most 1000 m/s^2", "1039"}));
}

// ---------------------------------------------------------------------------------------------
// 6. Whole numbers checked before conversion; every physical scalar finite and bounded

TEST(HostileInputs, APinIndexPastAnIntDoesNotWrapToParticleZero) {
  const std::string pins = "cloth.pins=[{index: 4294967296}]";
  EXPECT_TRUE(HasError(load(kBase, {pins}), at_set(pins),
                       {"cloth.pins.0.index", "<= 999999", "4294967296"}));
  const std::string coordinate = "cloth.pins=[[4294967296, 0]]";
  EXPECT_TRUE(HasError(load(kBase, {coordinate}), at_set(coordinate), {"cloth.pins.0.0"}));
  EXPECT_TRUE(HasError(load(kBase, {"cloth.resolution=[4294967298, 1]"}),
                       at_set("cloth.resolution=[4294967298, 1]"), {"cloth.resolution.0"}));
}

TEST(HostileInputs, HugePhysicalScalarsAreRefusedByName) {
  struct Case {
    std::string set;
    std::string key;
  };
  const std::vector<Case> cases = {
      {"cloth.air_damping=1e308", "cloth.air_damping"},
      {"cloth.mass=1e300", "cloth.mass"},
      {"cloth.thickness=1e300", "cloth.thickness"},
      {"cloth.perturbation=1e300", "cloth.perturbation"},
      {"cloth.springs.stretch.ks=1e300", "cloth.springs.stretch.ks"},
      {"cloth.springs.bend.kd=1e300", "cloth.springs.bend.kd"},
      {"cloth.rotation=[1e300, 0, 0]", "cloth.rotation.0"},
      {"contact.stiffness=1e300", "contact.stiffness"},
      {"contact.damping=1e300", "contact.damping"},
      {"contact.friction=1e300", "contact.friction"},
      {"frame_rate=1e300", "frame_rate"},
      {"duration=1e300", "duration"},
      {"solvers.0.max_speed=1e300", "solvers.0.max_speed"},
      {"solvers.0.runaway_stretch=1e300", "solvers.0.runaway_stretch"},
      {"cloth.pins=[{within: {center: [0, 1, 0], radius: 1e300}}]", "cloth.pins.0.within.radius"},
  };
  for (const auto& c : cases)
    EXPECT_TRUE(HasError(load(kBase, {c.set}), at_set(c.set), {c.key, "must be", "<="})) << c.set;
}

// ---------------------------------------------------------------------------------------------
// 7. An override changes only the key it names, aliases or not

TEST(HostileInputs, AnOverrideOfAnAliasedMapLeavesItsTwinAlone) {
  const std::string text =
      with_line(with_line(kBase, 18, "    stretch: &s {ks: 500, kd: 0.1}"), 19, "    shear: *s");
  const auto plain = load(text);
  ASSERT_LOADS(plain);
  EXPECT_DOUBLE_EQ(plain.scene->cloth.grid.shear.ks, 500.0);  // the alias itself works
  const auto result = load(text, {"cloth.springs.shear.ks=7"});
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.shear.ks, 7.0);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.shear.kd, 0.1);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.stretch.ks, 500.0);
}

TEST(HostileInputs, AnOverrideOfAnAliasedScalarOrListItemLeavesItsTwinAlone) {
  const std::string scalars = with_line(with_line(kBase, 18, "    stretch: {ks: &k 500, kd: 0.1}"),
                                        20, "    bend: {ks: *k, kd: 0.01}");
  const auto result = load(scalars, {"cloth.springs.bend.ks=3"});
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.bend.ks, 3.0);
  EXPECT_DOUBLE_EQ(result.scene->cloth.grid.stretch.ks, 500.0);

  // The same solver twice (as an alias), renamed in one place.
  const std::string solvers =
      without_lines(kBase, 30, 34) +
      "solvers:\n  - &one {name: one, type: spring_damper, dt: 0.001041666666666666667}\n"
      "  - *one\n";
  const auto renamed = load(solvers, {"solvers.1.name=two"});
  ASSERT_LOADS(renamed);
  ASSERT_EQ(renamed.scene->solvers.size(), 2u);
  EXPECT_EQ(renamed.scene->solvers[0].name, "one");
  EXPECT_EQ(renamed.scene->solvers[1].name, "two");
}

TEST(HostileInputs, AnOverrideUnderAnAliasedMapLeavesItsTwinAlone) {
  // The whole springs map is shared by two keys; the override goes through it.
  const std::string text =
      kBase +
      "colliders:\n  - {name: a, type: sphere, center: [0, 0, 0], radius: &r 0.2}\n"
      "  - {name: b, type: sphere, center: [1, 0, 0], radius: *r}\n";
  const auto result = load(text, {"colliders.1.radius=0.5"});
  ASSERT_LOADS(result);
  EXPECT_DOUBLE_EQ(result.scene->colliders[0].radius, 0.2);
  EXPECT_DOUBLE_EQ(result.scene->colliders[1].radius, 0.5);
  const std::string nested = with_line(kBase, 7, "cloth: &c") + "metrics: {drape_support: 0.1}\n";
  ASSERT_LOADS(load(nested));
}

// ---------------------------------------------------------------------------------------------
// 8. Particle counts and memory, checked before anything is allocated

TEST(HostileInputs, TheFormerMaximumOfRingsIsRefusedByItsRange) {
  const std::string disc = "cloth={shape: disc, rings: 2000, mass: 0.1}";
  EXPECT_TRUE(HasError(load(kMinimal, {disc}), at_set(disc), {"cloth.rings", "<= 1000", "2000"}));
  EXPECT_LOADS(load(kMinimal, {"cloth={shape: disc, rings: 30, mass: 0.1}"}));
}

TEST(HostileInputs, ADiscRingAHairInsideTheRimIsRefusedByItsParticleCount) {
  // The drape support's ring at 0.0999999 m of a 0.1 m disc: the last ring, 1e-7 m wide, would hold
  // about six million particles.
  const std::string text =
      "name: disc\nduration: 0.1\ncloth:\n  shape: disc\n  radius: 0.1\n  rings: 10\n"
      "  mass: 0.1\nmetrics: {drape_support: 0.0999999}\nsolvers: [{type: spring_damper}]\n";
  const auto result = load(text);
  EXPECT_TRUE(HasError(result, at(6), {"cloth.rings", "6283469 particles", "at most 1000000"}));
}

TEST(HostileInputs, AGridOverTheParticleLimitIsRefusedWithTheLimit) {
  EXPECT_TRUE(HasError(load(kBase, {"cloth.resolution=[1001,1000]"}),
                       at_set("cloth.resolution=[1001,1000]"),
                       {"cloth.resolution", "1001000 particles", "at most 1000000"}));
}

// ---------------------------------------------------------------------------------------------
// 9. Regular files of at most 64 MB

TEST(HostileInputs, ADeviceIsNotReadAsAScene) {
  const auto result = load_scene_file("/dev/zero");
  ASSERT_EQ(result.errors.size(), 1u) << all_errors(result);
  EXPECT_NE(result.errors[0].find("/dev/zero: is not a regular file"), std::string::npos)
      << result.errors[0];
}

TEST(HostileInputs, ASceneOrMeshOverSixtyFourMegabytesIsNotRead) {
  const TempFolder folder("big");
  const fs::path big = folder.write("big.yaml", "name: big\n");
  fs::resize_file(big, (64u << 20) + 1);  // sparse: no disk space used
  const auto result = load_scene_file(big);
  ASSERT_EQ(result.errors.size(), 1u) << all_errors(result);
  EXPECT_NE(result.errors[0].find("is 67108865 bytes; at most 67108864 bytes (64 MB)"),
            std::string::npos)
      << result.errors[0];

  const fs::path obj = folder.write("square.obj", kSquareMesh);
  fs::resize_file(obj, (64u << 20) + 1);
  const auto mesh = load_scene_file(folder.write("mesh.yaml", mesh_scene("1", "[0, 1, 0]")));
  EXPECT_TRUE(HasError(
      mesh, folder.path().string() + "/mesh.yaml:5:", {"cloth.path", "at most 67108864 bytes"}));
  const auto device = load_scene_file(
      folder.write("device.yaml", with_line(mesh_scene("1", "[0, 1, 0]"), 5, "  path: /dev/zero")));
  EXPECT_TRUE(HasError(
      device, folder.path().string() + "/device.yaml:5:", {"cloth.path", "is not a regular file"}));
}

// ---------------------------------------------------------------------------------------------
// 10. Empty scenes and second documents

TEST(HostileInputs, AnEmptySceneIsReportedAtLineOne) {
  EXPECT_TRUE(HasError(load(""), at(1), {"the scene is empty"}));
  EXPECT_TRUE(HasError(load("# only a comment\n"), at(1), {"the scene is empty"}));
}

TEST(HostileInputs, ASecondYamlDocumentIsRefusedAtItsLine) {
  EXPECT_TRUE(HasError(load(kBase + "---\nname: other\n"), at(35), {"second YAML document"}));
  EXPECT_TRUE(HasError(load("---\n" + kBase + "---\n"), at(36), {"second YAML document"}));
  EXPECT_LOADS(load("---\n" + kBase));
  // Content after a "..." end marker is a second document too; the marker alone is not.
  EXPECT_TRUE(HasError(load(kBase + "...\nname: other\n"), at(36), {"second YAML document"}));
  EXPECT_LOADS(load(kBase + "...\n"));
}

// yaml-cpp's multi-document reader never returns on a lone comma (found by the fuzzer): the loader
// reads one document and looks for a second by its markers.
TEST(HostileInputs, ALoneCommaIsAnErrorNotAHang) { EXPECT_FALSE(load(",").ok()); }

}  // namespace
