// Gershgorin bounds of the damped spring network (see stability.hpp).
#include "drapelab/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace drapelab {

NetworkRates network_rate_bounds(const ClothModel& model, double air_damping, ContactRates contact) {
  // Row i of the stiffness matrix holds sum_j k_ij on the diagonal and -k_ij (times a direction
  // projector) off it, so its Gershgorin disc reaches 2 sum_j k_ij; the damping matrix likewise.
  const int count = model.particle_count();
  Eigen::VectorXd row_stiffness = Eigen::VectorXd::Zero(count);  // N/m
  Eigen::VectorXd row_damping = Eigen::VectorXd::Zero(count);    // N*s/m
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    row_stiffness[s.v0[e]] += s.ks[e];
    row_stiffness[s.v1[e]] += s.ks[e];
    row_damping[s.v0[e]] += s.kd[e];
    row_damping[s.v1[e]] += s.kd[e];
  }
  NetworkRates rates;
  for (int i = 0; i < count; ++i) {
    const double w = model.inverse_mass[i];  // 1/kg, 0 when pinned
    rates.stiffness = std::max(rates.stiffness, (2.0 * row_stiffness[i] + contact.stiffness) * w);
    rates.damping = std::max(rates.damping, (2.0 * row_damping[i] + contact.damping) * w);
  }
  rates.damping += air_damping;
  return rates;
}

double largest_symmetric_eigenvalue(double a, double b, double c, double d, double e, double f) {
  // With q the mean eigenvalue and B = (A - q I) / p scaled to unit spread, the eigenvalues are
  // q + 2 p t for the roots t of 4 t^3 - 3 t = det(B) / 2 = r (cos 3 phi = 4 cos^3 phi - 3 cos phi, so
  // t = cos(acos(r) / 3) is the largest). Without trigonometric functions: at t = 1/2 + s the cubic is
  // 6 s^2 + 4 s^3 = 1 + r, so 1/2 + sqrt((1 + r) / 6) (and 1) lie above the root, and Newton's method
  // on this cubic, convex above its largest root, descends to it from there.
  const double off = d * d + e * e + f * f;
  const double q = (a + b + c) / 3.0;
  const double spread = (a - q) * (a - q) + (b - q) * (b - q) + (c - q) * (c - q) + 2.0 * off;
  if (spread <= 0.0) return q;  // a multiple of the identity
  const double p = std::sqrt(spread / 6.0);
  const double ba = (a - q) / p, bb = (b - q) / p, bc = (c - q) / p;
  const double bd = d / p, be = e / p, bf = f / p;
  const double det = ba * (bb * bc - bf * bf) - bd * (bd * bc - bf * be) + be * (bd * bf - bb * be);
  const double r = std::clamp(0.5 * det, -1.0, 1.0);
  double t = std::min(1.0, 0.5 + std::sqrt((1.0 + r) / 6.0));
  for (int k = 0; k < 3; ++k) {
    const double excess = 4.0 * t * t * t - 3.0 * t - r;  // > 0 above the root
    const double slope = 12.0 * t * t - 3.0;              // > 0 for t > 1/2
    if (!(excess > 0.0 && slope > 0.0)) break;            // at the root, to rounding
    t -= excess / slope;
  }
  const double largest = q + 2.0 * p * t;
  return largest + 1e-9 * std::abs(largest);
}

NetworkRates shape_rate_bounds(const ClothModel& model, const Eigen::Matrix3Xd& x, double air_damping,
                               ContactRates contact, Eigen::Matrix<double, 12, Eigen::Dynamic>& tensors) {
  const int count = model.particle_count();
  if (tensors.cols() != count) tensors.resize(12, count);
  tensors.setZero();  // rows 0-5: S_i (xx, yy, zz, xy, xz, yz) in N/m; rows 6-11: D_i in N*s/m
  const SpringSet& s = model.springs;
  const double* position = x.data();
  double* tensor = tensors.data();
  for (std::size_t e = 0; e < s.size(); ++e) {
    const int i = s.v0[e], j = s.v1[e];
    const double dx = position[3 * i] - position[3 * j];
    const double dy = position[3 * i + 1] - position[3 * j + 1];
    const double dz = position[3 * i + 2] - position[3 * j + 2];
    const double squared = dx * dx + dy * dy + dz * dz;  // m^2
    double term[12];  // the spring's ks [u u^T + across (I - u u^T)], then kd u u^T, packed as the tensors
    if (squared > 0.0) {
      const double inverse_length = 1.0 / std::sqrt(squared);  // 1/m
      const double ux = dx * inverse_length, uy = dy * inverse_length, uz = dz * inverse_length;
      const double across = std::max(0.0, 1.0 - s.rest_length[e] * inverse_length);  // per ks
      const double along = s.ks[e] * (1.0 - across);  // N/m, on u u^T once the across part is split off
      const double isotropic = s.ks[e] * across;      // N/m, on I
      const double uu[6] = {ux * ux, uy * uy, uz * uz, ux * uy, ux * uz, uy * uz};
      for (int k = 0; k < 6; ++k) {
        term[k] = along * uu[k] + (k < 3 ? isotropic : 0.0);
        term[6 + k] = s.kd[e] * uu[k];
      }
    } else {  // no direction: count it as stiff and damped in every direction
      for (int k = 0; k < 6; ++k) {
        term[k] = k < 3 ? s.ks[e] : 0.0;
        term[6 + k] = k < 3 ? s.kd[e] : 0.0;
      }
    }
    for (int k = 0; k < 12; ++k) {
      tensor[12 * i + k] += term[k];
      tensor[12 * j + k] += term[k];
    }
  }
  NetworkRates rates;
  for (int i = 0; i < count; ++i) {
    const double w = model.inverse_mass[i];  // 1/kg, 0 when pinned
    if (w == 0.0) continue;
    const double* t = tensors.col(i).data();
    const double stiffness = largest_symmetric_eigenvalue(t[0], t[1], t[2], t[3], t[4], t[5]);
    const double damping = largest_symmetric_eigenvalue(t[6], t[7], t[8], t[9], t[10], t[11]);
    rates.stiffness = std::max(rates.stiffness, (2.0 * stiffness + contact.stiffness) * w);
    rates.damping = std::max(rates.damping, (2.0 * damping + contact.damping) * w);
  }
  rates.damping += air_damping;
  return rates;
}

namespace {

double symplectic_step_of_rates(const NetworkRates& r) {
  if (r.stiffness > 0.0) return (std::sqrt(r.damping * r.damping + 4.0 * r.stiffness) - r.damping) / r.stiffness;
  if (r.damping > 0.0) return 2.0 / r.damping;
  return std::numeric_limits<double>::infinity();
}

}  // namespace

double symplectic_euler_stable_step(const ClothModel& model, double air_damping, ContactRates contact) {
  return symplectic_step_of_rates(network_rate_bounds(model, air_damping, contact));
}

double step_from_rates(const NetworkRates& rates, Integrator integrator, double damping_ratio) {
  const double symplectic = symplectic_step_of_rates(rates);
  switch (integrator) {
    case Integrator::symplectic_euler:
    case Integrator::verlet:
    case Integrator::leapfrog: return symplectic;
    case Integrator::rk4: return 1.39 * symplectic;
    case Integrator::explicit_euler:
    case Integrator::midpoint: return std::min(damping_ratio, symplectic);
    case Integrator::implicit_euler: break;
  }
  return std::numeric_limits<double>::infinity();
}

double damping_ratio_step(const ClothModel& model, ContactRates contact) {
  double smallest = std::numeric_limits<double>::infinity();  // s
  const SpringSet& s = model.springs;
  for (std::size_t e = 0; e < s.size(); ++e) {
    if (s.ks[e] <= 0.0) continue;
    if (model.is_pinned(s.v0[e]) && model.is_pinned(s.v1[e])) continue;  // never moves
    smallest = std::min(smallest, s.kd[e] / s.ks[e]);
  }
  if (contact.stiffness > 0.0) smallest = std::min(smallest, contact.damping / contact.stiffness);
  return smallest;
}

double stable_step_estimate(const ClothModel& model, double air_damping, ContactRates contact,
                            Integrator integrator) {
  if (contact_at_step_end(integrator)) contact = {};  // the network alone bounds the step
  const bool ratio_bounds_step = integrator == Integrator::explicit_euler || integrator == Integrator::midpoint;
  return step_from_rates(network_rate_bounds(model, air_damping, contact), integrator,
                         ratio_bounds_step ? damping_ratio_step(model, contact) : 0.0);
}

}  // namespace drapelab
