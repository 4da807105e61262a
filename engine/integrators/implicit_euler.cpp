// Backward Euler's linear system: fixed block pattern, values rewritten each step, solved by CG.
#include "drapelab/implicit_euler.hpp"

#include <algorithm>

#include "drapelab/continuum.hpp"
#include "forces/spring_jacobian.hpp"
#include "integrators/coupled_matrix.hpp"
#include "integrators/weighted_couplings.hpp"

namespace drapelab {

struct CoupledConjugateGradient {
  std::vector<kernels::Coupling> couplings;
  Eigen::ConjugateGradient<CoupledMatrix, Eigen::Lower | Eigen::Upper, CoupledJacobiPreconditioner>
      cg;
};

namespace {

constexpr int kSlotsPerBlock = 9;
constexpr int kSlotsPerSpring = 4 * kSlotsPerBlock;

void add_block_triplets(std::vector<Eigen::Triplet<double>>& triplets, int row, int col) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * row + r, 3 * col + c, 0.0);
}

// Every corner pair of a continuum cloth's elements (for_each_corner_pair); nothing for springs.
template <typename Visit>
void for_each_element_pair(const ClothModel& model, Visit visit) {
  if (model.uses_continuum()) for_each_corner_pair(*model.continuum, visit);
}

// Adds a continuum element's terms: h^2 H + h alpha H_m into the matrix (H its projected Hessian,
// H_m the part the damping acts through: K = -H, D = -alpha H_m) on the rows of moving corners, and
// K v0 = -H v0.
template <int Corners, typename AddBlock>
void add_element(const std::array<std::int32_t, Corners>& corners,
                 const Eigen::Matrix<double, 3 * Corners, 3 * Corners>& hessian,
                 const Eigen::Matrix<double, 3 * Corners, 3 * Corners>& damping_hessian, double h,
                 double alpha, const Eigen::Matrix3Xd& v,
                 Eigen::Matrix3Xd& stiffness_times_velocity, AddBlock add_block) {
  for (int k = 0; k < Corners; ++k)
    for (int l = 0; l < Corners; ++l) {
      const Eigen::Matrix3d block = hessian.template block<3, 3>(3 * k, 3 * l);
      add_block(k, l,
                (h * h) * block + (h * alpha) * damping_hessian.template block<3, 3>(3 * k, 3 * l));
      stiffness_times_velocity.col(corners[k]) -= block * v.col(corners[l]);
    }
}

}  // namespace

void record_solve(ImplicitSolveStats& stats, int iterations, double relative_residual,
                  bool converged) {
  ++stats.solves;
  stats.iterations_total += iterations;
  stats.iterations_max = std::max(stats.iterations_max, iterations);
  stats.iterations_last = iterations;
  stats.residual_last = relative_residual;
  stats.residual_max = std::max(stats.residual_max, relative_residual);
  if (!converged) ++stats.unconverged;
}

ImplicitEulerSystem::ImplicitEulerSystem(const ClothModel& model, ImplicitSolveSettings settings)
    : settings_(settings) {
  const int n = model.particle_count();
  // A continuum cloth's elements replace its springs in the system (their Hessians couple every
  // pair of an element's corners); the springs then stay out of it.
  const SpringSet no_springs;
  const SpringSet& s = model.uses_continuum() ? no_springs : model.springs;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(n) * kSlotsPerBlock + s.size() * kSlotsPerSpring);
  for (int i = 0; i < n; ++i) add_block_triplets(triplets, i, i);
  for (std::size_t e = 0; e < s.size(); ++e) {
    add_block_triplets(triplets, s.v0[e], s.v1[e]);
    add_block_triplets(triplets, s.v1[e], s.v0[e]);
  }
  for_each_element_pair(model, [&](int a, int b) { add_block_triplets(triplets, a, b); });
  matrix_.resize(3 * n, 3 * n);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();

  // Where each block's entries live in the compressed value array (coeffRef finds, never inserts).
  const double* values = matrix_.valuePtr();
  auto block_slots = [&](int row, int col) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        slots_.push_back(
            static_cast<std::int32_t>(&matrix_.coeffRef(3 * row + r, 3 * col + c) - values));
  };
  slots_.reserve(static_cast<std::size_t>(n) * kSlotsPerBlock + s.size() * kSlotsPerSpring);
  for (int i = 0; i < n; ++i) block_slots(i, i);
  for (std::size_t e = 0; e < s.size(); ++e) {
    block_slots(s.v0[e], s.v0[e]);
    block_slots(s.v1[e], s.v1[e]);
    block_slots(s.v0[e], s.v1[e]);
    block_slots(s.v1[e], s.v0[e]);
  }
  element_base_ = slots_.size();
  for_each_element_pair(model, [&](int a, int b) { block_slots(a, b); });
  free_.resize(n);
  for (int i = 0; i < n; ++i) free_[i] = model.is_pinned(i) ? 0.0 : 1.0;
  rhs_ = Eigen::VectorXd::Zero(3 * n);
  solution_ = Eigen::VectorXd::Zero(3 * n);
  stiffness_times_velocity_ = Eigen::Matrix3Xd::Zero(3, n);
  cg_ = std::make_unique<CoupledConjugateGradient>();
  cg_->cg.setTolerance(settings_.tolerance);
  cg_->cg.setMaxIterations(settings_.max_iterations);
}

ImplicitEulerSystem::~ImplicitEulerSystem() = default;

void ImplicitEulerSystem::add_block(std::size_t first, const Eigen::Matrix3d& block) {
  double* values = matrix_.valuePtr();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) values[slots_[first + 3 * r + c]] += block(r, c);
}

void ImplicitEulerSystem::add_continuum_terms(const ClothModel& model, const Eigen::Matrix3Xd& x,
                                              const Eigen::Matrix3Xd& v, double h) {
  const ContinuumElements& c = *model.continuum;
  const double alpha = c.params.damping;
  std::size_t first = element_base_;
  const auto moving = [&](int i) { return free_[static_cast<std::size_t>(i)] != 0.0; };
  // A block lands only on a moving corner's row, and off the diagonal only between moving corners
  // (a pinned particle's row and column stay the identity's).
  const auto block_adder = [&](const auto& corners) {
    return [&, corners](int k, int l, const Eigen::Matrix3d& block) {
      if (moving(corners[k]) && moving(corners[l]))
        add_block(first + static_cast<std::size_t>(kSlotsPerBlock) * (corners.size() * k + l),
                  block);
    };
  };
  for (std::size_t t = 0; t < c.triangle_count(); ++t, first += 9 * kSlotsPerBlock) {
    const TriangleTerms terms = triangle_terms(c, t, x);
    add_element<3>(c.triangle[t], terms.hessian, terms.damping_hessian, h, alpha, v,
                   stiffness_times_velocity_, block_adder(c.triangle[t]));
  }
  for (std::size_t e = 0; e < c.hinge_count(); ++e, first += 16 * kSlotsPerBlock) {
    // The hinge's Gauss-Newton Hessian has no geometric term: its damping acts through all of it.
    const HingeTerms terms = hinge_terms(c, e, x);
    add_element<4>(c.hinge[e], terms.hessian, terms.hessian, h, alpha, v, stiffness_times_velocity_,
                   block_adder(c.hinge[e]));
  }
}

void ImplicitEulerSystem::solve(const ClothModel& model, const Eigen::Matrix3Xd& x,
                                const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& force, double h,
                                double air_damping, const ContactParameters& contact,
                                const std::vector<ActiveContact>& contacts,
                                const std::vector<WeightedContact>& couplings,
                                Eigen::Matrix3Xd& dv) {
  const int n = model.particle_count();
  const auto moving = [&](int i) { return free_[static_cast<std::size_t>(i)] != 0.0; };
  std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
  stiffness_times_velocity_.setZero();

  // Diagonal: M + h a M (air damping), or the identity for a pinned particle.
  for (int i = 0; i < n; ++i) {
    const double diagonal = moving(i) ? model.mass[i] * (1.0 + h * air_damping) : 1.0;
    add_block(static_cast<std::size_t>(kSlotsPerBlock) * i, diagonal * Eigen::Matrix3d::Identity());
  }
  // Springs: A gets -(h D + h^2 K) on the two diagonal blocks and its negative off the diagonal.
  // (A continuum cloth's springs are for the Bullet cloths; its elements take their place.)
  const SpringSet no_springs;
  const SpringSet& s = model.uses_continuum() ? no_springs : model.springs;
  const std::size_t spring_base = static_cast<std::size_t>(kSlotsPerBlock) * n;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const int a = s.v0[e], b = s.v1[e];
    const SpringJacobian j =
        spring_jacobian_for_solve(x.col(a), x.col(b), s.ks[e], s.kd[e], s.rest_length[e]);
    const Eigen::Matrix3d block = -(h * j.dforce_dv + h * h * j.dforce_dx);
    const std::size_t first = spring_base + kSlotsPerSpring * e;
    if (moving(a)) add_block(first, block);
    if (moving(b)) add_block(first + kSlotsPerBlock, block);
    if (moving(a) && moving(b)) {
      add_block(first + 2 * kSlotsPerBlock, -block);
      add_block(first + 3 * kSlotsPerBlock, -block);
    }
    const Eigen::Vector3d kv = j.dforce_dx * (v.col(a) - v.col(b));  // K v0 of this spring, N/s
    stiffness_times_velocity_.col(a) += kv;
    stiffness_times_velocity_.col(b) -= kv;
  }
  if (model.uses_continuum()) add_continuum_terms(model, x, v, h);
  // Pushing contacts: a spring k and damper c along the normal, tied to the (moving) collider.
  for (const ActiveContact& touch : contacts) {
    const Eigen::Matrix3d along = touch.normal * touch.normal.transpose();
    add_block(static_cast<std::size_t>(kSlotsPerBlock) * touch.particle,
              (h * contact.damping + h * h * contact.stiffness) * along);
    stiffness_times_velocity_.col(touch.particle) -=
        contact.stiffness * along * v.col(touch.particle);
  }

  // Contacts between particles: their diagonal blocks into the matrix, their K v0 into the
  // right-hand side, their off-diagonal blocks into the operator's products.
  build_couplings(couplings, v, h, moving, cg_->couplings,
                  [&](int i, const Eigen::Matrix3d& block, const Eigen::Vector3d& kv) {
                    add_block(static_cast<std::size_t>(kSlotsPerBlock) * i, block);
                    stiffness_times_velocity_.col(i) += kv / (h * h);
                  });

  for (int i = 0; i < n; ++i)
    rhs_.segment<3>(3 * i) =
        moving(i) ? Eigen::Vector3d(h * (force.col(i) + h * stiffness_times_velocity_.col(i)))
                  : Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i)
    if (!moving(i)) solution_.segment<3>(3 * i).setZero();

  const CoupledMatrix system(matrix_, cg_->couplings, free_);
  cg_->cg.compute(system);
  solution_ = cg_->cg.solveWithGuess(rhs_, solution_);
  record_solve(stats_, static_cast<int>(cg_->cg.iterations()), cg_->cg.error(),
               cg_->cg.info() == Eigen::Success);
  dv = Eigen::Map<const Eigen::Matrix3Xd>(solution_.data(), 3, n);
}

}  // namespace drapelab
