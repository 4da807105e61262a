// What the bridge's solvers expose inside the bridge, for the diagnostics: every solver that owns a
// Bullet world (Bullet's two cloths, our hosted cloth) has its kinematic colliders; Bullet's cloths
// also have their btSoftBody.
#pragma once

#include <BulletSoftBody/btSoftBody.h>

#include "bullet_colliders.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

class BulletWorldSolver : public Solver {
 public:
  virtual const KinematicColliders& colliders() const = 0;
  std::vector<BodyState> bodies() const override { return colliders().dynamic_bodies(); }
};

class BulletClothSolver : public BulletWorldSolver {
 public:
  virtual const btSoftBody& cloth() const = 0;
};

}  // namespace drapelab::bullet
