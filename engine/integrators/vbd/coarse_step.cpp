// Vertex block descent's coarse step (vertex_block_descent.hpp): the aggregates' sparse system,
// its pattern built once from the springs that join them, its factorisation and its solve, which
// moves each aggregate as a rigid patch (a translation, and for a small cloth a turn) between the
// sweeps.
#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "integrators/vbd/vertex_block_descent.hpp"

namespace drapelab {
namespace {

// Particles per aggregate of the coarse step: a 4 x 4 patch of a grid. Smaller aggregates make a
// larger coarse system; larger ones move more of the cloth rigidly.
constexpr int kAggregateSize = 16;
// At most about this many aggregates: their sparse Cholesky factorisation grows faster than the
// cloth, so a larger cloth gets larger aggregates.
constexpr int kMostAggregates = 256;
// The coarse steps after a step's first solve with its factorisation as a preconditioner, to this
// relative residual, in at most this many iterations; past them, they factorise afresh.
constexpr double kCoarseTolerance = 1e-3;
constexpr int kMostCoarseIterations = 8;

}  // namespace

void VertexBlockDescent::build_coarse_system(const ClothModel& model) {
  const int aggregate_size =
      std::max(kAggregateSize, (model.particle_count() + kMostAggregates - 1) / kMostAggregates);
  const std::vector<std::int32_t> aggregate = aggregate_particles(model, aggregate_size);
  const std::int32_t count =
      aggregate.empty() ? 0 : *std::max_element(aggregate.begin(), aggregate.end()) + 1;
  // Aggregates of kAggregateSize particles turn as well as translate (6 unknowns each): the patches
  // of a cloth of at most kMostAggregates x kAggregateSize particles. The turns let the coarse step
  // carry the bending of a skirt, which translations alone cannot: without them a 24-ring Cusick
  // specimen crept for seconds. A rigid turn is a fair model of a 4 x 4 patch, not of a larger one:
  // on the sphere drape at 0.4 s, turning patches of 17 particles (65 x 65) stretched the sheet to
  // 4.3 % against 3.8 % translating, patches of 33 to 7 %, and patches of 65 (129 x 129) to 19 %
  // against 3.7 %. So a larger cloth's patches only translate.
  coarse_dofs_ = aggregate_size == kAggregateSize ? kRigidUnknowns : 3;
  stats_.coarse_unknowns = coarse_dofs_;
  // Members by aggregate, in particle order.
  aggregate_offsets_.assign(static_cast<std::size_t>(count) + 1, 0);
  for (std::int32_t a : aggregate)
    if (a >= 0) ++aggregate_offsets_[static_cast<std::size_t>(a) + 1];
  for (std::int32_t a = 0; a < count; ++a) aggregate_offsets_[a + 1] += aggregate_offsets_[a];
  aggregate_members_.resize(static_cast<std::size_t>(aggregate_offsets_.back()));
  std::vector<std::int32_t> fill(aggregate_offsets_.begin(), aggregate_offsets_.end() - 1);
  for (std::size_t i = 0; i < aggregate.size(); ++i)
    if (aggregate[i] >= 0)
      aggregate_members_[static_cast<std::size_t>(fill[static_cast<std::size_t>(aggregate[i])]++)] =
          static_cast<std::int32_t>(i);
  aggregate_of_ = aggregate;
  // The springs that join two aggregates, grouped by pair (pairs in order of their first spring),
  // each oriented from the pair's first aggregate.
  const SpringSet& springs = model.springs;
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> pair_index;
  std::vector<std::vector<std::size_t>> pair_springs;
  for (std::size_t e = 0; e < springs.size(); ++e) {
    const std::int32_t a = aggregate[static_cast<std::size_t>(springs.v0[e])];
    const std::int32_t b = aggregate[static_cast<std::size_t>(springs.v1[e])];
    if (a < 0 || b < 0 || a == b) continue;
    const auto key = std::minmax(a, b);
    const auto [at, added] =
        pair_index.emplace(key, static_cast<std::int32_t>(pair_springs.size()));
    if (added) {
      pair_springs.emplace_back();
      pair_aggregates_.push_back(key.first);
      pair_aggregates_.push_back(key.second);
    }
    pair_springs[static_cast<std::size_t>(at->second)].push_back(e);
  }
  pair_offsets_.assign(1, 0);
  for (std::size_t q = 0; q < pair_springs.size(); ++q) {
    for (const std::size_t e : pair_springs[q]) {
      const bool forward =
          aggregate[static_cast<std::size_t>(springs.v0[e])] == pair_aggregates_[2 * q];
      joining_v0_.push_back(forward ? springs.v0[e] : springs.v1[e]);
      joining_v1_.push_back(forward ? springs.v1[e] : springs.v0[e]);
      joining_rest_.push_back(springs.rest_length[e]);
      joining_ks_.push_back(springs.ks[e]);
      joining_kd_.push_back(springs.kd[e]);
    }
    pair_offsets_.push_back(static_cast<std::int32_t>(joining_v0_.size()));
  }
  // The matrix's pattern: a block per aggregate and one each way per pair.
  const int dofs = coarse_dofs_;
  std::vector<Eigen::Triplet<double>> pattern;
  const auto add_pattern = [&](std::int32_t a, std::int32_t b) {
    for (int r = 0; r < dofs; ++r)
      for (int c = 0; c < dofs; ++c) pattern.emplace_back(dofs * a + r, dofs * b + c, 0.0);
  };
  for (std::int32_t a = 0; a < count; ++a) add_pattern(a, a);
  const std::size_t pairs = pair_springs.size();
  for (std::size_t q = 0; q < pairs; ++q) {
    add_pattern(pair_aggregates_[2 * q], pair_aggregates_[2 * q + 1]);
    add_pattern(pair_aggregates_[2 * q + 1], pair_aggregates_[2 * q]);
  }
  const Eigen::Index size = dofs * static_cast<Eigen::Index>(count);
  coarse_matrix_.resize(size, size);
  coarse_matrix_.setFromTriplets(pattern.begin(), pattern.end());
  coarse_matrix_.makeCompressed();
  // Where each block's entries sit among the matrix's values (row-major within the block;
  // column-major storage).
  const auto slots_of = [&](std::int32_t a, std::int32_t b, std::int32_t* into) {
    for (int c = 0; c < dofs; ++c) {
      const Eigen::Index column = dofs * b + c;
      const int* rows = coarse_matrix_.innerIndexPtr() + coarse_matrix_.outerIndexPtr()[column];
      const int* end = coarse_matrix_.innerIndexPtr() + coarse_matrix_.outerIndexPtr()[column + 1];
      for (int r = 0; r < dofs; ++r) {
        const int* at = std::lower_bound(rows, end, dofs * a + r);
        into[dofs * r + c] = static_cast<std::int32_t>(at - coarse_matrix_.innerIndexPtr());
      }
    }
  };
  const std::size_t kBlock = static_cast<std::size_t>(dofs * dofs);
  diagonal_slots_.resize(kBlock * static_cast<std::size_t>(count));
  for (std::int32_t a = 0; a < count; ++a) slots_of(a, a, &diagonal_slots_[kBlock * a]);
  pair_slots_.resize(2 * kBlock * pairs);
  for (std::size_t q = 0; q < pairs; ++q) {
    slots_of(pair_aggregates_[2 * q], pair_aggregates_[2 * q + 1], &pair_slots_[2 * kBlock * q]);
    slots_of(pair_aggregates_[2 * q + 1], pair_aggregates_[2 * q],
             &pair_slots_[2 * kBlock * q + kBlock]);
  }
  if (count > 0) coarse_solver_.analyzePattern(coarse_matrix_);
  coarse_centre_.resize(3 * static_cast<std::size_t>(count));
  coarse_radius_.resize(static_cast<std::size_t>(count));
  coarse_force_.resize(kRigidUnknowns * static_cast<std::size_t>(count));
  coarse_block_.resize(kRigidUnknowns * kRigidUnknowns * static_cast<std::size_t>(count));
  pair_block_.resize(kRigidUnknowns * kRigidUnknowns * pairs);
  coarse_move_.resize(dofs * static_cast<Eigen::Index>(count));
  coarse_rhs_.resize(dofs * static_cast<Eigen::Index>(count));
  for (Eigen::VectorXd* v : {&cg_residual_, &cg_preconditioned_, &cg_direction_, &cg_product_})
    v->resize(dofs * static_cast<Eigen::Index>(count));
  coarse_reach_ = springs.size() > 0 ? 0.5 * *std::min_element(springs.rest_length.begin(),
                                                               springs.rest_length.end())
                                     : 0.0;
  if (model.uses_continuum()) coarse_springs_ = spring_rows(springs, model.particle_count());
  aggregates_ = {
      count,
      aggregate_offsets_.data(),
      aggregate_members_.data(),
      aggregate_of_.data(),
      model.uses_continuum() ? coarse_springs_.view() : springs_.view(),
      !model.uses_continuum(),
      coarse_dofs_ == kRigidUnknowns,
      static_cast<std::int64_t>(pairs),
      pair_aggregates_.data(),
      pair_offsets_.data(),
      {static_cast<std::int64_t>(joining_v0_.size()), joining_v0_.data(), joining_v1_.data(),
       joining_rest_.data(), joining_ks_.data(), joining_kd_.data()}};
}

void VertexBlockDescent::coarse_step(const kernels::VbdProblem& problem, bool refactor,
                                     Eigen::Matrix3Xd& x) {
  if (aggregates_.count == 0) return;
  kernels::vbd_coarse_terms(problem, x.data(), aggregates_,
                            {coarse_centre_.data(), coarse_radius_.data(), coarse_force_.data(),
                             coarse_block_.data(), pair_block_.data()});
  const int dofs = coarse_dofs_;
  Eigen::VectorXd& rhs = coarse_rhs_;
  for (Eigen::Index a = 0; a < aggregates_.count; ++a)
    for (int d = 0; d < dofs; ++d)
      rhs[dofs * a + d] = coarse_force_[static_cast<std::size_t>(kRigidUnknowns * a + d)];
  assemble_coarse_matrix();
  if (refactor || !coarse_factored_ || !solve_with_last_factor()) {
    coarse_solver_.factorize(coarse_matrix_);
    coarse_factored_ = coarse_solver_.info() == Eigen::Success;  // else no coarse step now
    if (!coarse_factored_) return;
    coarse_move_ = coarse_solver_.solve(rhs);
    ++stats_.coarse_factorizations;
  }
  // A trust region: the step is Newton's on a model whose contacts and friction switch as the
  // cloth moves, so it can overshoot where they do (seen as a divergence on a disc sliding over a
  // cylinder's rim at 1/120 s). No particle moves more than half the shortest spring per coarse
  // step, by the translation or by the turn at the aggregate's rim; the sweeps and the next
  // coarse steps take any remainder. Each particle moves by t + w x r: the model's matrix is the
  // Hessian of G along this linear motion (a finite turn would also bring in the forces'
  // curvature along its arc).
  for (Eigen::Index a = 0; a < aggregates_.count; ++a) {
    Eigen::Vector3d t = coarse_move_.segment<3>(dofs * a);  // m
    Eigen::Vector3d w = dofs == kRigidUnknowns
                            ? Eigen::Vector3d(coarse_move_.segment<3>(dofs * a + 3))
                            : Eigen::Vector3d::Zero();                          // rad
    const double rim = w.norm() * coarse_radius_[static_cast<std::size_t>(a)];  // m
    const double longest = std::max(t.norm(), rim);                             // m
    if (longest > coarse_reach_) {
      t *= coarse_reach_ / longest;
      w *= coarse_reach_ / longest;
    }
    const Eigen::Map<const Eigen::Vector3d> centre(
        &coarse_centre_[3 * static_cast<std::size_t>(a)]);
    for (std::int32_t k = aggregate_offsets_[a]; k < aggregate_offsets_[a + 1]; ++k) {
      const std::int32_t i = aggregate_members_[static_cast<std::size_t>(k)];
      x.col(i) += t + w.cross(x.col(i) - centre);
    }
  }
}

bool VertexBlockDescent::solve_with_last_factor() {
  // Conjugate gradients on the matrix at this iterate, preconditioned by the factorisation of the
  // step's first: the matrices differ where contacts and spring directions changed, so a few
  // iterations reach the Newton step a new factorisation would give.
  const Eigen::VectorXd& b = coarse_rhs_;
  const double target = kCoarseTolerance * b.norm();
  Eigen::VectorXd& x = coarse_move_;
  Eigen::VectorXd& r = cg_residual_;
  Eigen::VectorXd& z = cg_preconditioned_;
  Eigen::VectorXd& p = cg_direction_;
  Eigen::VectorXd& q = cg_product_;
  x.setZero();
  r = b;
  if (!(r.norm() > target)) return true;
  z = coarse_solver_.solve(r);
  p = z;
  double rz = r.dot(z);
  for (int k = 0; k < kMostCoarseIterations; ++k) {
    q.noalias() = coarse_matrix_.selfadjointView<Eigen::Lower>() * p;
    const double pq = p.dot(q);
    if (!(pq > 0.0)) return false;
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    if (r.norm() <= target) return true;
    z = coarse_solver_.solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return false;
}

void VertexBlockDescent::assemble_coarse_matrix() {
  // The kernel's blocks are 6 x 6 (row-major); a translating aggregate takes their top left 3 x 3.
  const int dofs = coarse_dofs_;
  const std::size_t block_size = static_cast<std::size_t>(dofs * dofs);
  constexpr std::size_t kFull = kRigidUnknowns * kRigidUnknowns;
  double* values = coarse_matrix_.valuePtr();
  std::fill(values, values + coarse_matrix_.nonZeros(), 0.0);
  for (std::int64_t a = 0; a < aggregates_.count; ++a) {
    const std::int32_t* slots = &diagonal_slots_[block_size * static_cast<std::size_t>(a)];
    const double* block = &coarse_block_[kFull * static_cast<std::size_t>(a)];
    for (int r = 0; r < dofs; ++r)
      for (int c = 0; c < dofs; ++c) values[slots[dofs * r + c]] += block[kRigidUnknowns * r + c];
    // An aggregate of one particle, or of particles in a line, has no inertia against some turn,
    // and no force turns it that way: a small stiffness there keeps the matrix definite and
    // leaves the step as it is.
    const double translation = block[0] + block[7] + block[14];                    // N/m, the trace
    const double turn_floor = 1e-9 * translation * coarse_reach_ * coarse_reach_;  // N*m
    for (int d = 3; d < dofs; ++d) values[slots[dofs * d + d]] += turn_floor;
  }
  for (std::size_t q = 0; q < pair_block_.size() / kFull; ++q) {
    const std::int32_t* ab = &pair_slots_[2 * block_size * q];
    const std::int32_t* ba = ab + block_size;
    const double* block = &pair_block_[kFull * q];
    for (int r = 0; r < dofs; ++r)
      for (int c = 0; c < dofs; ++c) {
        values[ab[dofs * r + c]] += block[kRigidUnknowns * r + c];
        values[ba[dofs * c + r]] += block[kRigidUnknowns * r + c];
      }
  }
}

}  // namespace drapelab
