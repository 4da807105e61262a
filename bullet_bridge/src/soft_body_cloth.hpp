// What Bullet's two cloths share: a btSoftBody built from our model (node i = particle i, our
// masses, pins, links and rest lengths), reading its state back, estimating contact forces, and the
// health check.
#pragma once

#include <BulletSoftBody/btSoftBody.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bullet_colliders.hpp"
#include "drapelab/air.hpp"
#include "drapelab/attachments.hpp"
#include "drapelab/cloth_model.hpp"
#include "drapelab/cloth_state.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

// Built in the rest pose so that Bullet computes our rest lengths (it recomputes them from current
// positions whenever masses or links change: docs/bullet.md, "Masses, pins and rest lengths"), then
// set exactly to ours and moved to the initial state. `link_stiffness(e)` gives spring e's kLST
// (the classic solver's only stiffness).
// `attachments` (may be null): a pinned particle attached to a dynamic collider keeps its mass, as
// the anchor that holds it to the body needs (anchor_attached_nodes).
std::unique_ptr<btSoftBody> make_soft_body(btSoftBodyWorldInfo& info, const ClothModel& model,
                                           const ClothState& initial,
                                           const std::function<double(std::size_t)>& link_stiffness,
                                           const Attachments* attachments);

void read_soft_body_state(const btSoftBody& body, ClothState& state);
// Puts the attached nodes (pinned: mass 0) where their colliders carry them at time t (s):
// position, previous position and velocity. Both Bullet cloths call it before every substep and
// after it, so an attached node is a kinematic node that follows its collider.
// Nodes attached to a dynamic collider are skipped: anchors hold them (anchor_attached_nodes).
void place_attached_nodes(const Attachments& attachments, double t, btSoftBody& body);
// The deformable world: anchors every node attached to a dynamic collider to that collider's rigid
// body with `appendDeformableAnchor`, Bullet's own two-way attachment. `body_of(c)` is collider
// c's rigid body. (The classic cloth refuses such attachments: docs/bullet.md, "Constraints".)
void anchor_attached_nodes(const Attachments& attachments,
                           const std::function<btRigidBody*(std::size_t)>& body_of,
                           btSoftBody& cloth);

// The soft distance constraints as an explicit external force of the substep [t, t + h]: each
// free node's velocity gains h f / m (what btSoftBody::addForce does in the classic cloth, which
// the deformable world's solver does not read), and the dynamic bodies some of them end on take
// the reactions as the impulse h f. `scratch` receives the nodes' state.
// When some of `constraints` end on a dynamic collider: replaces them with this solver's own copy,
// whose ends follow the returned pose table (to fill from this world's bodies before every substep
// with KinematicColliders::write_substep); null otherwise.
std::shared_ptr<ColliderPoseTable> follow_own_bodies(
    std::shared_ptr<const DistanceConstraints>& constraints, std::size_t colliders);

void kick_soft_constraints(const DistanceConstraints& constraints, const ClothModel& model,
                           double t, double h, btSoftBody& body, ClothState& scratch,
                           KinematicColliders& bodies);
// Our air (air.hpp) on the deformable world's nodes, which Bullet's aerodynamics do not reach: the
// triangles' drag and lift at the substep's start change each free node's velocity by h f / m.
void kick_air(const AirSettings& air, const Wind& wind, const ClothModel& model, double t, double h,
              btSoftBody& body, ClothState& scratch);
// The hard and rope constraints at the substep's end t (s): the nodes' positions and velocities
// projected as our solver projects its particles (distance_constraints.hpp), written back.
ConstraintProjection project_node_constraints(const DistanceConstraints& constraints,
                                              const ClothModel& model, double t, double h,
                                              btSoftBody& body, ClothState& scratch);

// A node touching a collider during the last step, with the contact's outward normal.
struct NodeContact {
  int node = 0;
  int collider = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
};

// For the classic cloth, which keeps no contact impulses (its contacts are position projections
// whose impulse PSolve_RContacts computes and discards), the force a collider exerted on a node in
// contact is estimated from the node's momentum change over the step beyond gravity, m ((v(n+1) -
// v(n)) / h - g), split along the contact normal (normal force, pushing part only) and across it
// (friction). It includes the node's link forces: it averages to the weight of a cloth resting flat
// but jitters from step to step (test_bullet_contact_forces). The deformable world reads its
// impulses instead (deformable_contact_forces.hpp).
void estimate_contact_forces(const ClothModel& model, const std::vector<NodeContact>& contacts,
                             const Eigen::Matrix3Xd& previous_velocity,
                             const Eigen::Matrix3Xd& velocity, const Eigen::Vector3d& gravity,
                             double h, std::vector<ColliderForce>& forces);

}  // namespace drapelab::bullet
