// Vertex block descent's coarse step (vertex_block_descent.hpp): the aggregates' sparse system,
// built once from the springs that cross between them, its factorisation and its solve, which
// moves each aggregate rigidly between the sweeps.
#include <algorithm>
#include <cstdint>
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

}  // namespace

void VertexBlockDescent::build_coarse_system(const ClothModel& model) {
  const std::vector<std::int32_t> aggregate = aggregate_particles(
      model,
      std::max(kAggregateSize, (model.particle_count() + kMostAggregates - 1) / kMostAggregates));
  const std::int32_t count =
      aggregate.empty() ? 0 : *std::max_element(aggregate.begin(), aggregate.end()) + 1;
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
  // The springs that cross between aggregates (or reach a pin), and the matrix's pattern: a block
  // per aggregate and one each way per pair of aggregates a spring joins.
  const SpringSet& springs = model.springs;
  std::vector<Eigen::Triplet<double>> pattern;
  const auto add_pattern = [&](std::int32_t a, std::int32_t b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) pattern.emplace_back(3 * a + r, 3 * b + c, 0.0);
  };
  for (std::int32_t a = 0; a < count; ++a) add_pattern(a, a);
  for (std::size_t e = 0; e < springs.size(); ++e) {
    const std::int32_t a = aggregate[static_cast<std::size_t>(springs.v0[e])];
    const std::int32_t b = aggregate[static_cast<std::size_t>(springs.v1[e])];
    if (a == b) continue;
    crossing_v0_.push_back(springs.v0[e]);
    crossing_v1_.push_back(springs.v1[e]);
    crossing_rest_.push_back(springs.rest_length[e]);
    crossing_ks_.push_back(springs.ks[e]);
    crossing_kd_.push_back(springs.kd[e]);
    if (a >= 0 && b >= 0) {
      add_pattern(a, b);
      add_pattern(b, a);
    }
  }
  const Eigen::Index size = 3 * static_cast<Eigen::Index>(count);
  coarse_matrix_.resize(size, size);
  coarse_matrix_.setFromTriplets(pattern.begin(), pattern.end());
  coarse_matrix_.makeCompressed();
  // Where each block's nine entries sit among the matrix's values (column-major storage).
  const auto slots_of = [&](std::int32_t a, std::int32_t b, std::int32_t* into) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Index column = 3 * b + c;
      const int* rows = coarse_matrix_.innerIndexPtr() + coarse_matrix_.outerIndexPtr()[column];
      const int* end = coarse_matrix_.innerIndexPtr() + coarse_matrix_.outerIndexPtr()[column + 1];
      for (int r = 0; r < 3; ++r) {
        const int* at = std::lower_bound(rows, end, 3 * a + r);
        into[3 * r + c] = static_cast<std::int32_t>(at - coarse_matrix_.innerIndexPtr());
      }
    }
  };
  diagonal_slots_.resize(9 * static_cast<std::size_t>(count));
  for (std::int32_t a = 0; a < count; ++a) slots_of(a, a, &diagonal_slots_[9 * a]);
  crossing_slots_.assign(36 * crossing_v0_.size(), -1);
  for (std::size_t e = 0; e < crossing_v0_.size(); ++e) {
    const std::int32_t a = aggregate[static_cast<std::size_t>(crossing_v0_[e])];
    const std::int32_t b = aggregate[static_cast<std::size_t>(crossing_v1_[e])];
    std::int32_t* slots = &crossing_slots_[36 * e];
    if (a >= 0) slots_of(a, a, slots);
    if (b >= 0) slots_of(b, b, slots + 9);
    if (a >= 0 && b >= 0) {
      slots_of(a, b, slots + 18);
      slots_of(b, a, slots + 27);
    }
  }
  if (count > 0) coarse_solver_.analyzePattern(coarse_matrix_);
  coarse_force_.resize(3 * static_cast<std::size_t>(count));
  coarse_diagonal_.resize(6 * static_cast<std::size_t>(count));
  crossing_blocks_.resize(6 * crossing_v0_.size());
  aggregates_ = {count, aggregate_offsets_.data(), aggregate_members_.data()};
  coarse_reach_ = springs.size() > 0 ? 0.5 * *std::min_element(springs.rest_length.begin(),
                                                               springs.rest_length.end())
                                     : 0.0;
  crossing_ = {static_cast<std::int64_t>(crossing_v0_.size()),
               crossing_v0_.data(),
               crossing_v1_.data(),
               crossing_rest_.data(),
               crossing_ks_.data(),
               crossing_kd_.data()};
}

void VertexBlockDescent::coarse_step(const kernels::VbdProblem& problem, bool refactor,
                                     Eigen::Matrix3Xd& x) {
  if (aggregates_.count == 0) return;
  kernels::vbd_coarse_terms(problem, x.data(), aggregates_, crossing_, coarse_force_.data(),
                            coarse_diagonal_.data(), crossing_blocks_.data());
  if (refactor) factor_coarse_matrix();
  if (!coarse_factored_) return;
  Eigen::VectorXd move = coarse_solver_.solve(
      Eigen::Map<const Eigen::VectorXd>(coarse_force_.data(), 3 * aggregates_.count));
  // A trust region: the step is Newton's on a model whose contacts and friction switch as the
  // cloth moves, so it can overshoot where they do (seen as a divergence on a disc sliding over a
  // cylinder's rim at 1/120 s). An aggregate moves at most half the shortest spring per coarse
  // step; the sweeps and the next coarse steps take any remainder.
  for (Eigen::Index a = 0; a < aggregates_.count; ++a) {
    const double length = move.segment<3>(3 * a).norm();  // m
    if (length > coarse_reach_) move.segment<3>(3 * a) *= coarse_reach_ / length;
  }
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const std::int32_t a = aggregate_of_[static_cast<std::size_t>(i)];
    if (a >= 0) x.col(i) += move.segment<3>(3 * a);
  }
}

void VertexBlockDescent::factor_coarse_matrix() {
  double* values = coarse_matrix_.valuePtr();
  std::fill(values, values + coarse_matrix_.nonZeros(), 0.0);
  // Adds sign times the symmetric block of six entries at nine slots.
  const auto add = [values](const std::int32_t* slots, const double* h, double sign) {
    const double full[9] = {h[0], h[3], h[4], h[3], h[1], h[5], h[4], h[5], h[2]};
    for (int k = 0; k < 9; ++k) values[slots[k]] += sign * full[k];
  };
  for (std::int64_t a = 0; a < aggregates_.count; ++a)
    add(&diagonal_slots_[9 * static_cast<std::size_t>(a)],
        &coarse_diagonal_[6 * static_cast<std::size_t>(a)], 1.0);
  for (std::size_t e = 0; e < crossing_v0_.size(); ++e) {
    const std::int32_t* slots = &crossing_slots_[36 * e];
    const double* block = &crossing_blocks_[6 * e];
    for (int part = 0; part < 4; ++part)
      if (slots[9 * part] >= 0) add(slots + 9 * part, block, part < 2 ? 1.0 : -1.0);
  }
  coarse_solver_.factorize(coarse_matrix_);
  coarse_factored_ = coarse_solver_.info() == Eigen::Success;  // else no coarse step this step
}

}  // namespace drapelab
