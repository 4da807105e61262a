// Our scene as MJCF text (mjcf_writer.hpp).
#include "mjcf_writer.hpp"

#include <cstdio>
#include <sstream>

namespace drapelab::mujoco {
namespace {

// Numbers exactly as doubles: MuJoCo reads them back bit for bit.
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string vector_text(const Eigen::Vector3d& v) {
  return number(v.x()) + " " + number(v.y()) + " " + number(v.z());
}

// MuJoCo's quaternion order: w x y z.
std::string quaternion_text(const Eigen::Quaterniond& q) {
  return number(q.w()) + " " + number(q.x()) + " " + number(q.y()) + " " + number(q.z());
}

std::string solimp_text() { return number(kImpedance) + " " + number(kImpedance) + " 0.001 0.5 2"; }

std::string solref_text(const ContactReference& r) {
  return number(-r.stiffness) + " " + number(-r.damping);
}

// A collider's geom, placed by `pose` (geom frame -> its body's frame). Colliders' own geoms mix
// nothing into a contact with a particle (solmix 0): the particle's reference, scaled to its mass,
// is the contact's; the colliders carry the mean particle's reference for completeness (they
// never meet each other).
void write_collider_geom(std::ostringstream& xml, const Collider& collider,
                         const Eigen::Isometry3d& pose, const ContactReference& reference) {
  const GeomShape shape = geom_shape(collider);
  const Eigen::Quaterniond rotation(pose.linear() * shape.local.toRotationMatrix());
  xml << "<geom type=\"" << shape.type << "\" size=\"" << vector_text(shape.size) << "\" pos=\""
      << vector_text(pose.translation()) << "\" quat=\"" << quaternion_text(rotation) << "\"";
  // Contact bits: particles 1, colliders 2, so that colliders meet particles only.
  xml << " contype=\"2\" conaffinity=\"1\" condim=\"3\"";
  xml << " friction=\"" << number(collider.friction) << " 0.005 0.0001\"";
  xml << " solmix=\"0\" solref=\"" << solref_text(reference) << "\" solimp=\"" << solimp_text()
      << "\" margin=\"0\"";
  xml << "/>\n";
}

const char* solver_attribute(ConstraintSolver solver) {
  switch (solver) {
    case ConstraintSolver::cg:
      return "CG";
    case ConstraintSolver::pgs:
      return "PGS";
    default:
      return "Newton";
  }
}

}  // namespace

bool collider_is_body(const Collider& collider) { return collider.moves(); }

std::string write_mjcf(const MjcfInputs& in) {
  const ClothModel& model = *in.model;
  std::ostringstream xml;
  xml << "<mujoco model=\"drapelab\">\n";
  xml << "<compiler angle=\"radian\" inertiafromgeom=\"auto\"/>\n";
  xml << "<option timestep=\"" << number(in.dt) << "\" gravity=\"" << vector_text(in.gravity)
      << "\" integrator=\"Euler\" cone=\"elliptic\" jacobian=\"sparse\" solver=\""
      << solver_attribute(in.solver) << "\" iterations=\"" << in.numerics.solver_iterations
      << "\" tolerance=\"" << number(in.numerics.tolerance) << "\" impratio=\""
      << number(in.impratio) << "\"/>\n";
  std::int64_t dofs = 0, bodies = 1;  // the world
  for (int i = 0; i < model.particle_count(); ++i)
    if (!model.is_pinned(i)) {
      dofs += 3;
      ++bodies;
    }
  for (const Collider& collider : *in.colliders)
    if (collider_is_body(collider)) {
      dofs += 6;
      ++bodies;
    }
  xml << "<size nconmax=\"" << in.contacts << "\" njmax=\"" << 3 * in.contacts << "\" nstack=\""
      << stack_size(in.contacts, dofs, bodies, in.solver) << "\"/>\n";
  xml << "<worldbody>\n";

  // The free particles' mean mass sets the reference of contacts between two colliders.
  const ContactReference collider_reference =
      contact_reference(in.contact_stiffness, in.contact_damping, mean_free_mass(model));

  // Static colliders: geoms of the world body, at their pose at t = 0.
  for (const Collider& collider : *in.colliders)
    if (!collider_is_body(collider))
      write_collider_geom(xml, collider, collider_pose(collider, 0.0), collider_reference);
  // Moving colliders: one heavy free body each, its frame the collider's.
  for (const Collider& collider : *in.colliders) {
    if (!collider_is_body(collider)) continue;
    const Eigen::Isometry3d pose = collider_pose(collider, 0.0);
    xml << "<body pos=\"" << vector_text(pose.translation()) << "\" quat=\""
        << quaternion_text(Eigen::Quaterniond(pose.linear())) << "\">\n<joint type=\"free\"/>\n";
    xml << "<inertial pos=\"0 0 0\" mass=\"" << number(kKinematicMass) << "\" diaginertia=\""
        << vector_text(Eigen::Vector3d::Constant(kKinematicMass)) << "\"/>\n";
    write_collider_geom(xml, collider, Eigen::Isometry3d::Identity(), collider_reference);
    xml << "</body>\n";
  }
  // Free particles, in particle order: a body at the origin whose three slides are its position.
  const std::string solimp = solimp_text();
  const double self_radius = 0.5 * in.self_collision.thickness;  // m: two keep the thickness
  for (int i = 0; i < model.particle_count(); ++i) {
    if (model.is_pinned(i)) continue;
    const double m = model.mass[i];                                                    // kg
    const double inertia = 0.4 * m * in.particle_radius * in.particle_radius + 1e-12;  // kg*m^2
    xml << "<body>\n";
    for (const char* axis : {"1 0 0", "0 1 0", "0 0 1"})
      xml << "<joint type=\"slide\" axis=\"" << axis << "\" damping=\""
          << number(in.air_damping * m) << "\"/>\n";
    xml << "<inertial pos=\"0 0 0\" mass=\"" << number(m) << "\" diaginertia=\"" << number(inertia)
        << " " << number(inertia) << " " << number(inertia) << "\"/>\n";
    xml << "<geom type=\"sphere\" size=\"" << number(in.particle_radius)
        << "\" contype=\"1\" conaffinity=\"0\" condim=\"3\" friction=\"0 0 0\" solmix=\"1\""
        << " solref=\""
        << solref_text(contact_reference(in.contact_stiffness, in.contact_damping, m))
        << "\" solimp=\"" << solimp << "\" margin=\"0\"/>\n";
    if (in.self_collision.enabled)
      xml << "<geom type=\"sphere\" size=\"" << number(self_radius)
          << "\" contype=\"4\" conaffinity=\"4\" condim=\"3\" friction=\""
          << number(in.self_collision.friction) << " 0.005 0.0001\" solmix=\"1\" solref=\""
          << solref_text(
                 pair_contact_reference(in.self_collision.stiffness, in.self_collision.damping, m))
          << "\" solimp=\"" << solimp << "\" margin=\"0\"/>\n";
    xml << "</body>\n";
  }
  xml << "</worldbody>\n</mujoco>\n";
  return xml.str();
}

}  // namespace drapelab::mujoco
