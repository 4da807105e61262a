// Integrator names and properties. The schemes themselves are in schemes/.
#include "drapelab/integrators.hpp"

#include <cmath>
#include <limits>

namespace drapelab {

std::vector<Integrator> all_integrators() {
  return {Integrator::explicit_euler, Integrator::symplectic_euler,
          Integrator::midpoint,       Integrator::rk4,
          Integrator::verlet,         Integrator::leapfrog,
          Integrator::implicit_euler, Integrator::vbd};
}

const char* integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::explicit_euler:
      return "explicit_euler";
    case Integrator::symplectic_euler:
      return "symplectic_euler";
    case Integrator::midpoint:
      return "midpoint";
    case Integrator::rk4:
      return "rk4";
    case Integrator::verlet:
      return "verlet";
    case Integrator::leapfrog:
      return "leapfrog";
    case Integrator::implicit_euler:
      return "implicit_euler";
    case Integrator::vbd:
      return "vbd";
  }
  return "unknown";
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (Integrator integrator : all_integrators()) names.emplace_back(integrator_name(integrator));
  return names;
}

std::optional<Integrator> parse_integrator(std::string_view name) {
  for (Integrator integrator : all_integrators())
    if (name == integrator_name(integrator)) return integrator;
  return std::nullopt;
}

int force_evaluations_per_step(Integrator integrator) {
  switch (integrator) {
    case Integrator::midpoint:
      return 2;
    case Integrator::rk4:
      return 4;
    default:
      return 1;  // leapfrog reuses the end-of-step force as the next step's first kick
  }
}

int order_of_accuracy(Integrator integrator) {
  switch (integrator) {
    case Integrator::midpoint:
    case Integrator::verlet:
    case Integrator::leapfrog:
      return 2;
    case Integrator::rk4:
      return 4;
    default:
      return 1;
  }
}

double undamped_stability_limit(Integrator integrator) {
  switch (integrator) {
    case Integrator::symplectic_euler:
    case Integrator::verlet:
    case Integrator::leapfrog:
      return 2.0;
    case Integrator::rk4:
      return 2.0 * std::sqrt(2.0);
    case Integrator::implicit_euler:
    case Integrator::vbd:
      return std::numeric_limits<double>::infinity();
    default:
      return 0.0;
  }
}

}  // namespace drapelab
