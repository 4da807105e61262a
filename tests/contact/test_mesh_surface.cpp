// Mesh colliders' surfaces (drapelab/mesh_surface.hpp) and their particle contact: the signed
// distance against the exact sphere and box it approximates, the pseudo-normal sign inside and
// out, the topology counts behind the loader's warnings, and the sharp-feature triangle distance.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "drapelab/contact_fcl.hpp"
#include "drapelab/mesh_surface.hpp"
#include "drapelab/obj_reader.hpp"
#include "drapelab/triangle_penetration.hpp"

namespace drapelab {
namespace {

TriangleMesh read_mesh(const std::string& name) {
  const ObjReadResult read =
      read_obj_file(std::string(DRAPELAB_SOURCE_DIR) + "/scenes/meshes/" + name);
  EXPECT_TRUE(read.mesh) << read.error;
  return *read.mesh;
}

// The 1,280-triangle icosphere of radius 0.15 m: vertices on the sphere, faces at most 0.68 mm
// inside it.
constexpr double kSphereRadius = 0.15;  // m
constexpr double kSphereSag = 0.7e-3;   // m

TEST(MeshSurface, SignedDistanceFollowsTheSphereWithinItsSag) {
  const MeshSurface surface(read_mesh("icosphere_r015.obj"));
  EXPECT_EQ(surface.quality().border_edges, 0);
  EXPECT_EQ(surface.quality().misoriented_edges, 0);
  EXPECT_NEAR(surface.quality().volume, 4.0 / 3.0 * M_PI * std::pow(kSphereRadius, 3), 2e-4);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> radius(0.0, 0.3), axis(-1.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    Eigen::Vector3d direction(axis(random), axis(random), axis(random));
    if (direction.norm() < 1e-3) continue;
    direction.normalize();
    const Eigen::Vector3d p = radius(random) * direction;
    const double exact = p.norm() - kSphereRadius;  // m
    const auto near = surface.nearest(p, std::numeric_limits<double>::infinity());
    ASSERT_TRUE(near);
    // The faces lie inside the sphere: the mesh's distance is larger outside, smaller inside.
    EXPECT_GE(near->distance, exact - 1e-12) << p.transpose();
    EXPECT_LE(near->distance, exact + kSphereSag) << p.transpose();
    if (std::abs(exact) > 2.0 * kSphereSag && p.norm() > 0.05) {
      EXPECT_EQ(near->distance < 0.0, exact < 0.0) << p.transpose();
      EXPECT_GT(near->normal.dot(direction), 0.97) << p.transpose();  // the way out: radial
    }
  }
}

TEST(MeshSurface, ParticleContactMatchesTheSphereCollider) {
  Collider sphere;
  sphere.shape = ColliderShape::sphere;
  sphere.radius = kSphereRadius;
  Collider mesh;
  mesh.shape = ColliderShape::mesh;
  mesh.mesh = std::make_shared<const TriangleMesh>(read_mesh("icosphere_r015.obj"));
  const FclCollider exact = make_fcl_collider(sphere), faceted = make_fcl_collider(mesh);
  const ParticleContactQuery query(0.005);
  const Eigen::Isometry3d pose(Eigen::Translation3d(0.0, 0.5, 0.0));
  for (const double height : {0.153, 0.149, 0.14, 0.1}) {  // m above the centre
    const Eigen::Vector3d x = pose * Eigen::Vector3d(0.01, height, 0.02);
    const auto want = query.contact(exact, pose, x);
    const auto got = query.contact(faceted, pose, x);
    ASSERT_TRUE(want && got) << height;
    EXPECT_NEAR(got->depth, want->depth, kSphereSag) << height;
    EXPECT_GT(got->normal.dot(want->normal), 0.99) << height;
    EXPECT_NEAR(query.clearance(faceted, pose, x), query.clearance(exact, pose, x), kSphereSag);
  }
  EXPECT_FALSE(query.contact(faceted, pose, pose * Eigen::Vector3d(0, 0.16, 0)));
}

TEST(MeshSurface, BoxMeshDistancesAreExactAtFacesEdgesAndCorners) {
  const MeshSurface box(read_mesh("box_040x020x040.obj"));  // half extents 0.2, 0.1, 0.2
  const double infinity = std::numeric_limits<double>::infinity();
  struct Case {
    Eigen::Vector3d p;
    double distance;
  };
  const Case cases[] = {
      {{0.05, 0.13, 0.0}, 0.03},                                  // over the top face
      {{0.23, 0.14, 0.0}, std::hypot(0.03, 0.04)},                // beyond an edge
      {{0.23, 0.14, 0.22}, std::sqrt(0.0009 + 0.0016 + 0.0004)},  // beyond a corner
      {{0.0, 0.07, 0.0}, -0.03},                                  // inside, under the top face
      {{0.19, 0.095, 0.1}, -0.005},                               // inside, at an edge
  };
  for (const Case& c : cases) {
    const auto near = box.nearest(c.p, infinity);
    ASSERT_TRUE(near);
    EXPECT_NEAR(near->distance, c.distance, 1e-12) << c.p.transpose();
  }
  // Beyond the bound: nothing; within the box's bounds the search is unbounded.
  EXPECT_FALSE(box.nearest(Eigen::Vector3d(0, 0.3, 0), 0.1));
  EXPECT_TRUE(box.signed_nearest(Eigen::Vector3d(0, 0, 0), 0.001));
}

TEST(MeshSurface, CountsOpenFinnedAndMisorientedEdges) {
  TriangleMesh tetrahedron;
  tetrahedron.vertices.resize(3, 5);
  tetrahedron.vertices << 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 0, 1, 1;
  tetrahedron.triangles.resize(3, 4);
  tetrahedron.triangles << 0, 0, 0, 1, 2, 1, 3, 2, 1, 3, 2, 3;
  // Columns: (0 2 1), (0 1 3), (0 3 2), (1 2 3): closed and outward.
  const MeshSurface closed(tetrahedron);
  EXPECT_EQ(closed.quality().border_edges, 0);
  EXPECT_EQ(closed.quality().non_manifold_edges, 0);
  EXPECT_EQ(closed.quality().misoriented_edges, 0);
  EXPECT_NEAR(closed.quality().volume, 1.0 / 6.0, 1e-15);
  TriangleMesh open = tetrahedron;
  open.triangles.conservativeResize(3, 3);
  EXPECT_EQ(MeshSurface(open).quality().border_edges, 3);
  TriangleMesh turned = tetrahedron;
  turned.triangles.col(0) = Eigen::Vector3i(0, 1, 2);
  EXPECT_EQ(MeshSurface(turned).quality().misoriented_edges, 3);
  TriangleMesh finned = tetrahedron;
  finned.triangles.conservativeResize(3, 5);
  finned.triangles.col(4) = Eigen::Vector3i(0, 1, 4);
  EXPECT_EQ(MeshSurface(finned).quality().non_manifold_edges, 1);
  TriangleMesh flat = tetrahedron;
  flat.vertices.col(3) = Eigen::Vector3d(2, 0, 0);  // on the line through vertices 0 and 1
  EXPECT_NE(mesh_surface_problem(flat), std::nullopt);
  EXPECT_THROW(MeshSurface{flat}, std::invalid_argument);
}

// A cloth triangle over a box's edge: the mesh box and the box collider give the same signed
// distance when the edge lies under the triangle (no corner of it near the box), and both see a
// crossing.
TEST(MeshSurface, TriangleDistanceSeesAnEdgeBetweenCorners) {
  Collider box;
  box.shape = ColliderShape::box;
  box.half_extents = Eigen::Vector3d(0.2, 0.1, 0.2);
  Collider mesh;
  mesh.shape = ColliderShape::mesh;
  mesh.mesh = std::make_shared<const TriangleMesh>(read_mesh("box_040x020x040.obj"));
  const FclCollider exact = make_fcl_collider(box), faceted = make_fcl_collider(mesh);
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  // A triangle in the plane tilted 45 degrees over the edge x = 0.2, y = 0.1, at distance d from
  // it (negative: the edge pokes through), its corners 6 cm and more from the box.
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 0).normalized();
  const Eigen::Vector3d u = Eigen::Vector3d(-1, 1, 0).normalized(), w = Eigen::Vector3d::UnitZ();
  for (const double d : {0.02, 0.004, -0.003}) {
    const Eigen::Vector3d q = Eigen::Vector3d(0.2, 0.1, 0.0) + d * n;
    const Eigen::Vector3d a = q + 0.08 * u - 0.05 * w, b = q - 0.08 * u - 0.05 * w,
                          c = q + 0.08 * w;
    const double want = collider_triangle_signed_distance(exact, pose, a, b, c);
    const double got = collider_triangle_signed_distance(faceted, pose, a, b, c);
    EXPECT_NEAR(want, d, 1e-9) << d;
    // Through the triangle, the mesh measures how deep the triangle's point over the edge lies
    // (|d| / sqrt 2 from both faces), not the shortest way out of the whole triangle (|d|).
    EXPECT_NEAR(got, d > 0.0 ? d : d / std::sqrt(2.0), 1e-9) << d;
  }
}

}  // namespace
}  // namespace drapelab
