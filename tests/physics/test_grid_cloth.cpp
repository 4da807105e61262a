// The grid model builder: spring counts and rest lengths, masses, vertex areas, pins, triangles.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <set>

#include "drapelab/grid_cloth.hpp"

namespace drapelab {
namespace {

GridClothSpec grid(int nx, int ny, GridPlane plane = GridPlane::xz) {
  GridClothSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.plane = plane;
  spec.size = {2.0, 1.0};
  spec.center = {0.5, 1.0, -0.25};
  spec.mass = 0.3;
  return spec;
}

std::size_t clamp0(int n) { return n > 0 ? static_cast<std::size_t>(n) : 0; }

TEST(GridCloth, SpringCountsFollowTheGridFormulas) {
  for (const auto& [nx, ny] :
       std::vector<std::pair<int, int>>{{2, 2}, {3, 5}, {7, 4}, {33, 33}, {1, 10}, {12, 1}}) {
    const ClothModel model = build_grid_cloth(grid(nx, ny));
    SCOPED_TRACE(std::to_string(nx) + " x " + std::to_string(ny));
    EXPECT_EQ(model.particle_count(), nx * ny);
    EXPECT_EQ(model.springs.count(SpringKind::stretch), clamp0(nx * (ny - 1) + ny * (nx - 1)));
    EXPECT_EQ(model.springs.count(SpringKind::shear), clamp0(2 * (nx - 1) * (ny - 1)));
    EXPECT_EQ(model.springs.count(SpringKind::bend), clamp0(nx * (ny - 2)) + clamp0(ny * (nx - 2)));
    EXPECT_EQ(model.triangles.cols(), 2 * (nx - 1) * (ny - 1));
  }
}

TEST(GridCloth, RestLengthsAreTheLatticeDistances) {
  const GridClothSpec spec = grid(5, 9);
  const ClothModel model = build_grid_cloth(spec);
  const double dx = spec.size.x() / 4, dz = spec.size.y() / 8;
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const int a = s.v0[e], b = s.v1[e];
    const int di = std::abs(a % 5 - b % 5), dj = std::abs(a / 5 - b / 5);
    const double expected = std::hypot(di * dx, dj * dz);
    EXPECT_NEAR(s.rest_length[e], expected, 1e-14);
    switch (s.kind[e]) {
      case SpringKind::stretch:
        EXPECT_EQ(di + dj, 1);
        break;
      case SpringKind::shear:
        EXPECT_TRUE(di == 1 && dj == 1);
        break;
      case SpringKind::bend:
        EXPECT_TRUE((di == 2 && dj == 0) || (di == 0 && dj == 2));
        break;
    }
    EXPECT_LT(a, model.particle_count());
    EXPECT_LT(b, model.particle_count());
  }
}

TEST(GridCloth, SpringParametersComeFromTheirKind) {
  GridClothSpec spec = grid(4, 4);
  spec.stretch = {1000, 1};
  spec.shear = {100, 0.5};
  spec.bend = {10, 0.25};
  const ClothModel model = build_grid_cloth(spec);
  for (std::size_t e = 0; e < model.springs.size(); ++e) {
    const SpringParams& expected = model.springs.kind[e] == SpringKind::stretch ? spec.stretch
                                   : model.springs.kind[e] == SpringKind::shear ? spec.shear
                                                                                : spec.bend;
    EXPECT_EQ(model.springs.ks[e], expected.ks);
    EXPECT_EQ(model.springs.kd[e], expected.kd);
  }
}

TEST(GridCloth, RestPositionsFollowTheSceneFormat) {
  for (GridPlane plane : {GridPlane::xz, GridPlane::xy}) {
    const GridClothSpec spec = grid(5, 3, plane);
    const ClothModel model = build_grid_cloth(spec);
    const Eigen::Vector3d second =
        plane == GridPlane::xz ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) {
        const Eigen::Vector3d expected = spec.center +
                                         (i / 4.0 - 0.5) * 2.0 * Eigen::Vector3d::UnitX() +
                                         (j / 2.0 - 0.5) * 1.0 * second;
        EXPECT_NEAR((model.rest_positions.col(j * 5 + i) - expected).norm(), 0.0, 1e-15);
        EXPECT_DOUBLE_EQ(model.uvs(0, j * 5 + i), i / 4.0);
        EXPECT_DOUBLE_EQ(model.uvs(1, j * 5 + i), j / 2.0);
      }
  }
}

TEST(GridCloth, RotationTurnsTheSheetAboutItsCentreAndItsNormal) {
  GridClothSpec spec = grid(5, 3);
  const ClothModel flat = build_grid_cloth(spec);
  spec.rotation = {0, 0, 30};  // deg about z
  const ClothModel turned = build_grid_cloth(spec);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (int k = 0; k < 15; ++k)
    EXPECT_LT((turned.rest_positions.col(k) -
               (spec.center + r * (flat.rest_positions.col(k) - spec.center)))
                  .norm(),
              1e-14);
  for (std::size_t e = 0; e < flat.springs.size(); ++e)
    EXPECT_NEAR(turned.springs.rest_length[e], flat.springs.rest_length[e], 1e-14);
  // The perturbation follows the turned normal.
  const ClothState state = initial_grid_state(turned, spec, 0.01, 7);
  const Eigen::Vector3d normal = r * Eigen::Vector3d::UnitY();
  for (int k = 0; k < 15; ++k) {
    const Eigen::Vector3d offset = state.x.col(k) - turned.rest_positions.col(k);
    EXPECT_LT((offset - offset.dot(normal) * normal).norm(), 1e-15);
  }
}

TEST(GridCloth, ASingleParticleSideSitsAtTheCentre) {
  const GridClothSpec spec = grid(1, 6, GridPlane::xy);
  const ClothModel model = build_grid_cloth(spec);
  for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(model.rest_positions(0, k), spec.center.x());
  EXPECT_DOUBLE_EQ(model.rest_positions(1, 0), spec.center.y() - 0.5);
  EXPECT_DOUBLE_EQ(model.rest_positions(1, 5), spec.center.y() + 0.5);
  EXPECT_EQ(model.springs.size(), 5u + 4u);  // 5 links, 4 skip-one bends, no shear
}

TEST(GridCloth, TrianglesFaceAlongTheSheetNormal) {
  for (GridPlane plane : {GridPlane::xz, GridPlane::xy}) {
    const ClothModel model = build_grid_cloth(grid(6, 5, plane));
    const Eigen::Vector3d normal =
        plane == GridPlane::xz ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
    for (Eigen::Index t = 0; t < model.triangles.cols(); ++t) {
      const auto& x = model.rest_positions;
      const Eigen::Vector3d n =
          (x.col(model.triangles(1, t)) - x.col(model.triangles(0, t)))
              .cross(x.col(model.triangles(2, t)) - x.col(model.triangles(0, t)));
      EXPECT_GT(n.dot(normal), 0.0);
    }
  }
}

TEST(GridCloth, EqualMassesIncludingPinnedParticles) {
  GridClothSpec spec = grid(4, 5);
  spec.pins = {PinNamed{"corners"}};
  const ClothModel model = build_grid_cloth(spec);
  for (int k = 0; k < model.particle_count(); ++k) EXPECT_DOUBLE_EQ(model.mass[k], 0.3 / 20);
  EXPECT_NEAR(model.total_mass(), 0.3, 1e-15);
  EXPECT_EQ((model.inverse_mass.array() == 0.0).count(), 4);
}

TEST(GridCloth, ArealDensityUsesVertexAreasThatSumToTheSheetArea) {
  GridClothSpec spec = grid(7, 4);
  spec.mass.reset();
  spec.areal_density = 0.2;  // kg/m^2
  const ClothModel model = build_grid_cloth(spec);
  EXPECT_NEAR(model.vertex_area.sum(), 2.0 * 1.0, 1e-14);
  EXPECT_NEAR(model.total_mass(), 0.2 * 2.0, 1e-14);
  const double cell = (2.0 / 6) * (1.0 / 3);
  for (int j = 1; j < 3; ++j)
    for (int i = 1; i < 6; ++i)
      EXPECT_NEAR(model.vertex_area[j * 7 + i], cell, 1e-14);  // six half-cells / 3
  EXPECT_NEAR(model.vertex_area[3], cell / 2, 1e-14);          // edge: three half-cells / 3
  for (int k = 0; k < model.particle_count(); ++k)
    EXPECT_NEAR(model.mass[k], 0.2 * model.vertex_area[k], 1e-15);
}

TEST(GridCloth, ArealDensityIsRefusedForAChain) {
  GridClothSpec spec = grid(1, 5);
  spec.mass.reset();
  spec.areal_density = 0.2;
  EXPECT_THROW(build_grid_cloth(spec), std::invalid_argument);
}

std::set<int> pins_of(const GridClothSpec& spec, const PinSelector& selector) {
  std::string error;
  const auto picked = select_pins(spec, selector, &error);
  return {picked.begin(), picked.end()};
}

TEST(GridCloth, NamedPinSets) {
  const GridClothSpec xz = grid(4, 3);  // k = j * 4 + i
  EXPECT_EQ(pins_of(xz, PinNamed{"corners"}), (std::set<int>{0, 3, 8, 11}));
  EXPECT_EQ(pins_of(xz, PinNamed{"top_corners"}), (std::set<int>{8, 11}));  // greatest z
  EXPECT_EQ(pins_of(xz, PinNamed{"edge_min_x"}), (std::set<int>{0, 4, 8}));
  EXPECT_EQ(pins_of(xz, PinNamed{"edge_max_x"}), (std::set<int>{3, 7, 11}));
  EXPECT_EQ(pins_of(xz, PinNamed{"edge_min_z"}), (std::set<int>{0, 1, 2, 3}));
  EXPECT_EQ(pins_of(xz, PinNamed{"edge_max_z"}), (std::set<int>{8, 9, 10, 11}));
  const GridClothSpec xy = grid(5, 5, GridPlane::xy);
  EXPECT_EQ(pins_of(xy, PinNamed{"top_corners"}), (std::set<int>{20, 24}));  // greatest y
  EXPECT_EQ(pins_of(xy, PinNamed{"edge_max_y"}), (std::set<int>{20, 21, 22, 23, 24}));
  EXPECT_EQ(pins_of(xy, PinNamed{"center"}), (std::set<int>{12}));
  EXPECT_TRUE(pins_of(xy, PinNamed{"edge_min_z"}).empty());  // a vertical sheet has no z edges
  EXPECT_TRUE(pins_of(xz, PinNamed{"middle"}).empty());
  // The top of a vertical chain is its last particle.
  EXPECT_EQ(pins_of(grid(1, 6, GridPlane::xy), PinNamed{"top_corners"}), (std::set<int>{5}));
}

TEST(GridCloth, CoordinateIndexAndBallSelectors) {
  const GridClothSpec spec = grid(5, 5);
  EXPECT_EQ(pins_of(spec, PinGridCoord{2, 3}), (std::set<int>{17}));
  EXPECT_EQ(pins_of(spec, PinIndex{24}), (std::set<int>{24}));
  std::string error;
  EXPECT_TRUE(select_pins(spec, PinGridCoord{5, 0}, &error).empty());
  EXPECT_NE(error.find("outside"), std::string::npos);
  EXPECT_TRUE(select_pins(spec, PinIndex{25}, &error).empty());
  // A ball of radius 0.3 m around the centre particle: the spacing is 0.5 m along x and 0.25 m
  // along z, so it holds the centre and its two z-neighbours.
  const Eigen::Vector3d centre = spec.center;
  const auto picked = pins_of(spec, PinWithin{centre, 0.3});
  std::set<int> expected;
  const ClothModel model = build_grid_cloth(spec);
  for (int k = 0; k < 25; ++k)
    if ((model.rest_positions.col(k) - centre).norm() <= 0.3) expected.insert(k);
  EXPECT_EQ(picked, expected);
  EXPECT_EQ(picked, (std::set<int>{7, 12, 17}));  // spacing 0.5 m along x, 0.25 m along z
  EXPECT_TRUE(select_pins(spec, PinWithin{Eigen::Vector3d(10, 0, 0), 0.1}, &error).empty());
}

TEST(GridCloth, PinnedParticlesHaveZeroInverseMassOnly) {
  GridClothSpec spec = grid(5, 5);
  spec.pins = {PinGridCoord{0, 0}, PinIndex{4}, PinIndex{4}};
  const ClothModel model = build_grid_cloth(spec);
  for (int k = 0; k < 25; ++k) EXPECT_EQ(model.is_pinned(k), k == 0 || k == 4) << k;
}

TEST(GridCloth, PerturbationIsReproducibleBoundedAlongTheNormalAndSkipsPins) {
  GridClothSpec spec = grid(9, 9);
  spec.pins = {PinNamed{"corners"}};
  const ClothModel model = build_grid_cloth(spec);
  const ClothState a = initial_grid_state(model, spec, 0.01, 42);
  const ClothState b = initial_grid_state(model, spec, 0.01, 42);
  const ClothState c = initial_grid_state(model, spec, 0.01, 43);
  EXPECT_EQ(a.x, b.x);
  EXPECT_NE(a.x, c.x);
  const Eigen::Matrix3Xd offset = a.x - model.rest_positions;
  EXPECT_EQ(offset.row(0).norm() + offset.row(2).norm(), 0.0);  // only along y
  EXPECT_LE(offset.row(1).cwiseAbs().maxCoeff(), 0.01);
  EXPECT_GT(offset.row(1).cwiseAbs().maxCoeff(), 0.005);
  for (int k = 0; k < model.particle_count(); ++k)
    if (model.is_pinned(k)) {
      EXPECT_EQ(offset.col(k).norm(), 0.0);
    }
  EXPECT_EQ(a.v.norm(), 0.0);
}

TEST(GridCloth, AGridPastTheParticleLimitIsRefusedBeforeItIsAllocated) {
  // 50000 x 50000 particles would take hundreds of gigabytes; the builder refuses it from its
  // counts.
  try {
    build_grid_cloth(grid(50000, 50000));
    ADD_FAILURE() << "a 50000 x 50000 grid was built";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2500000000 particles; at most 1000000"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace drapelab
