// The continuum model's element kernels (drapelab/continuum.hpp) on plain arrays: one element at a
// time in continuum_elements.cpp, the vectorised force loop in continuum_force_loops.cpp. Like the
// other *_loops files this header and its sources include no Eigen: the sources are built with
// OpenMP for the build machine's CPU. Positions and velocities are 3 x n packed as in ClothState.
// Forces are first computed per element, then summed per particle over its elements in a fixed
// order, so the result does not depend on the number of threads.
#pragma once

#include <cstdint>

namespace drapelab::kernels {

struct ContinuumFamilies;  // continuum_families.hpp

struct ContinuumArrays {
  std::int64_t particles = 0;
  double mu = 0.0;      // N/m, membrane Lame parameters (plane stress)
  double lambda = 0.0;  // N/m
  double alpha = 0.0;   // s, stiffness-proportional (Kelvin-Voigt) damping time
  std::int64_t triangles = 0;
  const std::int32_t* triangle = nullptr;  // 3 per triangle
  const double* shape_gradient = nullptr;  // 6 per triangle: g_0, g_1, g_2 (1/m)
  const double* rest_area = nullptr;       // m^2 per triangle
  std::int64_t hinges = 0;
  const std::int32_t* hinge = nullptr;  // 4 per hinge: a, b (edge), c, d (opposite)
  const std::int32_t* hinge_triangle =
      nullptr;                                // 2 per hinge: the triangles of (a, b, c), (b, a, d)
  const double* hinge_second_sign = nullptr;  // +-1 per hinge: orients the second's normal
  const double* hinge_stiffness = nullptr;    // N*m per hinge
  const double* rest_angle = nullptr;         // rad per hinge
  // The same as unit-stride columns (ContinuumElements::Columns) for the vectorised force loop.
  const std::int32_t* triangle_corner[3] = {nullptr, nullptr, nullptr};
  const double* gradient[4] = {nullptr, nullptr, nullptr, nullptr};  // g_1x, g_1y, g_2x, g_2y
  const std::int32_t* hinge_corner[4] = {nullptr, nullptr, nullptr, nullptr};
  const std::int32_t* hinge_wing[2] = {nullptr, nullptr};
  // The same elements as dense families when they form them (a grid), else null.
  const ContinuumFamilies* families = nullptr;
  // Per particle its triangles and hinges (compressed rows) and its corner slot in each.
  const std::int32_t* triangle_offsets = nullptr;
  const std::int32_t* triangle_of = nullptr;
  const std::int32_t* triangle_slot = nullptr;
  const std::int32_t* hinge_offsets = nullptr;
  const std::int32_t* hinge_of = nullptr;
  const std::int32_t* hinge_slot = nullptr;
};

// One membrane triangle at x: its energy (J), and when non-null its force -dE/dx (9: corner by
// corner), Hessian (81, row-major, corner blocks) and the Hessian's material part H_m (81: without
// the geometric term, the damping's matrix). `exact`: the true Hessian; otherwise the stress in the
// geometric term is clamped to positive semidefinite.
double membrane_element(const ContinuumArrays& c, std::int64_t t, const double* x, bool exact,
                        double* force, double* hessian, double* material_hessian);
// One hinge at x: its energy (J), its dihedral angle (rad) into *angle when non-null, and when
// non-null its force (12) and Gauss-Newton Hessian 2 k grad(theta) grad(theta)^T (144, row-major).
double hinge_element(const ContinuumArrays& c, std::int64_t e, const double* x, double* angle,
                     double* force, double* hessian);

// The power the Kelvin-Voigt damping takes at (x, v) (W): A alpha (2 mu |dG/dt|^2 + lambda
// tr(dG/dt)^2) per triangle and 2 k alpha (d theta / dt)^2 per hinge. One plain pass over the
// elements, in element order.
double continuum_damping_power(const ContinuumArrays& c, const double* x, const double* v);

// The whole elastic energy at x (J).
double continuum_energy_sum(const ContinuumArrays& c, const double* x, double* membrane,
                            double* bending);

// Adds every element's force at (x, v) into `force` (3 x particles): elastic plus the damping
// -alpha H_m v (H_m: the Hessian without the membrane's geometric term). `element_force` is
// scratch of ContinuumElements::force_scratch_size() doubles.
void add_continuum_forces(const ContinuumArrays& c, const double* x, const double* v,
                          double* element_force, double* force);

// Vertex block descent's per-particle terms: the force on particle i (N, added to f) and the block
// d2/dx_i2 (N/m, the 6 entries xx, yy, zz, xy, xz, yz added to block) of the elastic energy plus
// the dissipation alpha / (2 h) dx^T H_m dx, dx = x - start, at positions x.
void continuum_particle_terms(const ContinuumArrays& c, std::int64_t i, const double* x,
                              const double* start, double h, double* f, double* block);

}  // namespace drapelab::kernels
