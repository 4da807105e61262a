// The finite range of every number a scene gives, so that every quantity derived from them (forces,
// energies, steps, metrics) stays finite: 1e308 anywhere is an error naming the key, not an inf or
// nan in the metrics of a run reported as ok. docs/scene-reference.md states each range next to its
// key; every scene in scenes/ and every test lies well inside them.
#pragma once

#include <cstddef>
#include <string>

#include "drapelab/cloth_limits.hpp"
#include "yaml_reader.hpp"

namespace drapelab::scene {

// Names (scene, solver, collider) become file names (meshes/SOLVER.pc2): [a-z0-9_-]{1,64}.
inline constexpr std::size_t kMaxNameLength = 64;

inline constexpr double kMaxCoordinate = 1e4;   // m, each coordinate of a position
inline constexpr double kMaxAngle = 3600.0;     // deg, each Euler angle (ten turns)
inline constexpr double kMaxGravity = 1000.0;   // m/s^2, |gravity|, about 100 g
inline constexpr double kMaxDirection = 1e6;    // each component of an axis or normal
inline constexpr double kMinDirection = 1e-12;  // the smallest length of an axis or normal

// Positions (m): centres, points, keyframe centres.
constexpr Range coordinate_range() { return {-kMaxCoordinate, true, kMaxCoordinate, true}; }
constexpr Range angle_range() { return {-kMaxAngle, true, kMaxAngle, true}; }  // deg
constexpr Range direction_range() { return {-kMaxDirection, true, kMaxDirection, true}; }
constexpr Range gravity_range() { return {-kMaxGravity, true, kMaxGravity, true}; }  // m/s^2

// Time (s) and rate (1/s).
constexpr Range duration_range() { return {0.0, false, 1e8, true}; }
constexpr Range frame_rate_range() { return {0.0, false, 1e6, true}; }
constexpr Range keyframe_time_range() { return {0.0, true, 1e8, true}; }

// The cloth.
constexpr Range cloth_length_range() { return {1e-3, true, 1e3, true}; }  // m: size, radius, extent
constexpr Range mesh_scale_range() { return {1e-6, true, 1e6, true}; }
constexpr Range mass_range() { return {1e-9, true, 1e6, true}; }           // kg
constexpr Range areal_density_range() { return {1e-6, true, 1e3, true}; }  // kg/m^2
constexpr Range thickness_range() { return {1e-6, true, 1.0, true}; }      // m
constexpr Range perturbation_range() { return {0.0, true, 1.0, true}; }    // m
constexpr Range air_damping_range() { return {0.0, true, 1e4, true}; }     // 1/s
constexpr Range stretch_ks_range() { return {0.0, false, 1e12, true}; }    // N/m
constexpr Range spring_ks_range() { return {0.0, true, 1e12, true}; }      // N/m: shear, bend
constexpr Range spring_kd_range() { return {0.0, true, 1e9, true}; }       // N*s/m
constexpr Range pin_radius_range() { return {0.0, false, 1e5, true}; }     // m

// The continuum model (cloth.continuum).
constexpr Range stretch_modulus_range() { return {0.0, false, 1e12, true}; }   // N/m
constexpr Range poisson_range() { return {0.0, true, 0.5, false}; }            // [0, 0.5)
constexpr Range bending_rigidity_range() { return {0.0, true, 1e3, true}; }    // N*m
constexpr Range continuum_damping_range() { return {0.0, true, 10.0, true}; }  // s

// Colliders and contact.
constexpr Range collider_size_range() { return {1e-6, true, 1e4, true}; }     // m
constexpr Range velocity_range() { return {-1e3, true, 1e3, true}; }          // m/s
constexpr Range angular_velocity_range() { return {-1e5, true, 1e5, true}; }  // deg/s
constexpr Range friction_range() { return {0.0, true, 100.0, true}; }
constexpr Range contact_stiffness_range() { return {0.0, false, 1e12, true}; }  // N/m
constexpr Range contact_damping_range() { return {0.0, true, 1e9, true}; }      // N*s/m
constexpr Range drape_support_range() { return {0.0, false, 1e4, true}; }       // m

// Solvers.
constexpr Range max_speed_range() { return {0.0, false, 1e12, true}; }       // m/s
constexpr Range runaway_stretch_range() { return {0.0, false, 1e6, true}; }  // of the rest length
constexpr Range bullet_length_range() { return {1e-7, true, 1.0, true}; }  // m: margins, voxel size

// Whole numbers, each checked before it is converted to an int.
constexpr Range resolution_range() { return {1.0, true, 1e6, true}; }
constexpr Range rings_range() { return {1.0, true, 1000.0, true}; }
constexpr Range particle_index_range() {
  return {0.0, true, static_cast<double>(kMaxClothParticles - 1), true};
}
constexpr Range grid_coordinate_range() { return {0.0, true, 1e6 - 1.0, true}; }
// air: density (kg/m^3), drag and lift coefficients, wind (m/s per component), gusts.
constexpr Range air_density_range() { return {0.0, true, 1e4, true}; }
constexpr Range air_coefficient_range() { return {0.0, true, 100.0, true}; }
constexpr Range wind_range() { return {-1000.0, true, 1000.0, true}; }
constexpr Range gust_amplitude_range() { return {0.0, true, 1000.0, true}; }
constexpr Range gust_period_range() { return {1e-3, true, 1e6, true}; }
constexpr Range turbulence_length_range() { return {1e-3, true, 1e4, true}; }  // m
// constraints[].tolerance: the largest relative length error a hard or rope projection leaves.
constexpr Range constraint_tolerance_range() { return {1e-12, true, 0.1, true}; }
constexpr Range seed_range() { return {0.0, true, 9.2e18, true}; }

}  // namespace drapelab::scene
