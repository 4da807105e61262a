// What vbd's collider contacts did over a step (vertex_block_descent.hpp): the planes' and the
// features' spring-dampers and friction at the step's end state, where backward Euler's forces
// act, as each collider's totals (its load, contact count, and the power the ledger takes).
#include <algorithm>

#include "drapelab/energy_ledger.hpp"
#include "integrators/vbd/vertex_block_descent.hpp"

namespace drapelab {
namespace {

// One contact's terms as the sweeps took them, at the step's end.
struct ContactAtEnd {
  Eigen::Vector3d n;        // unit, the push's direction
  Eigen::Vector3d rel;      // m: the cloth point's move over the step relative to the surface
  Eigen::Vector3d surface;  // m: the surface's move over the step
  Eigen::Vector3d point;    // m: the cloth point at the end
  double depth = 0.0;       // m, within the thickness when > 0
  double load = 0.0;        // N: friction's, lagged at the step's start
  double kinetic = 0.0, fixed = 0.0;
};

void add_contact(const ContactAtEnd& c, double stiffness, double damping, double h,
                 double friction_velocity, ColliderContactTotals& t) {
  // The step's mean velocities relative to the surface and of the surface (m/s).
  const Eigen::Vector3d relative_velocity = c.rel / h, surface_velocity = c.surface / h;
  Eigen::Vector3d on_cloth = Eigen::Vector3d::Zero();  // N
  if (c.depth > 0.0) {
    const double spring = stiffness * c.depth;  // N
    const double fn = std::max(
        0.0, spring + damping * kernels::contact_closing(c.depth, c.rel.dot(c.n)) / h);  // N
    t.power += push_power(fn, spring, c.n, relative_velocity, surface_velocity);
    if (fn > 0.0) {
      ++t.contact_count;
      t.normal_force += fn;
      t.max_depth = std::max(t.max_depth, c.depth);
      on_cloth += fn * c.n;
    }
  }
  if (c.load > 0.0) {
    const Eigen::Vector3d slide = c.rel - c.rel.dot(c.n) * c.n;  // m over the step
    const double slip = slide.norm();
    const double scale = friction_velocity * h;  // m: the stick-slip boundary
    const double friction =
        slip < scale ? c.fixed * c.load * slip / scale : c.kinetic * c.load;  // N
    t.friction_force += friction;
    if (slip > 0.0) {
      const Eigen::Vector3d rub = -(friction / slip) * slide;  // N
      on_cloth += rub;
      t.power += friction_power(rub, relative_velocity, surface_velocity);
    }
  }
  t.force -= on_cloth;
  t.torque -= c.point.cross(on_cloth);
}

}  // namespace

void VertexBlockDescent::record_contact_totals(const Eigen::Matrix3Xd& x, double h,
                                               std::vector<ColliderContactTotals>& totals) const {
  if (totals.empty()) return;
  for (ColliderContactTotals& t : totals) t = ColliderContactTotals{};
  for (std::size_t i = 0; i < plane_count_.size(); ++i)
    for (int k = 0; k < plane_count_[i]; ++k) {
      const std::size_t e = i * kPlaneSlots + static_cast<std::size_t>(k);
      const Eigen::Index col = static_cast<Eigen::Index>(i);
      ContactAtEnd c;
      c.n = Eigen::Map<const Eigen::Vector3d>(&plane_normal_[3 * e]);
      c.surface = Eigen::Map<const Eigen::Vector3d>(&plane_surface_move_[3 * e]);
      c.point = x.col(col);
      c.rel = x.col(col) - start_.col(col) - c.surface;
      c.depth = contact_.radius -
                (c.point - Eigen::Map<const Eigen::Vector3d>(&plane_point_[3 * e])).dot(c.n);
      c.load = plane_load_[e];
      c.kinetic = plane_kinetic_[e];
      c.fixed = plane_fixed_[e];
      add_contact(c, contact_.stiffness, contact_.damping, h, settings_.friction_velocity,
                  totals[static_cast<std::size_t>(plane_collider_[e])]);
    }
}

void VertexBlockDescent::record_feature_totals(const Eigen::Matrix3Xd& x, double h,
                                               std::vector<ColliderContactTotals>& totals) const {
  if (totals.empty()) return;
  const kernels::VbdFeatures features = feature_view(contact_.radius, 0.0, 0.0);
  const auto position = [&](std::int32_t j) { return x.data() + 3 * static_cast<std::int64_t>(j); };
  for (std::size_t f = 0; f < features_.collider.size(); ++f) {
    kernels::FeatureGeometry g;
    if (!kernels::feature_geometry(features, static_cast<std::int64_t>(f), position, start_.data(),
                                   g))
      continue;
    ContactAtEnd c;
    c.n = Eigen::Map<const Eigen::Vector3d>(g.n);
    c.surface = Eigen::Map<const Eigen::Vector3d>(&features_.surface_move[3 * f]);
    c.rel = Eigen::Map<const Eigen::Vector3d>(g.move) - c.surface;
    c.point = Eigen::Vector3d::Zero();
    for (int s = 0; s < 3; ++s) {
      const int j = features_.particle[3 * f + static_cast<std::size_t>(s)];
      if (j >= 0) c.point += g.w[s] * x.col(j);
    }
    c.depth = g.depth;
    c.load = features_.load[f];
    c.kinetic = features_.kinetic[f];
    c.fixed = features_.fixed[f];
    add_contact(c, contact_.stiffness, contact_.damping, h, settings_.friction_velocity,
                totals[static_cast<std::size_t>(features_.collider[f])]);
  }
}

}  // namespace drapelab
