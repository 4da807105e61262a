// Per-link damped springs for Bullet's deformable world (see per_link_spring_force.hpp).
#include "per_link_spring_force.hpp"

namespace drapelab::bullet {
namespace {

// Unit vector along v, or zero for a link of no length.
btVector3 direction_of(const btVector3& v) {
  const btScalar length = v.norm();
  return length > SIMD_EPSILON ? v / length : btVector3(0, 0, 0);
}

}  // namespace

PerLinkSpringForce::PerLinkSpringForce(std::vector<double> ks, std::vector<double> kd)
    : ks_(std::move(ks)), kd_(std::move(kd)) {}

void PerLinkSpringForce::addScaledForces(btScalar scale, TVStack& force) {
  addScaledDampingForce(scale, force);
  addScaledElasticForce(scale, force);
}

void PerLinkSpringForce::addScaledExplicitForce(btScalar scale, TVStack& force) {
  addScaledElasticForce(scale, force);
}

void PerLinkSpringForce::addScaledElasticForce(btScalar scale, TVStack& force) {
  for (int b = 0; b < m_softBodies.size(); ++b) {
    const btSoftBody* body = m_softBodies[b];
    for (int j = 0; j < body->m_links.size(); ++j) {
      const btSoftBody::Link& link = body->m_links[j];
      const btVector3 d = link.m_n[1]->m_q - link.m_n[0]->m_q;
      const btVector3 f =
          scale * ks_[j] *
          (d - direction_of(d) * link.m_rl);  // pulls node 0 towards 1 when stretched
      force[link.m_n[0]->index] += f;
      force[link.m_n[1]->index] -= f;
    }
  }
}

void PerLinkSpringForce::addScaledDampingForce(btScalar scale, TVStack& force) {
  for (int b = 0; b < m_softBodies.size(); ++b) {
    const btSoftBody* body = m_softBodies[b];
    for (int j = 0; j < body->m_links.size(); ++j) {
      const btSoftBody::Link& link = body->m_links[j];
      const btVector3 u = direction_of(link.m_n[1]->m_x - link.m_n[0]->m_x);
      const btVector3 f = scale * kd_[j] * (link.m_n[1]->m_v - link.m_n[0]->m_v).dot(u) * u;
      force[link.m_n[0]->index] += f;
      force[link.m_n[1]->index] -= f;
    }
  }
}

void PerLinkSpringForce::addScaledDampingForceDifferential(btScalar scale, const TVStack& dv,
                                                           TVStack& df) {
  for (int b = 0; b < m_softBodies.size(); ++b) {
    const btSoftBody* body = m_softBodies[b];
    for (int j = 0; j < body->m_links.size(); ++j) {
      const btSoftBody::Link& link = body->m_links[j];
      const int a = link.m_n[0]->index, c = link.m_n[1]->index;
      const btVector3 u = direction_of(link.m_n[1]->m_x - link.m_n[0]->m_x);
      const btVector3 f = scale * kd_[j] * (dv[c] - dv[a]).dot(u) * u;
      df[a] += f;
      df[c] -= f;
    }
  }
}

void PerLinkSpringForce::buildDampingForceDifferentialDiagonal(btScalar scale, TVStack& diagA) {
  for (int b = 0; b < m_softBodies.size(); ++b) {
    const btSoftBody* body = m_softBodies[b];
    for (int j = 0; j < body->m_links.size(); ++j) {
      const btSoftBody::Link& link = body->m_links[j];
      const btVector3 u = direction_of(link.m_n[1]->m_x - link.m_n[0]->m_x);
      for (int k = 0; k < 2; ++k) {
        if (link.m_n[k]->m_im <= 0) continue;  // pinned
        for (int d = 0; d < 3; ++d) diagA[link.m_n[k]->index][d] -= scale * kd_[j] * u[d] * u[d];
      }
    }
  }
}

void PerLinkSpringForce::addScaledElasticForceDifferential(btScalar scale, const TVStack& dx,
                                                           TVStack& df) {
  // d f1 = -K (dx1 - dx2) with K = ks [u u^T + (1 - L/|d|) (I - u u^T)], the spring's stiffness
  // matrix.
  for (int b = 0; b < m_softBodies.size(); ++b) {
    const btSoftBody* body = m_softBodies[b];
    for (int j = 0; j < body->m_links.size(); ++j) {
      const btSoftBody::Link& link = body->m_links[j];
      const int a = link.m_n[0]->index, c = link.m_n[1]->index;
      const btVector3 d = link.m_n[0]->m_q - link.m_n[1]->m_q;
      const btScalar length = d.norm();
      if (length <= SIMD_EPSILON) continue;
      const btVector3 u = d / length;
      const btVector3 relative = dx[a] - dx[c];
      const btScalar along = u.dot(relative);
      const btScalar slack = 1.0 - link.m_rl / length;
      const btVector3 f = -scale * ks_[j] * (along * u + slack * (relative - along * u));
      df[a] += f;
      df[c] -= f;
    }
  }
}

double PerLinkSpringForce::totalElasticEnergy(btScalar) {
  double energy = 0.0;  // J
  for (int b = 0; b < m_softBodies.size(); ++b) {
    const btSoftBody* body = m_softBodies[b];
    for (int j = 0; j < body->m_links.size(); ++j) {
      const btSoftBody::Link& link = body->m_links[j];
      const double extension = (link.m_n[1]->m_q - link.m_n[0]->m_q).norm() - link.m_rl;
      energy += 0.5 * ks_[j] * extension * extension;
    }
  }
  return energy;
}

}  // namespace drapelab::bullet
