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
  const std::size_t n = static_cast<std::size_t>(model.particle_count());
  for (int c = 0; c < 3; ++c) {
    families->x_[c].resize(n);
    families->v_[c].resize(n);
    families->f_[c].resize(n);
    families->t_[c].resize(largest);
  }
  return families;
}

void SpringFamilies::add_forces(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force) {
  const Eigen::Index n = x.cols();
  for (int c = 0; c < 3; ++c) {
    Eigen::Map<Eigen::RowVectorXd>(x_[c].data(), n) = x.row(c);
    Eigen::Map<Eigen::RowVectorXd>(v_[c].data(), n) = v.row(c);
    Eigen::Map<Eigen::RowVectorXd>(f_[c].data(), n) = force.row(c);
  }
  const kernels::SoaState state{{x_[0].data(), x_[1].data(), x_[2].data()}, {v_[0].data(), v_[1].data(), v_[2].data()}};
  double* const t[3] = {t_[0].data(), t_[1].data(), t_[2].data()};
  double* const f[3] = {f_[0].data(), f_[1].data(), f_[2].data()};
  for (const SpringFamily& family : families_) {
    kernels::family_forces(state, family, t);
    kernels::family_scatter(family, t, f);
  }
  for (int c = 0; c < 3; ++c) force.row(c) = Eigen::Map<const Eigen::RowVectorXd>(f_[c].data(), n);
}

}  // namespace drapelab
