// The bound of a weighted contact's spring and damper for an explicit step
// (engine/contact/explicit_contact_bound.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/explicit_contact_bound.hpp"

namespace drapelab {
namespace {

// A particle of mass m held by `load` identical contacts along one normal, stepped by symplectic
// Euler: returns the largest energy 1/2 m v^2 + load 1/2 k' d^2 reached over `steps`, relative to
// the start (J / J).
double largest_energy_ratio(double stiffness, double damping, double mass, int load, double h,
                            bool bounded, int steps) {
  const PenaltyRates rates = bounded ? step_bounded_penalty(stiffness, damping, 1.0 / mass, load, h)
                                     : PenaltyRates{stiffness, damping};
  double depth = 1e-4, velocity = 0.0;  // m, m/s (velocity > 0: deeper)
  const auto energy = [&] {
    const double inside = std::max(depth, 0.0);  // m: the spring holds energy only in contact
    return 0.5 * mass * velocity * velocity + load * 0.5 * rates.stiffness * inside * inside;
  };
  const double start = energy();
  double largest = start;
  for (int n = 0; n < steps; ++n) {
    const double push = depth > 0.0 ? rates.stiffness * depth + rates.damping * velocity : 0.0;
    velocity -= h * load * std::max(0.0, push) / mass;
    depth += h * velocity;
    largest = std::max(largest, energy());
  }
  return largest / start;
}

// A 1e-4 kg particle in three contacts of the default 5000 N/m and 5 N s/m, at a cotton sheet's
// 2.5e-4 s: taken as they are, they throw it out with nine times the energy they held; bounded,
// never more than they held.
TEST(ExplicitContactBound, ThreeContactsOnALightParticleGainNoEnergyAtALargeStep) {
  EXPECT_GT(largest_energy_ratio(5000.0, 5.0, 1e-4, 3, 2.5e-4, false, 200), 5.0);
  EXPECT_LE(largest_energy_ratio(5000.0, 5.0, 1e-4, 3, 2.5e-4, true, 200), 1.0 + 1e-12);
}

// At a step where the explicit contact is stable already, the bound changes it by little.
TEST(ExplicitContactBound, LeavesAContactAtASmallStepAlmostAsItIs) {
  const PenaltyRates rates = step_bounded_penalty(5000.0, 5.0, 1.0 / 0.01, 1.0, 1e-6);
  EXPECT_NEAR(rates.stiffness, 5000.0, 5000.0 * 1e-5);
  EXPECT_NEAR(rates.damping, 5.0, 5.0 * 1e-3);
}

TEST(ExplicitContactBound, CountsEachParticlesContacts) {
  ContactLoads loads(4);
  loads.add(std::array<int, 2>{0, 1}, std::array<double, 2>{0.5, 0.5});
  loads.add(std::array<int, 2>{1, 2}, std::array<double, 2>{0.3, 0.7});
  loads.add(std::array<int, 2>{1, 3}, std::array<double, 2>{0.0, 1.0});  // weight 0: not on 1
  EXPECT_EQ(loads.load(std::array<int, 2>{0, 1}, std::array<double, 2>{0.5, 0.5}), 2.0);
  EXPECT_EQ(loads.load(std::array<int, 2>{3, -1}, std::array<double, 2>{1.0, 0.0}), 1.0);
  loads.clear();
  EXPECT_EQ(loads.load(std::array<int, 2>{0, 1}, std::array<double, 2>{0.5, 0.5}), 1.0);
}

}  // namespace
}  // namespace drapelab
