// The loops of backward Euler's linear solve for a cloth whose springs come in families
// (spring_families.hpp): the matrix is never stored as a sparse matrix. A step keeps, per spring
// slot, its direction and two coefficients, and the conjugate gradient applies the matrix spring by
// spring, streaming unit-stride arrays as the spring fast path does. Like that path, this header
// and its source include no Eigen (the source is built for the host CPU).
//
// The matrix (kg), with h the step (s):
//   A = M - h D - h^2 K = diag(body_i) + sum over springs s of (e_a - e_b) B_s (e_a - e_b)^T,
//   B_s = a_s u u^T + b_s I,   a_s = h kd + h^2 ks (1 - tau),   b_s = h^2 ks tau,
//   tau = max(0, 1 - l0 / l),
// with u the spring's unit direction, l its length, l0 its rest length (spring_jacobian.hpp's
// spring_jacobian_for_solve, written per spring: -h dF/dv - h^2 dF/dx = B on the particle's own
// block, -B on its neighbour's). body_i = m_i (1 + h air) I + the pushing contacts' (h c + h^2 k) n
// n^T. Pinned particles are filtered out: their rows and columns act as zero in products, their
// right- hand side and solution are zero.
//
// Determinism: every per-particle value is computed by one expression whatever thread computes it,
// and each dot product is summed per fixed block of particles, then over blocks in block order, so
// the solution is bitwise identical for any thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "forces/spring_family_loops.hpp"
#include "integrators/coupling.hpp"

namespace drapelab::kernels {

struct FamilySystem {
  std::int64_t particles = 0;
  std::int64_t padding = 0;           // the largest family offset
  std::vector<std::int32_t> offsets;  // per family
  // Per family 5 rows (ux, uy, uz, a, b) of padding + particles slots, the first `padding` zero so
  // that particle i may read slot i - offset. a, b in kg; zero for an empty slot.
  std::vector<double> springs;
  // 6 rows (xx, yy, zz, xy, xz, yz) of particles: body_i (kg).
  std::vector<double> body;
  // 6 rows: the inverse of A's diagonal block (1/kg), zero for a pinned particle (the
  // preconditioner).
  std::vector<double> inverse;
  std::vector<double> free;         // per particle: 1 if it moves, 0 if pinned
  std::vector<Coupling> couplings;  // this step's contacts between particles
  // Scratch: per family 3 rows of padding + particles slot terms (zero padding first), the CG's
  // vectors (3 rows each of particles + padding, zero padding last) and per-block partial sums.
  std::vector<double> terms;
  std::vector<double> vectors;
  std::vector<double> partials;

  void resize(std::int64_t particle_count, const std::vector<SpringFamily>& families);
  double* spring_row(std::size_t family, int row) {
    return springs.data() + (5 * family + static_cast<std::size_t>(row)) * (padding + particles) +
           padding;
  }
  double* term_row(std::size_t family, int component) {
    return terms.data() +
           (3 * family + static_cast<std::size_t>(component)) * (padding + particles) + padding;
  }
  // CG vector `which` (0 ..), component c: particles + padding values.
  double* vector_row(int which, int component) {
    return vectors.data() + static_cast<std::size_t>(3 * which + component) * (particles + padding);
  }
  double* body_row(int entry) { return body.data() + static_cast<std::size_t>(entry) * particles; }
  double* inverse_row(int entry) {
    return inverse.data() + static_cast<std::size_t>(entry) * particles;
  }
};

// Every slot's direction and coefficients from the packed positions x (m), and
// spring_stiffness_velocity[3i + c] = sum over i's springs of the stiffness part of B times the
// relative velocity, ±(h^2 ks (1 - tau) u u^T + b I)(v_a - v_b) = -h^2 K v, the springs' share of
// -h^2 K v0 (N s). Also sets body to m_i (1 + h air) I (the identity for a pinned particle).
void assemble_family_system(const double* x, const double* v, const double* mass,
                            const double* free, const std::vector<SpringFamily>& families, double h,
                            double air, FamilySystem& system, double* spring_stiffness_velocity);

// The preconditioner: inverts every particle's diagonal block of A (call after the last change to
// body).
void invert_diagonal_blocks(FamilySystem& system);

// y = A p for packed 3 x particles vectors (kg m/s for p in m/s), pinned rows and columns filtered.
void apply_family_system(FamilySystem& system, const double* p, double* y);

struct FamilySolveResult {
  int iterations = 0;
  double relative_residual = 0.0;  // |b - A x| / |b| at exit
  bool converged = false;
};

// Preconditioned conjugate gradient on A x = b (packed 3 x particles; b in N s, x in m/s). x holds
// the initial guess on entry and the solution on exit. The same algorithm and stopping rule as
// Eigen's ConjugateGradient: stops when |r| < tolerance |b| or after max_iterations.
FamilySolveResult solve_family_system(FamilySystem& system, const double* b, double* x,
                                      double tolerance, int max_iterations);

}  // namespace drapelab::kernels
