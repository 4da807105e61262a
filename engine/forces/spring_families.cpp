// Grouping springs by index offset, and the fast spring phase (spring_families.hpp).
#include "forces/spring_families.hpp"

#include <algorithm>
#include <map>

namespace drapelab {

namespace {

// A family whose springs all share rest length, ks and kd keeps those three numbers and the list of
// its empty slots (spring_family_loops.hpp); one whose springs share ks and kd only keeps those two
// and the list. An empty slot has rest = ks = kd = 0.
void mark_if_uniform(SpringFamily& family) {
  const std::size_t n = family.rest.size();
  const auto is_empty = [&](std::size_t i) {
    return family.rest[i] == 0.0 && family.ks[i] == 0.0 && family.kd[i] == 0.0;
  };
  std::size_t first = 0;
  while (first < n && is_empty(first)) ++first;
  if (first == n) return;
  const double rest = family.rest[first], ks = family.ks[first], kd = family.kd[first];
  bool same_rest = true;
  std::vector<std::int32_t> empty;
  for (std::size_t i = 0; i < n; ++i) {
    if (is_empty(i))
      empty.push_back(static_cast<std::int32_t>(i));
    else if (family.ks[i] != ks || family.kd[i] != kd)
      return;
    else
      same_rest = same_rest && family.rest[i] == rest;
  }
  family.uniform = same_rest;
  family.uniform_stiffness = !same_rest;
  family.uniform_rest = same_rest ? rest : 0.0;
  family.uniform_ks = ks;
  family.uniform_kd = kd;
  family.empty_slots = std::move(empty);
}

}  // namespace

std::unique_ptr<SpringFamilies> SpringFamilies::build(const ClothModel& model, int max_families) {
  const SpringSet& s = model.springs;
  const std::int64_t n = model.particle_count();
  if (s.size() == 0) return nullptr;
  // offset -> family, first particle the smaller index.
  std::map<std::int32_t, SpringFamily> by_offset;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const std::int32_t a = std::min(s.v0[e], s.v1[e]), b = std::max(s.v0[e], s.v1[e]);
    if (a == b) return nullptr;  // a spring on one particle has no offset
    auto [entry, added] = by_offset.try_emplace(b - a);
    SpringFamily& family = entry->second;
    if (added) {
      if (static_cast<int>(by_offset.size()) > max_families) return nullptr;
      family.offset = b - a;
      family.rest.assign(static_cast<std::size_t>(n), 0.0);
      family.ks.assign(static_cast<std::size_t>(n), 0.0);
      family.kd.assign(static_cast<std::size_t>(n), 0.0);
    }
    // A slot with ks = kd = 0 is empty: a zero-stiffness spring may share it with nothing else
    // either.
    if (family.rest[a] != 0.0 || family.ks[a] != 0.0 || family.kd[a] != 0.0)
      return nullptr;  // two springs start at one particle: not a family
    // The force formula is symmetric in the two ends, up to the sign the gather applies: the first
    // particle here may be the model's v1, which receives -f from add_spring_forces, and receives
    // here +f(x_first - x_second), the same vector.
    family.rest[a] = s.rest_length[e];
    family.ks[a] = s.ks[e];
    family.kd[a] = s.kd[e];
    ++family.springs;
  }
  auto families = std::make_unique<SpringFamilies>();
  std::int32_t max_offset = 0;
  for (auto& [offset, family] : by_offset) {
    max_offset = std::max(max_offset, offset);
    mark_if_uniform(family);
    families->families_.push_back(std::move(family));
  }
  const std::int64_t slots = n * static_cast<std::int64_t>(families->families_.size());
  if (2 * static_cast<std::int64_t>(s.size()) < slots)
    return nullptr;  // sparse: the edge list is as good
  families->scratch_.resize(n, static_cast<std::int64_t>(families->families_.size()), max_offset);
  return families;
}

void SpringFamilies::add_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                Eigen::Matrix3Xd& force) {
  // Matrix3Xd stores x, y, z of each particle together: the packed layout the loops read.
  kernels::add_family_forces(x.data(), v.data(), families_, scratch_, force.data());
}

void SpringFamilies::set_body_and_spring_forces(const Eigen::Matrix3Xd& x,
                                                const Eigen::Matrix3Xd& v,
                                                const Eigen::Matrix3Xd& weight,
                                                const Eigen::Matrix3Xd& mass, double air,
                                                Eigen::Matrix3Xd& force, bool state_split,
                                                const kernels::ForcesFinalHook* after) {
  const kernels::BodyForceInputs body{weight.data(), mass.data(), air};
  kernels::add_family_forces(x.data(), v.data(), families_, scratch_, force.data(), &body,
                             state_split, after);
}

}  // namespace drapelab
