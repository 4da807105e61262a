// The continuum cloth (cloth.model: continuum): a membrane of linear triangles and hinge bending on
// every interior edge, in place of the spring network for our solver. docs/physics.md, "The
// continuum model", gives the equations; in short, with E_t the energy of triangle t and E_e that
// of the hinge on interior edge e:
//
//   membrane (St. Venant-Kirchhoff, plane stress): F = [x1 - x0, x2 - x0] Dm^-1 (3 x 2),
//     G = (F^T F - I) / 2,  E_t = A_t (mu |G|^2 + lambda tr(G)^2 / 2),
//     mu = Y / (2 (1 + nu)),  lambda = Y nu / (1 - nu^2)   (Y: stretch modulus, N/m; nu: Poisson)
//   bending (discrete shells):  E_e = k_e (theta_e - rest_theta_e)^2,
//     k_e = B |e|^2 / (2 (A_1 + A_2))   (B: bending rigidity, N*m; A_1, A_2: the rest triangles)
//     k_e = B |e|^2 / (2 A_free) on a clamped edge, where the other triangle is pinned whole
//   damping (stiffness-proportional, Kelvin-Voigt): the membrane's stress is C : (G + alpha dG/dt)
//     and the hinge's moment 2 k (theta - rest_theta + alpha dtheta/dt), so f_damp = -alpha H_m v
//     with H_m the Hessian's material part (no geometric term): zero for every rigid motion.
//
// Every Hessian the solvers use is positive semidefinite by construction: the membrane's geometric
// term uses the second Piola-Kirchhoff stress S with its negative eigenvalues set to zero (a
// compressed direction stores no stiffness), and the hinge keeps its Gauss-Newton term
// 2 k grad(theta) grad(theta)^T (the curvature of theta itself is dropped).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace drapelab {

struct ClothModel;  // cloth_model.hpp
namespace kernels {
struct ContinuumFamilies;  // the force loop's dense families (engine/forces)
}

// The fabric's properties in physical units (scene keys cloth.continuum.*).
struct ContinuumParams {
  double stretch_modulus = 300.0;    // N/m: Young's modulus times thickness
  double poisson = 0.3;              // [0, 0.5)
  double bending_rigidity = 1.0e-5;  // N*m
  double damping = 0.01;             // s: alpha, the damping time of membrane and bending alike
};

// Plane-stress Lame parameters of the membrane (N/m).
struct MembraneLame {
  double mu = 0.0;
  double lambda = 0.0;
};
MembraneLame membrane_lame(const ContinuumParams& params);

// The elements as built, immutable. Indices into the cloth's particles.
struct ContinuumElements {
  ContinuumParams params;
  MembraneLame lame;
  // Triangles, in the order of ClothModel::triangles.
  std::vector<std::array<std::int32_t, 3>> triangle;
  // Per triangle the gradients of the deformation map F = sum_k x_k g_k^T: the three 2-vectors
  // g_0, g_1, g_2 (1/m; they sum to zero), 6 numbers per triangle.
  std::vector<double> shape_gradient;
  std::vector<double> rest_area;  // m^2 per triangle
  // Hinges: particles {a, b, c, d}, (a, b) the shared edge, c opposite it in the first triangle
  // (a, b, c) counter-clockwise, d in the second.
  std::vector<std::array<std::int32_t, 4>> hinge;
  // Per hinge its two triangles (the first has a, b, c) and the sign that turns the second's normal
  // (p1 - p0) x (p2 - p0) into (d - a) x (b - a): -1 where the two windings disagree.
  std::vector<std::array<std::int32_t, 2>> hinge_triangle;
  std::vector<double> hinge_second_sign;
  std::vector<double> hinge_stiffness;  // N*m: k_e above
  std::vector<double> rest_angle;       // rad: the rest shape's dihedral angle, signed
  // Per particle its triangles and hinges (compressed rows), with the particle's slot in each.
  std::vector<std::int32_t> triangle_offsets, triangle_of, triangle_slot;
  std::vector<std::int32_t> hinge_offsets, hinge_of, hinge_slot;

  // The same elements as unit-stride columns, which the vectorised force loop reads.
  struct Columns {
    std::array<std::vector<std::int32_t>, 3> triangle_corner;  // [k][t]
    std::array<std::vector<double>, 4> gradient;  // g_1x, g_1y, g_2x, g_2y per triangle (1/m)
    std::array<std::vector<std::int32_t>, 4> hinge_corner;    // [k][e]: a, b, c, d
    std::array<std::vector<std::int32_t>, 2> hinge_triangle;  // [k][e]
  } columns;

  // The elements as dense families when they form them (a grid): the force loop's fast path.
  std::shared_ptr<const kernels::ContinuumFamilies> families;

  std::size_t triangle_count() const { return triangle.size(); }
  std::size_t hinge_count() const { return hinge.size(); }
  // Scratch doubles the force kernel needs, zeroed before its first use.
  std::size_t force_scratch_size() const;
};

// Calls visit(a, b) for every ordered pair of corners (a == b included) of every element: per
// triangle its 3 x 3 pairs, then per hinge its 4 x 4, row-major. The implicit system's block
// pattern and vbd's colouring both follow it.
template <typename Visit>
void for_each_corner_pair(const ContinuumElements& elements, Visit visit) {
  for (const auto& corners : elements.triangle)
    for (std::int32_t a : corners)
      for (std::int32_t b : corners) visit(a, b);
  for (const auto& corners : elements.hinge)
    for (std::int32_t a : corners)
      for (std::int32_t b : corners) visit(a, b);
}

// Builds the elements of a cloth from its rest positions (m, 3 x N) and triangles. `held` marks the
// particles that never move (pins; empty: none): a hinge one of whose triangles is held whole is a
// clamped edge, whose bending happens on its free side alone, so its stiffness counts the free
// triangle's area only (docs/physics.md, "The continuum model"). Throws std::invalid_argument for
// out-of-range parameters or a degenerate rest triangle.
ContinuumElements build_continuum_elements(const Eigen::Matrix3Xd& rest,
                                           const Eigen::Matrix3Xi& triangles,
                                           const ContinuumParams& params,
                                           const std::vector<bool>& held = {});

// The particles of `model` that never move (its pins), for build_continuum_elements.
std::vector<bool> held_particles(const ClothModel& model);

// The elastic energy at positions x (J): membranes plus hinges.
double continuum_energy(const ContinuumElements& elements, const Eigen::Matrix3Xd& x);
double membrane_energy(const ContinuumElements& elements, const Eigen::Matrix3Xd& x);
double bending_energy(const ContinuumElements& elements, const Eigen::Matrix3Xd& x);

// Adds every element's force at (x, v) to `force` (N, 3 x N): -dE/dx - alpha H_m v. Summed per
// particle in a fixed order, so the bits do not depend on the thread count.
void add_continuum_forces(const ContinuumElements& elements, const Eigen::Matrix3Xd& x,
                          const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force);

// One element's force (-dE/dx, N, stacked per corner) and projected Hessian (N/m) at x, for the
// implicit solve and for tests; `exact_geometric` keeps the membrane's stress unclamped (its true
// Hessian, possibly indefinite).
struct TriangleTerms {
  Eigen::Matrix<double, 9, 1> force;
  Eigen::Matrix<double, 9, 9> hessian;
  // H_m: the Hessian without its geometric term, the matrix of the damping force -alpha H_m v
  Eigen::Matrix<double, 9, 9> damping_hessian;
};
TriangleTerms triangle_terms(const ContinuumElements& elements, std::size_t t,
                             const Eigen::Matrix3Xd& x, bool exact_geometric = false);
struct HingeTerms {
  Eigen::Matrix<double, 12, 1> force;
  Eigen::Matrix<double, 12, 12> hessian;  // Gauss-Newton: 2 k grad(theta) grad(theta)^T
  double angle = 0.0;                     // rad
};
HingeTerms hinge_terms(const ContinuumElements& elements, std::size_t e, const Eigen::Matrix3Xd& x);

// The signed dihedral angle (rad) of the hinge {a, b, c, d} at x: 0 when flat, positive when the
// triangles fold towards their normals' side.
double hinge_angle(const Eigen::Matrix3Xd& x, const std::array<std::int32_t, 4>& hinge);

}  // namespace drapelab
