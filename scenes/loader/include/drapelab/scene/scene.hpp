// The resolved scene: every key of docs/scene-reference.md with its default filled in. Loaded and
// validated by scene_loader.hpp; written back as resolved.yaml by scene_writer.hpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drapelab/air.hpp"
#include "drapelab/attachments.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/disc_cloth.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/drape_metrics.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/implicit_euler.hpp"
#include "drapelab/integrators.hpp"
#include "drapelab/mesh_cloth.hpp"
#include "drapelab/mujoco/mujoco_mapping.hpp"
#include "drapelab/self_collision.hpp"
#include "drapelab/solver.hpp"
#include "drapelab/stability.hpp"
#include "drapelab/vertex_block_descent.hpp"

namespace drapelab::scene {

// cloth.seams: particle a[k] is sewn to b[k] by a stitch (a soft constraint whose length falls from
// rest[k], their rest distance, to 0 over close_time, then stays 0).
struct SeamSpec {
  std::vector<int> a, b;
  std::vector<double> rest;  // m
  double close_time = 0.5;   // s
  double stiffness = 0.0;    // N/m
  double damping = 0.0;      // N*s/m
};

struct ClothSpec {
  std::string shape = "grid";  // grid | disc | mesh
  // Every shape's common keys live here too: center, rotation, mass or areal_density, thickness,
  // springs and pins (grid coordinates only for a grid).
  GridClothSpec grid;  // size, resolution, plane, ...
  DiscSpec disc;       // shape: disc: radius, rings (center, rotation and ring_at filled in)
  std::filesystem::path
      mesh_file;            // shape: mesh: the OBJ file, resolved against the scene file's folder
  double mesh_scale = 1.0;  // shape: mesh: factor applied to the file's coordinates
  std::shared_ptr<const TriangleMesh> mesh;  // shape: mesh: read at load, scaled, turned and moved
  std::string material;       // preset applied before the explicit keys (empty: none)
  double perturbation = 0.0;  // m, random initial offset along the sheet normal
  double air_damping = 0.0;   // 1/s
  // cloth.self_collision, resolved (thickness and static_friction filled in).
  SelfCollisionSettings self_collision;
  // The fabric's continuum parameters, resolved (cloth.continuum over the preset over the
  // defaults) whatever cloth.model is: a solver with model: continuum uses them (grid.continuum is
  // set only when the cloth itself is model: continuum).
  ContinuumParams continuum;
  bool continuum_given = false;  // the scene has a cloth.continuum block
  // Per entry of grid.pins: the collider its particles move with (cloth.pins[].attach), or empty.
  std::vector<std::string> pin_attach;
  std::vector<SeamSpec> seams;  // resolved on the built cloth
};

// metrics.drape_support: the support disc of the drape coefficient.
struct DrapeSupportSpec {
  std::string collider;  // the collider it comes from, or empty when given as a radius
  DrapeSupport disc;     // centre and radius (m)
};

struct ContactSpec {
  double stiffness = 5000.0;     // N/m per particle
  double damping = 5.0;          // N*s/m
  double friction = 0.3;         // kinetic Coulomb coefficient, the colliders' default
  double static_friction = 0.3;  // static Coulomb coefficient (default: friction), >= friction
  // Our cloth only: the colliders' edges and corners also push on the cloth's edges and triangles,
  // not only on its particles (docs/contact.md, "Contact on triangles").
  bool triangles = true;
};

struct SolverSpec {
  std::string name;  // label in every output; defaults to the type
  SolverType type = SolverType::spring_damper;
  Integrator integrator = Integrator::symplectic_euler;
  // spring_damper only: the solver's cloth model (solvers.N.model; default cloth.model). Bullet's
  // cloths always take the springs.
  bool continuum = false;
  double dt = 0.0;                // s, internal step; a frame is steps_per_frame steps
  bool round_dt = false;          // round dt down to a whole number of steps per frame
  int steps_per_frame = 0;        // derived: frame period / dt
  double max_speed = 0.0;         // m/s, a faster particle stops the solver as unstable
  double runaway_stretch = 10.0;  // a stretch spring longer than (1 + this) x rest is unstable
  std::string note;               // what the loader chose or changed (automatic or rounded dt)
  // spring_damper: whether the scene names the integrator (otherwise the loader chooses it, with
  // the step, by its cost at the scene: step_rates.hpp).
  bool integrator_named = false;
  // The run's estimated wall time on the reference machine (s), and, when another integrator would
  // be much faster, what it is and its estimate ("vbd, about 4 s"); empty otherwise.
  double estimated_seconds = 0.0;
  std::string faster_choice;
  // spring_damper only: stepped as an action inside a Bullet world (host: bullet) or bare (host:
  // none).
  bool bullet_host = true;
  // spring_damper only: split each dt into the substeps the current shape's stable step needs
  // (SpringDamperSettings::adaptive_substeps); symplectic_euler only.
  bool adaptive_substeps = false;
  // spring_damper with implicit_euler only: the conjugate gradient's relative tolerance and cap.
  ImplicitSolveSettings implicit;
  // spring_damper with vbd only: sweeps per step and their Chebyshev acceleration.
  VbdSettings vbd;
  // Bullet's cloths (docs/bullet.md, "Fairness table"); iterations and link_stiffness are for
  // bullet_softbody only (docs/bullet.md, "Mapping our parameters to the classic cloth"):
  int iterations = 1;       // position-solver sweeps per substep
  double margin = 0.0;      // m, soft collision margin (default: the cloth's thickness)
  double voxel_size = 0.0;  // m, sparse SDF cell (default: min(margin, smallest feature / 10))
  double collider_margin = 1e-3;  // m, Bullet's rounding of box and cylinder edges
  std::array<std::optional<double>, 3>
      link_stiffness;  // raw kLST per spring kind, replacing the mapping
  // MuJoCo's own numerics (docs/mujoco.md); its particle radius is `margin` above.
  mujoco::MujocoSettings mujoco;
};

enum class MeshOutput { none, obj, pc2, both };
const char* mesh_output_name(MeshOutput output);

struct OutputSpec {
  MeshOutput meshes = MeshOutput::none;  // per-frame OBJ files and/or a .pc2 point cache per solver
};

// interactions: a scripted drag (what the viewer records): a particle pulled by a spring of rest
// length 0 toward a target moving through keyframes (drapelab/drag_track.hpp).
struct DragSpec {
  int particle = 0;        // index into the cloth
  double stiffness = 0.0;  // N/m
  double damping = 0.0;    // N*s/m, along the spring
  std::vector<DragKeyframe> keyframes;
};

struct Scene {
  std::filesystem::path source;  // the scene file as given
  std::string name;              // [a-z0-9_-]+
  std::string description;
  double duration = 0.0;                     // s
  double frame_rate = 60.0;                  // frames recorded per simulated second
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2
  std::uint64_t seed = 0;
  ClothSpec cloth;
  std::vector<Collider> colliders;
  // constraints: ends resolved to particle indices and indices into `colliders`, lengths filled in.
  std::vector<DistanceConstraint> constraints;
  std::vector<DragSpec> interactions;  // drags, in the scene's order
  AirSettings air;  // air: drag, lift and wind (enabled only when the scene has the key)
  ContactSpec contact;
  std::vector<SolverSpec> solvers;
  std::optional<DrapeSupportSpec> drape_support;
  OutputSpec output;

  int frame_count() const;  // recorded frames after frame 0: duration x frame_rate
  double frame_period() const { return 1.0 / frame_rate; }  // s
  // The penalty contact's stiffness and damping when there are colliders (they bound the step).
  ContactRates contact_rates() const {
    return colliders.empty() ? ContactRates{} : ContactRates{contact.stiffness, contact.damping};
  }
};

// The scene's cloth as a model (any shape), and its initial state (rest pose, the seeded
// perturbation along the normals, zero velocity). A grid is perturbed along its sheet's one normal,
// exact and the same for every particle (initial_grid_state), so the initial state that grid
// scenes' golden files rest on does not depend on how vertex normals round; other shapes use their
// vertex normals (initial_mesh_state).
ClothModel build_scene_cloth(const Scene& scene);
// The cloth as `solver` runs it: `cloth` itself when the solver's model is the cloth's; otherwise a
// copy with the continuum's elements added (from scene.cloth.continuum) or taken away (a spring
// solver on a continuum cloth, and the Bullet cloths, run its springs). Throws
// std::invalid_argument when the elements cannot be built (a chain).
std::shared_ptr<const ClothModel> cloth_for_solver(const Scene& scene, const SolverSpec& solver,
                                                   std::shared_ptr<const ClothModel> cloth);
ClothState initial_scene_state(const Scene& scene, const ClothModel& model);
// The pinned particles that move with a collider (cloth.pins[].attach), their offsets taken from
// `initial` at time 0; null when no pin is attached.
std::shared_ptr<const Attachments> scene_attachments(const Scene& scene, const ClothState& initial);

// Whether any collider is a dynamic rigid body (then every solver has its own copy of it).
bool has_dynamic_colliders(const Scene& scene);

// The scene's distance constraints for a solver (their colliders the scene's), its drags
// (`interactions`) among them as soft constraints to their moving targets, and its seams' stitches;
// null when none.
std::shared_ptr<const DistanceConstraints> scene_constraints(const Scene& scene);
// A drag as the soft constraint of length 0 every solver applies (its own track).
DistanceConstraint drag_constraint(const DragSpec& drag);
// A seam's k-th stitch.
DistanceConstraint seam_stitch(const SeamSpec& seam, std::size_t k);

// Named pin sets of the scene's cloth shape (grid: corners, ...; disc: center, rim; mesh: center).
std::vector<std::string> pin_set_names(const ClothSpec& cloth);
// The particles a selector picks on the scene's cloth, or empty with `error` set.
std::vector<int> select_cloth_pins(const ClothSpec& cloth, const PinSelector& selector,
                                   std::string* error);

}  // namespace drapelab::scene
