#include "frame_tables.hpp"

#include <algorithm>
#include <cmath>

#include "drapelab/runner/metric_columns.hpp"
#include "drapelab/scene/number_format.hpp"
#include "drapelab/surface_distance.hpp"

namespace drapelab::runner {
namespace {

std::string optional_cell(const std::optional<double>& value) {
  return value ? format_number(*value) : std::string();
}

std::vector<std::string> metrics_header() {
  std::vector<std::string> header{"solver", "frame", "time"};
  for (const MetricColumn& column : metric_columns()) header.push_back(column.name);
  return header;
}

}  // namespace

StateDifference compare_states(const ClothModel& model, const ClothState& a, const ClothState& b) {
  StateDifference d;
  const bool has_area = model.rest_area() > 0.0;
  double weighted = 0.0, weight = 0.0;
  for (int i = 0; i < model.particle_count(); ++i) {
    const double distance_squared = (a.x.col(i) - b.x.col(i)).squaredNorm();
    const double w = has_area ? model.vertex_area[i] : 1.0;
    weighted += w * distance_squared;
    weight += w;
    d.max_distance = std::max(d.max_distance, std::sqrt(distance_squared));
  }
  d.rms_distance = weight > 0.0 ? std::sqrt(weighted / weight) : 0.0;
  d.hausdorff_distance = hausdorff_distance(a.x, b.x, model.triangles);
  return d;
}

FrameTables::FrameTables(const std::filesystem::path& folder, bool bodies)
    : metrics_(folder / "metrics.csv", metrics_header()),
      compare_(folder / "compare.csv", {"solver_a", "solver_b", "frame", "time", "rms_distance",
                                        "max_distance", "hausdorff_distance"}),
      contacts_(folder / "contacts.csv", {"solver", "frame", "time", "collider", "contact_count",
                                          "normal_force", "friction_force", "max_penetration"}) {
  if (bodies)
    bodies_.emplace(
        folder / "bodies.csv",
        std::vector<std::string>{"solver", "frame", "time", "collider", "x", "y", "z", "qx", "qy",
                                 "qz", "qw", "vx", "vy", "vz", "wx", "wy", "wz"});
}

void FrameTables::add_metrics(const std::string& solver, int frame, double time,
                              const ClothMetrics& m) {
  std::vector<std::string> cells{solver, std::to_string(frame), format_number(time)};
  for (const MetricColumn& column : metric_columns())
    cells.push_back(optional_cell(column.value(m)));
  metrics_.row(cells);
}

void FrameTables::add_comparison(const std::string& solver_a, const std::string& solver_b,
                                 int frame, double time, const StateDifference& difference) {
  compare_.row({solver_a, solver_b, std::to_string(frame), format_number(time),
                format_number(difference.rms_distance), format_number(difference.max_distance),
                format_number(difference.hausdorff_distance)});
}

void FrameTables::add_contact(const std::string& solver, int frame, double time,
                              const std::string& collider, int contact_count, double normal_force,
                              double friction_force, double max_penetration) {
  contacts_.row({solver, std::to_string(frame), format_number(time), collider,
                 std::to_string(contact_count), format_number(normal_force),
                 format_number(friction_force), format_number(max_penetration)});
}

void FrameTables::add_body(const std::string& solver, int frame, double time,
                           const std::string& collider, const BodyState& body) {
  const Eigen::Vector3d& p = body.pose.translation();
  const Eigen::Quaterniond q(body.pose.linear());
  const Eigen::Vector3d& v = body.velocity;
  const Eigen::Vector3d& w = body.angular_velocity;
  bodies_->row({solver, std::to_string(frame), format_number(time), collider, format_number(p.x()),
                format_number(p.y()), format_number(p.z()), format_number(q.x()),
                format_number(q.y()), format_number(q.z()), format_number(q.w()),
                format_number(v.x()), format_number(v.y()), format_number(v.z()),
                format_number(w.x()), format_number(w.y()), format_number(w.z())});
}

void FrameTables::flush() {
  metrics_.flush();
  compare_.flush();
  contacts_.flush();
  if (bodies_) bodies_->flush();
}

void FrameTables::commit() {
  metrics_.commit();
  compare_.commit();
  contacts_.commit();
  if (bodies_) bodies_->commit();
}

bool FrameTables::rollback() noexcept {
  const bool metrics = metrics_.rollback();
  const bool compare = compare_.rollback();
  const bool contacts = contacts_.rollback();
  const bool bodies = !bodies_ || bodies_->rollback();
  return metrics && compare && contacts && bodies;
}

}  // namespace drapelab::runner
