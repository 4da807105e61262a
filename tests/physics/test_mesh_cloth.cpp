// Disc and OBJ mesh cloth: ring layout, spring counts by kind, vertex areas, UVs, and bad OBJ files
// refused with the line and the reason.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "drapelab/cloth_limits.hpp"
#include "drapelab/disc_cloth.hpp"
#include "drapelab/drape_metrics.hpp"
#include "drapelab/mesh_cloth.hpp"
#include "drapelab/obj_reader.hpp"
#include "metrics/projected_area.hpp"

namespace drapelab {
namespace {

MeshClothSpec cloth_of(TriangleMesh mesh) {
  MeshClothSpec spec;
  spec.mesh = std::move(mesh);
  spec.areal_density = 0.2;  // kg/m^2
  return spec;
}

double triangle_area_sum(const ClothModel& model) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < model.triangles.cols(); ++t) {
    const auto& x = model.rest_positions;
    sum += 0.5 * (x.col(model.triangles(1, t)) - x.col(model.triangles(0, t)))
                     .cross(x.col(model.triangles(2, t)) - x.col(model.triangles(0, t)))
                     .norm();
  }
  return sum;
}

TEST(DiscCloth, HasARingExactlyAtTheSupportRadius) {
  DiscSpec spec;
  spec.radius = 0.15;
  spec.rings = 20;
  spec.ring_at = 0.09;
  const std::vector<double> radii = disc_ring_radii(spec);
  ASSERT_EQ(radii.size(), 20u);
  EXPECT_EQ(radii[11], 0.09) << "12 of 20 rings inside 0.09 / 0.15";
  EXPECT_EQ(radii.back(), 0.15);
  for (std::size_t k = 1; k < radii.size(); ++k) EXPECT_GT(radii[k], radii[k - 1]);
  const TriangleMesh mesh = make_disc_mesh(spec);
  const int start = disc_ring_start(spec, 12), count = disc_ring_count(spec, 12);
  for (int p = 0; p < count; ++p)
    EXPECT_NEAR((mesh.vertices.col(start + p) - spec.center).norm(), 0.09, 1e-15);
}

TEST(DiscCloth, SpringCountsAreaAndWinding) {
  DiscSpec spec;
  spec.radius = 0.15;
  spec.rings = 10;
  const ClothModel model = build_mesh_cloth(cloth_of(make_disc_mesh(spec)));
  const int v = model.particle_count(), f = static_cast<int>(model.triangles.cols());
  const int rim = disc_ring_count(spec, 10);
  // Ring k of an evenly spaced disc has round(2 pi k) particles.
  EXPECT_EQ(disc_ring_count(spec, 1), 6);
  EXPECT_EQ(disc_ring_count(spec, 10), 63);
  // A disc is a topological disc: V - E + F = 1, every edge a stretch spring, and every interior
  // edge one spring across it: shear where the edge is the long diagonal of both its triangles
  // (where neighbouring rings' particles line up), bend elsewhere.
  const int edges = v + f - 1;
  EXPECT_EQ(static_cast<int>(model.springs.count(SpringKind::stretch)), edges);
  EXPECT_EQ(static_cast<int>(model.springs.count(SpringKind::bend) +
                             model.springs.count(SpringKind::shear)),
            edges - rim);
  EXPECT_GT(model.springs.count(SpringKind::bend), 2 * model.springs.count(SpringKind::shear));
  // Vertex areas add up to the triangles' area, the inscribed rim polygon's, close to pi R^2.
  const double polygon = 0.5 * rim * 0.15 * 0.15 * std::sin(2.0 * std::numbers::pi / rim);
  EXPECT_NEAR(model.rest_area(), triangle_area_sum(model), 1e-15);
  EXPECT_NEAR(model.rest_area(), polygon, 1e-12);
  EXPECT_NEAR(model.rest_area(), std::numbers::pi * 0.0225, 0.002 * std::numbers::pi * 0.0225);
  EXPECT_NEAR(model.total_mass(), 0.2 * model.rest_area(), 1e-15);
  for (Eigen::Index t = 0; t < model.triangles.cols(); ++t) {
    const auto& x = model.rest_positions;
    const Eigen::Vector3d n =
        (x.col(model.triangles(1, t)) - x.col(model.triangles(0, t)))
            .cross(x.col(model.triangles(2, t)) - x.col(model.triangles(0, t)));
    ASSERT_GT(n.y(), 0.0) << "triangle " << t << " is wound clockwise about +y";
  }
  // The flat disc's union shadow is its area.
  EXPECT_NEAR(projected_union_area(model.rest_positions, model.triangles, Eigen::Vector3d::UnitY()),
              polygon, 0.005 * polygon);
}

TEST(DiscCloth, FlatDiscOverItsSupportHasDrapeCoefficientOne) {
  DiscSpec spec;
  spec.ring_at = 0.09;
  const ClothModel model = build_mesh_cloth(cloth_of(make_disc_mesh(spec)));
  const DrapeMeter meter(model, {spec.center, 0.09}, Eigen::Vector3d::UnitY());
  const DrapeMeasure flat = meter.measure(model, model.rest_positions);
  EXPECT_DOUBLE_EQ(flat.coefficient, 1.0);
  EXPECT_EQ(flat.nodes, 0) << "a circle has no folds";
}

TEST(MeshCloth, QuadGridSplitIntoTrianglesGetsTheGridsShearDiagonals) {
  // 3 x 3 vertices, 4 unit cells, each split along the same diagonal.
  TriangleMesh mesh;
  mesh.vertices.resize(3, 9);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) mesh.vertices.col(3 * j + i) = Eigen::Vector3d(i, 0, j);
  mesh.triangles.resize(3, 8);
  int t = 0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 3 * j + i;
      mesh.triangles.col(t++) << a, a + 4, a + 1;
      mesh.triangles.col(t++) << a, a + 3, a + 4;
    }
  const ClothModel model = build_mesh_cloth(cloth_of(mesh));
  // 12 grid edges + 4 diagonals; each cell's other diagonal is a shear spring; the 4 interior grid
  // edges each get a bend spring between the vertices opposite them.
  EXPECT_EQ(model.springs.count(SpringKind::stretch), 16u);
  EXPECT_EQ(model.springs.count(SpringKind::shear), 4u);
  EXPECT_EQ(model.springs.count(SpringKind::bend), 4u);
  for (std::size_t e = 0; e < model.springs.size(); ++e)
    if (model.springs.kind[e] == SpringKind::shear) {
      EXPECT_NEAR(model.springs.rest_length[e], std::sqrt(2.0), 1e-15);
      const int a = model.springs.v0[e], b = model.springs.v1[e];
      EXPECT_EQ(std::abs(a - b), 2) << "the anti-diagonal of a cell joins (i+1, j) and (i, j+1)";
    }
  EXPECT_NEAR(model.rest_area(), 4.0, 1e-15);
  EXPECT_EQ(model.uvs.cols(), 9) << "planar UVs when the mesh has none";
  EXPECT_DOUBLE_EQ(model.uvs.maxCoeff(), 1.0);
}

ObjReadResult parse(const std::string& text) {
  std::istringstream in(text);
  return read_obj(in);
}

TEST(ObjReader, ReadsVerticesUvsAndSplitsPolygons) {
  const auto result = parse(
      "# a unit square as one quad\n"
      "o square\n"
      "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "vn 0 1 0\n"
      "f 1/1/1 2/2/1 3/3/1 4/4/1\n");
  ASSERT_TRUE(result.mesh) << result.error;
  EXPECT_EQ(result.mesh->vertices.cols(), 4);
  EXPECT_EQ(result.mesh->triangles.cols(), 2);
  ASSERT_EQ(result.mesh->uvs.cols(), 4);
  EXPECT_EQ(result.mesh->uvs.col(2), Eigen::Vector2d(1, 1));
  EXPECT_FALSE(mesh_problem(*result.mesh));
  // Negative indices count back from the last vertex.
  const auto relative = parse("v 0 0 0\nv 1 0 0\nv 0 0 1\nf -3 -2 -1\n");
  ASSERT_TRUE(relative.mesh) << relative.error;
  EXPECT_EQ(relative.mesh->triangles.col(0), Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(relative.mesh->uvs.cols(), 0);
}

TEST(ObjReader, BadFilesAreRefusedWithTheLineAndTheReason) {
  struct Case {
    std::string text;
    int line;
    std::string says;
  };
  const Case cases[] = {
      {"v 0 0 0\nv 1 zero 0\n", 2, "'zero' is not a number"},
      {"v 0 0\n", 1, "'v' needs 3 numbers"},
      {"v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 4\n", 4, "face uses vertex 4 but 3 vertices"},
      {"v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "at least 3 corners"},
      {"v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1/7 2 3\n", 4, "texture coordinate 7"},
      {"v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 x 3\n", 4, "does not start with a vertex index"},
      {"v 0 0 0\nv 1 0 0\n", 0, "no faces"},
      {"", 0, "no vertices"},
  };
  for (const Case& c : cases) {
    const auto result = parse(c.text);
    EXPECT_FALSE(result.mesh) << c.text;
    EXPECT_EQ(result.error_line, c.line) << c.text;
    EXPECT_NE(result.error.find(c.says), std::string::npos) << result.error;
  }
  EXPECT_NE(read_obj_file("/nonexistent/cloth.obj").error.find("cannot be read (no such file)"),
            std::string::npos);
}

TEST(MeshCloth, MeshesThatAreNotAClothSurfaceAreRefused) {
  auto problem = [](const std::string& text) {
    const auto result = parse(text);
    EXPECT_TRUE(result.mesh) << result.error;
    return result.mesh ? mesh_problem(*result.mesh).value_or("") : std::string("unreadable");
  };
  EXPECT_NE(problem("v 0 0 0\nv 1 0 0\nv 0 0 1\nv 5 5 5\nf 1 2 3\n")
                .find("vertex 3 is used by no triangle"),
            std::string::npos);
  EXPECT_NE(problem("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").find("triangle 0 has no area"),
            std::string::npos);
  EXPECT_NE(problem("v 0 0 0\nv 1 0 0\nv 0 0 1\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 1 2 4\nf 1 2 5\n")
                .find("shared by 3 triangles"),
            std::string::npos);
  const auto fine = parse("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");
  MeshClothSpec spec = cloth_of(*fine.mesh);
  spec.pinned = {3};
  EXPECT_THROW(build_mesh_cloth(spec), std::invalid_argument);
  spec.pinned = {0};
  spec.mass = 0.1;  // and areal_density: not both
  EXPECT_THROW(build_mesh_cloth(spec), std::invalid_argument);
}

// Limits (cloth_limits.hpp): sizes are checked from counts, before anything is allocated.
TEST(ClothLimits, DiscSizeIsCountedWithoutBuildingIt) {
  DiscSpec disc;
  disc.rings = 10;
  const TriangleMesh mesh = make_disc_mesh(disc);
  const ClothSize size = disc_cloth_size(disc);
  EXPECT_EQ(size.particles, static_cast<double>(mesh.vertices.cols()));
  EXPECT_EQ(size.triangles, static_cast<double>(mesh.triangles.cols()));
  EXPECT_GE(size.springs, static_cast<double>(build_mesh_cloth(cloth_of(mesh)).springs.size()));
}

TEST(ClothLimits, ADiscRingAHairInsideTheRimIsRefusedBeforeItIsBuilt) {
  DiscSpec disc;
  disc.radius = 0.1;
  disc.rings = 4;
  disc.ring_at = 0.1 * (1.0 - 1e-12);  // the last ring would hold about 6e12 particles
  EXPECT_GT(disc_cloth_size(disc).particles, 1e12);
  EXPECT_THROW(make_disc_mesh(disc), std::invalid_argument);
  EXPECT_THROW(disc_ring_count(disc, 4), std::invalid_argument);
  EXPECT_EQ(disc_ring_count(disc, 1), 6);
}

TEST(ClothLimits, ParticlesAndTrianglesEachHaveALimit) {
  EXPECT_FALSE(cloth_size_problem(grid_cloth_size(1000, 1000)));  // the largest square grid
  const auto particles = cloth_size_problem(grid_cloth_size(2000, 2000));
  ASSERT_TRUE(particles);
  EXPECT_NE(particles->find("gives 4000000 particles; at most 1000000"), std::string::npos);
  const auto triangles = cloth_size_problem(mesh_cloth_size(1000, 3e6));
  ASSERT_TRUE(triangles);
  EXPECT_NE(triangles->find("3000000 triangles; at most 2000000"), std::string::npos);
}

TEST(ClothLimits, AMeshProblemIsFoundBeforeItsEdgeMapIsBuilt) {
  TriangleMesh mesh;
  mesh.vertices = Eigen::Matrix3Xd::Zero(3, 3);
  mesh.triangles = Eigen::Matrix3Xi::Zero(3, kMaxClothTriangles + 1);  // 24 MB of indices
  const auto problem = mesh_problem(mesh);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("triangles; at most 2000000"), std::string::npos) << *problem;
  mesh.triangles.resize(3, 1);
  mesh.triangles.col(0) << 0, 1, 2;
  mesh.vertices.col(1) << 1, 0, std::nan("");
  mesh.vertices.col(2) << 0, 0, 1;
  const auto nan = mesh_problem(mesh);
  ASSERT_TRUE(nan);
  EXPECT_NE(nan->find("vertex 1 has a coordinate that is not a finite number"), std::string::npos);
}

TEST(ObjReader, ReadsOnlyRegularFilesOfAtMostSixtyFourMegabytes) {
  EXPECT_NE(read_obj_file("/dev/zero").error.find("is not a regular file"), std::string::npos);
  const auto folder = std::filesystem::temp_directory_path() / "drapelab_obj_limits";
  std::filesystem::create_directories(folder);
  const auto big = folder / "big.obj";
  std::ofstream(big) << "v 0 0 0\n";
  std::filesystem::resize_file(big, kMaxObjFileBytes + 1);  // sparse: no disk space used
  const ObjReadResult result = read_obj_file(big);
  std::filesystem::remove_all(folder);
  EXPECT_FALSE(result.mesh);
  EXPECT_NE(result.error.find("is 67108865 bytes; at most 67108864 bytes (64 MB)"),
            std::string::npos)
      << result.error;
}

TEST(ObjReader, StopsReadingPastTheTriangleLimit) {
  // One face of kMaxClothTriangles + 3 corners fans into one triangle too many.
  std::string face = "f";
  for (long long k = 0; k < kMaxClothTriangles + 3; ++k) face += k % 2 ? " 2" : " 1";
  std::istringstream in("v 0 0 0\nv 1 0 0\n" + face + "\n");
  const ObjReadResult result = read_obj(in);
  EXPECT_FALSE(result.mesh);
  EXPECT_EQ(result.error_line, 3);
  EXPECT_NE(result.error.find("more than 2000000 triangles"), std::string::npos) << result.error;
}

}  // namespace
}  // namespace drapelab
