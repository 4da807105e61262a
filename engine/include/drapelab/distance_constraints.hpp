// Distance constraints (scene key `constraints:`): each joins a particle `a` to a second end `b`
// (another particle, a fixed point, or a point carried by a collider) at a length L.
//   hard: |a - b| = L, held to a relative tolerance after every step by projection;
//   rope: |a - b| <= L, the same projection, only while the rope would be longer than L;
//   soft: a damped spring between the ends, f_a = -[k (l - L) + c (v_a - v_b).n] n, n = (a - b)/l.
// A seam's stitch (cloth.seams) is a soft constraint between two particles whose length L falls
// from their rest distance to 0 over its close time, then stays 0: it pulls the seam shut, then
// holds it.
// Only a soft constraint may end on a dynamic collider (a rigid body of the solver's world): its
// end then follows the solver's own body (`poses`) and the body takes the spring's reaction.
// Every solver applies them itself: our solver adds the soft ones as forces (implicit for implicit
// Euler and vbd, as couplings) and projects the hard and rope ones at the end of each step;
// Bullet's cloths get the same forces and projection through bullet_bridge/.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "drapelab/collider.hpp"
#include "drapelab/collider_pose_table.hpp"
#include "drapelab/drag_track.hpp"
#include "drapelab/energy_ledger.hpp"
#include "drapelab/solver.hpp"
#include "drapelab/weighted_contact.hpp"

namespace drapelab {

enum class ConstraintMode { hard, rope, soft };
const char* constraint_mode_name(ConstraintMode mode);

// The second end of a constraint.
struct ConstraintEnd {
  enum class Kind { particle, point, collider_point, drag };
  Kind kind = Kind::point;
  int particle = -1;                                // Kind::particle
  int collider = -1;                                // Kind::collider_point: index into colliders
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // m: the world point, or the offset in the
                                                    // collider's own frame
  // Kind::drag: the moving target; the constraint is soft, of length 0, pulls the track's particle
  // with the track's stiffness and damping (not the constraint's own, so that a viewer can move one
  // drag from particle to particle and change its spring) and acts only while the track is active.
  std::shared_ptr<const DragTrack> drag;
};

struct DistanceConstraint {
  int a = 0;  // particle
  ConstraintEnd b;
  double length = 0.0;  // m, L
  ConstraintMode mode = ConstraintMode::hard;
  double stiffness = 0.0;   // N/m (soft)
  double damping = 0.0;     // N*s/m (soft)
  double tolerance = 1e-6;  // hard and rope: the largest |l - L| / L a projection leaves
  // s, soft only: when > 0 the length falls linearly from `length` at t = 0 to 0 at close_time
  // (a seam's stitch), and stays 0 after.
  double close_time = 0.0;

  // L at time t (s), m.
  double length_at(double t) const {
    if (close_time <= 0.0) return length;
    return t >= close_time ? 0.0 : length * (1.0 - std::max(0.0, t) / close_time);
  }
  // dL/dt at time t (m/s): -length / close_time while the stitch closes, else 0.
  double length_rate(double t) const {
    return close_time > 0.0 && t >= 0.0 && t < close_time ? -length / close_time : 0.0;
  }
};

// What one projection did (hard and rope constraints).
struct ConstraintProjection {
  int position_sweeps = 0;  // Gauss-Seidel sweeps over the constraints' lengths
  int velocity_sweeps = 0;  // ... and over their stretching velocities
  bool converged = true;    // every length within its tolerance before the sweep cap
  bool moved = false;       // some particle was moved
};

struct DistanceConstraints {
  std::vector<Collider> colliders;  // the scene's colliders, indexed by ConstraintEnd::collider
  std::vector<DistanceConstraint> list;
  int max_sweeps = 1000;  // the cap of each Gauss-Seidel projection
  // Where the solver's world holds its dynamic colliders over the current substep (each solver
  // sets its own copy's). Null: every collider is posed by collider_pose(t).
  std::shared_ptr<const ColliderPoseTable> poses;

  bool empty() const { return list.empty(); }
  // The particle a constraint pulls at its first end, and whether it acts at time t (s).
  static int particle_a(const DistanceConstraint& c) {
    return c.b.kind == ConstraintEnd::Kind::drag ? c.b.drag->particle : c.a;
  }
  static bool acts(const DistanceConstraint& c, double t) {
    return c.b.kind != ConstraintEnd::Kind::drag || c.b.drag->active(t);
  }
  bool has_soft() const;
  bool has_hard() const;  // hard or rope
  // Whether some constraint ends on a dynamic collider (then it is soft: see above).
  bool any_on_dynamic() const;

  // b's position (m) and velocity (m/s) at time t (s), the state x, v (3 x N) holding particles.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> end_b(const DistanceConstraint& c, double t,
                                                    const Eigen::Matrix3Xd& x,
                                                    const Eigen::Matrix3Xd& v) const;

  // Adds the soft constraints' spring-damper forces (N) to `force`. When `couplings` is given, each
  // is also appended as a two-sided weighted contact (normal n = (a - b)/l, weights +1 on a and -1
  // on a particle b, depth L - l, the push f = k (L - l) - c (v_a - v_b).n), so that implicit
  // Euler and vbd take its stiffness and damping into their solves. When `body_loads` is given
  // (one entry per collider), it is reset and receives the reactions on the dynamic colliders:
  // the force on each (N) and its moment about the world origin (N*m). When `power` is given, it
  // is reset and receives the dampers' dissipation and the moving ends' work (W,
  // energy_ledger.hpp), and a closing stitch's: its shortening does work k (l - L) (-dL/dt).
  void add_soft_forces(double t, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                       Eigen::Matrix3Xd& force, std::vector<WeightedContact>* couplings,
                       std::vector<ColliderForce>* body_loads = nullptr,
                       PowerSplit* power = nullptr) const;

  // Moves the particles of x (m) onto the hard and rope constraints at time t (s): Gauss-Seidel
  // sweeps, each moving a constraint's ends along it in proportion to their inverse masses (a
  // pinned particle, a point and a collider point do not move), until every length is within its
  // tolerance or max_sweeps. `inverse_mass` is 1/kg per particle, 0 when pinned.
  ConstraintProjection project_positions(double t, const Eigen::VectorXd& inverse_mass,
                                         Eigen::Matrix3Xd& x) const;
  // Then removes each hard constraint's stretching velocity (v_a - v_b).n, and a taut rope's when
  // it would lengthen it, by equal and opposite impulses (an inelastic constraint: the kinetic
  // energy along the constraint is lost). Sweeps until every rate is below tolerance L / h.
  void project_velocities(double t, double h, const Eigen::VectorXd& inverse_mass,
                          const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v,
                          ConstraintProjection& result) const;

  // The largest relative length error of the hard (|l - L| / L) and rope (max(0, l - L) / L)
  // constraints at time t: metrics.csv's constraint_error. 0 when there are none.
  double largest_error(double t, const Eigen::Matrix3Xd& x) const;
  // The soft constraints' elastic energy k (l - L)^2 / 2 (J).
  double soft_energy(double t, const Eigen::Matrix3Xd& x) const;
};

// A solver's own copy of `constraints` whose ends on dynamic colliders follow `poses` (where that
// solver's world holds its bodies); `constraints` itself when none ends on a dynamic collider.
std::shared_ptr<const DistanceConstraints> constraints_on_own_bodies(
    std::shared_ptr<const DistanceConstraints> constraints,
    std::shared_ptr<const ColliderPoseTable> poses);

}  // namespace drapelab
