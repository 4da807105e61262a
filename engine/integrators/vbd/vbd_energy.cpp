// The mechanical energy vbd's step watches (vertex_block_descent.hpp): kinetic, gravity's, the
// springs' or the continuum's, and what the step's collider planes, collider features and offset
// self-contacts store. The sweeps keep going while a passive step's end holds more of it than
// its start did.
#include <cmath>

#include "forces/spring_force.hpp"
#include "integrators/vbd/vertex_block_descent.hpp"

namespace drapelab {

double VertexBlockDescent::mechanical_energy(const kernels::VbdProblem& problem,
                                             const Eigen::Vector3d& gravity,
                                             const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                             const OffsetContacts* self) const {
  const Eigen::Index n = x.cols();
  double kinetic = 0.0, potential = 0.0;  // J
  for (Eigen::Index i = 0; i < n; ++i) {
    kinetic += 0.5 * problem.mass[i] * v.col(i).squaredNorm();
    potential -= problem.mass[i] * gravity.dot(x.col(i));
  }
  // Each spring sits in both its ends' rows: half its energy from each.
  double springs = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (std::int32_t s = springs_.offsets[static_cast<std::size_t>(i)];
         s < springs_.offsets[static_cast<std::size_t>(i) + 1]; ++s)
      springs += spring_energy(x.col(i), x.col(springs_.other[static_cast<std::size_t>(s)]),
                               springs_.ks[static_cast<std::size_t>(s)],
                               springs_.rest_length[static_cast<std::size_t>(s)]);
  potential += 0.5 * springs;
  if (continuum_)
    potential += kernels::continuum_energy_sum(*continuum_, x.data(), nullptr, nullptr);
  // Collider planes and features: k depth^2 / 2 inside the thickness.
  const double k = contact_.stiffness;  // N/m
  for (Eigen::Index i = 0; i < n; ++i)
    for (int slot = 0; slot < plane_count_[static_cast<std::size_t>(i)]; ++slot) {
      const std::size_t e =
          static_cast<std::size_t>(i) * kPlaneSlots + static_cast<std::size_t>(slot);
      const double depth =
          contact_.radius - (x.col(i) - Eigen::Map<const Eigen::Vector3d>(&plane_point_[3 * e]))
                                .dot(Eigen::Map<const Eigen::Vector3d>(&plane_normal_[3 * e]));
      if (depth > 0.0) potential += 0.5 * k * depth * depth;
    }
  if (problem.features.offsets) {
    const auto position = [&](std::int32_t j) {
      return x.data() + 3 * static_cast<std::int64_t>(j);
    };
    for (std::size_t f = 0; f < features_.collider.size(); ++f) {
      kernels::FeatureGeometry g;
      if (kernels::feature_geometry(problem.features, static_cast<std::int64_t>(f), position,
                                    start_.data(), g) &&
          g.depth > 0.0)
        potential += 0.5 * k * g.depth * g.depth;
    }
  }
  if (self)
    potential +=
        offset_contact_totals(self->arrays(), x.data(), start_.data(), problem.h, 0.0).energy;
  return kinetic + potential;
}

bool VertexBlockDescent::passive_step(const ClothModel& model, const VbdStepInput& input) const {
  if (settings_.order != 1 || input.explicit_force ||
      (input.couplings && !input.couplings->empty()))
    return false;
  // A moving collider, or a pin a collider carries, does work on the cloth.
  for (std::size_t i = 0; i < plane_count_.size(); ++i)
    for (int slot = 0; slot < plane_count_[i]; ++slot)
      if (!Eigen::Map<const Eigen::Vector3d>(&plane_surface_move_[3 * (i * kPlaneSlots + slot)])
               .isZero(0))
        return false;
  for (double move : features_.surface_move)
    if (move != 0.0) return false;
  for (int i = 0; i < model.particle_count(); ++i)
    if (model.is_pinned(i) && !base_v_.col(i).isZero(0)) return false;
  return true;
}

double VertexBlockDescent::energy_slack(const Eigen::Vector3d& gravity, double energy) const {
  return 1e-5 * weight_height_ * gravity.norm() + 1e-9 * std::abs(energy);
}

}  // namespace drapelab
