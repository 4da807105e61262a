// A contact whose point on the cloth is a weighted sum of up to four particles: a particle against
// a triangle (weights 1, -a, -b, -c), two edges, or a collider's edge against a cloth edge. The
// penalty force f n at the contact acts on particle j as w_j f n; for the implicit solve its
// Jacobians are K = -k (w w^T) (x) n n^T and D = -c (w w^T) (x) n n^T (the normal held fixed, as
// for the particle contacts of contact_model.hpp), which couple the contact's particles.
#pragma once

#include <Eigen/Core>
#include <array>

namespace drapelab {

struct WeightedContact {
  std::array<int, 4> particle{-1, -1, -1, -1};        // -1: unused slot
  std::array<double, 4> weight{};                     // dimensionless
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // unit: the direction the force pushes
  double stiffness = 0.0;                             // N/m
  double damping = 0.0;                               // N*s/m
  double depth = 0.0;  // m: how far inside the contact distance at the evaluation
  double force = 0.0;  // N: the push f at the evaluation
  // A contact only pushes (vbd drops it while f < 0); a soft distance constraint, also a coupling,
  // pulls as well.
  bool two_sided = false;
  // m/s: how fast an end that is not a particle (a moving collider point) moves along n. The depth
  // grows by h end_rate over a step wherever the particles stay, so the implicit solves take the
  // particles' rate relative to it.
  double end_rate = 0.0;
};

}  // namespace drapelab
