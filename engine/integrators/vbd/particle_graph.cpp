// Vertex block descent's particle graph, built once per cloth: each particle's neighbours, the
// colours that let a sweep solve every particle of one colour at once, and the aggregates of the
// coarse step, and the springs per particle (vertex_block_descent.hpp).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "drapelab/continuum.hpp"
#include "integrators/vbd/vertex_block_descent.hpp"

namespace drapelab {

std::vector<std::vector<std::int32_t>> particle_neighbours(const ClothModel& model) {
  const int n = model.particle_count();
  std::vector<std::vector<std::int32_t>> neighbours(static_cast<std::size_t>(n));
  const auto join = [&](std::int32_t a, std::int32_t b) {
    if (a == b) return;
    neighbours[static_cast<std::size_t>(a)].push_back(b);
  };
  for (std::size_t e = 0; e < model.springs.size(); ++e) {
    join(model.springs.v0[e], model.springs.v1[e]);
    join(model.springs.v1[e], model.springs.v0[e]);
  }
  if (model.uses_continuum()) for_each_corner_pair(*model.continuum, join);
  return neighbours;
}

std::vector<std::vector<std::int32_t>> color_particles(const ClothModel& model) {
  const int n = model.particle_count();
  const auto neighbours = particle_neighbours(model);
  std::vector<int> color(static_cast<std::size_t>(n), -1);
  std::vector<std::vector<std::int32_t>> colors;
  std::vector<char> taken;
  for (int i = 0; i < n; ++i) {
    taken.assign(colors.size() + 1, 0);
    for (std::int32_t j : neighbours[static_cast<std::size_t>(i)])
      if (color[static_cast<std::size_t>(j)] >= 0) taken[static_cast<std::size_t>(color[j])] = 1;
    const int c = static_cast<int>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
    if (c == static_cast<int>(colors.size())) colors.emplace_back();
    colors[static_cast<std::size_t>(c)].push_back(i);
    color[static_cast<std::size_t>(i)] = c;
  }
  return colors;
}

std::vector<std::int32_t> aggregate_particles(const ClothModel& model, int size) {
  const int n = model.particle_count();
  const auto neighbours = particle_neighbours(model);
  std::vector<std::int32_t> aggregate(static_cast<std::size_t>(n), -1);
  std::int32_t next = 0;
  std::vector<std::int32_t> members;
  for (int seed = 0; seed < n; ++seed) {
    if (aggregate[static_cast<std::size_t>(seed)] >= 0 || model.is_pinned(seed)) continue;
    // Breadth first from the seed over free, unassigned particles, until the aggregate is full.
    members.assign(1, seed);
    aggregate[static_cast<std::size_t>(seed)] = next;
    for (std::size_t k = 0; k < members.size() && static_cast<int>(members.size()) < size; ++k)
      for (std::int32_t j : neighbours[static_cast<std::size_t>(members[k])]) {
        if (static_cast<int>(members.size()) >= size) break;
        if (aggregate[static_cast<std::size_t>(j)] >= 0 || model.is_pinned(j)) continue;
        aggregate[static_cast<std::size_t>(j)] = next;
        members.push_back(j);
      }
    ++next;
  }
  return aggregate;
}

SpringRows spring_rows(const SpringSet& springs, int particle_count) {
  SpringRows rows;
  // Count each particle's springs, then place each spring at both its ends.
  rows.offsets.assign(static_cast<std::size_t>(particle_count) + 1, 0);
  for (std::size_t e = 0; e < springs.size(); ++e) {
    ++rows.offsets[static_cast<std::size_t>(springs.v0[e]) + 1];
    ++rows.offsets[static_cast<std::size_t>(springs.v1[e]) + 1];
  }
  for (int i = 0; i < particle_count; ++i) rows.offsets[i + 1] += rows.offsets[i];
  const std::size_t entries = static_cast<std::size_t>(rows.offsets.back());
  rows.other.resize(entries);
  rows.rest_length.resize(entries);
  rows.ks.resize(entries);
  rows.kd.resize(entries);
  std::vector<std::int32_t> fill(rows.offsets.begin(), rows.offsets.end() - 1);
  for (std::size_t e = 0; e < springs.size(); ++e)
    for (int end = 0; end < 2; ++end) {
      const std::int32_t at = end == 0 ? springs.v0[e] : springs.v1[e];
      const std::size_t slot = static_cast<std::size_t>(fill[static_cast<std::size_t>(at)]++);
      rows.other[slot] = end == 0 ? springs.v1[e] : springs.v0[e];
      rows.rest_length[slot] = springs.rest_length[e];
      rows.ks[slot] = springs.ks[e];
      rows.kd[slot] = springs.kd[e];
    }
  return rows;
}

}  // namespace drapelab
