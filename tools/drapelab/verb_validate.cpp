// drapelab validate SCENE: load and check a scene, print what it describes, run nothing.
#include <iostream>

#include "drapelab/continuum.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/scene/scene_loader.hpp"
#include "drapelab/scene/scene_writer.hpp"
#include "drapelab/spring_damper_solver.hpp"
#include "drapelab/stability.hpp"
#include "scene_warnings.hpp"
#include "verbs.hpp"

namespace drapelab::cli {

void add_validate_options(CLI::App& verb, ValidateArguments& arguments) {
  verb.add_option("scene", arguments.scene, "Scene file (YAML)")->required();
  verb.add_option(
      "--set", arguments.overrides,
      "Override a key before validation: key.path=value (list items by index: solvers.0.dt=1e-4)");
  verb.add_flag("--print-resolved", arguments.print_resolved,
                "Print the resolved scene (every default filled in) as YAML");
  verb.add_flag("--allow-start-inside", arguments.allow_start_inside,
                "Accept a cloth that starts inside or through a collider, with a warning (an error "
                "without it)");
  verb.footer(
      "Example:\n  drapelab validate scenes/curtain.yaml --set cloth.springs.stretch.ks=500\n"
      "Exit code 0 when the scene is valid, 2 with one line per problem otherwise.");
}

int validate_verb(const ValidateArguments& arguments) {
  const auto result = scene::load_scene_file(
      arguments.scene, arguments.overrides,
      arguments.allow_start_inside ? scene::StartInside::warning : scene::StartInside::error);
  if (!result.ok()) {
    for (const auto& error : result.errors) std::cerr << "error: " << error << "\n";
    return kExitBadInput;
  }
  for (const auto& note : result.notes) std::cerr << "note: " << note << "\n";
  for (const auto& warning : result.warnings) std::cerr << "warning: " << warning << "\n";
  const scene::Scene& s = *result.scene;
  if (arguments.print_resolved) {
    std::cout << scene::resolved_scene_yaml(s);
    return 0;
  }
  const ClothModel& model = *result.model;
  // s: symplectic Euler takes its contact force at the step's end, so its springs alone bound it.
  const double stable_step = stable_step_estimate(model, s.cloth.air_damping, s.contact_rates(),
                                                  Integrator::symplectic_euler);
  std::cout.precision(6);
  std::cout << arguments.scene << ": ok\n"
            << "  scene " << s.name << ": " << format_number(s.duration) << " s, "
            << s.frame_count() << " frames at " << format_number(s.frame_rate) << " frames/s\n"
            << "  cloth: " << model.particle_count() << " particles ("
            << (model.inverse_mass.array() == 0.0).count() << " pinned), " << model.springs.size()
            << " springs, " << model.triangles.cols() << " triangles, " << model.total_mass()
            << " kg\n";
  if (model.continuum) {
    const ContinuumParams& c = model.continuum->params;
    std::cout << "  cloth model: continuum (stretch modulus " << format_number(c.stretch_modulus)
              << " N/m, Poisson ratio " << format_number(c.poisson) << ", bending rigidity "
              << format_number(c.bending_rigidity) << " N*m, damping " << format_number(c.damping)
              << " s): " << model.continuum->triangle_count() << " membrane triangles, "
              << model.continuum->hinge_count()
              << " hinges; our solver uses them in place of the springs, which are derived from "
                 "them for the Bullet cloths and the metrics\n";
  } else {
    std::cout << "  cloth model: springs (the spring-damper network)\n";
  }
  std::cout << "  colliders: " << s.colliders.size() << "\n"
            << "  stable symplectic step (Gershgorin bound of "
            << (model.continuum ? "the membrane and hinges at rest, with their damping"
                                : "springs and dampers")
            << "; the contact, taken at the step's end, does not bound it): " << stable_step
            << " s\n";
  for (const auto& solver : s.solvers) {
    std::cout << "  solver " << solver.name << ": " << solver_type_name(solver.type);
    if (solver.type == SolverType::spring_damper)
      std::cout << ", " << integrator_name(solver.integrator);
    if (solver.type == SolverType::spring_damper && solver.integrator == Integrator::vbd)
      std::cout << " (" << solver.vbd.iterations << " sweeps per step, "
                << (solver.vbd.order == 2 ? "BDF2" : "backward Euler")
                << (solver.vbd.chebyshev_rho > 0.0
                        ? ", Chebyshev rho " + format_number(solver.vbd.chebyshev_rho)
                        : std::string())
                << ")";
    if (solver.type == SolverType::spring_damper && solver.integrator == Integrator::implicit_euler)
      std::cout << " (conjugate gradient to " << solver.implicit.tolerance << ", at most "
                << solver.implicit.max_iterations << " iterations per step)";
    if (solver.type == SolverType::bullet_softbody)
      std::cout << ", " << solver.iterations << " iteration(s)";
    if (solver.type == SolverType::mujoco)
      std::cout << ", particle radius " << solver.margin << " m, "
                << mujoco::constraint_solver_name(solver.mujoco.constraint_solver)
                << " constraint solver";
    else if (solver.type != SolverType::spring_damper)
      std::cout << ", margin " << solver.margin << " m, voxel " << solver.voxel_size << " m";
    std::cout << ", dt " << solver.dt << " s (" << solver.steps_per_frame << " steps per frame)";
    if (solver.estimated_seconds > 0.0)
      std::cout << ", about " << describe_seconds(solver.estimated_seconds) << " of wall time";
    std::cout << "\n";
    if (solver.type != SolverType::spring_damper || !solver.adaptive_substeps) continue;
    // The shape bound at the start; it is re-evaluated at every dt as the cloth moves.
    const double shape_step =
        shape_stable_step(model, scene::initial_scene_state(s, model).x, s.cloth.air_damping);
    const double safety = SpringDamperSettings{}.substep_safety;
    std::cout << "    adaptive substeps: " << safety << " x the shape's stable step, " << shape_step
              << " s at the start (" << std::ceil(solver.dt / (safety * shape_step))
              << " substeps per dt), re-evaluated at every dt\n";
  }
  for (const auto& warning : scene_warnings(s, model)) std::cerr << "warning: " << warning << "\n";
  return 0;
}

}  // namespace drapelab::cli
