// The continuum elements of a structured mesh as dense families, for the force loop's fast path.
// On a grid every triangle of one kind has its corners at the same offsets from its lowest corner
// (its slot), and so has every hinge of one kind: a family stores one value per slot (zero where
// the slot holds no element), so the loop over a family reads its corners' positions at fixed
// offsets, unit stride, in vector lanes, instead of gathering them through index lists, and each
// particle sums its shares from fixed offsets too. Like the other *_loops files, no Eigen here.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace drapelab::kernels {

struct TriangleFamily {
  std::array<std::int32_t, 3> offset{};    // corner k is particle slot + offset[k]
  std::vector<double> g1x, g1y, g2x, g2y;  // 1/m per slot: the shape gradients g_1, g_2
  std::vector<double> area;                // m^2 per slot; 0 where the slot holds no triangle
  std::vector<std::int64_t> runs;          // [begin, end) pairs of slots worth computing
};

struct HingeFamily {
  std::array<std::int32_t, 4> offset{};  // a, b, c, d at slot + offset[k]
  // The hinge's triangles: of family wing_family[k], at slot + wing_shift[k].
  std::array<std::int32_t, 2> wing_family{};
  std::array<std::int32_t, 2> wing_shift{};
  double second_sign = 1.0;        // orients the second triangle's normal (ContinuumElements)
  std::vector<double> stiffness;   // N*m per slot; 0 where the slot holds no hinge
  std::vector<double> rest_angle;  // rad per slot
  std::vector<std::int64_t> runs;  // [begin, end) pairs of slots worth computing
};

struct ContinuumFamilies {
  std::int64_t particles = 0;
  std::int64_t padding = 0;  // the largest offset: the state columns run this far past the end
  std::vector<TriangleFamily> triangles;
  std::vector<HingeFamily> hinges;
  // Scratch doubles the family force loop needs (zeroed once, as the padding must read zeros): the
  // state split into 6 columns, 12 sums (3 components for each of 4 corner numbers) and per
  // triangle family its normal, each column span() long.
  std::int64_t span() const { return particles + 2 * padding; }
  std::int64_t scratch_size() const {
    return (18 + 3 * static_cast<std::int64_t>(triangles.size())) * span();
  }
};

// Groups the elements into families, or returns false (and leaves `out` empty) when they do not
// form at most `max_families` families each at least a quarter full: then the indexed loop serves.
// Triangles: 3 corners each, 4 shape-gradient numbers (g_1x, g_1y, g_2x, g_2y) and an area; hinges:
// 4 corners, 2 triangles, a sign, a stiffness and a rest angle each.
struct ElementLists {
  std::int64_t particles = 0;
  const std::int32_t* triangle = nullptr;  // 3 per triangle
  const double* gradient[4] = {nullptr, nullptr, nullptr, nullptr};
  const double* area = nullptr;
  std::int64_t triangles = 0;
  const std::int32_t* hinge = nullptr;           // 4 per hinge
  const std::int32_t* hinge_triangle = nullptr;  // 2 per hinge
  const double* second_sign = nullptr;
  const double* stiffness = nullptr;
  const double* rest_angle = nullptr;
  std::int64_t hinges = 0;
};
bool build_continuum_families(const ElementLists& elements, int max_families,
                              ContinuumFamilies& out);

}  // namespace drapelab::kernels
