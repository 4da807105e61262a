// resolved.yaml: the scene with every default filled in, written by hand so that the layout is
// stable, numbers round-trip exactly and units sit beside the values.
#include "drapelab/scene/scene_writer.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "drapelab/scene/number_format.hpp"

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
  out << "  - type: distance\n"
      << "    a: {index: " << c.a << "}\n"
      << "    b: " << end_text(c.b, colliders) << "\n"
      << "    length: " << format_number(c.length) << "  # m\n"
      << "    mode: " << constraint_mode_name(c.mode) << "\n";
  if (c.mode == ConstraintMode::soft)
    out << "    stiffness: " << format_number(c.stiffness) << "  # N/m\n"
        << "    damping: " << format_number(c.damping) << "  # N*s/m\n";
  else
    out << "    tolerance: " << format_number(c.tolerance) << "  # largest relative length error\n";
}

std::string spring_text(const SpringParams& p) {
  return "{ks: " + format_number(p.ks) + ", kd: " + format_number(p.kd) + "}";
}

void write_collider(std::ostream& out, const Collider& c) {
  out << "  - name: " << c.name << "\n"
      << "    type: " << collider_shape_name(c.shape) << "\n";
  switch (c.shape) {
    case ColliderShape::plane:
      out << "    point: " << format_list(c.center) << "  # m\n"
          << "    normal: " << format_list(c.normal) << "  # solid below\n";
      break;
    case ColliderShape::box:
      out << "    center: " << format_list(c.center) << "  # m\n"
          << "    half_extents: " << format_list(c.half_extents) << "  # m\n";
      break;
    case ColliderShape::sphere:
      out << "    center: " << format_list(c.center) << "  # m\n"
          << "    radius: " << format_number(c.radius) << "  # m\n";
      break;
    case ColliderShape::cylinder:
    case ColliderShape::capsule:
      out << "    center: " << format_list(c.center) << "  # m\n"
          << "    radius: " << format_number(c.radius) << "  # m\n"
          << "    height: " << format_number(c.height) << "  # m\n"
          << "    axis: " << format_list(c.axis) << "\n";
      break;
  }
  out << "    rotation: " << format_list(c.rotation) << "  # deg, Euler x, y, z\n"
      << "    friction: " << format_number(c.friction) << "\n"
      << "    static_friction: " << format_number(c.static_friction) << "\n";
  if (c.dynamic()) out << "    dynamic: {mass: " << format_number(c.dynamic_mass) << "}  # kg\n";
  if (!c.parent.empty())
    out << "    parent: " << c.parent << "  # center, rotation, motion in its frame\n";
  const ColliderMotion& m = c.motion;
  if (!m.keyframes.empty()) {
    out << "    motion:\n      keyframes:\n";
    for (const auto& k : m.keyframes)
      out << "        - {t: " << format_number(k.t) << ", center: " << format_list(k.center)
          << ", rotation: " << format_list(k.rotation) << "}\n";
  } else if (!m.is_static()) {
    out << "    motion: {velocity: " << format_list(m.velocity)
        << ", angular_velocity: " << format_list(m.angular_velocity) << "}  # m/s, deg/s\n";
  }
}

}  // namespace

std::string resolved_scene_yaml(const Scene& s) {
  std::ostringstream out;
  const GridClothSpec& g = s.cloth.grid;
  out << "# Resolved by drapelab " << DRAPELAB_VERSION << " from " << quoted(s.source.string())
      << ": every default filled in, every --set applied.\n"
      << "# Run it again with: drapelab run resolved.yaml --out DIR\n"
      << "name: " << s.name << "\n"
      << "description: " << quoted(s.description) << "\n"
      << "duration: " << format_number(s.duration) << "  # s\n"
      << "frame_rate: " << format_number(s.frame_rate)
      << "  # frames recorded per simulated second\n"
      << "gravity: " << format_list(s.gravity) << "  # m/s^2\n"
      << "seed: " << s.seed << "\n"
      << "cloth:\n"
      << "  shape: " << s.cloth.shape << "\n";
  if (s.cloth.shape == "grid")
    out << "  size: " << format_list(g.size) << "  # m\n"
        << "  resolution: [" << g.nx << ", " << g.ny << "]  # particles along each side\n"
        << "  plane: " << (g.plane == GridPlane::xz ? "xz" : "xy") << "\n";
  if (s.cloth.shape == "disc")
    out << "  radius: " << format_number(s.cloth.disc.radius) << "  # m\n"
        << "  rings: " << s.cloth.disc.rings << "\n";
  if (s.cloth.shape == "mesh")
    out << "  path: " << quoted(s.cloth.mesh_file.string()) << "\n"
        << "  scale: " << format_number(s.cloth.mesh_scale) << "\n";
  if (!s.cloth.material.empty())
    out << "  material: " << s.cloth.material
        << "  # a preset; the values below are what it gave, with any explicit keys\n";
  out << "  center: " << format_list(g.center) << "  # m\n"
      << "  rotation: " << format_list(g.rotation) << "  # deg, Euler x, y, z about the centre\n";
  if (g.mass) out << "  mass: " << format_number(*g.mass) << "  # kg, total\n";
  if (g.areal_density)
    out << "  areal_density: " << format_number(*g.areal_density) << "  # kg/m^2\n";
  out << "  thickness: " << format_number(g.thickness) << "  # m\n"
      << "  perturbation: " << format_number(s.cloth.perturbation) << "  # m\n"
      << "  air_damping: " << format_number(s.cloth.air_damping) << "  # 1/s\n";
  if (g.continuum) {
    // The springs are derived from these at load, so they are written as a comment only.
    const ContinuumParams& c = *g.continuum;
    out << "  model: continuum  # triangle membrane and hinge bending\n"
        << "  continuum:\n"
        << "    stretch_modulus: " << format_number(c.stretch_modulus)
        << "  # N/m, Young's modulus x thickness\n"
        << "    poisson: " << format_number(c.poisson) << "\n"
        << "    bending_rigidity: " << format_number(c.bending_rigidity) << "  # N*m\n"
        << "    damping: " << format_number(c.damping) << "  # s, stiffness-proportional\n"
        << "  # springs derived from the continuum for the Bullet cloths and the metrics:\n"
        << "  #   stretch: " << spring_text(g.stretch) << "\n"
        << "  #   shear: " << spring_text(g.shear) << "\n"
        << "  #   bend: " << spring_text(g.bend) << "\n";
  } else {
    out << "  model: springs  # the spring-damper network\n"
        << "  springs:  # ks in N/m, kd in N*s/m, per spring\n"
        << "    stretch: " << spring_text(g.stretch) << "\n"
        << "    shear: " << spring_text(g.shear) << "\n"
        << "    bend: " << spring_text(g.bend) << "\n";
    // The fabric of the solvers with model: continuum on this springs cloth.
    const bool used = std::any_of(s.solvers.begin(), s.solvers.end(), [](const SolverSpec& v) {
      return v.type == SolverType::spring_damper && v.continuum;
    });
    if (used) {
      const ContinuumParams& c = s.cloth.continuum;
      out << "  continuum:  # for the solvers with model: continuum\n"
          << "    stretch_modulus: " << format_number(c.stretch_modulus) << "  # N/m\n"
          << "    poisson: " << format_number(c.poisson) << "\n"
          << "    bending_rigidity: " << format_number(c.bending_rigidity) << "  # N*m\n"
          << "    damping: " << format_number(c.damping) << "  # s\n";
    }
  }
  if (g.pins.empty()) {
    out << "  pins: []\n";
  } else {
    out << "  pins:\n";
    for (std::size_t k = 0; k < g.pins.size(); ++k) {
      std::string text = pin_text(g.pins[k]);
      const std::string attach = k < s.cloth.pin_attach.size() ? s.cloth.pin_attach[k] : "";
      if (!attach.empty()) text.insert(text.size() - 1, ", attach: " + attach);  // a map's
      out << "    - " << text << "\n";
    }
  }
  const SelfCollisionSettings& self = s.cloth.self_collision;
  out << "  self_collision:\n"
      << "    enabled: " << (self.enabled ? "true" : "false") << "\n"
      << "    thickness: " << format_number(self.thickness) << "  # m, kept between layers\n"
      << "    stiffness: " << format_number(self.stiffness) << "  # N/m per contact\n"
      << "    damping: " << format_number(self.damping) << "  # N*s/m per contact\n"
      << "    friction: " << format_number(self.friction) << "  # kinetic Coulomb coefficient\n"
      << "    static_friction: " << format_number(self.static_friction)
      << "  # static Coulomb coefficient\n";
  if (s.colliders.empty())
    out << "colliders: []\n";
  else
    out << "colliders:\n";
  for (const auto& collider : s.colliders) write_collider(out, collider);
  if (s.air.enabled) {
    out << "air:\n"
        << "  density: " << format_number(s.air.density) << "  # kg/m^3\n"
        << "  drag: " << format_number(s.air.drag) << "  # C_d along a triangle's normal\n"
        << "  lift: " << format_number(s.air.lift) << "  # C_l\n"
        << "  wind: " << format_list(s.air.wind) << "  # m/s\n";
    if (s.air.gust_amplitude > 0.0)
      out << "  gusts: {amplitude: " << format_number(s.air.gust_amplitude)
          << ", period: " << format_number(s.air.gust_period) << "}  # m/s RMS, s\n";
    if (s.air.turbulence_intensity > 0.0)
      out << "  turbulence: {intensity: " << format_number(s.air.turbulence_intensity)
          << ", length: " << format_number(s.air.turbulence_length) << "}  # m/s RMS, m\n";
  }
  if (!s.constraints.empty()) out << "constraints:\n";
  for (const auto& constraint : s.constraints) write_constraint(out, constraint, s.colliders);
  if (!s.interactions.empty()) out << "interactions:\n";
  for (const DragSpec& drag : s.interactions) {
    out << "  - type: drag\n"
        << "    particle: {index: " << drag.particle << "}\n"
        << "    stiffness: " << format_number(drag.stiffness) << "  # N/m\n"
        << "    damping: " << format_number(drag.damping) << "  # N*s/m\n"
        << "    keyframes:\n";
    for (const DragKeyframe& key : drag.keyframes)
      out << "      - {t: " << format_number(key.t) << ", target: " << format_list(key.target)
          << "}\n";
  }
  out << "contact:\n"
      << "  stiffness: " << format_number(s.contact.stiffness) << "  # N/m per particle\n"
      << "  damping: " << format_number(s.contact.damping) << "  # N*s/m\n"
      << "  friction: " << format_number(s.contact.friction) << "  # kinetic Coulomb coefficient\n"
      << "  static_friction: " << format_number(s.contact.static_friction)
      << "  # static Coulomb coefficient\n"
      << "  triangles: " << (s.contact.triangles ? "true" : "false")
      << "  # collider edges and corners against the cloth's edges and triangles\n"
      << "solvers:\n";
  for (const auto& solver : s.solvers) {
    out << "  - name: " << solver.name << "\n"
        << "    type: " << solver_type_name(solver.type) << "\n";
    if (solver.type == SolverType::spring_damper)
      out << "    integrator: " << integrator_name(solver.integrator) << "\n"
          << "    model: " << (solver.continuum ? "continuum" : "springs") << "\n"
          << "    host: " << (solver.bullet_host ? "bullet" : "none")
          << "  # a plugin in a Bullet world, or bare\n"
          << "    adaptive_substeps: " << (solver.adaptive_substeps ? "true" : "false")
          << "  # split dt into the substeps the shape's stable step needs\n";
    if (solver.type == SolverType::spring_damper && solver.integrator == Integrator::vbd)
      out << "    vbd: {iterations: " << solver.vbd.iterations << ", order: " << solver.vbd.order
          << ", chebyshev_rho: " << format_number(solver.vbd.chebyshev_rho)
          << ", friction_velocity: " << format_number(solver.vbd.friction_velocity)
          << ", coarse: " << (solver.vbd.coarse_correction ? "true" : "false")
          << "}  # sweeps per step\n";
    if (solver.type == SolverType::spring_damper && solver.integrator == Integrator::implicit_euler)
      out << "    implicit: {tolerance: " << format_number(solver.implicit.tolerance)
          << ", max_iterations: " << solver.implicit.max_iterations << "}  # conjugate gradient\n";
    if (solver.type != SolverType::spring_damper) {
      if (solver.type == SolverType::bullet_softbody)
        out << "    iterations: " << solver.iterations << "\n";
      out << "    margin: " << format_number(solver.margin) << "  # m, soft collision margin\n"
          << "    voxel_size: " << format_number(solver.voxel_size) << "  # m, sparse SDF cell\n"
          << "    collider_margin: " << format_number(solver.collider_margin) << "  # m\n";
      std::string raw;
      const char* kinds[] = {"stretch", "shear", "bend"};
      for (int k = 0; k < 3; ++k)
        if (solver.link_stiffness[k])
          raw += std::string(raw.empty() ? "" : ", ") + kinds[k] + ": " +
                 format_number(*solver.link_stiffness[k]);
      if (!raw.empty()) out << "    kLST: {" << raw << "}\n";
    }
    out << "    dt: " << format_number(solver.dt) << "  # s, " << solver.steps_per_frame
        << " steps per frame\n"
        << "    round_dt: " << (solver.round_dt ? "true" : "false") << "\n"
        << "    max_speed: " << format_number(solver.max_speed) << "  # m/s, runaway limit\n"
        << "    runaway_stretch: " << format_number(solver.runaway_stretch)
        << "  # stretch spring strain limit\n";
  }
  if (!s.drape_support)
    out << "metrics: {}\n";
  else if (!s.drape_support->collider.empty())
    out << "metrics:\n  drape_support: " << s.drape_support->collider
        << "  # a collider's cross-section, radius " << format_number(s.drape_support->disc.radius)
        << " m\n";
  else
    out << "metrics:\n  drape_support: " << format_number(s.drape_support->disc.radius)
        << "  # m, a disc under the cloth's centre\n";
  out << "output:\n"
      << "  meshes: " << mesh_output_name(s.output.meshes) << "  # none | obj | pc2 | both\n";
  return out.str();
}

}  // namespace drapelab::scene
