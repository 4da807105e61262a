// Explicit integrators. Acceleration a = f / m with the model's inverse masses; a pinned particle
// (inverse mass 0) gets a = 0 and, starting at rest, never moves.
#include "drapelab/integrators.hpp"

namespace drapelab {

const char* integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::explicit_euler: return "explicit_euler";
    case Integrator::symplectic_euler: return "symplectic_euler";
  }
  return "unknown";
}

std::vector<std::string> integrator_names() { return {"explicit_euler", "symplectic_euler"}; }

std::optional<Integrator> parse_integrator(std::string_view name) {
  if (name == "explicit_euler") return Integrator::explicit_euler;
  if (name == "symplectic_euler") return Integrator::symplectic_euler;
  return std::nullopt;
}

void explicit_euler_update(const Eigen::VectorXd& inverse_mass, const Eigen::Matrix3Xd& force,
                           double h, Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v) {
  x.noalias() += h * v;                                  // x(n+1) = x(n) + v(n) h
  v.noalias() += h * (force * inverse_mass.asDiagonal());  // v(n+1) = v(n) + a(n) h
}

void symplectic_euler_update(const Eigen::VectorXd& inverse_mass, const Eigen::Matrix3Xd& force,
                             double h, Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v) {
  v.noalias() += h * (force * inverse_mass.asDiagonal());  // v(n+1) = v(n) + a(n) h
  x.noalias() += h * v;                                  // x(n+1) = x(n) + v(n+1) h
}

}  // namespace drapelab
