// The continuum model's element kernels (drapelab/continuum.hpp) on plain arrays. Like the other
// *_loops files this header and its source include no Eigen: the source is built with OpenMP for
// the build machine's CPU. Positions and velocities are 3 x n packed as in ClothState. Forces are
// first computed per element, then summed per particle over its elements in a fixed order, so the
// result does not depend on the number of threads.
#pragma once

#include <cstdint>

namespace drapelab::kernels {

struct ContinuumArrays {
  std::int64_t particles = 0;
  double mu = 0.0;      // N/m, membrane Lame parameters (plane stress)
  double lambda = 0.0;  // N/m
  double alpha = 0.0;   // s, Rayleigh damping
  std::int64_t triangles = 0;
  const std::int32_t* triangle = nullptr;  // 3 per triangle
  const double* shape_gradient = nullptr;  // 6 per triangle: g_0, g_1, g_2 (1/m)
  const double* rest_area = nullptr;       // m^2 per triangle
  std::int64_t hinges = 0;
  const std::int32_t* hinge = nullptr;      // 4 per hinge: a, b (edge), c, d (opposite)
  const double* hinge_stiffness = nullptr;  // N*m per hinge
  const double* rest_angle = nullptr;       // rad per hinge
  // Per particle its triangles and hinges (compressed rows) and its corner slot in each.
  const std::int32_t* triangle_offsets = nullptr;
  const std::int32_t* triangle_of = nullptr;
  const std::int32_t* triangle_slot = nullptr;
  const std::int32_t* hinge_offsets = nullptr;
  const std::int32_t* hinge_of = nullptr;
  const std::int32_t* hinge_slot = nullptr;
};

// One membrane triangle at x: its energy (J), and when non-null its force -dE/dx (9: corner by
// corner) and Hessian (81, row-major, corner blocks). `exact`: the true Hessian; otherwise the
// stress in the geometric term is clamped to positive semidefinite.
double membrane_element(const ContinuumArrays& c, std::int64_t t, const double* x, bool exact,
                        double* force, double* hessian);
// One hinge at x: its energy (J), its dihedral angle (rad) into *angle when non-null, and when
// non-null its force (12) and Gauss-Newton Hessian 2 k grad(theta) grad(theta)^T (144, row-major).
double hinge_element(const ContinuumArrays& c, std::int64_t e, const double* x, double* angle,
                     double* force, double* hessian);

// The whole elastic energy at x (J).
double continuum_energy_sum(const ContinuumArrays& c, const double* x, double* membrane,
                            double* bending);

// Adds every element's force at (x, v) into `force` (3 x particles): elastic plus the Rayleigh
// damping -alpha H v. `element_force` is scratch of 9 per triangle plus 12 per hinge.
void add_continuum_forces(const ContinuumArrays& c, const double* x, const double* v,
                          double* element_force, double* force);

// Vertex block descent's per-particle terms: the force on particle i (N, added to f) and the block
// d2/dx_i2 (N/m, the 6 entries xx, yy, zz, xy, xz, yz added to block) of the elastic energy plus
// the Rayleigh dissipation alpha / (2 h) dx^T H dx, dx = x - start, at positions x.
void continuum_particle_terms(const ContinuumArrays& c, std::int64_t i, const double* x,
                              const double* start, double h, double* f, double* block);

}  // namespace drapelab::kernels
