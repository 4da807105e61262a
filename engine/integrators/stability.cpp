// Gershgorin bounds of the damped spring network (see stability.hpp).
#include "drapelab/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "drapelab/continuum.hpp"
#include "integrators/shape_bound.hpp"
#include "integrators/shape_bound_loops.hpp"

namespace drapelab {

namespace {

// The continuum elements' Gershgorin radii at the rest shape: per particle, the largest absolute
// row sum (N/m) of the projected Hessians of its elements over its three coordinate rows.
Eigen::VectorXd continuum_row_radii(const ClothModel& model) {
  const ContinuumElements& c = *model.continuum;
  Eigen::Matrix3Xd row_sums = Eigen::Matrix3Xd::Zero(3, model.particle_count());
  for (std::size_t t = 0; t < c.triangle_count(); ++t) {
    const auto hessian = triangle_terms(c, t, model.rest_positions).hessian;
    for (int r = 0; r < 9; ++r)
      row_sums(r % 3, c.triangle[t][r / 3]) += hessian.row(r).cwiseAbs().sum();
  }
  for (std::size_t e = 0; e < c.hinge_count(); ++e) {
    const auto hessian = hinge_terms(c, e, model.rest_positions).hessian;
    for (int r = 0; r < 12; ++r)
      row_sums(r % 3, c.hinge[e][r / 3]) += hessian.row(r).cwiseAbs().sum();
  }
  return row_sums.colwise().maxCoeff().transpose();
}

}  // namespace

NetworkRates network_rate_bounds(const ClothModel& model, double air_damping, ContactRates contact,
                                 const ParticleRates& extra) {
  // Row i of the stiffness matrix holds sum_j k_ij on the diagonal and -k_ij (times a direction
  // projector) off it, so its Gershgorin disc reaches 2 sum_j k_ij; the damping matrix likewise.
  // A continuum cloth's discs are its elements' Hessian rows at rest, and its damping is alpha
  // times its stiffness (at rest the stress is zero, so the Hessian is all material part).
  const int count = model.particle_count();
  Eigen::VectorXd row_stiffness = Eigen::VectorXd::Zero(count);  // N/m
  Eigen::VectorXd row_damping = Eigen::VectorXd::Zero(count);    // N*s/m
  if (model.uses_continuum()) {
    row_stiffness = continuum_row_radii(model);
    row_damping = model.continuum->params.damping * row_stiffness;
  } else {
    const SpringSet& s = model.springs;
    for (std::size_t e = 0; e < s.size(); ++e) {
      row_stiffness[s.v0[e]] += 2.0 * s.ks[e];
      row_stiffness[s.v1[e]] += 2.0 * s.ks[e];
      row_damping[s.v0[e]] += 2.0 * s.kd[e];
      row_damping[s.v1[e]] += 2.0 * s.kd[e];
    }
  }
  if (!extra.empty()) {
    row_stiffness += extra.stiffness;
    row_damping += extra.damping;
  }
  NetworkRates rates;
  for (int i = 0; i < count; ++i) {
    const double w = model.inverse_mass[i];  // 1/kg, 0 when pinned
    rates.stiffness = std::max(rates.stiffness, (row_stiffness[i] + contact.stiffness) * w);
    rates.damping = std::max(rates.damping, (row_damping[i] + contact.damping) * w);
  }
  rates.damping += air_damping;
  return rates;
}

NetworkRates shape_rate_bounds(const ClothModel& model, const Eigen::Matrix3Xd& x,
                               double air_damping, ContactRates contact,
                               ShapeBoundWorkspace& workspace,
                               const std::vector<SpringFamily>* families) {
  const int count = model.particle_count();
  if (families) {
    const kernels::ShapeRates maxima = kernels::family_shape_rate_maxima(
        count, *families, model.inverse_mass.data(), x.data(), contact.stiffness, contact.damping);
    return {maxima.stiffness, maxima.damping + air_damping};
  }
  const SpringSet& s = model.springs;
  if (workspace.first.size() != static_cast<std::size_t>(count) + 1) {
    // Each particle's springs in increasing index (a counting sort), built once per model.
    workspace.first.assign(static_cast<std::size_t>(count) + 1, 0);
    for (std::size_t e = 0; e < s.size(); ++e) {
      ++workspace.first[static_cast<std::size_t>(s.v0[e]) + 1];
      ++workspace.first[static_cast<std::size_t>(s.v1[e]) + 1];
    }
    for (int i = 0; i < count; ++i) workspace.first[i + 1] += workspace.first[i];
    workspace.incident.resize(2 * s.size());
    std::vector<std::int64_t> next(workspace.first.begin(), workspace.first.end() - 1);
    for (std::size_t e = 0; e < s.size(); ++e) {
      workspace.incident[next[s.v0[e]]++] = static_cast<std::int32_t>(e);
      workspace.incident[next[s.v1[e]]++] = static_cast<std::int32_t>(e);
    }
    workspace.terms.resize(8 * s.size());
  }
  const kernels::ShapeRates maxima = kernels::shape_rate_maxima(
      count, {workspace.first.data(), workspace.incident.data()},
      {s.v0.data(), s.v1.data(), s.rest_length.data(), s.ks.data(), s.kd.data()},
      model.inverse_mass.data(), x.data(), contact.stiffness, contact.damping,
      static_cast<std::int64_t>(s.size()), workspace.terms.data());
  return {maxima.stiffness, maxima.damping + air_damping};
}

double shape_stable_step(const ClothModel& model, const Eigen::Matrix3Xd& x, double air_damping,
                         ShapeBoundWorkspace& workspace,
                         const std::vector<SpringFamily>* families) {
  return step_from_rates(shape_rate_bounds(model, x, air_damping, {}, workspace, families),
                         Integrator::symplectic_euler, 0.0);
}

double shape_stable_step(const ClothModel& model, const Eigen::Matrix3Xd& x, double air_damping) {
  ShapeBoundWorkspace workspace;
  return shape_stable_step(model, x, air_damping, workspace);
}

namespace {

double symplectic_step_of_rates(const NetworkRates& r) {
  if (r.stiffness > 0.0)
    return (std::sqrt(r.damping * r.damping + 4.0 * r.stiffness) - r.damping) / r.stiffness;
  if (r.damping > 0.0) return 2.0 / r.damping;
  return std::numeric_limits<double>::infinity();
}

}  // namespace

double symplectic_euler_stable_step(const ClothModel& model, double air_damping,
                                    ContactRates contact) {
  return symplectic_step_of_rates(network_rate_bounds(model, air_damping, contact));
}

double step_from_rates(const NetworkRates& rates, Integrator integrator, double damping_ratio) {
  const double symplectic = symplectic_step_of_rates(rates);
  switch (integrator) {
    case Integrator::symplectic_euler:
    case Integrator::verlet:
    case Integrator::leapfrog:
      return symplectic;
    case Integrator::rk4:
      return 1.39 * symplectic;
    case Integrator::explicit_euler:
    case Integrator::midpoint:
      return std::min(damping_ratio, symplectic);
    case Integrator::implicit_euler:
    case Integrator::vbd:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

double damping_ratio_step(const ClothModel& model, ContactRates contact) {
  double smallest = std::numeric_limits<double>::infinity();  // s
  // Stiffness-proportional damping gives every continuum mode the same ratio c / w^2 = alpha.
  if (model.uses_continuum()) smallest = model.continuum->params.damping;
  const SpringSet no_springs;
  const SpringSet& s = model.uses_continuum() ? no_springs : model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    if (s.ks[e] <= 0.0) continue;
    if (model.is_pinned(s.v0[e]) && model.is_pinned(s.v1[e])) continue;  // never moves
    smallest = std::min(smallest, s.kd[e] / s.ks[e]);
  }
  if (contact.stiffness > 0.0) smallest = std::min(smallest, contact.damping / contact.stiffness);
  return smallest;
}

double stable_step_estimate(const ClothModel& model, double air_damping, ContactRates contact,
                            Integrator integrator, const ParticleRates& extra) {
  if (contact_at_step_end(integrator)) contact = {};  // the network alone bounds the step
  const bool ratio_bounds_step =
      integrator == Integrator::explicit_euler || integrator == Integrator::midpoint;
  return step_from_rates(network_rate_bounds(model, air_damping, contact, extra), integrator,
                         ratio_bounds_step ? damping_ratio_step(model, contact) : 0.0);
}

DefaultStep default_step(const ClothModel& model, Integrator integrator, bool adaptive_substeps,
                         double air_damping, ContactRates contact, const ParticleRates& extra) {
  DefaultStep chosen;
  if (adaptive_substeps) {
    chosen.step = kAdaptiveOuterStep;
    return chosen;
  }
  if (integrator == Integrator::implicit_euler) {
    chosen.step = kImplicitEulerDefaultStep;
    return chosen;
  }
  if (integrator == Integrator::vbd) {
    chosen.step = kVbdDefaultStep;
    return chosen;
  }
  chosen.from_stable_step = true;
  chosen.bound_integrator = integrator;
  chosen.bound = stable_step_estimate(model, air_damping, contact, integrator, extra);
  chosen.factor = 0.9;
  if (chosen.bound == 0.0) {  // an undamped spring: explicit Euler or midpoint has no stable step
    chosen.bound = symplectic_euler_stable_step(model, air_damping, contact);
    chosen.bound_integrator = Integrator::symplectic_euler;
    chosen.factor = 0.1;
  }
  chosen.step = chosen.factor * chosen.bound;
  return chosen;
}

}  // namespace drapelab
