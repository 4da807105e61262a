// Our spring constants as the classic solver's link stiffness (bullet-notes 1.7).
#include <algorithm>
#include <cmath>
#include <limits>

#include "drapelab/bullet/bullet_softbody_solver.hpp"

namespace drapelab::bullet {

double mapped_link_stiffness(double ks, double w, double h, int iterations) {
  // One Gauss-Seidel sweep moving a link by a fraction s is backward Euler on the spring when
  // s = ks w h^2 / (1 + ks w h^2); n sweeps move it by 1 - (1 - kLST)^n.
  if (ks <= 0.0 || w <= 0.0) return 0.0;
  return 1.0 - std::pow(1.0 + ks * w * h * h, -1.0 / iterations);
}

double largest_link_compliance_ratio(const ClothModel& model, double h) {
  double largest = 0.0;
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    const double w = model.inverse_mass[s.v0[e]] + model.inverse_mass[s.v1[e]];
    largest = std::max(largest, s.ks[e] * w * h * h);
  }
  return largest;
}

double default_voxel_size(const std::vector<Collider>& colliders, double margin) {
  double feature = std::numeric_limits<double>::infinity();  // m, the smallest size of any collider
  for (const auto& c : colliders) {
    switch (c.shape) {
      case ColliderShape::sphere: feature = std::min(feature, c.radius); break;
      case ColliderShape::capsule: feature = std::min(feature, c.radius); break;
      case ColliderShape::cylinder: feature = std::min({feature, c.radius, c.height}); break;
      case ColliderShape::box: feature = std::min(feature, 2.0 * c.half_extents.minCoeff()); break;
      case ColliderShape::plane: break;
    }
  }
  return std::min(margin, feature / 10.0);
}

}  // namespace drapelab::bullet
