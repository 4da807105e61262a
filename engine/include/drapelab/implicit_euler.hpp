// Backward Euler for the cloth, linearised once per step (Baraff & Witkin 1998):
//
//   (M - h D - h^2 K) dv = h (f0 + h K v0),   v1 = v0 + dv,   x1 = x0 + h v1
//
// f0 = f(x0, v0) is the total force at the start of the step (N), K = df/dx (N/m) and D = df/dv
// (N*s/m) are the Jacobians of the springs (spring_jacobian_for_solve) or of the continuum elements
// (K = -H, D = -alpha H with H their projected Hessian, drapelab/continuum.hpp), air damping (D =
// -a m I) and the pushing penalty contacts (K = -k n n^T, D = -c n n^T). Friction stays explicit
// (it is already bounded by mu fn). The matrix is symmetric positive definite and is solved by
// Eigen's conjugate gradient with a Jacobi preconditioner, warm-started from the previous step's
// dv. Pinned particles are filtered out of the system (their rows and columns become the identity
// and dv = 0), which is the exact elimination of a known zero velocity change.
//
// The sparsity pattern (3x3 blocks on the diagonal and for every spring) is built once; each step
// only rewrites the values. This assembled form serves every cloth; a cloth whose springs form
// families (a grid) solves the same system matrix-free instead (family_implicit.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/weighted_contact.hpp"

namespace drapelab {

struct ImplicitSolveSettings {
  double tolerance = 1e-6;   // relative residual |A dv - b| / |b| at which CG stops
  int max_iterations = 500;  // CG iteration cap per step
};

struct ImplicitSolveStats {
  std::int64_t solves = 0;
  std::int64_t iterations_total = 0;
  int iterations_max = 0;  // most iterations any step needed
  int iterations_last = 0;
  double residual_last = 0.0;    // relative residual reached at the last step
  double residual_max = 0.0;     // worst relative residual over all steps
  std::int64_t unconverged = 0;  // steps that hit max_iterations above the tolerance
};

// Adds one solve's outcome to the statistics.
void record_solve(ImplicitSolveStats& stats, int iterations, double relative_residual,
                  bool converged);

// The conjugate gradient on the matrix with the couplings of contacts between particles
// (integrators/coupled_matrix.hpp).
struct CoupledConjugateGradient;

class ImplicitEulerSystem {
 public:
  ImplicitEulerSystem(const ClothModel& model, ImplicitSolveSettings settings);
  ~ImplicitEulerSystem();

  // Computes dv (m/s, 3 x N) for a step of h (s) from (x, v) whose total force is `force` (N).
  // `air_damping` in 1/s; `contacts` the pushing contacts of that force evaluation, `couplings`
  // its pushing contacts between particles (weighted_contact.hpp).
  void solve(const ClothModel& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
             const Eigen::Matrix3Xd& force, double h, double air_damping,
             const ContactParameters& contact, const std::vector<ActiveContact>& contacts,
             const std::vector<WeightedContact>& couplings, Eigen::Matrix3Xd& dv);

  const ImplicitSolveStats& stats() const { return stats_; }
  const ImplicitSolveSettings& settings() const { return settings_; }
  // The system matrix of the last solve (kg), for tests.
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }
  const Eigen::VectorXd& right_hand_side() const { return rhs_; }

 private:
  // Adds `block` into the 3x3 block whose 9 value slots start at slots_[first].
  void add_block(std::size_t first, const Eigen::Matrix3d& block);
  // cloth.model: continuum: every element's projected Hessian and damping into the matrix, and its
  // K v0 into stiffness_times_velocity_.
  void add_continuum_terms(const ClothModel& model, const Eigen::Matrix3Xd& x,
                           const Eigen::Matrix3Xd& v, double h);

  ImplicitSolveSettings settings_;
  Eigen::SparseMatrix<double> matrix_;  // 3N x 3N, both triangles stored
  // Value indices of each 3x3 block, row-major within the block: per particle its diagonal block
  // (9 slots at 9 i), then per spring e the blocks (a,a), (b,b), (a,b), (b,a) (36 slots).
  std::vector<std::int32_t> slots_;
  std::size_t element_base_ = 0;  // continuum: the first element's first slot in slots_
  std::vector<double> free_;      // 1 for a particle that moves, 0 for a pinned one
  Eigen::VectorXd rhs_;           // N*s: h (f0 + h K v0), zero on pinned rows
  Eigen::VectorXd solution_;      // m/s: dv, kept as the next step's initial guess
  Eigen::Matrix3Xd stiffness_times_velocity_;  // K v0 (N/s)
  std::unique_ptr<CoupledConjugateGradient> cg_;
  ImplicitSolveStats stats_;
};

}  // namespace drapelab
