// What Bullet's two cloth solvers expose inside the bridge, for the diagnostics.
#pragma once

#include <BulletSoftBody/btSoftBody.h>

#include "bullet_colliders.hpp"
#include "drapelab/solver.hpp"

namespace drapelab::bullet {

class BulletClothSolver : public Solver {
 public:
  virtual const btSoftBody& cloth() const = 0;
  virtual const KinematicColliders& colliders() const = 0;
};

}  // namespace drapelab::bullet
