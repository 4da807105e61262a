// Backward Euler on spring families: assembly of the per-spring coefficients, the contacts and the
// right-hand side, then the matrix-free conjugate gradient (family_implicit.hpp).
#include "integrators/family_implicit.hpp"

#include "integrators/weighted_couplings.hpp"

namespace drapelab {

FamilyImplicitSystem::FamilyImplicitSystem(const ClothModel& model, const SpringFamilies& families,
                                           ImplicitSolveSettings settings)
    : families_(families), settings_(settings) {
  const int n = model.particle_count();
  system_.resize(n, families.families());
  free_.resize(n);
  for (int i = 0; i < n; ++i) free_[i] = model.is_pinned(i) ? 0.0 : 1.0;
  spring_kv_ = Eigen::Matrix3Xd::Zero(3, n);
  rhs_ = Eigen::Matrix3Xd::Zero(3, n);
  solution_ = Eigen::Matrix3Xd::Zero(3, n);
}

void FamilyImplicitSystem::solve(const ClothModel& model, const Eigen::Matrix3Xd& x,
                                 const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& force, double h,
                                 double air_damping, const ContactParameters& contact,
                                 const std::vector<ActiveContact>& contacts,
                                 const std::vector<WeightedContact>& couplings,
                                 Eigen::Matrix3Xd& dv) {
  kernels::assemble_family_system(x.data(), v.data(), model.mass.data(), free_.data(),
                                  families_.families(), h, air_damping, system_, spring_kv_.data());
  // rhs = h f0 + h^2 K v0: the springs' share came from the assembly, each pushing contact adds
  // -h^2 k n (n . v0), as its spring k and damper c along n add (h c + h^2 k) n n^T to the
  // diagonal.
  rhs_.noalias() = h * force - spring_kv_;
  const double contact_block = h * contact.damping + h * h * contact.stiffness;  // kg
  for (const ActiveContact& touch : contacts) {
    const int i = touch.particle;
    if (free_[i] == 0.0) continue;
    const Eigen::Vector3d& n = touch.normal;
    rhs_.col(i) -= h * h * contact.stiffness * n.dot(v.col(i)) * n;
    const double entries[6] = {n.x() * n.x(), n.y() * n.y(), n.z() * n.z(),
                               n.x() * n.y(), n.x() * n.z(), n.y() * n.z()};
    for (int e = 0; e < 6; ++e) system_.body_row(e)[i] += contact_block * entries[e];
  }
  // Contacts between particles (self-collision, collider edges on cloth edges).
  build_couplings(
      couplings, v, h, [&](int i) { return free_[i] != 0.0; }, system_.couplings,
      [&](int i, const Eigen::Matrix3d& block, const Eigen::Vector3d& rhs) {
        rhs_.col(i) += rhs;
        const double entries[6] = {block(0, 0), block(1, 1), block(2, 2),
                                   block(0, 1), block(0, 2), block(1, 2)};
        for (int e = 0; e < 6; ++e) system_.body_row(e)[i] += entries[e];
      });
  for (int i = 0; i < model.particle_count(); ++i)
    if (free_[i] == 0.0) {
      rhs_.col(i).setZero();
      solution_.col(i).setZero();
    }
  kernels::invert_diagonal_blocks(system_);
  const kernels::FamilySolveResult result = kernels::solve_family_system(
      system_, rhs_.data(), solution_.data(), settings_.tolerance, settings_.max_iterations);
  record_solve(stats_, result.iterations, result.relative_residual, result.converged);
  dv = solution_;
}

Eigen::Matrix3Xd FamilyImplicitSystem::apply(const Eigen::Matrix3Xd& p) {
  Eigen::Matrix3Xd y(3, p.cols());
  kernels::apply_family_system(system_, p.data(), y.data());
  return y;
}

}  // namespace drapelab
