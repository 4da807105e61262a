// One particle's Newton step in vbd's sweeps (vbd_loops.hpp): the running sums of its force and
// block, and the per-particle terms that live in their own sources. No Eigen (see vbd_loops.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "integrators/vbd/vbd_loops.hpp"

namespace drapelab::kernels {

// The running sums of one particle's Newton step: f (N) and the symmetric H (N/m), stored as its
// six entries xx, yy, zz, xy, xz, yz.
struct Block {
  double f[3] = {0.0, 0.0, 0.0};
  double h[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

  // H += a I
  void add_identity(double a) {
    h[0] += a;
    h[1] += a;
    h[2] += a;
  }
  // H += a u u^T
  void add_outer(double a, const double* u) {
    h[0] += a * u[0] * u[0];
    h[1] += a * u[1] * u[1];
    h[2] += a * u[2] * u[2];
    h[3] += a * u[0] * u[1];
    h[4] += a * u[0] * u[2];
    h[5] += a * u[1] * u[2];
  }
  void add_force(double a, const double* u) {
    f[0] += a * u[0];
    f[1] += a * u[1];
    f[2] += a * u[2];
  }
  // The move H^-1 f by Cramer's rule (H is 3 x 3 symmetric positive definite); no move when H is
  // singular to rounding.
  bool solve(double* move) const {
    const double c00 = h[1] * h[2] - h[5] * h[5];
    const double c01 = h[4] * h[5] - h[3] * h[2];
    const double c02 = h[3] * h[5] - h[4] * h[1];
    const double det = h[0] * c00 + h[3] * c01 + h[4] * c02;
    if (!(det > 1e-300)) return false;
    const double c11 = h[0] * h[2] - h[4] * h[4];
    const double c12 = h[3] * h[4] - h[0] * h[5];
    const double c22 = h[0] * h[1] - h[3] * h[3];
    const double inv = 1.0 / det;
    move[0] = (c00 * f[0] + c01 * f[1] + c02 * f[2]) * inv;
    move[1] = (c01 * f[0] + c11 * f[1] + c12 * f[2]) * inv;
    move[2] = (c02 * f[0] + c12 * f[1] + c22 * f[2]) * inv;
    return true;
  }
};

inline double dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// One damped spring seen from its end i: E = ks (l - l0)^2 / 2 and the damper's dissipation
// kd ((dx_i - dx_j) . u)^2 / (2 h) with dx the displacement over the step and u the unit spring
// from j to i. Adds the force on i to f and, when `hessian`, the block d2/dx_i2, which is also
// minus the block d2/dx_i dx_j. False when the ends coincide (no direction: nothing is added).
[[gnu::always_inline]] inline bool add_spring(const double* xi, const double* si, const double* xj,
                                              const double* sj, double rest_length, double ks,
                                              double kd, double h, bool hessian, Block& b) {
  double u[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
  const double length = std::sqrt(dot(u, u));
  if (!(length > 0.0)) return false;
  const double inv_length = 1.0 / length;
  u[0] *= inv_length;
  u[1] *= inv_length;
  u[2] *= inv_length;
  const double rel[3] = {(xi[0] - si[0]) - (xj[0] - sj[0]), (xi[1] - si[1]) - (xj[1] - sj[1]),
                         (xi[2] - si[2]) - (xj[2] - sj[2])};
  const double stretch_velocity = dot(rel, u) / h;  // m/s, > 0 lengthening
  b.add_force(-(ks * (length - rest_length) + kd * stretch_velocity), u);
  if (!hessian) return true;
  // ks u u^T along the spring; across it ks (1 - l0 / l), kept only while the spring is longer
  // than at rest (compressed, that term is negative and a Newton step could go uphill).
  const double across = ks * std::max(0.0, 1.0 - rest_length * inv_length);
  b.add_identity(across);
  b.add_outer(ks - across + kd / h, u);
  return true;
}

// Coulomb friction on a contact point that slipped `rel` (m, over the step, relative to the other
// side) under the normal load fn (N, lagged) along the unit n, seen from a particle that
// moves the point by w times its own move: the point's force is scaled by w, its block by w^2.
inline void add_friction(double fn, const double* n, const double* rel, double kinetic,
                         double fixed, double slip_scale, double w, Block& b) {
  const double along = dot(rel, n);
  const double slip[3] = {rel[0] - along * n[0], rel[1] - along * n[1], rel[2] - along * n[2]};
  const double slip_length = std::sqrt(dot(slip, slip));  // m over the step
  if (slip_length < slip_scale) {
    // Sticking: a tangential spring of mu_s fn / slip_scale, at most mu_s fn at the boundary.
    const double k_stick = fixed * fn / slip_scale;
    b.add_force(-w * k_stick, slip);
    b.add_identity(w * w * k_stick);
    b.add_outer(-w * w * k_stick, n);
  } else {
    // Sliding: mu_k fn against the slip, whose energy mu_k fn |s| has no curvature along the
    // slip. The block takes mu_k fn / |s| over the whole tangent plane T instead, the curvature of
    // the quadratic that touches mu_k fn |s| at this slip and lies above it everywhere
    // (|s| <= |s0| / 2 + |s|^2 / (2 |s0|)): the step then goes at most to where the slip stops,
    // never past it. With the exact Hessian a particle sliding across a collider edge overshot
    // the turn of its slip, and friction flipped it back and forth by a centimetre a sweep.
    const double k_slide = kinetic * fn / slip_length;
    b.add_force(-w * k_slide, slip);
    b.add_identity(w * w * k_slide);
    b.add_outer(-w * w * k_slide, n);
  }
}

// What a block takes of the cloth's own forces: the springs and a continuum cloth's elements with
// their Hessians (the sweeps), or no springs and the elements' forces alone (the coarse step,
// which models the stiffness with the springs itself).
enum class SpringTerms { all, none };

// Particle i's force f = -dG/dx_i and block H = d2G/dx_i2 at x (vbd_loops.cpp), with the springs'
// terms as `terms` says.
void particle_block(const VbdProblem& p, std::int64_t i, const double* x, SpringTerms terms,
                    Block& b);

// Particle i's offset self-contacts (vbd_contact_loops.cpp): the barrier, its damper and friction,
// the other particles read from x as contact_partner (vbd_loops.hpp) says.
void add_self_contacts(const VbdProblem& p, std::int64_t i, const double* xi, const double* x,
                       Block& b);

// Particle i's collider feature contacts (vbd_contact_loops.cpp): the penalty spring-damper of the
// collider planes along each contact's current direction, and friction, weighted by the
// particle's share of the cloth point.
void add_feature_contacts(const VbdProblem& p, std::int64_t i, const double* xi, const double* x,
                          Block& b);

// Pulls particle i back inside its conservative bound; true when it was outside.
bool keep_within_bound(const OffsetContactArrays& contacts, std::int64_t i, double* xi);

}  // namespace drapelab::kernels
