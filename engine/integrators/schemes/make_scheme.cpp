// Which scheme runs each integrator: a new integrator is one more case here.
#include "integrators/schemes/euler_schemes.hpp"
#include "integrators/schemes/implicit_schemes.hpp"

namespace drapelab {

std::unique_ptr<IntegratorScheme> make_scheme(const SchemeContext& context) {
  switch (context.settings.integrator) {
    case Integrator::explicit_euler:
    case Integrator::symplectic_euler:
      return std::make_unique<EulerScheme>(context);
    case Integrator::midpoint:
    case Integrator::rk4:
      return std::make_unique<StageScheme>(context);
    case Integrator::verlet:
    case Integrator::leapfrog:
      return std::make_unique<TwoLevelScheme>(context);
    case Integrator::implicit_euler:
      return std::make_unique<ImplicitEulerScheme>(context);
    case Integrator::vbd:
      return std::make_unique<VbdScheme>(context);
  }
  throw std::invalid_argument("an integrator without a scheme");
}

}  // namespace drapelab
