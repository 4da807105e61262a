// Camera framing, --camera parsing and the GL matrices.
#include "drapelab/render/camera.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

namespace drapelab::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// The default direction from the target to the eye: a 3/4 view from above.
constexpr double kDefaultAzimuthDegrees = 30.0;    // from +z towards +x
constexpr double kDefaultElevationDegrees = 35.0;  // above the horizontal plane
constexpr double kMinimumRadius = 0.05;            // m: frames at least a 10 cm scene

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator)) parts.push_back(part);
  return parts;
}

std::optional<double> parse_double(const std::string& text) {
  const std::string t = trim(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<Eigen::Vector3d> parse_vector(const std::string& text) {
  const auto parts = split(text, ',');
  if (parts.size() != 3) return std::nullopt;
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    const auto value = parse_double(parts[k]);
    if (!value) return std::nullopt;
    v[k] = *value;
  }
  return v;
}

Eigen::Vector3d default_direction() {  // unit, from the target towards the eye
  const double az = kDefaultAzimuthDegrees * kDegree, el = kDefaultElevationDegrees * kDegree;
  return {std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
}

// Up vector for a view direction: world y, unless the view is (nearly) along y, then -z / +z so the
// basis stays defined (looking straight down, image up is -z, the far side of the scene).
Eigen::Vector3d up_for(const Eigen::Vector3d& forward) {
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  if (forward.normalized().cross(y).norm() > 1e-6) return y;
  return forward.y() < 0 ? Eigen::Vector3d(0, 0, -1) : Eigen::Vector3d(0, 0, 1);
}

// The distance from `center` along the default direction at which all eight corners of `bounds` fit
// in the view (vertical fov, width / height = aspect) with kFill of the half-widths used: for a
// corner at offset o from the centre, seen from eye = center - d f (f the forward unit vector),
// depth is o.f + d, so |o.r| <= tan(half_h) kFill (o.f + d) gives d >= |o.r| / (tan(half_h) kFill)
// - o.f, and likewise vertically. Never closer than the bounding sphere (the eye stays outside it).
double fitting_distance(const Bounds& bounds, const Eigen::Vector3d& center, double radius,
                        double fov_degrees, double aspect) {
  constexpr double kFill = 0.92;  // leave 4 % of the panel free on each side
  const double tan_v = std::tan(0.5 * fov_degrees * kDegree), tan_h = tan_v * aspect;
  const Eigen::Vector3d forward = -default_direction();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  double distance = 1.05 * radius;
  if (bounds.empty()) return radius / std::sin(std::atan(std::min(tan_v, tan_h)));
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1) ? bounds.max.x() : bounds.min.x(),
                                 (k & 2) ? bounds.max.y() : bounds.min.y(),
                                 (k & 4) ? bounds.max.z() : bounds.min.z());
    const Eigen::Vector3d o = corner - center;
    distance = std::max({distance, std::abs(o.dot(right)) / (tan_h * kFill) - o.dot(forward),
                         std::abs(o.dot(up)) / (tan_v * kFill) - o.dot(forward)});
  }
  return distance;
}

}  // namespace

void Bounds::add(const Eigen::Vector3d& p) {
  if (!p.allFinite()) return;
  min = min.cwiseMin(p);
  max = max.cwiseMax(p);
}

void Bounds::add(const Bounds& other) {
  if (other.empty()) return;
  add(other.min);
  add(other.max);
}

std::optional<CameraSpec> parse_camera_spec(const std::string& text, std::string* error) {
  CameraSpec spec;
  for (const std::string& raw : split(text, ';')) {
    const std::string item = trim(raw);
    if (item.empty()) continue;
    const auto equals = item.find('=');
    const std::string key = trim(item.substr(0, equals));
    const std::string value = equals == std::string::npos ? "" : item.substr(equals + 1);
    if (key == "eye" || key == "target") {
      const auto v = parse_vector(value);
      if (!v) {
        *error = "--camera: " + key + " must be three numbers x,y,z (m), got '" + trim(value) + "'";
        return std::nullopt;
      }
      (key == "eye" ? spec.eye : spec.target) = *v;
    } else if (key == "fov") {
      const auto v = parse_double(value);
      if (!v || *v <= 0.0 || *v >= 180.0) {
        *error = "--camera: fov must be a vertical field of view in (0, 180) degrees, got '" +
                 trim(value) + "'";
        return std::nullopt;
      }
      spec.fov_degrees = *v;
    } else {
      *error = "--camera: unknown key '" + key + "' (expected eye=x,y,z; target=x,y,z; fov=deg)";
      return std::nullopt;
    }
  }
  if (spec.eye && spec.target && (*spec.eye - *spec.target).norm() < 1e-9) {
    *error = "--camera: eye and target are the same point";
    return std::nullopt;
  }
  return spec;
}

Camera frame_camera(const Bounds& bounds, double aspect, const CameraSpec& spec,
                    double extra_radius) {
  Camera camera;
  camera.fov_degrees = spec.fov_degrees.value_or(kDefaultFovDegrees);
  const Eigen::Vector3d center = bounds.empty() ? Eigen::Vector3d::Zero() : bounds.center();
  const double radius = std::max(bounds.radius(), kMinimumRadius);
  const double distance = fitting_distance(bounds, center, radius, camera.fov_degrees, aspect);

  camera.target = spec.target.value_or(center);
  if (spec.eye) {
    camera.eye = *spec.eye;
  } else if (spec.target) {  // a target alone: the default direction and distance from it
    camera.eye = camera.target + distance * default_direction();
  } else {
    camera.eye = center + distance * default_direction();
  }
  if ((camera.eye - camera.target).norm() < 1e-9)
    camera.eye = camera.target + distance * default_direction();
  camera.up = up_for(camera.target - camera.eye);

  // Clip distances: everything within radius + extra_radius of the bounds' centre, seen from the
  // eye.
  const Eigen::Vector3d forward = (camera.target - camera.eye).normalized();
  const double reach = radius + extra_radius;
  const double along = (center - camera.eye).dot(forward);
  camera.far = std::max(along + reach, 1e-3) * 1.01;
  camera.near = std::max({along - reach, camera.far * 1e-4, 1e-4});
  return camera;
}

Eigen::Matrix4d view_matrix(const Camera& camera) {
  const Eigen::Vector3d f = (camera.target - camera.eye).normalized();
  const Eigen::Vector3d s = f.cross(camera.up).normalized();  // right
  const Eigen::Vector3d u = s.cross(f);                       // image up
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(camera.eye);
  m(1, 3) = -u.dot(camera.eye);
  m(2, 3) = f.dot(camera.eye);
  return m;
}

Eigen::Matrix4d projection_matrix(const Camera& camera, double aspect) {
  const double f = 1.0 / std::tan(0.5 * camera.fov_degrees * kDegree);
  const double n = camera.near, fa = camera.far;
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (fa + n) / (n - fa);
  m(2, 3) = 2.0 * fa * n / (n - fa);
  m(3, 2) = -1.0;
  return m;
}

std::optional<Eigen::Vector2d> project_to_pixel(const Camera& camera, const Eigen::Vector3d& p,
                                                int width, int height) {
  const double aspect = double(width) / height;
  const Eigen::Vector4d clip =
      projection_matrix(camera, aspect) * view_matrix(camera) * p.homogeneous();
  if (clip.w() <= 0.0) return std::nullopt;
  const double x_ndc = clip.x() / clip.w(), y_ndc = clip.y() / clip.w();
  return Eigen::Vector2d(0.5 * (x_ndc + 1.0) * width, 0.5 * (1.0 - y_ndc) * height);
}

}  // namespace drapelab::render
