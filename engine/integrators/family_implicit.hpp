// Backward Euler's step for a cloth whose springs form families (a grid): the same system as
// ImplicitEulerSystem (implicit_euler.hpp), (M - h D - h^2 K) dv = h (f0 + h K v0), solved by a
// conjugate gradient that applies the matrix spring by spring instead of storing it
// (family_cg_loops.hpp): a step streams about 5 numbers per spring instead of 36 and a 3N-row
// sparse matrix, the preconditioner inverts each particle's whole 3x3 diagonal block instead of its
// three diagonal entries, and every loop is vectorised and threaded with results independent of the
// thread count. The solution agrees with ImplicitEulerSystem's to the CG tolerance
// (tests/test_family_implicit.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/weighted_contact.hpp"
#include "forces/spring_families.hpp"
#include "integrators/family_cg_loops.hpp"

namespace drapelab {

class FamilyImplicitSystem {
 public:
  // `families` must outlive the system (the solver owns both).
  FamilyImplicitSystem(const ClothModel& model, const SpringFamilies& families,
                       ImplicitSolveSettings settings);

  // Computes dv (m/s, 3 x N) for a step of h (s), as ImplicitEulerSystem::solve.
  void solve(const ClothModel& model, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
             const Eigen::Matrix3Xd& force, double h, double air_damping,
             const ContactParameters& contact, const std::vector<ActiveContact>& contacts,
             const std::vector<WeightedContact>& couplings, Eigen::Matrix3Xd& dv);

  const ImplicitSolveStats& stats() const { return stats_; }
  // A p for the system of the last solve (kg times p's unit; pinned rows and columns act as zero),
  // and that solve's right-hand side h (f0 + h K v0) (N s, zero on pinned particles): for tests.
  Eigen::Matrix3Xd apply(const Eigen::Matrix3Xd& p);
  const Eigen::Matrix3Xd& right_hand_side() const { return rhs_; }

 private:
  const SpringFamilies& families_;
  ImplicitSolveSettings settings_;
  kernels::FamilySystem system_;
  Eigen::VectorXd free_;        // 1 for a particle that moves, 0 for a pinned one
  Eigen::Matrix3Xd spring_kv_;  // N s: -h^2 K v0 of the springs
  Eigen::Matrix3Xd rhs_;        // N s
  Eigen::Matrix3Xd solution_;   // m/s: dv, kept as the next step's initial guess
  ImplicitSolveStats stats_;
};

}  // namespace drapelab
