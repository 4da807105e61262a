// The names of the Solver interface's enums, as scene files and outputs spell them.
#include "drapelab/solver.hpp"

namespace drapelab {

const char* solver_type_name(SolverType type) {
  switch (type) {
    case SolverType::spring_damper:
      return "spring_damper";
    case SolverType::bullet_softbody:
      return "bullet_softbody";
    case SolverType::bullet_deformable:
      return "bullet_deformable";
    case SolverType::mujoco:
      return "mujoco";
  }
  return "unknown";
}

std::optional<SolverType> parse_solver_type(std::string_view name) {
  for (const SolverType type : kSolverTypes)
    if (name == solver_type_name(type)) return type;
  return std::nullopt;
}

const char* solver_status_name(SolverStatus status) {
  switch (status) {
    case SolverStatus::ok:
      return "ok";
    case SolverStatus::unstable:
      return "unstable";
    case SolverStatus::error:
      return "error";
  }
  return "unknown";
}

}  // namespace drapelab
