// What every solver of a run simulates, described once: gravity, the air, the colliders with their
// motion and contact parameters, the cloth against itself, and what holds the cloth (attachments,
// distance constraints and drags). The runner builds it from the scene (runner::build_world) and
// every solver kind takes it as the base of its settings, adding only its own numerics: our solver
// its integrator and that integrator's options, Bullet's cloths their iterations and margins. The
// cloth model is each solver's own argument beside it, because each runs its own discretisation of
// the scene's cloth (springs, or the continuum's elements).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "drapelab/air.hpp"
#include "drapelab/attachments.hpp"
#include "drapelab/contact_model.hpp"
#include "drapelab/distance_constraints.hpp"
#include "drapelab/self_collision.hpp"

namespace drapelab {

struct World {
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2
  double air_damping = 0.0;                  // 1/s: force -air_damping * m * v
  // The colliders, their motion, and the penalty contact's parameters; none when null. Bullet's
  // cloths take the colliders as bodies of their own world and their contact from its margins.
  std::shared_ptr<const ContactModel> contacts;
  // The colliders' sharp edges and corners also push on the cloth's edges and triangles
  // (contact/edge_contact.hpp), not only on its particles. Our solver only.
  bool collider_edges = false;
  // The cloth against itself (self_collision.hpp). In our solver, a step in which one particle
  // would move more than half the thickness relative to another is split into smaller equal steps,
  // so that no layer passes through another between two force evaluations.
  SelfCollisionSettings self_collision;
  // Pinned particles carried by colliders (cloth.pins[].attach): placed on their colliders at the
  // start and the end of every step (and every substep), so each step moves them with the
  // colliders' velocities in between. They must be pinned in the model. None when null.
  std::shared_ptr<const Attachments> attachments;
  // Distance constraints and drags (distance_constraints.hpp): the soft ones are forces of every
  // evaluation (couplings of the implicit Euler and vbd solves); the hard and rope ones are
  // projected at the end of every step (and substep), after the attached particles are placed.
  // None when null.
  std::shared_ptr<const DistanceConstraints> constraints;
  // Aerodynamic drag and lift on the triangles (air.hpp), an explicit force of every evaluation.
  AirSettings air;
};

}  // namespace drapelab
