// Fixed-function GL drawing of one panel: background, lights, colliders, cloth.
#include "drapelab/render/panel_renderer.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>

#include "drapelab/render/texture.hpp"

namespace drapelab::render {
namespace {

const Eigen::Vector3f kColliderColor(0.55f, 0.62f, 0.72f);  // steel blue
const Eigen::Vector3f kFloorLight(0.82f, 0.82f, 0.80f);
const Eigen::Vector3f kFloorDark(0.75f, 0.75f, 0.73f);
constexpr float kBackgroundTop[3] = {0.93f, 0.95f, 0.98f};
constexpr float kBackgroundBottom[3] = {0.76f, 0.79f, 0.84f};

// Fills the viewport with a vertical gradient, behind everything (no depth written).
void draw_background() {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glDisable(GL_TEXTURE_2D);
  glDepthMask(GL_FALSE);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glBegin(GL_QUADS);
  glColor3fv(kBackgroundBottom);
  glVertex2d(-1, -1);
  glVertex2d(1, -1);
  glColor3fv(kBackgroundTop);
  glVertex2d(1, 1);
  glVertex2d(-1, 1);
  glEnd();
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
}

// Two directional lights fixed to the camera (positions given in eye coordinates, with an identity
// modelview): a key light from the upper left behind the viewer and a weaker fill from the right,
// plus ambient light. Two-sided lighting lights a face's back with its negated normal, so both
// sides of the cloth are shaded.
void set_lights() {
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  const GLfloat key_direction[4] = {-0.45f, 0.75f, 0.5f,
                                    0.0f};  // w = 0: a direction towards the light
  const GLfloat key_diffuse[4] = {0.75f, 0.75f, 0.72f, 1.0f};
  const GLfloat key_specular[4] = {0.35f, 0.35f, 0.35f, 1.0f};
  const GLfloat fill_direction[4] = {0.6f, 0.1f, 0.8f, 0.0f};
  const GLfloat fill_diffuse[4] = {0.25f, 0.26f, 0.30f, 1.0f};
  const GLfloat none[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  const GLfloat ambient[4] = {0.28f, 0.28f, 0.30f, 1.0f};
  glLightfv(GL_LIGHT0, GL_POSITION, key_direction);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, key_diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, key_specular);
  glLightfv(GL_LIGHT0, GL_AMBIENT, none);
  glLightfv(GL_LIGHT1, GL_POSITION, fill_direction);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, fill_diffuse);
  glLightfv(GL_LIGHT1, GL_SPECULAR, none);
  glLightfv(GL_LIGHT1, GL_AMBIENT, none);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glEnable(GL_LIGHT0);
  glEnable(GL_LIGHT1);
  glEnable(GL_LIGHTING);
  glEnable(
      GL_NORMALIZE);  // normals stay unit under the rigid collider poses anyway; cheap insurance
  glShadeModel(GL_SMOOTH);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
}

void set_specular(float strength, float shininess) {
  const GLfloat specular[4] = {strength, strength, strength, 1.0f};
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, shininess);
}

void draw_mesh(const DrawMesh& mesh) {
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_DOUBLE, 0, mesh.positions.data());
  glNormalPointer(GL_DOUBLE, 0, mesh.normals.data());
  glColorPointer(3, GL_FLOAT, 0, mesh.colors.data());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.triangles.size()), GL_UNSIGNED_INT,
                 mesh.triangles.data());
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

}  // namespace

Bounds framing_bounds(const RunFrames& run, int samples) {
  Bounds bounds;
  for (const auto& solver : run.solvers) {
    const int frames = solver.status == "ok" ? solver.source->frame_count()
                                             : std::min(1, solver.source->frame_count());
    const int count = std::min(samples, frames);
    for (int k = 0; k < count; ++k) {
      const int frame =
          count == 1 ? 0 : static_cast<int>(std::lround(double(k) * (frames - 1) / (count - 1)));
      const Eigen::Matrix3Xd x = solver.source->positions(frame);
      for (Eigen::Index i = 0; i < x.cols(); ++i) bounds.add(Eigen::Vector3d(x.col(i)));
    }
  }
  const int count = std::max(2, samples);
  for (const auto& collider : run.scene.colliders)
    for (int k = 0; k < count; ++k) {
      const double t = run.scene.duration * k / (count - 1);  // s
      add_collider_bounds(collider, collider_pose(collider, t), bounds);
    }
  for (const auto& solver : run.solvers)  // each solver's own dynamic bodies, at every frame
    for (const auto& [frame, poses] : solver.bodies)
      for (const auto& [collider, pose] : poses)
        add_collider_bounds(run.scene.colliders[static_cast<std::size_t>(collider)], pose, bounds);
  return bounds;
}

Eigen::Matrix3Xd vertex_normals(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xi& triangles) {
  Eigen::Matrix3Xd normals = Eigen::Matrix3Xd::Zero(3, x.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const int a = triangles(0, t), b = triangles(1, t), c = triangles(2, t);
    // The cross product's length is twice the triangle's area: area weighting for free.
    const Eigen::Vector3d n = (x.col(b) - x.col(a)).cross(x.col(c) - x.col(a));
    normals.col(a) += n;
    normals.col(b) += n;
    normals.col(c) += n;
  }
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    const double length = normals.col(i).norm();
    normals.col(i) = (length > 0.0 && std::isfinite(length))
                         ? Eigen::Vector3d(normals.col(i) / length)
                         : Eigen::Vector3d::UnitY();
  }
  return normals;
}

PanelRenderer::PanelRenderer(const scene::Scene& scene, const ClothModel& model,
                             const Image& texture, const Bounds& framing)
    : model_(model) {
  constraints_.colliders = scene.colliders;
  constraints_.list = scene.constraints;
  const Eigen::Vector3d center = framing.empty() ? Eigen::Vector3d::Zero() : framing.center();
  const double radius = std::max(framing.radius(), 0.05);
  // A floor patch reaching well beyond the framed scene, so its edge stays out of the default view.
  const double half_size = 2.5 * radius;
  for (const auto& collider : scene.colliders) {
    if (collider.shape != ColliderShape::plane) {
      colliders_.push_back({&collider, solid_collider_mesh(collider, kColliderColor)});
      continue;
    }
    const Eigen::Isometry3d pose = collider_pose(collider, 0.0);
    DrawMesh patch = plane_patch_mesh(collider, pose.inverse() * center, half_size,
                                      round_tile_size(2.0 * radius), kFloorLight, kFloorDark);
    for (Eigen::Index k = 0; k < patch.positions.cols(); ++k)
      extra_radius_ = std::max(
          extra_radius_, (pose * Eigen::Vector3d(patch.positions.col(k)) - center).norm() - radius);
    colliders_.push_back({&collider, std::move(patch)});
  }
  texture_ = upload_texture(texture);
}

void PanelRenderer::draw(const Camera& camera, int x, int y, int width, int height,
                         const Eigen::Matrix3Xd& cloth, double time,
                         const BodyPoses* bodies) const {
  glViewport(x, y, width, height);
  glScissor(x, y, width, height);
  glEnable(GL_SCISSOR_TEST);
  glClearColor(kBackgroundTop[0], kBackgroundTop[1], kBackgroundTop[2], 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  draw_background();

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(
      GL_CULL_FACE);  // the cloth is seen from both sides; closed colliders do not need culling
  set_lights();
  glMatrixMode(GL_PROJECTION);
  const Eigen::Matrix4d projection = projection_matrix(camera, double(width) / height);
  glLoadMatrixd(projection.data());  // Eigen's default storage is column-major, as GL expects
  glMatrixMode(GL_MODELVIEW);
  const Eigen::Matrix4d view = view_matrix(camera);
  glLoadMatrixd(view.data());

  glEnable(GL_COLOR_MATERIAL);
  set_specular(0.25f, 40.0f);
  for (const auto& drawable : colliders_) {
    const bool plane = drawable.collider->shape == ColliderShape::plane;
    if (plane) set_specular(0.0f, 1.0f);  // a matt floor
    glPushMatrix();
    Eigen::Matrix4d pose = collider_pose(*drawable.collider, time).matrix();
    if (bodies) {
      const auto body = bodies->find(static_cast<int>(&drawable - colliders_.data()));
      if (body != bodies->end()) pose = body->second.matrix();
    }
    glMultMatrixd(pose.data());
    draw_mesh(drawable.mesh);
    glPopMatrix();
    if (plane) set_specular(0.25f, 40.0f);
  }

  set_specular(0.0f, 1.0f);  // cloth: matt
  if (model_.triangles.cols() > 0) {
    const Eigen::Matrix3Xd normals = vertex_normals(cloth, model_.triangles);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);  // texture colour x lighting
    glColor3f(1.0f, 1.0f, 1.0f);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_NORMAL_ARRAY);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glVertexPointer(3, GL_DOUBLE, 0, cloth.data());
    glNormalPointer(GL_DOUBLE, 0, normals.data());
    glTexCoordPointer(2, GL_DOUBLE, 0, model_.uvs.data());
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(model_.triangles.size()), GL_UNSIGNED_INT,
                   model_.triangles.data());
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisableClientState(GL_NORMAL_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisable(GL_TEXTURE_2D);
  } else if (cloth.cols() > 0) {  // a chain has no triangles: a thick polyline with its particles
    glDisable(GL_LIGHTING);
    glColor3f(0.70f, 0.25f, 0.19f);
    glLineWidth(3.0f);
    glPointSize(6.0f);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_DOUBLE, 0, cloth.data());
    glDrawArrays(GL_LINE_STRIP, 0, static_cast<GLsizei>(cloth.cols()));
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(cloth.cols()));
    glDisableClientState(GL_VERTEX_ARRAY);
  }
  draw_constraints(cloth, time, bodies);
  glDisable(GL_COLOR_MATERIAL);
  glDisable(GL_LIGHTING);
  glDisable(GL_SCISSOR_TEST);
}

void PanelRenderer::draw_constraints(const Eigen::Matrix3Xd& cloth, double time,
                                     const BodyPoses* bodies) const {
  if (constraints_.empty()) return;
  glDisable(GL_LIGHTING);
  glLineWidth(2.0f);
  glBegin(GL_LINES);
  for (const DistanceConstraint& c : constraints_.list) {
    if (!DistanceConstraints::acts(c, time)) continue;  // a drag before or after its keyframes
    // Hard and rope constraints dark like a cord, soft ones lighter like an elastic.
    if (c.mode == ConstraintMode::soft)
      glColor3f(0.45f, 0.55f, 0.30f);
    else
      glColor3f(0.16f, 0.14f, 0.12f);
    const Eigen::Vector3d a = cloth.col(DistanceConstraints::particle_a(c));
    Eigen::Vector3d b = constraints_.end_b(c, time, cloth, cloth).first;
    // A string to a dynamic collider ends on this panel's own body.
    if (bodies && c.b.kind == ConstraintEnd::Kind::collider_point) {
      const auto body = bodies->find(c.b.collider);
      if (body != bodies->end()) b = body->second * c.b.point;
    }
    glVertex3d(a.x(), a.y(), a.z());
    glVertex3d(b.x(), b.y(), b.z());
  }
  glEnd();
  glEnable(GL_LIGHTING);
}

}  // namespace drapelab::render
