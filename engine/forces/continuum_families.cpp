// Grouping continuum elements into dense families (continuum_families.hpp).
#include "forces/continuum_families.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <tuple>

namespace drapelab::kernels {
namespace {

// An element's slot (its lowest corner) and its corners' offsets from it.
template <std::size_t Corners>
std::pair<std::int32_t, std::array<std::int32_t, Corners>> slot_and_offsets(
    const std::int32_t* corner) {
  const std::int32_t slot = *std::min_element(corner, corner + Corners);
  std::array<std::int32_t, Corners> offset{};
  for (std::size_t k = 0; k < Corners; ++k) offset[k] = corner[k] - slot;
  return {slot, offset};
}

// The occupied slots as [begin, end) runs, bridging gaps shorter than a vector's few lanes (a grid
// whose diagonal turns every row fills every other row of slots).
std::vector<std::int64_t> occupied_runs(const std::vector<bool>& occupied) {
  constexpr std::int64_t kBridge = 8;
  std::vector<std::int64_t> runs;
  const auto n = static_cast<std::int64_t>(occupied.size());
  for (std::int64_t i = 0; i < n; ++i) {
    if (!occupied[static_cast<std::size_t>(i)]) continue;
    if (!runs.empty() && i - runs.back() <= kBridge) {
      runs.back() = i + 1;
    } else {
      runs.push_back(i);
      runs.push_back(i + 1);
    }
  }
  return runs;
}

}  // namespace

bool build_continuum_families(const ElementLists& e, int max_families, ContinuumFamilies& out) {
  out = ContinuumFamilies{};
  const std::int64_t n = e.particles;
  const auto size = static_cast<std::size_t>(n);
  // Triangles by their offsets; each slot may hold one triangle of a family.
  std::map<std::array<std::int32_t, 3>, std::int32_t> triangle_kind;
  std::set<std::pair<std::int32_t, std::int32_t>> taken;  // (family, slot); hinge families < 0
  std::vector<std::pair<std::int32_t, std::int32_t>> placed(static_cast<std::size_t>(e.triangles));
  std::vector<std::int64_t> triangle_count;
  for (std::int64_t t = 0; t < e.triangles; ++t) {
    const auto [slot, offset] = slot_and_offsets<3>(e.triangle + 3 * t);
    auto [it, added] =
        triangle_kind.emplace(offset, static_cast<std::int32_t>(out.triangles.size()));
    if (added) {
      if (static_cast<int>(out.triangles.size()) >= max_families) return out = {}, false;
      TriangleFamily family;
      family.offset = offset;
      for (auto* column : {&family.g1x, &family.g1y, &family.g2x, &family.g2y, &family.area})
        column->assign(size, 0.0);
      out.triangles.push_back(std::move(family));
      triangle_count.push_back(0);
    }
    TriangleFamily& family = out.triangles[static_cast<std::size_t>(it->second)];
    const auto s = static_cast<std::size_t>(slot);
    if (!taken.insert({it->second, slot}).second) return out = {}, false;  // two on one slot
    family.g1x[s] = e.gradient[0][t];
    family.g1y[s] = e.gradient[1][t];
    family.g2x[s] = e.gradient[2][t];
    family.g2y[s] = e.gradient[3][t];
    family.area[s] = e.area[t];
    ++triangle_count[static_cast<std::size_t>(it->second)];
    placed[static_cast<std::size_t>(t)] = {it->second, slot};
  }
  // Hinges by their offsets and where their triangles sit relative to them.
  using HingeKey = std::tuple<std::array<std::int32_t, 4>, std::array<std::int32_t, 2>,
                              std::array<std::int32_t, 2>, double>;
  std::map<HingeKey, std::int32_t> hinge_kind;
  std::vector<std::int64_t> hinge_count;
  for (std::int64_t h = 0; h < e.hinges; ++h) {
    const auto [slot, offset] = slot_and_offsets<4>(e.hinge + 4 * h);
    std::array<std::int32_t, 2> wing_family{}, wing_shift{};
    for (int k = 0; k < 2; ++k) {
      const auto [family, wing_slot] =
          placed[static_cast<std::size_t>(e.hinge_triangle[2 * h + k])];
      wing_family[static_cast<std::size_t>(k)] = family;
      wing_shift[static_cast<std::size_t>(k)] = wing_slot - slot;
    }
    const HingeKey key{offset, wing_family, wing_shift, e.second_sign[h]};
    auto [it, added] = hinge_kind.emplace(key, static_cast<std::int32_t>(out.hinges.size()));
    if (added) {
      if (static_cast<int>(out.hinges.size()) >= max_families) return out = {}, false;
      HingeFamily family;
      family.offset = offset;
      family.wing_family = wing_family;
      family.wing_shift = wing_shift;
      family.second_sign = e.second_sign[h];
      family.stiffness.assign(size, 0.0);
      family.rest_angle.assign(size, 0.0);
      out.hinges.push_back(std::move(family));
      hinge_count.push_back(0);
    }
    HingeFamily& family = out.hinges[static_cast<std::size_t>(it->second)];
    const auto s = static_cast<std::size_t>(slot);
    if (!taken.insert({-1 - it->second, slot}).second) return out = {}, false;
    family.stiffness[s] = e.stiffness[h];
    family.rest_angle[s] = e.rest_angle[h];
    ++hinge_count[static_cast<std::size_t>(it->second)];
  }
  // Dense enough that computing every slot costs at most four times the elements themselves.
  for (std::int64_t count : triangle_count)
    if (4 * count < n) return out = {}, false;
  for (std::int64_t count : hinge_count)
    if (4 * count < n) return out = {}, false;
  std::int32_t padding = 0;
  for (const auto& family : out.triangles)
    for (std::int32_t o : family.offset) padding = std::max(padding, o);
  for (const auto& family : out.hinges) {
    for (std::int32_t o : family.offset) padding = std::max(padding, o);
    for (std::int32_t shift : family.wing_shift) padding = std::max(padding, std::abs(shift));
  }
  // Each family's occupied slots, from one pass over them all (hinge family f is -1 - f in taken).
  std::vector<std::vector<bool>> occupied(out.triangles.size() + out.hinges.size(),
                                          std::vector<bool>(size, false));
  const auto triangle_families = static_cast<std::int32_t>(out.triangles.size());
  for (const auto& [family, slot] : taken)
    occupied[static_cast<std::size_t>(family >= 0 ? family : triangle_families - 1 - family)]
            [static_cast<std::size_t>(slot)] = true;
  for (std::size_t f = 0; f < out.triangles.size(); ++f)
    out.triangles[f].runs = occupied_runs(occupied[f]);
  for (std::size_t f = 0; f < out.hinges.size(); ++f)
    out.hinges[f].runs = occupied_runs(occupied[out.triangles.size() + f]);
  out.particles = n;
  out.padding = padding;
  return true;
}

}  // namespace drapelab::kernels
