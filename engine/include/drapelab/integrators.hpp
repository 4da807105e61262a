// Time integrators for the particle system M x'' = f(x, v). Pinned particles (inverse mass 0) keep
// their position and a zero velocity under every scheme.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace drapelab {

enum class Integrator {
  explicit_euler,    // v(n+1) = v(n) + a(n) h,  x(n+1) = x(n) + v(n) h      (classic Forward Euler)
  symplectic_euler,  // v(n+1) = v(n) + a(n) h,  x(n+1) = x(n) + v(n+1) h    (semi-implicit Euler)
};

const char* integrator_name(Integrator integrator);
std::optional<Integrator> parse_integrator(std::string_view name);
std::vector<std::string> integrator_names();

// One step of each scheme from the force at the start of the step (N, 3 x N).
void explicit_euler_update(const Eigen::VectorXd& inverse_mass, const Eigen::Matrix3Xd& force,
                           double h, Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v);
void symplectic_euler_update(const Eigen::VectorXd& inverse_mass, const Eigen::Matrix3Xd& force,
                             double h, Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v);

}  // namespace drapelab
