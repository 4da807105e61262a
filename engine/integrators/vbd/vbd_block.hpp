// One particle's Newton step in vbd's sweeps (vbd_loops.hpp): the running sums of its force and
// block, and the per-particle terms that live in their own sources. No Eigen (see vbd_loops.hpp).
#pragma once

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

// Particle i's offset self-contacts (vbd_contact_loops.cpp): the barrier, its damper and friction,
// the other particles read at the sweep's start.
void add_self_contacts(const VbdProblem& p, std::int64_t i, const double* xi, Block& b);

// Pulls particle i back inside its conservative bound; true when it was outside.
bool keep_within_bound(const OffsetContactArrays& contacts, std::int64_t i, double* xi);

}  // namespace drapelab::kernels
