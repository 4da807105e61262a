// Distance constraints between particles, points and collider points (see
// distance_constraints.hpp).
#include "drapelab/distance_constraints.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace drapelab {
namespace {

bool projected(const DistanceConstraint& c) { return c.mode != ConstraintMode::soft; }

}  // namespace

const char* constraint_mode_name(ConstraintMode mode) {
  switch (mode) {
    case ConstraintMode::hard:
      return "hard";
    case ConstraintMode::rope:
      return "rope";
    case ConstraintMode::soft:
      return "soft";
  }
  return "?";
}

bool DistanceConstraints::has_soft() const {
  return std::any_of(list.begin(), list.end(),
                     [](const DistanceConstraint& c) { return c.mode == ConstraintMode::soft; });
}

bool DistanceConstraints::has_hard() const {
  return std::any_of(list.begin(), list.end(), projected);
}

bool DistanceConstraints::any_on_dynamic() const {
  return std::any_of(list.begin(), list.end(), [this](const DistanceConstraint& c) {
    return c.b.kind == ConstraintEnd::Kind::collider_point &&
           colliders[static_cast<std::size_t>(c.b.collider)].dynamic();
  });
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> DistanceConstraints::end_b(
    const DistanceConstraint& c, double t, const Eigen::Matrix3Xd& x,
    const Eigen::Matrix3Xd& v) const {
  switch (c.b.kind) {
    case ConstraintEnd::Kind::particle:
      return {x.col(c.b.particle), v.col(c.b.particle)};
    case ConstraintEnd::Kind::point:
      return {c.b.point, Eigen::Vector3d::Zero()};
    case ConstraintEnd::Kind::drag:
      return c.b.drag->target(t);
    case ConstraintEnd::Kind::collider_point: {
      const auto index = static_cast<std::size_t>(c.b.collider);
      const Collider& collider = colliders[index];
      if (poses && collider.dynamic()) {
        const ColliderKinematics body = poses->at(index, t);
        const Eigen::Vector3d position = body.pose * c.b.point;
        return {position, body.point_velocity(position)};
      }
      const Eigen::Vector3d position = collider_pose(collider, t) * c.b.point;
      return {position, collider_point_velocity(collider, t, position)};
    }
  }
  return {c.b.point, Eigen::Vector3d::Zero()};
}

void DistanceConstraints::add_soft_forces(double t, const Eigen::Matrix3Xd& x,
                                          const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& force,
                                          std::vector<WeightedContact>* couplings,
                                          std::vector<ColliderForce>* body_loads,
                                          PowerSplit* power) const {
  if (body_loads) body_loads->assign(colliders.size(), ColliderForce{});
  if (power) *power = {};
  for (const DistanceConstraint& c : list) {
    if (c.mode != ConstraintMode::soft || !acts(c, t)) continue;
    const int a = particle_a(c);
    const auto [b, vb] = end_b(c, t, x, v);
    const Eigen::Vector3d d = x.col(a) - b;
    const double l = d.norm();
    if (!(l > 0.0)) continue;  // coincident ends: no direction to pull along
    const Eigen::Vector3d n = d / l;
    // The push along n on a (N): negative while the spring is stretched.
    const bool drag = c.b.kind == ConstraintEnd::Kind::drag;
    const double k = drag ? c.b.drag->stiffness : c.stiffness;    // N/m
    const double damping = drag ? c.b.drag->damping : c.damping;  // N*s/m
    const double length = c.length_at(t);                         // m
    const double push = k * (length - l) - damping * (v.col(a) - vb).dot(n);
    force.col(a) += push * n;
    const bool b_particle = c.b.kind == ConstraintEnd::Kind::particle;
    if (b_particle) force.col(c.b.particle) -= push * n;
    // A particle end is cloth: only a collider's point or a drag's target moves from outside.
    if (power) {
      *power += push_power(push, k * (length - l), n, v.col(a) - vb,
                           b_particle ? Eigen::Vector3d::Zero() : Eigen::Vector3d(vb));
      power->external += k * (l - length) * -c.length_rate(t);
    }
    const bool b_body = c.b.kind == ConstraintEnd::Kind::collider_point &&
                        colliders[static_cast<std::size_t>(c.b.collider)].dynamic();
    if (body_loads && b_body) {
      ColliderForce& load = (*body_loads)[static_cast<std::size_t>(c.b.collider)];
      load.force -= push * n;
      load.torque -= b.cross(push * n);
    }
    if (!couplings) continue;
    WeightedContact coupling;
    coupling.particle[0] = a;
    coupling.weight[0] = 1.0;
    if (b_particle) {
      coupling.particle[1] = c.b.particle;
      coupling.weight[1] = -1.0;
    }
    coupling.normal = n;
    coupling.stiffness = k;
    coupling.damping = damping;
    coupling.depth = length - l;
    coupling.force = push;
    coupling.two_sided = true;
    if (!b_particle) coupling.end_rate = n.dot(vb);
    couplings->push_back(coupling);
  }
}

ConstraintProjection DistanceConstraints::project_positions(double t,
                                                            const Eigen::VectorXd& inverse_mass,
                                                            Eigen::Matrix3Xd& x) const {
  ConstraintProjection result;
  // The far ends that are not particles stay where they are at t: one pose per constraint.
  std::vector<Eigen::Vector3d> fixed_b(list.size(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < list.size(); ++k)
    if (projected(list[k]) && list[k].b.kind != ConstraintEnd::Kind::particle)
      fixed_b[k] = end_b(list[k], t, x, x).first;
  result.converged = false;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    bool within = true;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const DistanceConstraint& c = list[k];
      if (!projected(c)) continue;
      const bool b_particle = c.b.kind == ConstraintEnd::Kind::particle;
      const Eigen::Vector3d b = b_particle ? Eigen::Vector3d(x.col(c.b.particle)) : fixed_b[k];
      const Eigen::Vector3d d = x.col(c.a) - b;
      const double l = d.norm();
      const double excess = l - c.length;  // m
      if (c.mode == ConstraintMode::rope && excess <= 0.0) continue;
      if (std::abs(excess) > c.tolerance * c.length) within = false;
      const double wa = inverse_mass[c.a];
      const double wb = b_particle ? inverse_mass[c.b.particle] : 0.0;
      if (wa + wb == 0.0 || !(l > 0.0) || excess == 0.0) continue;
      const Eigen::Vector3d step = (excess / ((wa + wb) * l)) * d;  // along n, per 1/kg
      x.col(c.a) -= wa * step;
      if (b_particle) x.col(c.b.particle) += wb * step;
      result.moved = true;
    }
    result.position_sweeps = sweep + 1;
    if (within) {
      result.converged = true;
      break;
    }
  }
  return result;
}

void DistanceConstraints::project_velocities(double t, double h,
                                             const Eigen::VectorXd& inverse_mass,
                                             const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v,
                                             ConstraintProjection& result) const {
  // Each constraint's direction and far end's velocity, fixed for the sweeps.
  struct Row {
    std::size_t k;
    Eigen::Vector3d n;
    Eigen::Vector3d b_velocity;  // m/s, a point's or collider point's (a particle's is read live)
  };
  std::vector<Row> rows;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const DistanceConstraint& c = list[k];
    if (!projected(c)) continue;
    const auto [b, vb] = end_b(c, t, x, v);
    const Eigen::Vector3d d = x.col(c.a) - b;
    const double l = d.norm();
    if (!(l > 0.0)) continue;
    // A rope acts only when taut: at its length, within its tolerance.
    if (c.mode == ConstraintMode::rope && l < c.length * (1.0 - c.tolerance)) continue;
    rows.push_back({k, d / l, vb});
  }
  result.velocity_sweeps = 0;
  for (int sweep = 0; sweep < max_sweeps && !rows.empty(); ++sweep) {
    bool within = true;
    for (const Row& row : rows) {
      const DistanceConstraint& c = list[row.k];
      const bool b_particle = c.b.kind == ConstraintEnd::Kind::particle;
      const Eigen::Vector3d vb = b_particle ? Eigen::Vector3d(v.col(c.b.particle)) : row.b_velocity;
      const double rate = (v.col(c.a) - vb).dot(row.n);  // m/s, > 0 lengthens
      if (c.mode == ConstraintMode::rope && rate <= 0.0) continue;
      if (std::abs(rate) > c.tolerance * c.length / h) within = false;
      const double wa = inverse_mass[c.a];
      const double wb = b_particle ? inverse_mass[c.b.particle] : 0.0;
      if (wa + wb == 0.0) continue;
      const Eigen::Vector3d impulse = (rate / (wa + wb)) * row.n;  // kg m/s
      v.col(c.a) -= wa * impulse;
      if (b_particle) v.col(c.b.particle) += wb * impulse;
    }
    result.velocity_sweeps = sweep + 1;
    if (within) break;
  }
}

double DistanceConstraints::largest_error(double t, const Eigen::Matrix3Xd& x) const {
  double largest = 0.0;
  for (const DistanceConstraint& c : list) {
    if (!projected(c)) continue;
    const double l = (x.col(c.a) - end_b(c, t, x, x).first).norm();
    const double error =
        c.mode == ConstraintMode::rope ? std::max(0.0, l - c.length) : std::abs(l - c.length);
    largest = std::max(largest, error / c.length);
  }
  return largest;
}

double DistanceConstraints::soft_energy(double t, const Eigen::Matrix3Xd& x) const {
  double energy = 0.0;
  for (const DistanceConstraint& c : list) {
    if (c.mode != ConstraintMode::soft || !acts(c, t)) continue;
    const double stretch = (x.col(particle_a(c)) - end_b(c, t, x, x).first).norm() - c.length_at(t);
    const double k = c.b.kind == ConstraintEnd::Kind::drag ? c.b.drag->stiffness : c.stiffness;
    energy += 0.5 * k * stretch * stretch;
  }
  return energy;
}

std::shared_ptr<const DistanceConstraints> constraints_on_own_bodies(
    std::shared_ptr<const DistanceConstraints> constraints,
    std::shared_ptr<const ColliderPoseTable> poses) {
  if (!constraints || !constraints->any_on_dynamic()) return constraints;
  auto own = std::make_shared<DistanceConstraints>(*constraints);
  own->poses = std::move(poses);
  return own;
}

}  // namespace drapelab
