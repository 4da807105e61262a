// Solvers: type, integrator, step (given, rounded or automatic) and Bullet options.
#include "solver_reader.hpp"

#include <cmath>
#include <cstdint>
#include <set>

#include "drapelab/bullet/parameter_mapping.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/stability.hpp"
#include "run_limits.hpp"
#include "scene_keys.hpp"
#include "step_rates.hpp"
#include "text_checks.hpp"
#include "value_ranges.hpp"

namespace drapelab::scene {
namespace {

class SolverReader {
 public:
  SolverReader(SceneReader& r, const Scene& scene, const ClothModel* model,
               std::vector<std::string>& notes)
      : r_(r), scene_(scene), model_(model), notes_(notes) {}

  std::optional<SolverSpec> read(const YAML::Node& node, const std::string& path) {
    // The type decides which keys are valid, so read it first.
    SolverType type = SolverType::spring_damper;
    record_key_lines(r_, node, path);
    if (node.IsMap() && node["type"].IsDefined()) {
      const auto chosen =
          r_.choice(node["type"], path + ".type", key_choices(key("solvers[].type")));
      if (!chosen) return std::nullopt;
      type = *parse_solver_type(*chosen);
    }
    MapReader solver(r_, node, path, key_names("solvers[]", solver_type_name(type)));
    if (!solver.valid()) return std::nullopt;
    const std::size_t errors_before = r_.error_count();
    SolverSpec spec;
    spec.type = type;
    spec.name = solver.text("name", solver_type_name(type)).value_or(solver_type_name(type));
    if (const auto problem = name_problem(spec.name))
      r_.error(solver.get("name"), path + ".name", *problem);
    if (type == SolverType::spring_damper) {
      read_integrator(solver, path, spec);
      const bool cloth_continuum = scene_.cloth.grid.continuum.has_value();
      const std::string model = cloth_continuum ? "continuum" : "springs";  // the cloth's
      spec.continuum = solver.choice(key("solvers[].model"), model).value_or(model) == "continuum";
      if (spec.continuum && model_ && model_->triangles.cols() == 0)
        r_.error(solver.get("model"), path + ".model",
                 "is continuum, which needs a two-dimensional cloth; this cloth is a chain, with "
                 "no triangles: use model: springs");
      // A plugin in a Bullet world (default), or stepped bare, without Bullet.
      const std::string host = default_choice(key("solvers[].host"));
      spec.bullet_host = solver.choice(key("solvers[].host")).value_or(host) == "bullet";
      read_adaptive_substeps(solver, path, spec);
    } else if (type == SolverType::mujoco)
      read_mujoco_options(solver, spec);
    else
      read_bullet_options(solver, spec);
    const double frame_period = scene_.frame_period();
    if (solver.has("dt"))
      spec.dt = solver.number(key("solvers[].dt"), std::nullopt).value_or(frame_period);
    else
      spec.dt = automatic_step(spec);
    estimate_cost(spec);
    spec.round_dt = solver.boolean(key("solvers[].round_dt")).value_or(false);
    const double free_fall_speed = scene_.gravity.norm() * std::max(scene_.duration, 0.0);  // m/s
    const double default_max_speed = 100.0 + 2.0 * free_fall_speed;
    spec.max_speed =
        solver.number(key("solvers[].max_speed"), default_max_speed).value_or(default_max_speed);
    const double runaway_stretch = default_number(key("solvers[].runaway_stretch"));
    spec.runaway_stretch =
        solver.number(key("solvers[].runaway_stretch")).value_or(runaway_stretch);
    if (r_.error_count() != errors_before) return std::nullopt;
    if (!whole_steps_per_frame(solver, path, spec)) return std::nullopt;
    if (type == SolverType::mujoco && model_ && !fill_mujoco_defaults(solver, path, spec))
      return std::nullopt;
    return spec;
  }

 private:
  void read_integrator(MapReader& solver, const std::string& path, SolverSpec& spec) {
    spec.integrator_named = solver.has("integrator");
    if (solver.has("integrator"))
      if (const auto name = r_.choice(solver.get("integrator"), path + ".integrator",
                                      key_choices(key("solvers[].integrator"))))
        spec.integrator = *parse_integrator(*name);
    read_vbd(solver, path, spec);
    if (!solver.has("implicit")) return;
    if (spec.integrator != Integrator::implicit_euler) {
      r_.error(solver.get("implicit"), path + ".implicit",
               "applies only to integrator: implicit_euler (this solver uses " +
                   std::string(integrator_name(spec.integrator)) + ")");
      return;
    }
    MapReader implicit(r_, solver.get("implicit"), solver.path_of("implicit"),
                       key_names("solvers[].implicit"));
    if (!implicit.valid()) return;
    const ImplicitSolveSettings defaults;  // the table's (test_scene_keys.cpp)
    spec.implicit.tolerance =
        implicit.number(key("solvers[].implicit.tolerance")).value_or(defaults.tolerance);
    spec.implicit.max_iterations =
        static_cast<int>(implicit.integer(key("solvers[].implicit.max_iterations"))
                             .value_or(defaults.max_iterations));
  }

  void read_vbd(MapReader& solver, const std::string& path, SolverSpec& spec) {
    if (!solver.has("vbd")) return;
    if (spec.integrator != Integrator::vbd) {
      r_.error(solver.get("vbd"), path + ".vbd",
               "applies only to integrator: vbd (this solver uses " +
                   std::string(integrator_name(spec.integrator)) + ")");
      return;
    }
    MapReader vbd(r_, solver.get("vbd"), solver.path_of("vbd"), key_names("solvers[].vbd"));
    if (!vbd.valid()) return;
    const VbdSettings defaults;  // the table's (test_scene_keys.cpp)
    spec.vbd.iterations = static_cast<int>(
        vbd.integer(key("solvers[].vbd.iterations")).value_or(defaults.iterations));
    spec.vbd.order =
        static_cast<int>(vbd.integer(key("solvers[].vbd.order")).value_or(defaults.order));
    spec.vbd.coarse_correction =
        vbd.boolean(key("solvers[].vbd.coarse")).value_or(defaults.coarse_correction);
    spec.vbd.chebyshev_rho =
        vbd.number(key("solvers[].vbd.chebyshev_rho")).value_or(defaults.chebyshev_rho);
    spec.vbd.friction_velocity =
        vbd.number(key("solvers[].vbd.friction_velocity")).value_or(defaults.friction_velocity);
  }

  // Adaptive substeps follow symplectic Euler's stable step as the shape changes: its damped
  // stability condition is exact, where the other schemes' differ (SpringDamperSettings). The
  // bound is built from the springs, so the continuum model, which our solver uses in their place,
  // has none.
  void read_adaptive_substeps(MapReader& solver, const std::string& path, SolverSpec& spec) {
    spec.adaptive_substeps = solver.boolean(key("solvers[].adaptive_substeps")).value_or(false);
    if (spec.adaptive_substeps && spec.integrator != Integrator::symplectic_euler)
      r_.error(solver.get("adaptive_substeps"), path + ".adaptive_substeps",
               "needs integrator symplectic_euler, whose stable step the shape bound gives exactly "
               "(this solver "
               "uses " +
                   std::string(integrator_name(spec.integrator)) + ")");
    else if (spec.adaptive_substeps && spec.continuum)
      r_.error(solver.get("adaptive_substeps"), path + ".adaptive_substeps",
               "cannot be used with the continuum model: the shape's stable step is built from "
               "the springs, which this solver does not use; set adaptive_substeps: false, with a "
               "fixed dt or none (the automatic step), or give the solver model: springs");
  }

  // Bullet's cloths: soft margin = thickness, voxel small enough
  // (docs/bullet.md, "Fairness table" and "Mapping our parameters to the classic cloth").
  void read_bullet_options(MapReader& solver, SolverSpec& spec) {
    if (spec.type == SolverType::bullet_softbody)
      spec.iterations =
          static_cast<int>(solver.integer(key("solvers[].iterations"))
                               .value_or(default_integer(key("solvers[].iterations"))));
    const double thickness = scene_.cloth.grid.thickness;  // every shape's thickness lives in grid
    spec.margin = solver.number(key("solvers[].margin"), thickness).value_or(thickness);
    const double collider_margin = default_number(key("solvers[].collider_margin"));
    spec.collider_margin =
        solver.number(key("solvers[].collider_margin")).value_or(collider_margin);
    const double voxel = bullet::default_voxel_size(scene_.colliders, spec.margin);
    spec.voxel_size = solver.number(key("solvers[].voxel_size"), voxel).value_or(voxel);
    if (!solver.has("kLST")) return;
    MapReader raw(r_, solver.get("kLST"), solver.path_of("kLST"), key_names("solvers[].kLST"));
    if (!raw.valid()) return;
    // In the order of link_stiffness: stretch, shear, bend.
    const SceneKey* kinds[] = {&key("solvers[].kLST.stretch"), &key("solvers[].kLST.shear"),
                               &key("solvers[].kLST.bend")};
    for (int k = 0; k < 3; ++k)
      if (raw.has(std::string(kinds[k]->name()))) spec.link_stiffness[k] = raw.number(*kinds[k]);
  }

  // MuJoCo (docs/mujoco.md): the particles' radius is the cloth's thickness, as Bullet's margin.
  void read_mujoco_options(MapReader& solver, SolverSpec& spec) {
    const double thickness = scene_.cloth.grid.thickness;
    spec.margin = solver.number(key("solvers[].margin"), thickness).value_or(thickness);
    mujoco::MujocoSettings& m = spec.mujoco;
    if (const auto name = solver.choice(key("solvers[].constraint_solver")))
      for (const auto candidate :
           {mujoco::ConstraintSolver::automatic, mujoco::ConstraintSolver::newton,
            mujoco::ConstraintSolver::cg, mujoco::ConstraintSolver::pgs})
        if (*name == mujoco::constraint_solver_name(candidate)) m.constraint_solver = candidate;
    m.solver_iterations = static_cast<int>(
        solver.integer(key("solvers[].solver_iterations")).value_or(m.solver_iterations));
    m.tolerance = solver.number(key("solvers[].tolerance")).value_or(m.tolerance);
    m.impratio = solver.number(key("solvers[].impratio")).value_or(m.impratio);
    m.max_contacts =
        static_cast<int>(solver.integer(key("solvers[].max_contacts")).value_or(m.max_contacts));
  }

  // MuJoCo's derived numerics, which resolved.yaml records: the friction's impedance ratio at the
  // step chosen, and the contacts it makes room for (docs/mujoco.md).
  // False, with an error, when MuJoCo could not hold the model: Newton's dense stack beyond the
  // int MuJoCo 2.2 sizes it with.
  bool fill_mujoco_defaults(MapReader& solver, const std::string& path, SolverSpec& spec) {
    mujoco::MujocoSettings& m = spec.mujoco;
    if (!(m.impratio > 0.0))
      m.impratio = mujoco::friction_impratio(scene_.contact.damping,
                                             mujoco::mean_free_mass(*model_), spec.dt);
    std::int64_t free_particles = 0;
    for (int i = 0; i < model_->particle_count(); ++i)
      if (!model_->is_pinned(i)) ++free_particles;
    std::int64_t dofs = 3 * free_particles, bodies = 1 + free_particles;
    for (const Collider& collider : scene_.colliders)
      if (collider.moves()) {
        dofs += 6;
        ++bodies;
      }
    if (!(m.max_contacts > 0))
      m.max_contacts = static_cast<int>(mujoco::contact_capacity(0, free_particles, dofs));
    const auto chosen = mujoco::chosen_solver(m.constraint_solver, static_cast<int>(dofs));
    if (mujoco::stack_size(m.max_contacts, dofs, bodies, chosen) <= INT32_MAX) return true;
    const bool newton = chosen == mujoco::ConstraintSolver::newton;
    r_.error(solver.get("type"), path + ".type",
             "is mujoco, whose stack for " + std::to_string(bodies) + " bodies and " +
                 std::to_string(dofs) + " degrees of freedom (the broadphase's bodies^2 / 2 pairs" +
                 (newton ? std::string(" and Newton's dense 4 nv^2") : std::string()) +
                 ") is over the 2^31 numbers MuJoCo 2.2 can size; use fewer particles" +
                 (newton ? std::string(", or constraint_solver: cg") : std::string()),
             solver.node());
    return false;
  }

  // Without a dt: our solver takes the step its integrator asks for (default_step,
  // stability.hpp): its own default, or a share of its stable step estimate on the springs,
  // dampers, contact and the forces between particles. Bullet's classic cloth takes the step where
  // its stiffness mapping holds, ks w h^2 = 0.1; the deformable cloth 0.9 of its explicit springs'
  // stable step. All are rounded down to a whole number of steps per frame.
  double automatic_step(SolverSpec& spec) {
    const double frame_period = scene_.frame_period();
    if (!model_ || r_.error_count() > 0) return frame_period;  // the scene is refused anyway
    // The cloth as this solver runs it: with or without the continuum's elements.
    const std::shared_ptr<const ClothModel> own = cloth_for_solver(
        scene_, spec,
        std::shared_ptr<const ClothModel>(std::shared_ptr<const ClothModel>(), model_));
    const ClothModel& model = *own;
    double target = frame_period;
    std::string reason;
    if (spec.type == SolverType::bullet_softbody) {
      target = std::min(target, bullet::largest_mapped_step(model));
      reason = "where ks w h^2 = " + format_number(bullet::kMaxMappedLinkCompliance) +
               ", the limit of the stiffness mapping";
    } else if (spec.type == SolverType::bullet_deformable) {
      // Its elastic force is explicit and its damping implicit: the springs alone bound the step.
      const double stiffness = network_rate_bounds(model, 0.0).stiffness;  // 1/s^2
      if (stiffness > 0.0) target = 0.9 * 2.0 / std::sqrt(stiffness);
      reason = "0.9 x the stable step of its explicit springs";
    } else if (spec.type == SolverType::mujoco) {
      // Our springs and MuJoCo's contact springs are explicit; its air damping is implicit.
      const double stable =
          stable_step_estimate(model, 0.0, scene_.contact_rates(), Integrator::verlet,
                               explicit_particle_rates(scene_, model));
      if (std::isfinite(stable)) target = std::min(target, 0.9 * stable);
      reason = "0.9 x the stable step of its explicit springs and contact springs";
    } else {
      const DefaultStep chosen =
          default_step(model, spec.integrator, spec.adaptive_substeps, scene_.cloth.air_damping,
                       scene_.contact_rates(), explicit_particle_rates(scene_, model));
      target = chosen.step;
      reason = default_step_reason(spec, chosen);
    }
    const double steps = std::max(1.0, std::ceil(frame_period / target));
    spec.note =
        "dt chosen automatically: " + format_number(steps) + " steps per frame (" + reason + ")";
    const double dt = frame_period / steps;
    if (spec.type == SolverType::spring_damper && !spec.integrator_named && !spec.adaptive_substeps)
      return choose_integrator(spec, model, dt);
    return dt;
  }

  // Why the engine's default step is what it is, for the resolved scene's note.
  static std::string default_step_reason(const SolverSpec& spec, const DefaultStep& chosen) {
    if (chosen.from_stable_step)
      return format_number(chosen.factor) + " x the " + integrator_name(spec.integrator) +
             " stable step estimate " + format_number(chosen.bound) + " s";
    if (spec.adaptive_substeps)
      return "1/120 s: the solver splits each step into the substeps its current shape needs";
    if (spec.integrator == Integrator::implicit_euler) return "implicit Euler's default of 1/240 s";
    return "vbd's default of 1/120 s with " + std::to_string(spec.vbd.iterations) +
           " sweeps per step";
  }

  // No integrator named and no dt: symplectic Euler at its stable step, unless that would take over
  // a minute and more than four times as long as vbd at its own step, which then takes the scene
  // (it is unconditionally stable; implicit Euler, also, costs about five times vbd at the
  // scenes of scenes/). Returns the step of the method chosen.
  double choose_integrator(SolverSpec& spec, const ClothModel& model, double explicit_dt) {
    SolverSpec explicit_run = spec;
    explicit_run.dt = explicit_dt;
    const double explicit_seconds = estimated_wall_seconds(model, explicit_run, scene_.duration);
    const double vbd_seconds = vbd_estimate(spec, model);
    if (explicit_seconds <= 60.0 || explicit_seconds <= 4.0 * vbd_seconds) return explicit_dt;
    const double frame_period = scene_.frame_period();
    const double steps = std::max(1.0, std::ceil(frame_period / kVbdDefaultStep));
    spec.integrator = Integrator::vbd;
    spec.note = "integrator chosen automatically: vbd, " + format_number(steps) +
                " steps per frame with " + std::to_string(spec.vbd.iterations) +
                " sweeps each (symplectic_euler's stable step of " + format_number(explicit_dt) +
                " s would take about " + describe_seconds(explicit_seconds) + "; vbd about " +
                describe_seconds(vbd_seconds) + ")";
    return frame_period / steps;
  }

  // The run's estimated wall time, and, for an explicit run of over ten minutes, the faster choice.
  void estimate_cost(SolverSpec& spec) {
    if (!model_ || !(spec.dt > 0.0)) return;
    spec.estimated_seconds = estimated_wall_seconds(*model_, spec, scene_.duration);
    if (spec.type != SolverType::spring_damper || spec.estimated_seconds <= 600.0) return;
    if (spec.integrator == Integrator::vbd || spec.integrator == Integrator::implicit_euler) return;
    spec.faster_choice =
        "integrator: vbd without a dt, about " + describe_seconds(vbd_estimate(spec, *model_));
  }

  // The estimated wall time (s) of `spec` run by vbd at its default step.
  double vbd_estimate(const SolverSpec& spec, const ClothModel& model) const {
    SolverSpec vbd_run = spec;
    vbd_run.integrator = Integrator::vbd;
    vbd_run.dt = kVbdDefaultStep;
    return estimated_wall_seconds(model, vbd_run, scene_.duration);
  }

  bool whole_steps_per_frame(MapReader& solver, const std::string& path, SolverSpec& spec) {
    const double frame_period = scene_.frame_period();
    if (spec.dt > frame_period * (1.0 + 1e-12)) {
      r_.error(solver.get("dt"), path + ".dt",
               "must not exceed the frame period 1/frame_rate = " + format_number(frame_period) +
                   " s, got " + format_number(spec.dt));
      return false;
    }
    if (frame_period / spec.dt > kMaxStepsPerFrame) {  // before any count is cast to int
      r_.error(solver.get("dt"), path + ".dt",
               too_many_steps_message(frame_period, spec.dt, !solver.has("dt")), solver.node());
      return false;
    }
    const double steps = frame_period / spec.dt;
    const double whole = std::round(steps);
    if (std::abs(steps - whole) <= 1e-9 * steps) {
      spec.steps_per_frame = static_cast<int>(whole);
      if (!spec.note.empty()) notes_.push_back("solver '" + spec.name + "': " + spec.note);
      return true;
    }
    if (spec.round_dt) {
      spec.steps_per_frame = static_cast<int>(std::ceil(steps));
      const double rounded = frame_period / spec.steps_per_frame;
      spec.note = "dt rounded from " + format_number(spec.dt) + " s to " + format_number(rounded) +
                  " s (" + std::to_string(spec.steps_per_frame) + " steps per frame)";
      notes_.push_back("solver '" + spec.name + "': " + spec.note);
      spec.dt = rounded;
      return true;
    }
    r_.error(solver.get("dt"), path + ".dt",
             "must divide the frame period 1/frame_rate = " + format_number(frame_period) +
                 " s into whole steps, got " + format_number(spec.dt) + " (" +
                 format_number(steps) +
                 " steps per frame); try dt = " + format_number(frame_period / std::ceil(steps)) +
                 ", or set round_dt: true on this solver");
    return false;
  }

  SceneReader& r_;
  const Scene& scene_;
  const ClothModel* model_;  // the scene's cloth, null when refused
  std::vector<std::string>& notes_;
};

}  // namespace

std::vector<SolverSpec> read_solvers(SceneReader& reader, const YAML::Node& list,
                                     const Scene& scene, const ClothModel* model,
                                     std::vector<std::string>& notes) {
  std::vector<SolverSpec> solvers;
  if (!list.IsSequence() || list.size() == 0) {
    reader.error(list, "solvers",
                 "must be a non-empty list of solvers, got " + describe_scalar(list));
    return solvers;
  }
  record_item_lines(reader, list, "solvers");
  SolverReader solver_reader(reader, scene, model, notes);
  std::set<std::string> names;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string path = "solvers." + std::to_string(k);
    auto solver = solver_reader.read(list[k], path);
    if (!solver) continue;
    if (!names.insert(solver->name).second) {
      const YAML::Node& item = list[k];
      const YAML::Node at =
          item["name"].IsDefined() ? item["name"] : item;  // a default name: the item
      reader.error(
          at, path + ".name",
          "'" + solver->name + "' is already used by another solver; names must be unique");
      continue;
    }
    solvers.push_back(*solver);
  }
  return solvers;
}

}  // namespace drapelab::scene
