// Grouping springs by index offset, and the fast spring phase (spring_families.hpp).
#include "drapelab/spring_families.hpp"

#include <algorithm>
#include <map>

namespace drapelab {

std::unique_ptr<SpringFamilies> SpringFamilies::build(const ClothModel& model, int max_families) {
  const SpringSet& s = model.springs;
  if (s.size() == 0) return nullptr;
  // offset -> (first particle, spring index), first particle the smaller index.
  std::map<std::int32_t, std::vector<std::pair<std::int32_t, std::size_t>>> by_offset;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const std::int32_t a = std::min(s.v0[e], s.v1[e]), b = std::max(s.v0[e], s.v1[e]);
    if (a == b) return nullptr;  // a spring on one particle has no offset
    by_offset[b - a].emplace_back(a, e);
    if (static_cast<int>(by_offset.size()) > max_families) return nullptr;
  }
  auto families = std::make_unique<SpringFamilies>();
  std::size_t runs = 0;
  for (auto& [offset, members] : by_offset) {
    std::sort(members.begin(), members.end());
    SpringFamily family;
    family.offset = offset;
    for (std::size_t m = 0; m < members.size(); ++m) {
      const auto [first, e] = members[m];
      if (m > 0 && members[m - 1].first == first) return nullptr;  // two springs on one pair: not a family
      const bool continues = m > 0 && members[m - 1].first + 1 == first;
      if (!continues) {
        family.run_start.push_back(first);
        family.run_length.push_back(0);
        family.run_slot.push_back(static_cast<std::int32_t>(m));
      }
      ++family.run_length.back();
      // The force formula is symmetric in the two ends, up to the sign the scatter applies: the
      // first particle here may be the model's v1, which receives -f from add_spring_forces, and
      // receives here +f(x_first - x_second), the same vector.
      family.rest.push_back(s.rest_length[e]);
      family.ks.push_back(s.ks[e]);
      family.kd.push_back(s.kd[e]);
    }
    runs += family.run_start.size();
    families->families_.push_back(std::move(family));
  }
  if (s.size() < 4 * runs) return nullptr;  // short runs: the gather path is as good
  std::size_t largest = 0;
  for (const auto& family : families->families_) largest = std::max(largest, family.rest.size());
  for (int c = 0; c < 3; ++c) families->t_[c].resize(largest);
  return families;
}

void SpringFamilies::add_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force) {
  // Matrix3Xd stores x, y, z of each particle together: the packed layout the loops read.
  const kernels::PackedState state{x.data(), v.data()};
  double* const t[3] = {t_[0].data(), t_[1].data(), t_[2].data()};
  for (const SpringFamily& family : families_) {
    kernels::family_forces(state, family, t);
    kernels::family_scatter(family, t, force.data());
  }
}

}  // namespace drapelab
