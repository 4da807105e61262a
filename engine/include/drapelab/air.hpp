// Air (scene key `air:`): aerodynamic drag and lift on the cloth's triangles, from the velocity of
// each triangle relative to the wind. For a triangle of area A and unit normal n whose corners move
// at mean velocity v, in air of density rho blowing at W(t), with u = W - v and u_n = u . n:
//   drag  F_d = 1/2 rho C_d A |u_n| u_n n                  (the pressure on the plate, along n)
//   lift  F_l = 1/2 rho C_l A |u_n| |u - u_n n| l          (l: unit, across u, towards the pushed
//   side)
// Both sides of a triangle are alike (the signs follow u_n), a triangle moving in its own plane
// feels neither, and each corner takes a third. The mean wind is uniform in space; with gusts its
// speed varies in time by a smooth, seeded sum of sinusoids, and with turbulence a seeded field of
// eddies, carried along by the mean wind, adds to it from place to place (Wind); a triangle feels
// the wind at its centroid.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/energy_ledger.hpp"

namespace drapelab {

struct AirSettings {
  bool enabled = false;
  double density = 1.2;                            // kg/m^3, rho
  double drag = 1.0;                               // C_d of a triangle moving along its normal
  double lift = 0.0;                               // C_l
  Eigen::Vector3d wind = Eigen::Vector3d::Zero();  // m/s, the mean wind
  // Gusts: the wind speed along the mean wind's direction varies by g(t), a sum of four sinusoids
  // whose periods lie within a factor 2 of `gust_period` and whose phases come from `seed`, scaled
  // so that the root mean square of g is `gust_amplitude`. 0: steady.
  double gust_amplitude = 0.0;  // m/s
  double gust_period = 1.0;     // s
  // Turbulence: a frozen field of eddies u'(x - W t) carried by the mean wind W (Taylor's
  // hypothesis), the sum of 16 seeded sinusoidal shear waves whose wavelengths lie within a factor
  // 2 of `turbulence_length`; each wave's velocity is normal to its wave vector, so the field is
  // divergence-free (incompressible), and the root mean square of |u'| over space is
  // `turbulence_intensity`. 0: none.
  double turbulence_intensity = 0.0;  // m/s
  double turbulence_length = 1.0;     // m
  std::uint64_t seed = 0;
};

// The wind velocity of AirSettings: the same seed gives the same gusts and eddies bit for bit.
class Wind {
 public:
  explicit Wind(const AirSettings& air);
  Eigen::Vector3d at(double t) const;  // m/s at time t (s): the mean wind and its gusts
  // m/s at time t (s) and place x (m): at(t) plus the turbulence there.
  Eigen::Vector3d at(double t, const Eigen::Vector3d& x) const;
  bool varies_in_space() const { return !turbulence_.empty(); }
  // The turbulence alone at x (m) and time t (s).
  Eigen::Vector3d eddies(double t, const Eigen::Vector3d& x) const;

 private:
  struct ShearWave {
    Eigen::Vector3d wave_vector;  // rad/m
    Eigen::Vector3d velocity;     // m/s, normal to wave_vector
    double phase = 0.0;           // rad
  };
  void add_turbulence(const AirSettings& air);

  std::vector<ShearWave> turbulence_;
  Eigen::Vector3d mean_;               // m/s
  Eigen::Vector3d direction_;          // unit, the gusts' direction (the mean wind's)
  std::array<double, 4> weight_{};     // m/s per sinusoid
  std::array<double, 4> frequency_{};  // rad/s
  std::array<double, 4> phase_{};      // rad
};

// Adds the drag and lift of every triangle of `model` at (x, v) and time t (s) to `force` (N,
// 3 x N). Pinned particles take their share too (it is their holders' to bear). When `power` is
// given, it is reset and receives the drag's dissipation relative to the air and the wind's work
// (W, energy_ledger.hpp).
void add_air_forces(const ClothModel& model, const AirSettings& air, const Wind& wind, double t,
                    const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force,
                    PowerSplit* power = nullptr);

// The force on one triangle of area `area` (m^2) and unit normal `normal` whose air moves at
// `relative` (m/s, the wind minus the triangle's velocity): drag plus lift (N).
Eigen::Vector3d triangle_air_force(const AirSettings& air, double area,
                                   const Eigen::Vector3d& normal, const Eigen::Vector3d& relative);

}  // namespace drapelab
