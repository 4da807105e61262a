// Our damped springs as a force of Bullet's deformable world. btDeformableMassSpringForce has one
// stiffness for every non-bending link (and a world takes one mass-spring force per body), so it
// cannot give shear springs their own ks; this force carries ks and kd per link, in our spring
// order. Elastic: f1 = ks (|d| - L) d/|d| with d = x2 - x1 (at the start of the step, Bullet's
// m_q); damping: f1 = kd ((v2 - v1).d^) d^ (along the link only, as ours); f2 = -f1.
#pragma once

#include <BulletSoftBody/btDeformableLagrangianForce.h>

#include <vector>

namespace drapelab::bullet {

class PerLinkSpringForce final : public btDeformableLagrangianForce {
 public:
  // ks (N/m) and kd (N*s/m) of link j of the body this force is added to.
  PerLinkSpringForce(std::vector<double> ks, std::vector<double> kd);

  void addScaledForces(btScalar scale, TVStack& force) override;
  void addScaledExplicitForce(btScalar scale, TVStack& force) override;
  void addScaledDampingForce(btScalar scale, TVStack& force) override;
  void addScaledElasticForce(btScalar scale, TVStack& force);
  void addScaledDampingForceDifferential(btScalar scale, const TVStack& dv, TVStack& df) override;
  void buildDampingForceDifferentialDiagonal(btScalar scale, TVStack& diagA) override;
  void addScaledElasticForceDifferential(btScalar scale, const TVStack& dx, TVStack& df) override;
  double totalElasticEnergy(btScalar dt) override;
  btDeformableLagrangianForceType getForceType() override { return BT_MASSSPRING_FORCE; }

 private:
  std::vector<double> ks_, kd_;
};

}  // namespace drapelab::bullet
