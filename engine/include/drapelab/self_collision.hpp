// Self-collision of our cloth: the settings a scene gives (cloth.self_collision) and the counters a
// run reports. The force itself is private to the engine (self_collision/self_contact.hpp).
//
// Two parts of the cloth closer than `thickness` push apart: every particle against every triangle
// it is not a corner of, and every edge against every edge it shares no particle with. The push is
// a penalty spring-damper along the line between the closest points that never pulls, spread over
// the primitives' particles by their barycentric weights (so it sums to zero: momentum is kept),
// with Coulomb friction between the layers. docs/contact.md, "Self-collision", gives the model, its
// broad phase and its limits.
#pragma once

namespace drapelab {

// The thickness must stay below this fraction of the cloth's shortest rest edge: on a square grid
// of spacing d a particle lies d / sqrt(2) (0.707 d) from the far edge of a neighbouring triangle,
// so a thicker layer pushes a flat sheet's neighbouring parts apart at rest. The scene loader
// refuses a thickness at or above it.
inline constexpr double kMaxSelfThicknessPerEdge = 0.7;

struct SelfCollisionSettings {
  bool enabled = false;
  double thickness = 0.0;         // m, the distance two layers keep (0: the cloth's thickness)
  double stiffness = 2000.0;      // N/m, per contact
  double damping = 0.01;          // N*s/m, per contact, on the closing speed only
  double friction = 0.3;          // kinetic Coulomb coefficient between layers
  double static_friction = -1.0;  // static Coulomb coefficient (< 0: the kinetic one)

  // The thickness used when `thickness` is 0: the cloth's (m).
  double thickness_or(double cloth_thickness) const {
    return thickness > 0.0 ? thickness : cloth_thickness;
  }
  double static_friction_or_kinetic() const {
    return static_friction >= 0.0 ? static_friction : friction;
  }
};

}  // namespace drapelab
