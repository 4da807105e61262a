// Self-collision of Bullet's deformable cloth (docs/bullet.md, "Self-collision"): Bullet's
// face-node repulsion switched on and given our settings where it has a counterpart.
#pragma once

#include <BulletSoftBody/btSoftBody.h>

#include "drapelab/self_collision.hpp"

namespace drapelab::bullet {

// kDF for a cloth whose layers have the kinetic friction `settings.friction`: Bullet gives a
// self-contact the friction kDF * kDF (both sides' kDF), so kDF is its square root, held above
// kMinSelfFrictionFactor. Bullet also scales every collider's friction by kDF, so the colliders'
// Bullet bodies get their friction divided by it (KinematicColliders' friction_divisor), which
// keeps the product at the scene's collider friction.
inline constexpr double kMinSelfFrictionFactor = 1e-3;
double deformable_self_friction_factor(const SelfCollisionSettings& settings);

// The repulsion stiffness (N/m per contact) for settings.stiffness on a cloth whose lightest free
// node has the inverse mass `largest_inverse_mass` (1/kg), stepped by h (s). Bullet's repulsion
// impulse per node-face pair and step is min(k h d, m (0.1 d / h - v_n)) at overlap d; above
// k = 0.1 m / h^2 its velocity cap takes over, and a node near several faces (up to about ten
// pairs, some with coplanar faces of its own layer) then gets the cap once per pair and is thrown
// off: a stack of 0.3 g nodes at h = 1 ms rests at 100 N/m (3.3 times the bound), wobbles at 300
// and flies apart at 1000. So the stiffness is held at that bound.
double deformable_repulsion_stiffness(const SelfCollisionSettings& settings,
                                      double largest_inverse_mass, double h);

// Turns on the face-node self-contacts of `cloth`, a soft body of a
// btDeformableMultiBodyDynamicsWorld built in its initial pose and stepped by h (s) (call before
// the first step): the VF_DD collision flag, setSelfCollision(true), m_repulsionStiffness and kDF
// as above, and the face tree those contacts search. Layers then keep twice the soft body's margin
// apart.
void enable_deformable_self_collision(btSoftBody& cloth, const SelfCollisionSettings& settings,
                                      double h);

// Builds `cloth`'s face tree (m_fdbvt) and the copy with normal cones the self-contact search walks
// (m_fdbvnt), by inserting one face at a time. Bullet's own initializeFaceTree() never returns when
// the faces form more than one edge-connected piece (two separate sheets) or when a node has no
// link: its bottom-up build only pairs neighbours and loops while more than one root is left.
void build_face_tree(btSoftBody& cloth);

}  // namespace drapelab::bullet
