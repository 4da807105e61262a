// Mesh colliders (colliders[].type: mesh) and garment seams (cloth.seams) in scene files: what
// loads, what a bad OBJ gives (a located error, or a warning for a mesh that is usable but odd),
// and the seams' checks.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "fixtures/scene_text.hpp"

namespace drapelab {
namespace {

namespace fs = std::filesystem;
using fixtures::at_line;
using fixtures::HasError;
using scene::load_scene_file;
using scene::load_scene_text;

class MeshColliderScene : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("drapelab_mesh_collider_" + std::to_string(::getpid()));
    fs::create_directories(folder_ / "meshes");
    scene_file_ = folder_ / "scene.yaml";  // before any at(): arguments run in no fixed order
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(folder_ / name) << text;
    return folder_ / name;
  }
  // Loads kScene with the collider's file and scale lines as given.
  scene::LoadResult load_with(const std::string& obj) {
    write("meshes/solid.obj", obj);
    write("scene.yaml", kScene);
    return load_scene_file(scene_file_);
  }
  std::string at(int line) const { return at_line(scene_file_.string(), line); }

  static constexpr const char* kScene =
      "name: mesh\n"                         // 1
      "duration: 0.1\n"                      // 2
      "cloth:\n"                             // 3
      "  resolution: [5, 5]\n"               // 4
      "  center: [0, 2, 0]\n"                // 5
      "  mass: 0.1\n"                        // 6
      "colliders:\n"                         // 7
      "  - name: solid\n"                    // 8
      "    type: mesh\n"                     // 9
      "    file: meshes/solid.obj\n"         // 10
      "    scale: [2, 1, 2]\n"               // 11
      "    center: [0, 0.5, 0]\n"            // 12
      "solvers: [{type: spring_damper}]\n";  // 13
  fs::path folder_;
  fs::path scene_file_;
};

// A unit tetrahedron, wound outwards (every face counter-clockwise seen from outside).
const std::string kTetrahedron =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

bool any_warning(const scene::LoadResult& result, const std::string& part) {
  for (const std::string& w : result.warnings)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

TEST_F(MeshColliderScene, LoadsScaledInItsFrameAndWritesItsFileAndScale) {
  const auto result = load_with(kTetrahedron);
  ASSERT_TRUE(result.ok()) << (result.errors.empty() ? "" : result.errors.front());
  EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
  const Collider& solid = result.scene->colliders.front();
  ASSERT_EQ(solid.shape, ColliderShape::mesh);
  ASSERT_TRUE(solid.mesh);
  EXPECT_EQ(solid.mesh->vertices.col(1), Eigen::Vector3d(2, 0, 0));  // scaled by [2, 1, 2]
  EXPECT_EQ(collider_pose(solid, 0.0).translation(), Eigen::Vector3d(0, 0.5, 0));
  const auto again = load_scene_text(scene::resolved_scene_yaml(*result.scene), "resolved.yaml");
  ASSERT_TRUE(again.ok()) << (again.errors.empty() ? "" : again.errors.front());
  EXPECT_EQ(again.scene->colliders.front().mesh->vertices, solid.mesh->vertices);
}

TEST_F(MeshColliderScene, ABadFileIsAnErrorNamingTheSceneLineAndTheObjLine) {
  EXPECT_TRUE(HasError(load_with("v 0 0 0\nv 1 0 zero\n"), at(10),
                       {"colliders.0.file", "solid.obj:2", "'zero' is not a number"}));
  // Degenerate: the fourth vertex on the line through the first two.
  EXPECT_TRUE(
      HasError(load_with("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 3 2\nf 1 2 4\n"), at(10),
               {"colliders.0.file", "not a usable collider surface", "triangle 2 has no area"}));
  EXPECT_TRUE(HasError(load_with("v 0 0 0\nv 1e9 0 0\nv 0 1 0\nf 1 2 3\n"), at(10),
                       {"colliders.0.file", "at most 10000 m"}));
  fs::remove(folder_ / "meshes/solid.obj");
  EXPECT_TRUE(HasError(load_scene_file(scene_file_), at(10),
                       {"colliders.0.file", "cannot be read (no such file)"}));
}

// Bullet gives a concave mesh no inertia: a mesh collider is static or kinematic only.
TEST_F(MeshColliderScene, AMeshCannotBeDynamic) {
  write("meshes/solid.obj", kTetrahedron);
  std::string text = kScene;
  text.insert(text.find("solvers:"), "    dynamic: {mass: 1}\n");
  write("scene.yaml", text);
  EXPECT_TRUE(HasError(load_scene_file(scene_file_), at(13),
                       {"colliders.0.dynamic", "a mesh collider cannot be dynamic"}));
}

TEST_F(MeshColliderScene, AnOpenOrOddMeshLoadsWithAWarning) {
  // The tetrahedron without its last face: open.
  const auto open = load_with("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  ASSERT_TRUE(open.ok());
  EXPECT_TRUE(any_warning(open, "is open (3 edges have one triangle)"));
  EXPECT_TRUE(any_warning(open, at(10)));
  // One face turned the wrong way round.
  const auto flipped =
      load_with("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  ASSERT_TRUE(flipped.ok());
  EXPECT_TRUE(any_warning(flipped, "is not wound consistently"));
  // A fin: a third triangle on one edge.
  const auto fin = load_with(kTetrahedron + "v 1 1 1\nf 1 2 5\n");
  ASSERT_TRUE(fin.ok());
  EXPECT_TRUE(any_warning(fin, "shared by three or more triangles"));
}

TEST_F(MeshColliderScene, AMeshWoundInwardsIsTurnedOutwards) {
  const auto inwards =
      load_with("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n");
  ASSERT_TRUE(inwards.ok());
  EXPECT_TRUE(any_warning(inwards, "is wound inwards"));
  const auto outwards = load_with(kTetrahedron);
  EXPECT_EQ(inwards.scene->colliders.front().mesh->triangles.col(0),
            Eigen::Vector3i(0, 2, 1));  // face 1 3 2, as the outward tetrahedron has it
  EXPECT_EQ(outwards.scene->colliders.front().mesh->triangles.col(0), Eigen::Vector3i(0, 2, 1));
}

// Two 3 x 3 panels of a mesh cloth, the second 0.1 m behind the first, sewn along two sides.
const std::string kPanelsObj =
    "v 0 0 0\nv 0.1 0 0\nv 0.2 0 0\nv 0 0.1 0\nv 0.1 0.1 0\nv 0.2 0.1 0\n"
    "v 0 0 -0.1\nv 0.1 0 -0.1\nv 0.2 0 -0.1\nv 0 0.1 -0.1\nv 0.1 0.1 -0.1\nv 0.2 0.1 -0.1\n"
    "f 1 2 5 4\nf 2 3 6 5\nf 7 10 11 8\nf 8 11 12 9\n";

std::string seam_scene(const std::string& seams) {
  return "name: sewn\n"                                // 1
         "duration: 0.1\n"                             // 2
         "cloth:\n"                                    // 3
         "  shape: mesh\n"                             // 4
         "  path: meshes/panels.obj\n"                 // 5
         "  mass: 0.01\n"                              // 6
         "  springs: {stretch: {ks: 300, kd: 0.2}}\n"  // 7
         "  seams:\n" +                                // 8
         seams +                                       // 9...
         "solvers: [{type: spring_damper}]\n";
}

TEST_F(MeshColliderScene, SeamsPairTheirParticlesWithTheirRestGapsAndDefaults) {
  write("meshes/panels.obj", kPanelsObj);
  const auto result = load_scene_file(
      write("sewn.yaml", seam_scene("    - {a: [0, 3], b: [6, 9], close_time: 0.25}\n"
                                    "    - {a: [2, 5], b: [8, 11], stiffness: 50, damping: 0}\n")));
  ASSERT_TRUE(result.ok()) << (result.errors.empty() ? "" : result.errors.front());
  const auto& seams = result.scene->cloth.seams;
  ASSERT_EQ(seams.size(), 2u);
  EXPECT_EQ(seams[0].b, (std::vector<int>{6, 9}));
  EXPECT_NEAR(seams[0].rest[1], 0.1, 1e-12);
  EXPECT_EQ(seams[0].close_time, 0.25);
  EXPECT_EQ(seams[0].stiffness, 300.0);  // the stretch springs'
  EXPECT_EQ(seams[0].damping, 0.2);
  EXPECT_EQ(seams[1].close_time, 0.5);
  EXPECT_EQ(seams[1].stiffness, 50.0);
  const auto constraints = scene::scene_constraints(*result.scene);
  ASSERT_TRUE(constraints);
  ASSERT_EQ(constraints->list.size(), 4u);
  const DistanceConstraint& stitch = constraints->list.front();
  EXPECT_NEAR(stitch.length_at(0.0), 0.1, 1e-12);
  EXPECT_NEAR(stitch.length_at(0.125), 0.05, 1e-12);
  EXPECT_EQ(stitch.length_at(0.25), 0.0);
  EXPECT_EQ(stitch.length_at(1.0), 0.0);
  // resolved.yaml gives the same seams back.
  const auto again = load_scene_text(scene::resolved_scene_yaml(*result.scene), "resolved.yaml");
  ASSERT_TRUE(again.ok()) << (again.errors.empty() ? "" : again.errors.front());
  EXPECT_EQ(again.scene->cloth.seams[1].a, seams[1].a);
  EXPECT_EQ(again.scene->cloth.seams[1].stiffness, 50.0);
}

TEST_F(MeshColliderScene, BadSeamsAreLocatedErrors) {
  write("meshes/panels.obj", kPanelsObj);
  scene_file_ = folder_ / "sewn.yaml";
  const auto load_seams = [&](const std::string& seams) {
    return load_scene_file(write("sewn.yaml", seam_scene(seams)));
  };
  EXPECT_TRUE(HasError(load_seams("    - {a: [0, 3], b: [6]}\n"), at(9),
                       {"cloth.seams.0.b", "must be as long as a (2 particles), got 1"}));
  EXPECT_TRUE(HasError(load_seams("    - {a: [0, 3], b: [6, 3]}\n"), at(9),
                       {"cloth.seams.0.b.1", "sews particle 3 to itself"}));
  EXPECT_TRUE(HasError(load_seams("    - {a: [0, 12], b: [6, 9]}\n"), at(9),
                       {"cloth.seams.0.a.1", "must be a particle of the cloth (0 to 11), got 12"}));
  EXPECT_TRUE(HasError(load_seams("    - {a: edge_min_x, b: [6, 9]}\n"), at(9),
                       {"cloth.seams.0.a", "edge names are a grid's"}));
  EXPECT_TRUE(HasError(load_seams("    - {a: [0]}\n"), at(9), {"cloth.seams.0.b"}));
}

}  // namespace
}  // namespace drapelab
