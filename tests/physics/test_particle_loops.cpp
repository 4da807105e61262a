// The per-particle passes and the block-parallel contact phase (particle_loops.hpp,
// contact_model.hpp): the Euler passes apply their formulas exactly, the health scan names the
// first bad particle (and only a bad one), the vectorised broad phase keeps exactly the particles
// the direct test keeps, and contact forces and totals are bitwise identical for 1 and 2 threads
// and equal a direct sum.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <tuple>
#include <vector>

#include "contact/broad_phase_loops.hpp"
#include "core/penalty_contact.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "fixtures/colliders.hpp"
#include "fixtures/sheets.hpp"
#include "forces/body_force_loops.hpp"
#include "forces/spring_family_loops.hpp"
#include "integrators/particle_loops.hpp"

namespace drapelab {
namespace {

// A deterministic spread of values in [-1, 1] (no global random state).
double wave(int i, double frequency) { return std::sin(frequency * i + 0.3); }

TEST(ParticleLoops, EulerPassesApplyTheirFormulasAndHoldPinnedParticles) {
  const int n = 5;
  std::vector<double> inverse_mass(3 * n), f(3 * n), x(3 * n), v(3 * n);
  for (int k = 0; k < 3 * n; ++k) {
    inverse_mass[k] = (k / 3 == 2) ? 0.0 : 1.0 + k / 3;  // particle 2 is pinned
    f[k] = wave(k, 1.1);
    x[k] = wave(k, 0.7);
    v[k] = (k / 3 == 2) ? 0.0 : wave(k, 1.9);
  }
  const double h = 0.01;
  std::vector<double> xs = x, vs = v, xe = x, ve = v;
  EXPECT_EQ(kernels::symplectic_euler_pass(n, inverse_mass.data(), f.data(), h, xs.data(),
                                           vs.data(), 1e6),
            -1);
  EXPECT_EQ(
      kernels::explicit_euler_pass(n, inverse_mass.data(), f.data(), h, xe.data(), ve.data(), 1e6),
      -1);
  for (int k = 0; k < 3 * n; ++k) {
    const double v_new = v[k] + h * (f[k] * inverse_mass[k]);
    EXPECT_EQ(vs[k], v_new) << k;
    EXPECT_EQ(xs[k], x[k] + h * v_new) << k;  // symplectic: the new velocity moves the particle
    EXPECT_EQ(ve[k], v_new) << k;
    EXPECT_EQ(xe[k], x[k] + h * v[k]) << k;  // forward: the old one
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(xs[6 + c], x[6 + c]);
    EXPECT_EQ(vs[6 + c], 0.0);
  }
}

TEST(ParticleLoops, BodyForcesAreWeightLessAirDrag) {
  const int n = 4;
  std::vector<double> weight(3 * n), mass(3 * n), v(3 * n), f(3 * n, 99.0);
  for (int k = 0; k < 3 * n; ++k) {
    mass[k] = 0.001 * (1 + k / 3);
    weight[k] = (k % 3 == 1) ? -9.81 * mass[k] : 0.0;
    v[k] = wave(k, 0.9);
  }
  kernels::set_body_forces(n, weight.data(), mass.data(), 0.5, v.data(), f.data());
  for (int k = 0; k < 3 * n; ++k) EXPECT_EQ(f[k], weight[k] - 0.5 * (v[k] * mass[k])) << k;
}

// The state of n particles at rest at x = 1 m.
struct Particles {
  explicit Particles(int n) : x(3 * n, 1.0), v(3 * n, 0.0) {}
  std::vector<double> x, v;
};

std::int64_t first_unhealthy(const Particles& p, double max_speed, int threads) {
  kernels::set_thread_count(threads);
  const std::int64_t first = kernels::first_unhealthy_particle(
      static_cast<std::int64_t>(p.x.size() / 3), p.x.data(), p.v.data(), max_speed * max_speed);
  kernels::set_thread_count(1);
  return first;
}

TEST(ParticleLoops, HealthScanNamesTheFirstBadParticleWhateverTheThreadCount) {
  const int n = 10000;         // above the threading threshold
  const double limit = 100.0;  // m/s
  Particles p(n);
  // Healthy: particle 10 at 0.999 of the limit along the diagonal passes the quick per-coordinate
  // test; particle 20, with one coordinate at 0.99 of the limit, fails it and is cleared by the
  // exact per-particle test.
  const double diagonal = 0.999 * limit / std::sqrt(3.0);
  p.v[3 * 10] = p.v[3 * 10 + 1] = p.v[3 * 10 + 2] = diagonal;
  p.v[3 * 20 + 1] = 0.99 * limit;
  p.v[3 * 30 + 2] = limit;  // exactly at the limit: still healthy
  for (int threads : {1, 2}) EXPECT_EQ(first_unhealthy(p, limit, threads), -1) << threads;

  p.v[3 * 9500] = std::nextafter(limit, 2.0 * limit);  // one step of rounding above the limit
  for (int threads : {1, 2}) EXPECT_EQ(first_unhealthy(p, limit, threads), 9500) << threads;

  p.v[3 * 9000] = p.v[3 * 9000 + 1] = p.v[3 * 9000 + 2] =
      1.001 * limit / std::sqrt(3.0);  // just too fast
  for (int threads : {1, 2}) EXPECT_EQ(first_unhealthy(p, limit, threads), 9000) << threads;
  p.v[3 * 7001 + 2] = std::numeric_limits<double>::infinity();
  for (int threads : {1, 2}) EXPECT_EQ(first_unhealthy(p, limit, threads), 7001) << threads;
  p.x[3 * 7000] = std::numeric_limits<double>::quiet_NaN();
  for (int threads : {1, 2}) EXPECT_EQ(first_unhealthy(p, limit, threads), 7000) << threads;
  p.x[3 * 5 + 1] = -std::numeric_limits<double>::infinity();
  for (int threads : {1, 2}) EXPECT_EQ(first_unhealthy(p, limit, threads), 5) << threads;
}

TEST(ParticleLoops, HealthScanCatchesAnInfiniteVelocityUnderAnEnormousLimit) {
  Particles p(5000);
  p.v[3 * 4000] = std::numeric_limits<double>::infinity();
  const double limit = 1e200;  // m/s: its square overflows to infinity
  for (int threads : {1, 2}) EXPECT_EQ(first_unhealthy(p, limit, threads), 4000) << threads;
}

TEST(ParticleLoops, EulerPassesReportTheParticleTheyMadeUnhealthy) {
  const int n = 6000;
  std::vector<double> inverse_mass(3 * n, 1.0), f(3 * n, 0.0);
  f[3 * 4321 + 1] = 2.0e7;  // N on 1 kg for 1e-5 s: 200 m/s, twice the limit
  Particles symplectic(n), forward(n);
  EXPECT_EQ(kernels::symplectic_euler_pass(n, inverse_mass.data(), f.data(), 1e-5,
                                           symplectic.x.data(), symplectic.v.data(), 1e4),
            4321);
  // Forward Euler moves x with the old velocity, but the scan checks the new one.
  EXPECT_EQ(kernels::explicit_euler_pass(n, inverse_mass.data(), f.data(), 1e-5, forward.x.data(),
                                         forward.v.data(), 1e4),
            4321);
  EXPECT_EQ(forward.x[3 * 4321 + 1], 1.0);
}

TEST(ParticleLoops, BroadPhaseKeepsExactlyTheParticlesOfTheDirectTest) {
  const int n = 3000;
  std::vector<double> x(3 * n);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      x[3 * i + c] = wave(i, 2.3 + 0.77 * c);  // scattered in a cube of side 2 m
  kernels::NearCollider plane;
  plane.plane = true;
  plane.normal[0] = 0.6;
  plane.normal[1] = 0.8;
  plane.offset = 0.1;
  plane.radius = 0.05;
  kernels::NearCollider ball;
  for (int c = 0; c < 3; ++c) {
    ball.low[c] = -0.4 + 0.1 * c;
    ball.high[c] = 0.5 + 0.1 * c;
    ball.center[c] = 0.05 + 0.1 * c;
  }
  ball.reach_squared = 0.45 * 0.45;
  for (const kernels::NearCollider* collider : {&plane, &ball}) {
    std::vector<int> near(n);
    const int begin = 17, end = 2900;
    const int count = kernels::near_particles(*collider, x.data(), begin, end, near.data());
    std::vector<int> expected;
    for (int i = begin; i < end; ++i) {
      const double* p = &x[3 * i];
      bool keep = false;
      if (collider->plane) {
        keep = collider->normal[0] * p[0] + collider->normal[1] * p[1] +
                   collider->normal[2] * p[2] - collider->offset <
               collider->radius;
      } else {
        double d2 = 0.0;
        keep = true;
        for (int c = 0; c < 3; ++c) {
          keep = keep && p[c] >= collider->low[c] && p[c] <= collider->high[c];
          d2 += (p[c] - collider->center[c]) * (p[c] - collider->center[c]);
        }
        keep = keep && d2 < collider->reach_squared;
      }
      if (keep) expected.push_back(i);
    }
    ASSERT_GT(expected.size(), 10u);  // the test sees both outcomes
    ASSERT_LT(expected.size(), 2800u);
    EXPECT_EQ(std::vector<int>(near.begin(), near.begin() + count), expected);
  }
}

// Particles in a row along x, 1 mm apart, so that whole chunks of the broad phase lie near a
// collider (every one listed without the per-particle pass), far from it (skipped), or across its
// edge.
TEST(ParticleLoops, BroadPhaseListsWholeChunksNearAndSkipsChunksFar) {
  const int n = 3000;
  std::vector<double> x(3 * n, 0.0);
  for (int i = 0; i < n; ++i) x[3 * i] = 0.001 * i;  // m
  kernels::NearCollider wall;                        // x < 1.05 m passes: particles 0 to 1049
  wall.plane = true;
  wall.normal[0] = 1.0;
  wall.offset = 1.0;
  wall.radius = 0.05;
  kernels::NearCollider box;  // 1.5 <= x <= 2.6 and within 0.6 of x = 2.0: particles 1500 to 2599
  box.low[0] = 1.5;
  box.high[0] = 2.6;
  box.low[1] = box.low[2] = -1.0;
  box.high[1] = box.high[2] = 1.0;
  box.center[0] = 2.0;
  box.reach_squared = 0.6 * 0.6;
  for (const auto& [collider, first, last] :
       {std::tuple{&wall, 0, 1049}, std::tuple{&box, 1500, 2599}}) {
    for (const auto& [begin, end] : {std::pair{0, n}, std::pair{13, 2951}}) {
      std::vector<int> near(n);
      const int count = kernels::near_particles(*collider, x.data(), begin, end, near.data());
      std::vector<int> expected;
      for (int i = std::max(begin, first); i <= std::min(end - 1, last); ++i) expected.push_back(i);
      EXPECT_EQ(std::vector<int>(near.begin(), near.begin() + count), expected)
          << begin << ".." << end;
    }
  }
}

// A 97 x 97 cloth dropped into a sphere and a floor, its middle already inside the sphere.
struct ContactScene {
  ContactScene() {
    // 1 cm below the sphere's top: a patch of particles in contact.
    spec = fixtures::flat_sheet(97, 1.0, {0.0, 0.79, 0.0}, 0.25);
    model = std::make_shared<const ClothModel>(build_grid_cloth(spec));
    Collider ball = fixtures::ball_collider();
    ball.motion.angular_velocity = {5, 0, 0};  // its surface moves: friction relative to it
    // The cloth's edges rest 5 mm above the floor: within the contact radius.
    const Collider floor = fixtures::floor_collider(0.785);
    settings.air_damping = 0.1;
    settings.contacts = std::make_shared<const ContactModel>(
        std::vector<Collider>{ball, floor}, ContactParameters{1000.0, 0.2}, spec.thickness);
  }
  ClothState state() const {
    ClothState s = initial_grid_state(*model, spec, 0.002, 3);
    for (int i = 0; i < model->particle_count(); ++i)
      s.v.col(i) = 0.05 * Eigen::Vector3d(wave(i, 0.7), wave(i, 1.3), wave(i, 2.1));
    return s;
  }
  GridClothSpec spec;
  std::shared_ptr<const ClothModel> model;
  SpringDamperSettings settings;
};

struct ContactRun {
  ClothState state;
  std::vector<ColliderContactTotals> totals;
};

ContactRun run_contacts(const ContactScene& scene, int threads) {
  kernels::set_thread_count(threads);
  SpringDamperSolver solver("s", scene.model, scene.state(), scene.settings);
  for (int k = 0; k < 20; ++k) solver.step(3e-6);  // s, within the Gershgorin stable step (4e-6 s)
  EXPECT_EQ(solver.status(), SolverStatus::ok) << solver.message();
  kernels::set_thread_count(1);
  return {solver.state(), solver.contact_totals()};
}

TEST(ContactPhase, RunsWithContactsAreBitwiseIdenticalForOneAndTwoThreads) {
  const ContactScene scene;
  const ContactRun one = run_contacts(scene, 1);
  const ContactRun two = run_contacts(scene, 2);
  ASSERT_EQ(one.totals.size(), 2u);
  EXPECT_GT(one.totals[0].contact_count, 100);  // the sphere holds a patch of the cloth
  EXPECT_GT(one.totals[1].contact_count, 100);  // and the floor its edges
  EXPECT_TRUE((one.state.x.array() == two.state.x.array()).all())
      << "thread count changed the positions";
  EXPECT_TRUE((one.state.v.array() == two.state.v.array()).all())
      << "thread count changed the velocities";
  for (std::size_t c = 0; c < 2; ++c) {
    EXPECT_EQ(one.totals[c].contact_count, two.totals[c].contact_count);
    EXPECT_EQ(one.totals[c].normal_force, two.totals[c].normal_force);
    EXPECT_EQ(one.totals[c].friction_force, two.totals[c].friction_force);
    EXPECT_EQ(one.totals[c].max_depth, two.totals[c].max_depth);
  }
}

TEST(ContactPhase, BlockTotalsEqualADirectSumOverEveryParticle) {
  const ContactScene scene;
  kernels::set_thread_count(2);
  SpringDamperSolver solver("s", scene.model, scene.state(), scene.settings);
  const ClothState state = scene.state();
  const Eigen::Matrix3Xd without_contacts = [&] {
    SpringDamperSettings bare = scene.settings;
    bare.contacts = nullptr;
    SpringDamperSolver free_solver("free", scene.model, scene.state(), bare);
    return Eigen::Matrix3Xd(free_solver.evaluate_forces(state.x, state.v, 0.0, 2e-5));
  }();
  const Eigen::Matrix3Xd with_contacts = solver.evaluate_forces(state.x, state.v, 0.0, 2e-5);
  kernels::set_thread_count(1);
  // Every particle in contact, found directly with FCL, pushed out along its normal.
  const ContactModel& contacts = *scene.settings.contacts;
  ASSERT_EQ(scene.settings.integrator, Integrator::symplectic_euler);
  int on_both = 0;
  int direct_counts[2] = {0, 0};
  double direct_normals[2] = {0.0, 0.0};  // N
  for (int i = 0; i < scene.model->particle_count(); ++i) {
    // Both colliders' overlaps, ball first; symplectic Euler solves a particle's contacts together
    // at the step's end, starting from the contact-free force (penalty_contact.hpp).
    std::vector<NormalContact> overlaps;
    std::vector<int> colliders;
    for (int c = 0; c < 2; ++c) {
      const auto touching = contacts.query().contact(contacts.fcl_collider(c),
                                                     contacts.shape_pose(c, 0.0), state.x.col(i));
      if (!touching) continue;
      overlaps.push_back({touching->normal, touching->depth,
                          collider_point_velocity(contacts.collider(c), 0.0, state.x.col(i))});
      colliders.push_back(c);
    }
    if (overlaps.empty()) continue;
    on_both += overlaps.size() == 2 ? 1 : 0;
    const Eigen::Vector3d pushed = with_contacts.col(i) - without_contacts.col(i);
    if (colliders[0] == 0) {
      EXPECT_GT(pushed.dot(overlaps[0].normal), 0.0) << "particle " << i;
    }
    double fn[2] = {0.0, 0.0};
    linearly_implicit_normal_forces(overlaps.data(), static_cast<int>(overlaps.size()),
                                    state.v.col(i), without_contacts.col(i), scene.model->mass[i],
                                    2e-5, 1000.0, 0.2, fn);
    for (std::size_t a = 0; a < overlaps.size(); ++a) {
      ++direct_counts[colliders[a]];
      direct_normals[colliders[a]] += fn[a];
    }
  }
  EXPECT_GT(on_both, 10);  // the joint solve is exercised
  for (int c = 0; c < 2; ++c) {
    const ColliderContactTotals& total = solver.contact_totals()[static_cast<std::size_t>(c)];
    EXPECT_EQ(total.contact_count, direct_counts[c]) << "collider " << c;
    EXPECT_NEAR(total.normal_force, direct_normals[c], 1e-12 * direct_normals[c])
        << "collider " << c;  // N, summation order only
  }
  EXPECT_GT(direct_normals[0], 0.0);
}

}  // namespace
}  // namespace drapelab
