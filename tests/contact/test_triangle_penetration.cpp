// Triangle penetration: how deep a collider reaches into a cloth triangle, thickness included, on
// hand cases with known answers: a box edge and a cylinder's barrel between particles, a sphere
// under a triangle's centre, a plane, and the broad phase.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/contact_fcl.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/triangle_penetration.hpp"

namespace drapelab {
namespace {

using Eigen::Vector3d;

constexpr double kThickness = 0.005;  // m, h
constexpr double kPoke = 0.001;       // m, how far a collider crosses a triangle
// A big horizontal triangle at height y: its corners lie far outside every collider below.
Eigen::Matrix3Xd big_triangle(double y) {
  Eigen::Matrix3Xd x(3, 3);
  x.col(0) = Vector3d(-1.0, y, -1.0);
  x.col(1) = Vector3d(1.0, y, -1.0);
  x.col(2) = Vector3d(0.0, y, 1.5);
  return x;
}

ClothModel one_triangle_model() {
  ClothModel model;
  model.triangles.resize(3, 1);
  model.triangles.col(0) = Eigen::Vector3i(0, 1, 2);
  model.thickness = kThickness;
  return model;
}

double penetration(const Collider& collider, const Eigen::Matrix3Xd& x) {
  const ContactModel contacts({collider}, ContactParameters{}, kThickness);
  return triangle_penetration(one_triangle_model(), x, contacts, 0.0);
}

// A 0.2 m cube at the origin turned 45 degrees about x: an edge along x on top, at y = 0.1 sqrt 2.
Collider edge_up_box() {
  Collider box;
  box.name = "box";
  box.shape = ColliderShape::box;
  box.half_extents = Vector3d(0.1, 0.1, 0.1);
  box.rotation = Vector3d(45.0, 0.0, 0.0);
  return box;
}
const double kBoxTop = 0.1 * std::sqrt(2.0);

// Every particle's own clearance is positive: particle-based metrics see nothing.
void expect_every_particle_clear(const Collider& collider, const Eigen::Matrix3Xd& x) {
  const FclCollider fcl = make_fcl_collider(collider);
  const ParticleContactQuery query(kThickness);
  for (Eigen::Index i = 0; i < x.cols(); ++i)
    EXPECT_GT(query.clearance(fcl, collider_pose(collider, 0.0), x.col(i)), 0.1)
        << "particle " << i;
}

TEST(TrianglePenetration, ATriangleTwoThicknessesAboveABoxEdgeHasNone) {
  const Eigen::Matrix3Xd x = big_triangle(kBoxTop + 2.0 * kThickness);
  EXPECT_EQ(penetration(edge_up_box(), x), 0.0);
  const FclCollider fcl = make_fcl_collider(edge_up_box());
  EXPECT_NEAR(collider_triangle_signed_distance(fcl, collider_pose(edge_up_box(), 0.0), x.col(0),
                                                x.col(1), x.col(2)),
              2.0 * kThickness, 1e-9);
}

TEST(TrianglePenetration, ABoxEdgePokingThroughATrianglesInsideReachesThicknessPlusDepth) {
  const Eigen::Matrix3Xd x = big_triangle(kBoxTop - kPoke);
  expect_every_particle_clear(edge_up_box(), x);
  EXPECT_NEAR(penetration(edge_up_box(), x), kThickness + kPoke, 1e-6);
  // Touching the plane: exactly the thickness.
  EXPECT_NEAR(penetration(edge_up_box(), big_triangle(kBoxTop)), kThickness, 1e-6);
}

TEST(TrianglePenetration, ACylinderBarrelAndACapsuleBetweenParticles) {
  Collider cylinder;  // lying along x, its barrel's top line at y = 0.1
  cylinder.name = "bar";
  cylinder.shape = ColliderShape::cylinder;
  cylinder.radius = 0.1;
  cylinder.height = 0.4;
  cylinder.axis = Vector3d::UnitX();
  const Eigen::Matrix3Xd x = big_triangle(0.1 - kPoke);
  expect_every_particle_clear(cylinder, x);
  EXPECT_NEAR(penetration(cylinder, x), kThickness + kPoke, 1e-6);
  EXPECT_EQ(penetration(cylinder, big_triangle(0.1 + 2.0 * kThickness)), 0.0);
  // Standing upright: the rim of its top cap, at y = 0.2, 1 mm through the triangle.
  cylinder.axis = Vector3d::UnitY();
  EXPECT_NEAR(penetration(cylinder, big_triangle(0.2 - kPoke)), kThickness + kPoke, 1e-6);

  Collider capsule = cylinder;  // upright: its top at y = 0.2 + 0.1
  capsule.shape = ColliderShape::capsule;
  EXPECT_NEAR(penetration(capsule, big_triangle(0.3 - kPoke)), kThickness + kPoke, 1e-6);
  EXPECT_NEAR(penetration(capsule, big_triangle(0.3 + 0.5 * kThickness)), 0.5 * kThickness, 1e-6);
}

TEST(TrianglePenetration, ASphereUnderATrianglesCentre) {
  Collider sphere;
  sphere.name = "ball";
  sphere.shape = ColliderShape::sphere;
  sphere.radius = 0.3;
  Eigen::Matrix3Xd x(3, 3);  // centroid at (0, y, 0), corners 0.5 m out
  const double y = 0.3 + 0.5 * kThickness;
  x.col(0) = Vector3d(0.5, y, 0.0);
  x.col(1) = Vector3d(-0.25, y, 0.25 * std::sqrt(3.0));
  x.col(2) = Vector3d(-0.25, y, -0.25 * std::sqrt(3.0));
  EXPECT_NEAR(penetration(sphere, x), 0.5 * kThickness, 1e-12);
  x.row(1).setConstant(0.3 - 2.0 * kPoke);  // the sphere's cap 2 mm through the triangle
  expect_every_particle_clear(sphere, x);
  EXPECT_NEAR(penetration(sphere, x), kThickness + 2.0 * kPoke, 1e-12);
}

TEST(TrianglePenetration, APlaneReachesTheDeepestCorner) {
  Collider floor;
  floor.name = "floor";
  floor.shape = ColliderShape::plane;
  floor.center = Vector3d(0.0, 0.1, 0.0);
  floor.normal = Vector3d::UnitY();
  Eigen::Matrix3Xd x(3, 3);
  x.col(0) = Vector3d(0.0, 0.1 - kPoke, 0.0);  // 1 mm under the floor
  x.col(1) = Vector3d(1.0, 0.5, 0.0);
  x.col(2) = Vector3d(0.0, 0.3, 1.0);
  EXPECT_NEAR(penetration(floor, x), kThickness + kPoke, 1e-12);
  x.row(1).array() += kPoke + 3.0 * kThickness;  // every corner 3 h above
  EXPECT_EQ(penetration(floor, x), 0.0);
}

TEST(TrianglePenetration, TheDeepestOverEveryTriangleAndCollider) {
  // Two triangles, one far from both colliders (left out by the broad phase), one on the box.
  ClothModel model = one_triangle_model();
  model.triangles.conservativeResize(3, 2);
  model.triangles.col(1) = Eigen::Vector3i(3, 4, 5);
  Eigen::Matrix3Xd x(3, 6);
  x.leftCols(3) = big_triangle(kBoxTop - kPoke);
  x.rightCols(3) = big_triangle(50.0);
  Collider far_ball;
  far_ball.name = "far";
  far_ball.shape = ColliderShape::sphere;
  far_ball.center = Vector3d(0.0, -20.0, 0.0);
  far_ball.radius = 0.5;
  const ContactModel contacts({far_ball, edge_up_box()}, ContactParameters{}, kThickness);
  EXPECT_NEAR(triangle_penetration(model, x, contacts, 0.0), kThickness + kPoke, 1e-6);
  // A triangle with a non-finite corner is left out.
  x(0, 0) = std::nan("");
  EXPECT_EQ(triangle_penetration(model, x, contacts, 0.0), 0.0);
}

}  // namespace
}  // namespace drapelab
