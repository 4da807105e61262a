// Scene files with disc and mesh cloth, material presets and the drape support: what loads, what it
// builds, and the errors for what does not.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "fixtures/scene_text.hpp"

namespace drapelab {
namespace {

namespace fs = std::filesystem;
using fixtures::all_errors;
using fixtures::at_line;
using fixtures::HasError;
using scene::load_scene_file;
using scene::load_scene_text;

constexpr const char* kName = "shapes.yaml";

scene::LoadResult load(const std::string& text) { return load_scene_text(text, kName); }
std::string at(int line) { return at_line(kName, line); }

// A Cusick-like scene: a disc on a table. Line numbers matter for the error tests.
const std::string kDisc =
    "name: disc\n"                                                                           //  1
    "duration: 0.1\n"                                                                        //  2
    "cloth:\n"                                                                               //  3
    "  shape: disc\n"                                                                        //  4
    "  radius: 0.15\n"                                                                       //  5
    "  rings: 10\n"                                                                          //  6
    "  center: [0, 0.5, 0]\n"                                                                //  7
    "  material: cotton\n"                                                                   //  8
    "colliders:\n"                                                                           //  9
    "  - {name: table, type: cylinder, center: [0, 0.25, 0], radius: 0.09, height: 0.49}\n"  // 10
    "metrics:\n"                                                                             // 11
    "  drape_support: table\n"                                                               // 12
    "solvers: [{type: spring_damper}]\n";                                                    // 13

TEST(ClothShapes, DiscOnASupportHasARingAtItsRadius) {
  const auto result = load(kDisc);
  ASSERT_LOADS(result);
  const scene::Scene& s = *result.scene;
  EXPECT_EQ(s.cloth.shape, "disc");
  ASSERT_TRUE(s.drape_support);
  EXPECT_EQ(s.drape_support->collider, "table");
  EXPECT_DOUBLE_EQ(s.drape_support->disc.radius, 0.09);
  ASSERT_TRUE(s.cloth.disc.ring_at);
  EXPECT_DOUBLE_EQ(*s.cloth.disc.ring_at, 0.09);
  const ClothModel model = scene::build_scene_cloth(s);
  int on_support = 0;
  for (int i = 0; i < model.particle_count(); ++i) {
    const Eigen::Vector3d r = model.rest_positions.col(i) - Eigen::Vector3d(0, 0.5, 0);
    EXPECT_NEAR(r.y(), 0.0, 1e-15);
    if (std::abs(r.norm() - 0.09) < 1e-12) ++on_support;
  }
  EXPECT_EQ(on_support, disc_ring_count(s.cloth.disc, 6)) << "6 of 10 rings inside 0.09 / 0.15";
}

TEST(ClothShapes, MaterialGivesWeightAndSpringsAndExplicitKeysWin) {
  const auto cotton = load(kDisc);
  ASSERT_LOADS(cotton);
  const GridClothSpec& c = cotton.scene->cloth.grid;
  ASSERT_TRUE(c.areal_density);
  EXPECT_DOUBLE_EQ(*c.areal_density, 0.13);
  EXPECT_DOUBLE_EQ(c.thickness, 0.0003);
  EXPECT_DOUBLE_EQ(c.stretch.ks, 1000.0);
  // Bending from the rigidity 1e-5 N m at the disc's 1.5 cm ring spacing.
  EXPECT_NEAR(c.bend.ks, 16.0 * 1e-5 / (0.015 * 0.015 * 0.09), 1e-9);
  EXPECT_DOUBLE_EQ(c.bend.kd, 5e-5 * c.bend.ks);
  const auto denim = load(fixtures::with_line(kDisc, 8, "  material: denim"));
  ASSERT_LOADS(denim);
  EXPECT_GT(denim.scene->cloth.grid.bend.ks, 5.0 * c.bend.ks);
  // Explicit keys override the preset, key by key.
  const auto mixed =
      load(fixtures::insert_after(kDisc, 8, "  mass: 0.02\n  springs: {stretch: {ks: 700}}"));
  ASSERT_LOADS(mixed);
  EXPECT_FALSE(mixed.scene->cloth.grid.areal_density);
  EXPECT_DOUBLE_EQ(*mixed.scene->cloth.grid.mass, 0.02);
  EXPECT_DOUBLE_EQ(mixed.scene->cloth.grid.stretch.ks, 700.0);
  EXPECT_DOUBLE_EQ(mixed.scene->cloth.grid.stretch.kd, 5e-5 * 1000.0) << "kd stays the preset's";
  EXPECT_TRUE(HasError(load(fixtures::with_line(kDisc, 8, "  material: coton")), at(8),
                       {"cloth.material must be one of", "did you mean 'cotton'"}));
  EXPECT_TRUE(HasError(load(fixtures::without_lines(kDisc, 8, 8)), at(4),
                       {"cloth.mass is required", "material"}));
}

TEST(ClothShapes, DrapeSupportMustBeARoundColliderOrARadius) {
  const auto radius = load(fixtures::with_line(kDisc, 12, "  drape_support: 0.05"));
  ASSERT_LOADS(radius);
  EXPECT_TRUE(radius.scene->drape_support->collider.empty());
  EXPECT_EQ(radius.scene->drape_support->disc.center, Eigen::Vector3d(0, 0.5, 0))
      << "under the cloth's centre";
  EXPECT_TRUE(HasError(load(fixtures::with_line(kDisc, 12, "  drape_support: tabel")), at(12),
                       {"metrics.drape_support", "did you mean table"}));
  EXPECT_TRUE(HasError(load(fixtures::with_line(kDisc, 12, "  drape_support: -1")), at(12),
                       {"metrics.drape_support must be > 0"}));
  const std::string box =
      "  - {name: table, type: box, center: [0, 0.25, 0], half_extents: [0.1, 0.2, 0.1]}";
  EXPECT_TRUE(HasError(load(fixtures::with_line(kDisc, 10, box)), at(12),
                       {"'table' is a box", "no circular"}));
  const std::string tilted =
      "  - {name: table, type: cylinder, center: [0, 0.25, 0], radius: 0.09, height: 0.49, "
      "rotation: [90, 0, 0]}";
  EXPECT_TRUE(
      HasError(load(fixtures::with_line(kDisc, 10, tilted)), at(12), {"axis is along gravity"}));
}

TEST(ClothShapes, ShapeKeysBelongToTheirShape) {
  EXPECT_TRUE(HasError(load(fixtures::insert_after(kDisc, 6, "  resolution: [5, 5]")), at(7),
                       {"cloth.resolution is not a known key"}));
  EXPECT_TRUE(
      HasError(load(fixtures::insert_after(kDisc, 8, "  pins: [[0, 1]]")), at(9),
               {"cloth.pins.0 selects no particle", "grid coordinates [i, j] need shape: grid"}));
  EXPECT_TRUE(HasError(load(fixtures::insert_after(kDisc, 8, "  pins: [corners]")), at(9),
                       {"cloth.pins.0 must be one of", "center", "rim"}));
  const auto pinned = load(fixtures::insert_after(kDisc, 8, "  pins: [rim, center]"));
  ASSERT_LOADS(pinned);
  const ClothModel model = scene::build_scene_cloth(*pinned.scene);
  int count = 0;
  for (int i = 0; i < model.particle_count(); ++i) count += model.is_pinned(i);
  EXPECT_EQ(count, 1 + disc_ring_count(pinned.scene->cloth.disc, 10));
}

class MeshScene : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("drapelab_mesh_" + std::to_string(::getpid()));
    fs::create_directories(folder_ / "meshes");
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(folder_ / name) << text;
    return folder_ / name;
  }
  fs::path folder_;
};

const std::string kMeshScene =
    "name: cape\n"                                             // 1
    "duration: 0.1\n"                                          // 2
    "cloth:\n"                                                 // 3
    "  shape: mesh\n"                                          // 4
    "  path: meshes/square.obj\n"                              // 5
    "  scale: 0.5\n"                                           // 6
    "  center: [0, 1, 0]\n"                                    // 7
    "  mass: 0.1\n"                                            // 8
    "  pins: [{within: {center: [0, 1, 0], radius: 0.01}}]\n"  // 9
    "solvers: [{type: spring_damper}]\n";                      // 10

const std::string kSquareObj =
    "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0 0\n"
    "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";

TEST_F(MeshScene, LoadsRelativeToTheSceneFileScaledAndMoved) {
  write("meshes/square.obj", kSquareObj);
  const auto result = load_scene_file(write("cape.yaml", kMeshScene));
  ASSERT_LOADS(result);
  const ClothModel model = scene::build_scene_cloth(*result.scene);
  EXPECT_EQ(model.particle_count(), 5);
  EXPECT_EQ(model.rest_positions.col(0), Eigen::Vector3d(-0.5, 1.0, -0.5));
  EXPECT_TRUE(model.is_pinned(4));
  EXPECT_NEAR(model.rest_area(), 1.0, 1e-15);
  // resolved.yaml names the file so that it loads from anywhere.
  const auto again = load_scene_text(scene::resolved_scene_yaml(*result.scene), "resolved.yaml");
  ASSERT_LOADS(again);
  const auto without_header = [](const std::string& text) {
    return text.substr(text.find("\nname:"));
  };
  EXPECT_EQ(without_header(scene::resolved_scene_yaml(*again.scene)),
            without_header(scene::resolved_scene_yaml(*result.scene)));
  EXPECT_EQ(scene::build_scene_cloth(*again.scene).rest_positions, model.rest_positions);
}

TEST_F(MeshScene, BadOrMissingObjIsAnErrorNamingBothFiles) {
  write("meshes/square.obj", "v 0 0 0\nv 1 0 zero\n");
  const fs::path scene_file = write("cape.yaml", kMeshScene);
  const auto bad = load_scene_file(scene_file);
  EXPECT_TRUE(HasError(bad, at_line(scene_file.string(), 5),
                       {"cloth.path", "square.obj:2", "'zero' is not a number"}));
  write("meshes/square.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_TRUE(HasError(load_scene_file(scene_file), at_line(scene_file.string(), 5),
                       {"not a usable cloth", "no area"}));
  fs::remove(folder_ / "meshes/square.obj");
  EXPECT_TRUE(HasError(load_scene_file(scene_file), at_line(scene_file.string(), 5),
                       {"cloth.path", "cannot be read (no such file)"}));
}

}  // namespace
}  // namespace drapelab
