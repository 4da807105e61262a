// resolved.yaml: the scene with every default filled in, laid out so that it is stable, numbers
// round-trip exactly and units sit beside the values. Each key's name and comment are its row's in
// the key table (scene_keys.hpp); where a map's keys are all scalars written in the table's order,
// the writer walks the table, so a key added there is written here or fails every resolved-scene
// test (value_missing).
#include "drapelab/scene/scene_writer.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "drapelab/scene/number_format.hpp"
#include "key_writer.hpp"

namespace drapelab::scene {
namespace {

// JSON strings are YAML; a byte that is not UTF-8 (a file name's) is written as U+FFFD.
std::string quoted(const std::string& text) {
  return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string pin_text(const PinSelector& selector) {
  if (const auto* named = std::get_if<PinNamed>(&selector)) return named->name;
  if (const auto* coord = std::get_if<PinGridCoord>(&selector))
    return "[" + std::to_string(coord->i) + ", " + std::to_string(coord->j) + "]";
  if (const auto* index = std::get_if<PinIndex>(&selector))
    return "{index: " + std::to_string(index->index) + "}";
  const auto& ball = std::get<PinWithin>(selector);
  return "{within: {center: " + format_list(ball.center) +
         ", radius: " + format_number(ball.radius) + "}}";
}

// A constraint's end b as the scene gives it; particles by index.
std::string end_text(const ConstraintEnd& end, const std::vector<Collider>& colliders) {
  switch (end.kind) {
    case ConstraintEnd::Kind::particle:
      return "{index: " + std::to_string(end.particle) + "}";
    case ConstraintEnd::Kind::point:
      return "{point: " + format_list(end.point) + "}";
    case ConstraintEnd::Kind::collider_point:
      return "{collider: " + colliders[static_cast<std::size_t>(end.collider)].name +
             ", offset: " + format_list(end.point) + "}";
    case ConstraintEnd::Kind::drag:  // written as interactions:, not as a constraint
      break;
  }
  return "{}";
}

void write_constraint(std::ostream& out, const DistanceConstraint& c,
                      const std::vector<Collider>& colliders) {
  const std::string_view in = "    ";
  put(out, "  - ", key("constraints[].type"), "distance");
  put(out, in, key("constraints[].a"), "{index: " + std::to_string(c.a) + "}");
  put(out, in, key("constraints[].b"), end_text(c.b, colliders));
  put(out, in, key("constraints[].length"), format_number(c.length));
  put(out, in, key("constraints[].mode"), constraint_mode_name(c.mode));
  if (c.mode == ConstraintMode::soft) {
    put(out, in, key("constraints[].stiffness"), format_number(c.stiffness));
    put(out, in, key("constraints[].damping"), format_number(c.damping));
  } else {
    put(out, in, key("constraints[].tolerance"), format_number(c.tolerance));
  }
}

std::string spring_text(const SpringParams& p) {
  return flow_map("cloth.springs.stretch", [&](const SceneKey& row) {
    return format_number(row.name() == "ks" ? p.ks : p.kd);
  });
}

void write_motion(std::ostream& out, const ColliderMotion& m) {
  if (!m.keyframes.empty()) {
    out << "    motion:\n      keyframes:\n";
    for (const auto& k : m.keyframes)
      out << "        - " << flow_map("colliders[].motion.keyframes[]", [&](const SceneKey& row) {
        if (row.name() == "t") return format_number(k.t);
        return format_list(row.name() == "center" ? k.center : k.rotation);
      }) << "\n";
  } else if (!m.is_static()) {
    const SceneKey& velocity = key("colliders[].motion.velocity");
    const std::string units = std::string(velocity.unit) + ", " +
                              std::string(key("colliders[].motion.angular_velocity").unit);
    put(out, "    ", key("colliders[].motion"),
        flow_map("colliders[].motion",
                 [&](const SceneKey& row) {
                   return format_list(&row == &velocity ? m.velocity : m.angular_velocity);
                 }),
        units);
  }
}

void write_collider(std::ostream& out, const Collider& c) {
  const std::string_view in = "    ";
  const std::string shape = collider_shape_name(c.shape);
  put(out, "  - ", key("colliders[].name"), c.name);
  put(out, in, key("colliders[].type"), shape);
  // The shape's own keys (those with a `when`), in table order.
  for (const SceneKey* row : keys_under("colliders[]", shape)) {
    if (row->when.empty()) continue;
    const std::string_view name = row->name();
    if (name == "center" || name == "point")
      put(out, in, *row, format_list(c.center));
    else if (name == "radius")
      put(out, in, *row, format_number(c.radius));
    else if (name == "height")
      put(out, in, *row, format_number(c.height));
    else if (name == "axis")
      put(out, in, *row, format_list(c.axis));
    else if (name == "half_extents")
      put(out, in, *row, format_list(c.half_extents));
    else if (name == "normal")
      put(out, in, *row, format_list(c.normal));
    else if (name == "file")
      put(out, in, *row, quoted(c.mesh_file));
    else if (name == "scale")
      put(out, in, *row, format_list(c.mesh_scale));
    else
      value_missing(*row);
  }
  put(out, in, key("colliders[].rotation"), format_list(c.rotation));
  put(out, in, key("colliders[].friction"), format_number(c.friction));
  put(out, in, key("colliders[].static_friction"), format_number(c.static_friction));
  if (c.dynamic())
    put(out, in, key("colliders[].dynamic"), "{mass: " + format_number(c.dynamic_mass) + "}",
        key("colliders[].dynamic.mass").unit);
  if (!c.parent.empty()) put(out, in, key("colliders[].parent"), c.parent);
  write_motion(out, c.motion);
}

void write_cloth(std::ostream& out, const Scene& s) {
  const GridClothSpec& g = s.cloth.grid;
  const std::string_view in = "  ";
  out << "cloth:\n";
  put(out, in, key("cloth.shape"), s.cloth.shape);
  // The shape's own keys (those with a `when`), in table order.
  for (const SceneKey* row : keys_under("cloth", s.cloth.shape)) {
    if (row->when.empty()) continue;
    const std::string_view name = row->name();
    if (name == "size")
      put(out, in, *row, format_list(g.size));
    else if (name == "resolution")
      put(out, in, *row, "[" + std::to_string(g.nx) + ", " + std::to_string(g.ny) + "]");
    else if (name == "plane")
      put(out, in, *row, g.plane == GridPlane::xz ? "xz" : "xy");
    else if (name == "radius")
      put(out, in, *row, format_number(s.cloth.disc.radius));
    else if (name == "rings")
      put(out, in, *row, std::to_string(s.cloth.disc.rings));
    else if (name == "path")
      put(out, in, *row, quoted(s.cloth.mesh_file.string()));
    else if (name == "scale")
      put(out, in, *row, format_number(s.cloth.mesh_scale));
    else
      value_missing(*row);
  }
  if (!s.cloth.material.empty()) put(out, in, key("cloth.material"), s.cloth.material);
  put(out, in, key("cloth.center"), format_list(g.center));
  put(out, in, key("cloth.rotation"), format_list(g.rotation));
  if (g.mass) put(out, in, key("cloth.mass"), format_number(*g.mass));
  if (g.areal_density) put(out, in, key("cloth.areal_density"), format_number(*g.areal_density));
  put(out, in, key("cloth.thickness"), format_number(g.thickness));
  put(out, in, key("cloth.perturbation"), format_number(s.cloth.perturbation));
  put(out, in, key("cloth.air_damping"), format_number(s.cloth.air_damping));
  const auto continuum_value = [](const ContinuumParams& c) {
    return [&c](const SceneKey& row) {
      const std::string_view name = row.name();
      if (name == "stretch_modulus") return format_number(c.stretch_modulus);
      if (name == "poisson") return format_number(c.poisson);
      if (name == "bending_rigidity") return format_number(c.bending_rigidity);
      if (name == "damping") return format_number(c.damping);
      value_missing(row);
    };
  };
  const SceneKey* kinds[] = {&key("cloth.springs.stretch"), &key("cloth.springs.shear"),
                             &key("cloth.springs.bend")};
  const SpringParams* springs[] = {&g.stretch, &g.shear, &g.bend};
  if (g.continuum) {
    // The springs are derived from these at load, so they are written as a comment only.
    put(out, in, key("cloth.model"), "continuum", "triangle membrane and hinge bending");
    put(out, in, key("cloth.continuum"), "");
    put_keys(out, "    ", "cloth.continuum", {}, continuum_value(*g.continuum));
    out << "  # springs derived from the continuum for the Bullet cloths and the metrics:\n";
    for (int k = 0; k < 3; ++k)
      out << "  #   " << kinds[k]->name() << ": " << spring_text(*springs[k]) << "\n";
  } else {
    put(out, in, key("cloth.model"), "springs", "the spring-damper network");
    put(out, in, key("cloth.springs"), "");
    for (int k = 0; k < 3; ++k) put(out, "    ", *kinds[k], spring_text(*springs[k]));
    // The fabric of the solvers with model: continuum on this springs cloth, with units only.
    const bool used = std::any_of(s.solvers.begin(), s.solvers.end(), [](const SolverSpec& v) {
      return v.type == SolverType::spring_damper && v.continuum;
    });
    if (used) {
      put(out, in, key("cloth.continuum"), "", "for the solvers with model: continuum");
      const auto value_of = continuum_value(s.cloth.continuum);
      for (const SceneKey* row : keys_under("cloth.continuum"))
        put(out, "    ", *row, value_of(*row), row->unit);
    }
  }
  if (g.pins.empty()) {
    put(out, in, key("cloth.pins"), "[]");
  } else {
    put(out, in, key("cloth.pins"), "");
    for (std::size_t k = 0; k < g.pins.size(); ++k) {
      std::string text = pin_text(g.pins[k]);
      const std::string attach = k < s.cloth.pin_attach.size() ? s.cloth.pin_attach[k] : "";
      if (!attach.empty()) text.insert(text.size() - 1, ", attach: " + attach);  // a map's
      out << "    - " << text << "\n";
    }
  }
  if (!s.cloth.seams.empty()) {
    put(out, in, key("cloth.seams"), "");
    const auto indices = [](const std::vector<int>& list) {
      std::string text = "[";
      for (std::size_t k = 0; k < list.size(); ++k)
        text += (k ? ", " : "") + std::to_string(list[k]);
      return text + "]";
    };
    // The lists first (flow_map writes scalars only), then the scalars in table order.
    for (const SeamSpec& seam : s.cloth.seams) {
      const std::string scalars = flow_map("cloth.seams[]", [&](const SceneKey& row) {
        const std::string_view name = row.name();
        if (name == "close_time") return format_number(seam.close_time);
        if (name == "stiffness") return format_number(seam.stiffness);
        if (name == "damping") return format_number(seam.damping);
        value_missing(row);
      });
      out << "    - {a: " << indices(seam.a) << ", b: " << indices(seam.b) << ", "
          << scalars.substr(1) << "\n";
    }
  }
  const SelfCollisionSettings& self = s.cloth.self_collision;
  put(out, in, key("cloth.self_collision"), "");
  put_keys(out, "    ", "cloth.self_collision", {}, [&](const SceneKey& row) {
    const std::string_view name = row.name();
    if (name == "enabled") return std::string(yes_no(self.enabled));
    if (name == "thickness") return format_number(self.thickness);
    if (name == "stiffness") return format_number(self.stiffness);
    if (name == "damping") return format_number(self.damping);
    if (name == "friction") return format_number(self.friction);
    if (name == "static_friction") return format_number(self.static_friction);
    value_missing(row);
  });
}

void write_air(std::ostream& out, const AirSettings& air) {
  out << "air:\n";
  put_keys(out, "  ", "air", {}, [&](const SceneKey& row) {
    const std::string_view name = row.name();
    if (name == "density") return format_number(air.density);
    if (name == "drag") return format_number(air.drag);
    if (name == "lift") return format_number(air.lift);
    if (name == "wind") return format_list(air.wind);
    value_missing(row);
  });
  if (air.gust_amplitude > 0.0)
    put(out, "  ", key("air.gusts"), flow_map("air.gusts", [&](const SceneKey& row) {
          return format_number(row.name() == "amplitude" ? air.gust_amplitude : air.gust_period);
        }));
  if (air.turbulence_intensity > 0.0)
    put(out, "  ", key("air.turbulence"), flow_map("air.turbulence", [&](const SceneKey& row) {
          return format_number(row.name() == "intensity" ? air.turbulence_intensity
                                                         : air.turbulence_length);
        }));
}

void write_drag(std::ostream& out, const DragSpec& drag) {
  const std::string_view in = "    ";
  put(out, "  - ", key("interactions[].type"), "drag");
  put(out, in, key("interactions[].particle"), "{index: " + std::to_string(drag.particle) + "}");
  put(out, in, key("interactions[].stiffness"), format_number(drag.stiffness));
  put(out, in, key("interactions[].damping"), format_number(drag.damping));
  put(out, in, key("interactions[].keyframes"), "");
  for (const DragKeyframe& frame : drag.keyframes)
    out << "      - " << flow_map("interactions[].keyframes[]", [&](const SceneKey& row) {
      return row.name() == "t" ? format_number(frame.t) : format_list(frame.target);
    }) << "\n";
}

void write_solver(std::ostream& out, const SolverSpec& solver) {
  const std::string_view in = "    ";
  put(out, "  - ", key("solvers[].name"), solver.name);
  put(out, in, key("solvers[].type"), solver_type_name(solver.type));
  const bool ours = solver.type == SolverType::spring_damper;
  if (ours) {
    put(out, in, key("solvers[].integrator"), integrator_name(solver.integrator));
    put(out, in, key("solvers[].model"), solver.continuum ? "continuum" : "springs");
    put(out, in, key("solvers[].host"), solver.bullet_host ? "bullet" : "none");
    put(out, in, key("solvers[].adaptive_substeps"), yes_no(solver.adaptive_substeps));
  }
  if (ours && solver.integrator == Integrator::vbd)
    put(out, in, key("solvers[].vbd"), flow_map("solvers[].vbd", [&](const SceneKey& row) {
          const VbdSettings& v = solver.vbd;
          const std::string_view name = row.name();
          if (name == "iterations") return std::to_string(v.iterations);
          if (name == "order") return std::to_string(v.order);
          if (name == "chebyshev_rho") return format_number(v.chebyshev_rho);
          if (name == "friction_velocity") return format_number(v.friction_velocity);
          if (name == "coarse") return std::string(yes_no(v.coarse_correction));
          value_missing(row);
        }));
  if (ours && solver.integrator == Integrator::implicit_euler)
    put(out, in, key("solvers[].implicit"),
        flow_map("solvers[].implicit", [&](const SceneKey& row) {
          return row.name() == "tolerance" ? format_number(solver.implicit.tolerance)
                                           : std::to_string(solver.implicit.max_iterations);
        }));
  if (solver.type == SolverType::mujoco) {
    const mujoco::MujocoSettings& m = solver.mujoco;
    put(out, in, key("solvers[].margin"), format_number(solver.margin));
    put(out, in, key("solvers[].constraint_solver"),
        mujoco::constraint_solver_name(m.constraint_solver));
    put(out, in, key("solvers[].solver_iterations"), std::to_string(m.solver_iterations));
    put(out, in, key("solvers[].tolerance"), format_number(m.tolerance));
    put(out, in, key("solvers[].impratio"), format_number(m.impratio));
    put(out, in, key("solvers[].max_contacts"), std::to_string(m.max_contacts));
  } else if (!ours) {
    if (solver.type == SolverType::bullet_softbody)
      put(out, in, key("solvers[].iterations"), std::to_string(solver.iterations));
    put(out, in, key("solvers[].margin"), format_number(solver.margin));
    put(out, in, key("solvers[].voxel_size"), format_number(solver.voxel_size));
    put(out, in, key("solvers[].collider_margin"), format_number(solver.collider_margin));
    std::string raw;
    const auto kinds = keys_under("solvers[].kLST");  // stretch, shear, bend: link_stiffness's
    for (std::size_t k = 0; k < kinds.size() && k < 3; ++k)
      if (solver.link_stiffness[k])
        raw += std::string(raw.empty() ? "" : ", ") + std::string(kinds[k]->name()) + ": " +
               format_number(*solver.link_stiffness[k]);
    if (!raw.empty()) put(out, in, key("solvers[].kLST"), "{" + raw + "}");
  }
  put(out, in, key("solvers[].dt"), format_number(solver.dt),
      "s, " + std::to_string(solver.steps_per_frame) + " steps per frame");
  put(out, in, key("solvers[].round_dt"), yes_no(solver.round_dt));
  put(out, in, key("solvers[].max_speed"), format_number(solver.max_speed));
  put(out, in, key("solvers[].runaway_stretch"), format_number(solver.runaway_stretch));
}

}  // namespace

std::string resolved_scene_yaml(const Scene& s) {
  std::ostringstream out;
  out << "# Resolved by drapelab " << DRAPELAB_VERSION << " from " << quoted(s.source.string())
      << ": every default filled in, every --set applied.\n"
      << "# Run it again with: drapelab run resolved.yaml --out DIR\n";
  put_keys(out, "", "", {}, [&](const SceneKey& row) {
    const std::string_view name = row.name();
    if (name == "name") return s.name;
    if (name == "description") return quoted(s.description);
    if (name == "duration") return format_number(s.duration);
    if (name == "frame_rate") return format_number(s.frame_rate);
    if (name == "gravity") return format_list(s.gravity);
    if (name == "seed") return std::to_string(s.seed);
    value_missing(row);
  });
  write_cloth(out, s);
  out << (s.colliders.empty() ? "colliders: []\n" : "colliders:\n");
  for (const auto& collider : s.colliders) write_collider(out, collider);
  if (s.air.enabled) write_air(out, s.air);
  if (!s.constraints.empty()) out << "constraints:\n";
  for (const auto& constraint : s.constraints) write_constraint(out, constraint, s.colliders);
  if (!s.interactions.empty()) out << "interactions:\n";
  for (const DragSpec& drag : s.interactions) write_drag(out, drag);
  out << "contact:\n";
  put_keys(out, "  ", "contact", {}, [&](const SceneKey& row) {
    const ContactSpec& c = s.contact;
    const std::string_view name = row.name();
    if (name == "stiffness") return format_number(c.stiffness);
    if (name == "damping") return format_number(c.damping);
    if (name == "friction") return format_number(c.friction);
    if (name == "static_friction") return format_number(c.static_friction);
    if (name == "triangles") return std::string(yes_no(c.triangles));
    value_missing(row);
  });
  out << "solvers:\n";
  for (const auto& solver : s.solvers) write_solver(out, solver);
  const SceneKey& support = key("metrics.drape_support");
  if (!s.drape_support)
    out << "metrics: {}\n";
  else if (!s.drape_support->collider.empty())
    put(out << "metrics:\n", "  ", support, s.drape_support->collider,
        "a collider's cross-section, radius " + format_number(s.drape_support->disc.radius) + " m");
  else
    put(out << "metrics:\n", "  ", support, format_number(s.drape_support->disc.radius),
        "m, a disc under the cloth's centre");
  out << "output:\n";
  put_keys(out, "  ", "output", {}, [&](const SceneKey& row) {
    if (row.name() == "meshes") return std::string(mesh_output_name(s.output.meshes));
    value_missing(row);
  });
  return out.str();
}

}  // namespace drapelab::scene
