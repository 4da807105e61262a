// Our cloth hosted in a Bullet world (docs/bullet.md, "Parallel worlds with the same colliders"):
// at every substep its contacts use the poses of the host's Bullet bodies (not a copy of
// collider_pose(t)), and a hosted run agrees with a bare one to rounding.
#include <gtest/gtest.h>

#include <memory>

#include "drapelab/bullet/bullet_diagnostics.hpp"
#include "drapelab/bullet/bullet_host.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/sheets.hpp"

namespace drapelab {
namespace {

GridClothSpec pinned_sheet(int n, double size, Eigen::Vector3d center, double mass) {
  GridClothSpec spec = fixtures::bullet_test_sheet(n, size, center, mass);
  spec.pins = {PinNamed{"corners"}};
  return spec;
}

double largest_difference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

// Forwards to the solver it wraps and records, before each step, the poses (collider frame ->
// world) that the wrapped solver's contact model will use at the start and the end of the step.
class PoseRecorder final : public Solver {
 public:
  PoseRecorder(std::unique_ptr<Solver> inner, std::shared_ptr<const ContactModel> contacts)
      : inner_(std::move(inner)), contacts_(std::move(contacts)) {}

  void step(double h) override {
    const double t = inner_->state().time;
    start.clear();
    end.clear();
    velocity.clear();
    for (std::size_t c = 0; c < contacts_->size(); ++c) {
      start.push_back(contacts_->pose(c, t));
      end.push_back(contacts_->pose(c, t + h));
      velocity.push_back(contacts_->pose_table()->at(c, t).velocity);
    }
    inner_->step(h);
  }
  const ClothState& state() const override { return inner_->state(); }
  const std::string& name() const override { return inner_->name(); }
  drapelab::SolverType type() const override { return inner_->type(); }
  SolverStatus status() const override { return inner_->status(); }
  const std::string& message() const override { return inner_->message(); }
  std::vector<ColliderForce> collider_forces() const override { return inner_->collider_forces(); }

  std::vector<Eigen::Isometry3d> start, end;  // per collider, of the last step
  std::vector<Eigen::Vector3d> velocity;      // m/s, of each collider's origin in the last step

 private:
  std::unique_ptr<Solver> inner_;
  std::shared_ptr<const ContactModel> contacts_;
};

// Our solver on `colliders`, its contacts reading the pose table `poses` (null: analytic poses).
std::unique_ptr<SpringDamperSolver> ours(
    const std::shared_ptr<const ClothModel>& model, const ClothState& initial,
    const std::vector<Collider>& colliders, std::shared_ptr<const ColliderPoseTable> poses,
    std::shared_ptr<const ContactModel>* contacts_out = nullptr) {
  SpringDamperSettings settings;
  settings.contacts = std::make_shared<const ContactModel>(colliders, ContactParameters{500, 0.05},
                                                           model->thickness, poses);
  if (contacts_out) *contacts_out = settings.contacts;
  return std::make_unique<SpringDamperSolver>("s", model, initial, settings);
}

// A keyframed arm that turns and moves, a ball that moves and spins, and a tilting floor (whose
// Bullet box sits off the collider's origin, so its velocities differ from the shape's).
std::vector<Collider> moving_colliders() {
  Collider arm;
  arm.name = "arm";
  arm.shape = ColliderShape::capsule;
  arm.radius = 0.05;
  arm.height = 0.4;
  arm.axis = Eigen::Vector3d::UnitX();
  arm.motion.keyframes = {{0.0, {0, 0.5, 0}, {0, 0, 0}},
                          {0.05, {0.1, 0.6, 0}, {0, 45, 10}},
                          {0.08, {0.0, 0.55, 0.1}, {20, 0, -30}}};
  Collider ball;
  ball.name = "ball";
  ball.shape = ColliderShape::sphere;
  ball.center = {0.5, 0.2, 0};
  ball.radius = 0.1;
  ball.motion.velocity = {0, 1, 0};
  ball.motion.angular_velocity = {0, 90, 0};
  Collider floor;
  floor.name = "floor";
  floor.shape = ColliderShape::plane;
  floor.center = {0, -1, 0};
  floor.rotation = {5, 0, 0};
  floor.motion.angular_velocity = {0, 0, 30};
  return {arm, ball, floor};
}

TEST(BulletHost, ContactsUseThePosesOfBulletsBodiesAtEverySubstep) {
  const GridClothSpec spec = pinned_sheet(5, 0.4, {0, 0.8, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  const std::vector<Collider> colliders = moving_colliders();
  auto poses = std::make_shared<ColliderPoseTable>(colliders.size());
  std::shared_ptr<const ContactModel> contacts;
  auto recorder = std::make_unique<PoseRecorder>(
      ours(model, initial_grid_state(*model, spec, 0.0, 0), colliders, poses, &contacts), contacts);
  const PoseRecorder& seen = *recorder;
  auto hosted =
      bullet::host_in_bullet_world(std::move(recorder), poses, colliders, {0, -9.81, 0}, 1e-3);
  const double h = 1e-3;
  std::vector<Eigen::Isometry3d> bullet_before = bullet::bullet_collider_poses(*hosted);
  ASSERT_EQ(bullet_before.size(), colliders.size());
  for (int k = 1; k <= 100; ++k) {
    hosted->step(h);
    const std::vector<Eigen::Isometry3d> bullet_after = bullet::bullet_collider_poses(*hosted);
    const double t = k * h;  // the end of the substep just taken
    for (std::size_t c = 0; c < colliders.size(); ++c) {
      // What our contacts used is what Bullet's bodies held at both ends of the substep...
      EXPECT_LT(largest_difference(seen.start[c], bullet_before[c]), 1e-15)
          << colliders[c].name << " t=" << t;
      EXPECT_LT(largest_difference(seen.end[c], bullet_after[c]), 1e-15)
          << colliders[c].name << " t=" << t;
      // ...and Bullet's bodies did move as the scene says (so the check above is not between two
      // unmoved copies).
      EXPECT_LT(largest_difference(bullet_after[c], collider_pose(colliders[c], t)), 1e-12)
          << colliders[c].name;
      // The collider origin's velocity over the substep: the floor spins about its own point, which
      // stays put, although Bullet's box (centred 5 m below) moves.
      const Eigen::Vector3d expected = (collider_pose(colliders[c], t).translation() -
                                        collider_pose(colliders[c], t - h).translation()) /
                                       h;
      EXPECT_LT((seen.velocity[c] - expected).norm(), 1e-9) << colliders[c].name << " t=" << t;
    }
    bullet_before = bullet_after;
  }
  // The motions are under way by the end: the arm turned, the ball rose 0.1 m.
  EXPECT_GT(largest_difference(bullet_before[0], collider_pose(colliders[0], 0.0)), 0.1);
  EXPECT_NEAR(bullet_before[1].translation().y(), 0.3, 1e-12);
}

// A bare and a hosted run of a cloth pushed by a rising ball and brushed by a turning box agree to
// rounding: the hosted one reads every pose back from Bullet's bodies and takes the collider
// velocities as displacements over the substep, so bits differ, but only at the last place (a
// bitwise-equal test would pass even if the host were cosmetic; this one is paired with the test
// above).
TEST(BulletHost, HostedRunAgreesWithTheBareRunToRounding) {
  const GridClothSpec spec = pinned_sheet(11, 0.5, {0, 0.8, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  Collider ball;
  ball.shape = ColliderShape::sphere;
  ball.center = {0, 0.5, 0};
  ball.radius = 0.15;
  ball.motion.velocity = {0, 0.5, 0};
  Collider paddle;
  paddle.shape = ColliderShape::box;
  paddle.center = {0.2, 0.78, 0.2};
  paddle.half_extents = {0.1, 0.01, 0.05};
  paddle.motion.angular_velocity = {0, 60, 0};
  const std::vector<Collider> colliders{ball, paddle};
  const ClothState initial = initial_grid_state(*model, spec, 0.0, 0);
  auto bare = ours(model, initial, colliders, nullptr);
  auto poses = std::make_shared<ColliderPoseTable>(colliders.size());
  auto hosted = bullet::host_in_bullet_world(ours(model, initial, colliders, poses), poses,
                                             colliders, {0, -9.81, 0}, 1e-3);
  const double h = 2e-4;
  double largest_push = 0.0, largest_brush = 0.0;  // N
  for (int k = 0; k < 2000; ++k) {
    bare->step(h);
    hosted->step(h);
    largest_push = std::max(largest_push, hosted->collider_forces().at(0).normal);
    largest_brush = std::max(largest_brush, hosted->collider_forces().at(1).normal);
  }
  ASSERT_EQ(hosted->status(), SolverStatus::ok);
  EXPECT_EQ(hosted->state().step_count, 2000);
  EXPECT_LT((hosted->state().x - bare->state().x).cwiseAbs().maxCoeff(),
            1e-12);  // m (measured 1.8e-14)
  EXPECT_LT((hosted->state().v - bare->state().v).cwiseAbs().maxCoeff(),
            1e-9);                // m/s (measured 7e-12)
  EXPECT_GT(largest_push, 0.0);   // the ball reached the cloth
  EXPECT_GT(largest_brush, 0.0);  // so did the paddle
  EXPECT_FALSE(hosted->phase_seconds().empty());
}

TEST(BulletHost, RefusesAPoseTableOfTheWrongSize) {
  const GridClothSpec spec = pinned_sheet(3, 0.4, {0, 0.8, 0}, 0.05);
  const auto model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
  Collider ball;
  auto table = std::make_shared<ColliderPoseTable>(1);
  auto guest = ours(model, initial_grid_state(*model, spec, 0.0, 0), {ball}, table);
  EXPECT_THROW(
      bullet::host_in_bullet_world(std::move(guest), std::make_shared<ColliderPoseTable>(2), {ball},
                                   {0, -9.81, 0}, 1e-3),
      std::invalid_argument);
}

}  // namespace
}  // namespace drapelab
