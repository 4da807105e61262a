// Drag, lift and gusting wind on the cloth's triangles (see air.hpp).
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "drapelab/air.hpp"

namespace drapelab {

Wind::Wind(const AirSettings& air) : mean_(air.wind) {
  const double speed = air.wind.norm();
  direction_ = speed > 0.0 ? Eigen::Vector3d(air.wind / speed) : Eigen::Vector3d::UnitX();
  if (air.turbulence_intensity > 0.0) add_turbulence(air);
  if (!(air.gust_amplitude > 0.0)) return;  // steady: every weight stays 0
  // mt19937_64 is specified bit for bit, and the mapping to [0, 1) is ours (no library
  // distribution), so the gusts are the same on every machine.
  std::mt19937_64 random(air.seed);
  const auto uniform = [&random] {
    return static_cast<double>(random() >> 11) * 0x1.0p-53;  // [0, 1)
  };
  double sum_of_squares = 0.0;
  for (std::size_t k = 0; k < weight_.size(); ++k) {
    const double period = air.gust_period * std::exp2(2.0 * uniform() - 1.0);  // [T/2, 2T)
    frequency_[k] = 2.0 * std::numbers::pi / period;
    phase_[k] = 2.0 * std::numbers::pi * uniform();
    weight_[k] = 0.5 + uniform();  // [0.5, 1.5): no sinusoid dominates
    sum_of_squares += weight_[k] * weight_[k];
  }
  // A sinusoid of weight w has a mean square of w^2 / 2.
  const double scale = air.gust_amplitude / std::sqrt(0.5 * sum_of_squares);
  for (double& w : weight_) w *= scale;
}

namespace {

// A unit vector uniform on the sphere from two numbers of [0, 1).
Eigen::Vector3d unit_vector(double u, double w) {
  const double z = 2.0 * u - 1.0;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double angle = 2.0 * std::numbers::pi * w;
  return {r * std::cos(angle), r * std::sin(angle), z};
}

}  // namespace

void Wind::add_turbulence(const AirSettings& air) {
  // Its own stream of the seed, so that turning turbulence on leaves the gusts as they were.
  std::mt19937_64 random(air.seed ^ 0x9e3779b97f4a7c15ULL);
  const auto uniform = [&random] {
    return static_cast<double>(random() >> 11) * 0x1.0p-53;  // [0, 1)
  };
  constexpr int kWaves = 16;
  double sum_of_squares = 0.0;
  for (int k = 0; k < kWaves; ++k) {
    ShearWave wave;
    const double wavelength = air.turbulence_length * std::exp2(2.0 * uniform() - 1.0);  // m
    const Eigen::Vector3d along = unit_vector(uniform(), uniform());
    wave.wave_vector = (2.0 * std::numbers::pi / wavelength) * along;
    // A direction normal to the wave vector: a random one with its part along the wave removed.
    Eigen::Vector3d across = unit_vector(uniform(), uniform());
    across -= across.dot(along) * along;
    if (!(across.norm() > 1e-6)) across = along.unitOrthogonal();
    const double weight = 0.5 + uniform();  // [0.5, 1.5)
    wave.velocity = weight * across.normalized();
    wave.phase = 2.0 * std::numbers::pi * uniform();
    sum_of_squares += weight * weight;
    turbulence_.push_back(wave);
  }
  // Each wave's mean square over space is |velocity|^2 / 2, and different waves are uncorrelated.
  const double scale = air.turbulence_intensity / std::sqrt(0.5 * sum_of_squares);
  for (ShearWave& wave : turbulence_) wave.velocity *= scale;
}

Eigen::Vector3d Wind::eddies(double t, const Eigen::Vector3d& x) const {
  const Eigen::Vector3d carried = x - t * mean_;  // m: where this air was at t = 0
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (const ShearWave& wave : turbulence_)
    u += std::sin(wave.wave_vector.dot(carried) + wave.phase) * wave.velocity;
  return u;
}

Eigen::Vector3d Wind::at(double t, const Eigen::Vector3d& x) const {
  return turbulence_.empty() ? at(t) : Eigen::Vector3d(at(t) + eddies(t, x));
}

Eigen::Vector3d Wind::at(double t) const {
  double gust = 0.0;  // m/s
  for (std::size_t k = 0; k < weight_.size(); ++k)
    gust += weight_[k] * std::sin(frequency_[k] * t + phase_[k]);
  return mean_ + gust * direction_;
}

Eigen::Vector3d triangle_air_force(const AirSettings& air, double area,
                                   const Eigen::Vector3d& normal, const Eigen::Vector3d& relative) {
  const double along = relative.dot(normal);  // m/s, u_n
  const double half_rho_area = 0.5 * air.density * area;
  Eigen::Vector3d force = (half_rho_area * air.drag * std::abs(along) * along) * normal;
  if (air.lift != 0.0) {
    const Eigen::Vector3d across = relative - along * normal;  // m/s, u_t
    const double speed = relative.norm();
    const double slide = across.norm();
    if (speed > 0.0 && slide > 0.0 && along != 0.0) {
      // Across the flow, towards the side the air pushes: the part of the push direction
      // sign(u_n) n normal to u.
      const Eigen::Vector3d push = along > 0.0 ? normal : Eigen::Vector3d(-normal);
      const Eigen::Vector3d flow = relative / speed;
      const Eigen::Vector3d side = push - push.dot(flow) * flow;
      const double side_length = side.norm();
      if (side_length > 0.0)
        force += (half_rho_area * air.lift * std::abs(along) * slide / side_length) * side;
    }
  }
  return force;
}

void add_air_forces(const ClothModel& model, const AirSettings& air, const Wind& wind, double t,
                    const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force,
                    PowerSplit* power) {
  if (power) *power = {};
  const Eigen::Vector3d w = wind.at(t);
  const bool eddies = wind.varies_in_space();
  for (Eigen::Index k = 0; k < model.triangles.cols(); ++k) {
    const int a = model.triangles(0, k), b = model.triangles(1, k), c = model.triangles(2, k);
    const Eigen::Vector3d doubled = (x.col(b) - x.col(a)).cross(x.col(c) - x.col(a));
    const double twice_area = doubled.norm();  // m^2
    if (!(twice_area > 0.0)) continue;         // a collapsed triangle has no normal
    const Eigen::Vector3d here =
        eddies ? Eigen::Vector3d(w + wind.eddies(t, (x.col(a) + x.col(b) + x.col(c)) / 3.0)) : w;
    const Eigen::Vector3d relative = here - (v.col(a) + v.col(b) + v.col(c)) / 3.0;
    const Eigen::Vector3d share =
        triangle_air_force(air, 0.5 * twice_area, doubled / twice_area, relative) / 3.0;
    force.col(a) += share;
    force.col(b) += share;
    force.col(c) += share;
    // The triangle's force F = 3 share moves with the corners' mean velocity, here - relative:
    // F . relative is taken out relative to the air, F . here put in by the wind.
    if (power) *power += {3.0 * share.dot(relative), 3.0 * share.dot(here)};
  }
}

}  // namespace drapelab
