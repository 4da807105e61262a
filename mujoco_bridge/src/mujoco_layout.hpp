// Where our particles and colliders are in a MuJoCo model written by write_mjcf: each one's body,
// each geom's owner, and the contact loads on the colliders read back from MuJoCo's contacts.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "drapelab/cloth_model.hpp"
#include "drapelab/collider.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::mujoco {

struct MujocoLayout {
  std::vector<int> body_of_collider;  // MuJoCo body per collider, 0 for a world geom
  std::vector<int> particle_body;     // MuJoCo body per particle, -1 when pinned
  std::vector<int> geom_collider;     // per MuJoCo geom: its collider, or -1
  std::vector<int> geom_particle;     // per MuJoCo geom: its particle, or -1
};

// Bodies come in the order the MJCF lists them: the world, the colliders with bodies, then the
// free particles; the world's geoms are the static colliders in scene order. Throws
// std::logic_error when the model's counts disagree.
MujocoLayout layout_of(const mjModel& m, const ClothModel& model,
                       const std::vector<Collider>& colliders);

// Each collider's load from the step's contacts with particles (overwriting `forces`, one per
// collider): MuJoCo's force in the contact frame, whose normal points from geom1 to geom2 and
// which pushes geom2 along it.
void collect_collider_forces(const mjModel& m, const mjData& d, const MujocoLayout& layout,
                             std::vector<ColliderForce>& forces);

}  // namespace drapelab::mujoco
