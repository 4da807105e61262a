// Colliders: the FCL conversion against closed-form signed distances (inside, outside, cylinder cap
// rims, box corners, under rotation), kinematic motion, and the penalty and friction kernels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "core/penalty_contact.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/contact_fcl.hpp"

namespace drapelab {
namespace {

// Closed-form signed distances in the collider's local frame (negative inside).
double sphere_sdf(const Eigen::Vector3d& p, double radius) { return p.norm() - radius; }

double cylinder_sdf(const Eigen::Vector3d& p, const Eigen::Vector3d& axis, double radius,
                    double height) {
  const double along = p.dot(axis);
  const double across = (p - along * axis).norm();
  const Eigen::Vector2d q(across - radius, std::abs(along) - 0.5 * height);
  return std::min(q.maxCoeff(), 0.0) + q.cwiseMax(0.0).norm();
}

double capsule_sdf(const Eigen::Vector3d& p, const Eigen::Vector3d& axis, double radius,
                   double height) {
  const double along = std::clamp(p.dot(axis), -0.5 * height, 0.5 * height);
  return (p - along * axis).norm() - radius;
}

double box_sdf(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
  const Eigen::Vector3d q = p.cwiseAbs() - half;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

double plane_sdf(const Eigen::Vector3d& p, const Eigen::Vector3d& normal) {
  return p.dot(normal.normalized());
}

struct ShapeCase {
  Collider collider;
  std::function<double(const Eigen::Vector3d&)> local_sdf;
  double extent;  // m, sample points within this distance of the centre
};

std::vector<ShapeCase> shape_cases() {
  std::vector<ShapeCase> cases;
  Collider sphere;
  sphere.shape = ColliderShape::sphere;
  sphere.radius = 0.3;
  cases.push_back({sphere, [](const Eigen::Vector3d& p) { return sphere_sdf(p, 0.3); }, 0.5});
  Collider cylinder;
  cylinder.shape = ColliderShape::cylinder;
  cylinder.radius = 0.4;
  cylinder.height = 0.6;
  cylinder.axis = Eigen::Vector3d(0.2, 1.0, -0.3).normalized();
  cases.push_back(
      {cylinder,
       [a = cylinder.axis](const Eigen::Vector3d& p) { return cylinder_sdf(p, a, 0.4, 0.6); },
       0.6});
  Collider capsule;
  capsule.shape = ColliderShape::capsule;
  capsule.radius = 0.1;
  capsule.height = 0.5;
  capsule.axis = Eigen::Vector3d::UnitX();
  cases.push_back(
      {capsule,
       [](const Eigen::Vector3d& p) { return capsule_sdf(p, Eigen::Vector3d::UnitX(), 0.1, 0.5); },
       0.45});
  Collider box;
  box.shape = ColliderShape::box;
  box.half_extents = {0.5, 0.2, 0.3};
  cases.push_back({box, [](const Eigen::Vector3d& p) { return box_sdf(p, {0.5, 0.2, 0.3}); }, 0.7});
  Collider plane;
  plane.shape = ColliderShape::plane;
  plane.normal = Eigen::Vector3d(0.1, 1.0, 0.2).normalized();
  cases.push_back(
      {plane, [n = plane.normal](const Eigen::Vector3d& p) { return plane_sdf(p, n); }, 0.5});
  return cases;
}

// Gradient of a signed distance by central differences; nothing where it is not differentiable.
std::optional<Eigen::Vector3d> sdf_gradient(
    const std::function<double(const Eigen::Vector3d&)>& sdf, const Eigen::Vector3d& p) {
  const double step = 1e-6;
  Eigen::Vector3d g;
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector3d plus = p, minus = p;
    plus[c] += step;
    minus[c] -= step;
    g[c] = (sdf(plus) - sdf(minus)) / (2 * step);
  }
  if (std::abs(g.norm() - 1.0) > 1e-4) return std::nullopt;  // a ridge (medial surface): no normal
  return g.normalized();
}

TEST(FclConversion, DepthAndNormalMatchClosedFormsUnderRotation) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double r = 0.02;  // m, particle radius
  const ParticleContactQuery query(r);
  for (ShapeCase& shape : shape_cases()) {
    SCOPED_TRACE(collider_shape_name(shape.collider.shape));
    shape.collider.center = {0.3, 1.1, -0.4};
    shape.collider.rotation = {25.0, -40.0, 70.0};
    const FclCollider fcl = make_fcl_collider(shape.collider);
    const Eigen::Isometry3d collider_in_world = collider_pose(shape.collider, 0.0);
    const Eigen::Isometry3d shape_pose = collider_in_world * fcl.shape_in_collider;
    int penetrating = 0, separated = 0;
    for (int trial = 0; trial < 4000; ++trial) {
      const Eigen::Vector3d local(u(random) * shape.extent, u(random) * shape.extent,
                                  u(random) * shape.extent);
      const double sd = shape.local_sdf(local);
      if (sd < -0.8 * shape.extent) continue;
      const Eigen::Vector3d world = collider_in_world * local;
      const double clearance = query.clearance(fcl, shape_pose, world);
      EXPECT_NEAR(clearance, sd - r, 1e-9) << local.transpose();
      const auto contact = query.contact(fcl, shape_pose, world);
      ASSERT_EQ(contact.has_value(), sd < r) << local.transpose() << " sd " << sd;
      if (!contact) {
        ++separated;
        continue;
      }
      ++penetrating;
      EXPECT_NEAR(contact->depth, r - sd, 1e-9);
      if (const auto gradient = sdf_gradient(shape.local_sdf, local)) {
        const Eigen::Vector3d expected = collider_in_world.linear() * *gradient;
        EXPECT_LT((contact->normal - expected).norm(), 1e-6) << local.transpose();
      }
    }
    EXPECT_GT(penetrating, 100);
    EXPECT_GT(separated, 100);
  }
}

TEST(FclConversion, CylinderCapRimAndBoxCornerAreExact) {
  const double r = 0.01;
  const ParticleContactQuery query(r);
  Collider cylinder;
  cylinder.shape = ColliderShape::cylinder;
  cylinder.radius = 0.5;
  cylinder.height = 1.0;  // caps at y = +-0.5
  const FclCollider cyl = make_fcl_collider(cylinder);
  const Eigen::Isometry3d cyl_pose = collider_pose(cylinder, 0.0) * cyl.shape_in_collider;
  // 5 mm outside the rim, diagonally: distance 5 mm * sqrt(2).
  const Eigen::Vector3d outside_rim(0.5 + 0.005, 0.5 + 0.005, 0.0);
  EXPECT_NEAR(query.clearance(cyl, cyl_pose, outside_rim), 0.005 * std::sqrt(2.0) - r, 1e-12);
  const auto rim = query.contact(cyl, cyl_pose, outside_rim);
  ASSERT_TRUE(rim.has_value());
  EXPECT_LT((rim->normal - Eigen::Vector3d(1, 1, 0).normalized()).norm(), 1e-9);
  // 3 mm inside the cap (closer to the cap than to the barrel): pushed up through the cap.
  const auto cap = query.contact(cyl, cyl_pose, Eigen::Vector3d(0.45, 0.497, 0.0));
  ASSERT_TRUE(cap.has_value());
  EXPECT_NEAR(cap->depth, r + 0.003, 1e-12);
  EXPECT_LT((cap->normal - Eigen::Vector3d::UnitY()).norm(), 1e-9);
  // 3 mm inside the barrel near the rim (closer to the barrel): pushed sideways.
  const auto barrel = query.contact(cyl, cyl_pose, Eigen::Vector3d(0.497, 0.45, 0.0));
  ASSERT_TRUE(barrel.has_value());
  EXPECT_LT((barrel->normal - Eigen::Vector3d::UnitX()).norm(), 1e-9);

  Collider box;
  box.shape = ColliderShape::box;
  box.half_extents = {0.5, 0.5, 0.5};
  const FclCollider b = make_fcl_collider(box);
  const Eigen::Isometry3d box_pose = collider_pose(box, 0.0) * b.shape_in_collider;
  const Eigen::Vector3d corner(0.5 + 0.004, 0.5 + 0.004, 0.5 + 0.004);
  EXPECT_NEAR(query.clearance(b, box_pose, corner), 0.004 * std::sqrt(3.0) - r, 1e-12);
  const auto at_corner = query.contact(b, box_pose, corner);
  ASSERT_TRUE(at_corner.has_value());
  EXPECT_LT((at_corner->normal - Eigen::Vector3d(1, 1, 1).normalized()).norm(), 1e-9);
}

TEST(FclConversion, PlaneIsAHalfSpaceNotATwoSidedPlane) {
  Collider floor;
  floor.shape = ColliderShape::plane;
  floor.center = {0, 0.2, 0};
  const FclCollider fcl = make_fcl_collider(floor);
  const ParticleContactQuery query(0.01);
  const Eigen::Isometry3d pose = collider_pose(floor, 0.0) * fcl.shape_in_collider;
  const auto deep =
      query.contact(fcl, pose, Eigen::Vector3d(3, 0.2 - 0.5, 1));  // half a metre below
  ASSERT_TRUE(deep.has_value());
  EXPECT_NEAR(deep->depth, 0.51, 1e-12);
  EXPECT_LT((deep->normal - Eigen::Vector3d::UnitY()).norm(), 1e-12);  // pushed up, never down
}

TEST(FclConversion, BoundsHoldTheShape) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (ShapeCase& shape : shape_cases()) {
    if (shape.collider.shape == ColliderShape::plane) continue;
    shape.collider.rotation = {10, 20, 30};
    shape.collider.center = {1, 2, 3};
    const FclCollider fcl = make_fcl_collider(shape.collider);
    const Eigen::Isometry3d pose = collider_pose(shape.collider, 0.0);
    const Eigen::AlignedBox3d bounds = collider_bounds(fcl, pose * fcl.shape_in_collider, 0.0);
    for (int trial = 0; trial < 2000; ++trial) {
      const Eigen::Vector3d local(u(random) * shape.extent, u(random) * shape.extent,
                                  u(random) * shape.extent);
      if (shape.local_sdf(local) <= 0.0) {
        EXPECT_TRUE(bounds.contains(pose * local));
      }
    }
  }
}

// The broad phase's bounding sphere: every point of the shape lies within it, and it is tight (the
// farthest point of each shape, a sphere's surface, a capsule's tip, a cylinder's rim, a box's
// corner, is on it).
TEST(FclConversion, BoundingRadiusHoldsTheShapeAndIsTight) {
  std::mt19937_64 random(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double expected[] = {0.3, std::hypot(0.3, 0.4), 0.25 + 0.1, std::sqrt(0.25 + 0.04 + 0.09)};
  int checked = 0;
  for (ShapeCase& shape : shape_cases()) {
    const FclCollider fcl = make_fcl_collider(shape.collider);
    if (shape.collider.shape == ColliderShape::plane) {
      EXPECT_TRUE(std::isinf(bounding_radius(fcl)));
      continue;
    }
    const double radius = bounding_radius(fcl);
    EXPECT_NEAR(radius, expected[checked++], 1e-12);
    double farthest = 0.0;  // m, of the sampled points inside the shape
    for (int trial = 0; trial < 20000; ++trial) {
      const Eigen::Vector3d local(u(random) * shape.extent, u(random) * shape.extent,
                                  u(random) * shape.extent);
      if (shape.local_sdf(local) > 0.0) continue;
      EXPECT_LE(local.norm(), radius) << local.transpose();
      farthest = std::max(farthest, local.norm());
    }
    EXPECT_GT(farthest, 0.8 * radius);  // the samples reached near the bound
  }
  EXPECT_EQ(checked, 4);
}

TEST(ColliderMotion, ConstantVelocityAndSpin) {
  Collider c;
  c.center = {1, 0, 0};
  c.rotation = {0, 0, 0};
  c.motion.velocity = {0, 0.5, 0};
  c.motion.angular_velocity = {0, 90, 0};  // deg/s about world y
  const Eigen::Isometry3d pose = collider_pose(c, 1.0);
  EXPECT_LT((pose.translation() - Eigen::Vector3d(1, 0.5, 0)).norm(), 1e-15);
  // After 1 s a quarter turn about y: local x goes to world -z.
  EXPECT_LT((pose.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  // Point velocity is the derivative of the posed material point.
  const Eigen::Vector3d local(0.3, -0.2, 0.1);
  const double dt = 1e-6;
  const Eigen::Vector3d numeric =
      (collider_pose(c, 1.0 + dt) * local - collider_pose(c, 1.0 - dt) * local) / (2 * dt);
  EXPECT_LT((collider_point_velocity(c, 1.0, pose * local) - numeric).norm(), 1e-7);
}

TEST(ColliderMotion, KeyframesInterpolateAndHoldAtTheEnds) {
  Collider c;
  c.motion.keyframes = {
      {0.5, {0, 0, 0}, {0, 0, 0}}, {1.5, {2, 0, 0}, {0, 0, 90}}, {2.5, {2, 1, 0}, {0, 0, 90}}};
  EXPECT_LT((collider_pose(c, 0.0).translation()).norm(), 1e-15);
  EXPECT_LT((collider_pose(c, 1.0).translation() - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((collider_pose(c, 2.0).translation() - Eigen::Vector3d(2, 0.5, 0)).norm(), 1e-15);
  EXPECT_LT((collider_pose(c, 9.0).translation() - Eigen::Vector3d(2, 1, 0)).norm(), 1e-15);
  // Halfway through the turn: 45 degrees about z.
  const Eigen::Vector3d turned = collider_pose(c, 1.0).linear() * Eigen::Vector3d::UnitX();
  EXPECT_LT((turned - Eigen::Vector3d(1, 1, 0).normalized()).norm(), 1e-12);
  const Eigen::Vector3d local(0.2, 0.3, -0.1);
  for (double t : {0.7, 1.2, 2.0}) {
    const double dt = 1e-6;
    const Eigen::Vector3d numeric =
        (collider_pose(c, t + dt) * local - collider_pose(c, t - dt) * local) / (2 * dt);
    EXPECT_LT((collider_point_velocity(c, t, collider_pose(c, t) * local) - numeric).norm(), 1e-6)
        << t;
  }
  EXPECT_EQ(collider_point_velocity(c, 0.1, Eigen::Vector3d(1, 1, 1)).norm(), 0.0);
  EXPECT_EQ(collider_point_velocity(c, 3.0, Eigen::Vector3d(1, 1, 1)).norm(), 0.0);
}

// The keyframes' rotation acts after the collider's own: R(t) = R_keyframes(t) R(rotation), about
// the keyframe centre; the velocity field is that of the keyframes alone (the fixed rotation
// cancels).
TEST(ColliderMotion, KeyframesTurnTheCollidersOwnRotationFurther) {
  Collider c;
  c.rotation = {30, 0, 0};
  c.motion.keyframes = {{0.0, {0, 1, 0}, {0, 0, 0}}, {1.0, {1, 1, 0}, {0, 0, 90}}};
  const Eigen::Matrix3d own = euler_rotation(c.rotation);
  for (double t : {0.0, 0.25, 0.5, 1.0, 2.0}) {
    const double s = std::clamp(t, 0.0, 1.0);
    const Eigen::Matrix3d keyed =
        Eigen::AngleAxisd(s * std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Isometry3d pose = collider_pose(c, t);
    EXPECT_LT((pose.linear() - keyed * own).cwiseAbs().maxCoeff(), 1e-12) << t;
    EXPECT_LT((pose.translation() - Eigen::Vector3d(s, 1, 0)).norm(), 1e-15) << t;
  }
  Collider plain = c;
  plain.rotation.setZero();
  const Eigen::Vector3d p(0.3, 1.2, -0.4);
  EXPECT_LT((collider_point_velocity(c, 0.5, p) - collider_point_velocity(plain, 0.5, p)).norm(),
            1e-12);
  const Eigen::Vector3d local(0.2, 0.3, -0.1);
  const double dt = 1e-6;
  const Eigen::Vector3d numeric =
      (collider_pose(c, 0.5 + dt) * local - collider_pose(c, 0.5 - dt) * local) / (2 * dt);
  EXPECT_LT((collider_point_velocity(c, 0.5, collider_pose(c, 0.5) * local) - numeric).norm(),
            1e-6);
}

TEST(PenaltyKernels, NormalForceIsSpringPlusDamperAndNeverPulls) {
  EXPECT_DOUBLE_EQ(penalty_normal_force(0.002, -0.1, 5000, 5),
                   5000 * 0.002 + 5 * 0.1);  // approaching
  EXPECT_DOUBLE_EQ(penalty_normal_force(0.002, 0.1, 5000, 5),
                   5000 * 0.002 - 5 * 0.1);                    // separating
  EXPECT_EQ(penalty_normal_force(0.002, 10.0, 5000, 5), 0.0);  // separating fast: no pull
}

TEST(PenaltyKernels, FrictionSticksWithinTheStaticConeAndSlidesBeyondIt) {
  const double m = 0.01, h = 1e-3, fn = 0.1;  // kg, s, N
  // Needs 0.01 / 1e-3 * 0.002 = 0.02 N to stop: within mu_s fn = 0.03 N, so it sticks exactly.
  const Eigen::Vector3d slow(0.002, 0, 0);
  const FrictionForce stick = coulomb_friction_force(slow, m, h, fn, 0.3, 0.2);
  EXPECT_LT((stick.force - Eigen::Vector3d(-0.02, 0, 0)).norm(), 1e-15);
  EXPECT_EQ(stick.magnitude, stick.force.norm());  // bit for bit: the totals sum it
  // Needs 0.05 N: beyond mu_s fn, so it slides with mu_k fn = 0.02 N against the motion.
  const Eigen::Vector3d fast(0, 0, -0.005);
  const FrictionForce slide = coulomb_friction_force(fast, m, h, fn, 0.3, 0.2);
  EXPECT_LT((slide.force - Eigen::Vector3d(0, 0, 0.02)).norm(), 1e-15);
  EXPECT_EQ(slide.magnitude, slide.force.norm());
  const FrictionForce unloaded =
      coulomb_friction_force(fast, m, h, 0.0, 0.3, 0.2);  // no load, no friction
  EXPECT_EQ(unloaded.force.norm(), 0.0);
  EXPECT_EQ(unloaded.magnitude, 0.0);
}

// The contact totals sum each friction's magnitude as returned, so it must be the force's norm to
// the last bit in both branches; along oblique directions (where a norm rounds) a magnitude taken
// from another expression, such as mu_k fn for sliding, differs from it in the last bits.
TEST(PenaltyKernels, FrictionMagnitudeIsTheForcesNormBitForBit) {
  const double m = 0.01, h = 1e-3, fn = 0.1;  // kg, s, N
  std::mt19937_64 random(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int sticking = 0, sliding = 0;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Vector3d direction = Eigen::Vector3d(u(random), u(random), u(random)).normalized();
    const double speed =
        0.001 +
        0.004 * (0.5 + 0.5 * u(random));  // m/s: 0.02 to 0.05 N to stop, either side of 0.03
    const FrictionForce friction = coulomb_friction_force(speed * direction, m, h, fn, 0.3, 0.2);
    const bool sticks = speed * m / h <= 0.3 * fn;
    (sticks ? sticking : sliding) += 1;
    ASSERT_EQ(friction.magnitude, friction.force.norm())
        << "direction " << direction.transpose() << ", speed " << speed;
    EXPECT_NEAR(friction.magnitude, sticks ? speed * m / h : 0.2 * fn, 1e-15);
  }
  EXPECT_GT(sticking, 50);
  EXPECT_GT(sliding, 50);
}

}  // namespace
}  // namespace drapelab
