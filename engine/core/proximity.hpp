// Closest points between cloth primitives, as pure functions over plain values: a point and a
// triangle, two segments. Both return where the closest points lie as barycentric weights, so a
// force at the contact can be spread over the primitives' particles.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace drapelab {

// The angle (rad) between two directions, as atan2(|u x w|, u . w): exact near 0 and pi, where an
// arccosine of the normalised dot product loses half its digits.
inline double angle_between(const Eigen::Vector3d& u, const Eigen::Vector3d& w) {
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

// Where the closest point of a triangle lies: inside it, on one of its edges, or at a corner.
enum class TriangleRegion { face, edge, corner };

struct PointTriangleProximity {
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric (a, b, c) of the closest point
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();  // m, the closest point of the triangle
  TriangleRegion region = TriangleRegion::face;
  // On an edge: the corner (0, 1, 2) opposite it, so the edge is the other two. At a corner: that
  // corner.
  int feature = 0;
};

// The point of triangle (a, b, c) closest to p, by the Voronoi regions of its corners and edges
// (Ericson, Real-Time Collision Detection, 5.1.5). A degenerate triangle is handled as its
// edges.
inline PointTriangleProximity closest_point_on_triangle(const Eigen::Vector3d& p,
                                                        const Eigen::Vector3d& a,
                                                        const Eigen::Vector3d& b,
                                                        const Eigen::Vector3d& c) {
  PointTriangleProximity out;
  auto corner = [&](int k, const Eigen::Vector3d& at) {
    out.weights.setZero();
    out.weights[k] = 1.0;
    out.closest = at;
    out.region = TriangleRegion::corner;
    out.feature = k;
    return out;
  };
  // Along edge from corner i (weight 1 - t) to corner j (weight t); `opposite` the third corner.
  auto edge = [&](int i, int j, int opposite, double t, const Eigen::Vector3d& from,
                  const Eigen::Vector3d& to) {
    out.weights.setZero();
    out.weights[i] = 1.0 - t;
    out.weights[j] = t;
    out.closest = from + t * (to - from);
    out.region = TriangleRegion::edge;
    out.feature = opposite;
    return out;
  };
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return corner(0, a);
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return corner(1, b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return edge(0, 1, 2, d1 / (d1 - d3), a, b);
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return corner(2, c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return edge(0, 2, 1, d2 / (d2 - d6), a, c);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return edge(1, 2, 0, (d4 - d3) / ((d4 - d3) + (d5 - d6)), b, c);
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // degenerate (zero-area) triangle: the nearest of its edges
    const auto on_segment = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
      const Eigen::Vector3d d = to - from;
      const double length2 = d.squaredNorm();
      return length2 > 0.0 ? std::clamp((p - from).dot(d) / length2, 0.0, 1.0) : 0.0;
    };
    const double t_ab = on_segment(a, b), t_ac = on_segment(a, c), t_bc = on_segment(b, c);
    const double e_ab = (a + t_ab * ab - p).squaredNorm();
    const double e_ac = (a + t_ac * ac - p).squaredNorm();
    const double e_bc = (b + t_bc * (c - b) - p).squaredNorm();
    if (e_ab <= e_ac && e_ab <= e_bc) return edge(0, 1, 2, t_ab, a, b);
    if (e_ac <= e_bc) return edge(0, 2, 1, t_ac, a, c);
    return edge(1, 2, 0, t_bc, b, c);
  }
  const double v = vb / sum, w = vc / sum;
  out.weights = Eigen::Vector3d(1.0 - v - w, v, w);
  out.closest = a + v * ab + w * ac;
  out.region = TriangleRegion::face;
  out.feature = -1;
  return out;
}

struct SegmentProximity {
  double s = 0.0;  // the closest point of the first segment: p0 + s (p1 - p0), s in [0, 1]
  double t = 0.0;  // ... of the second: q0 + t (q1 - q0)
  Eigen::Vector3d on_first = Eigen::Vector3d::Zero();   // m
  Eigen::Vector3d on_second = Eigen::Vector3d::Zero();  // m
};

// The closest points of segments p0-p1 and q0-q1 (Ericson 5.1.9). Parallel segments get the pair
// found from s = 0 (or the clamped one), so their closest points lie at an end of one of them.
inline SegmentProximity closest_points_of_segments(const Eigen::Vector3d& p0,
                                                   const Eigen::Vector3d& p1,
                                                   const Eigen::Vector3d& q0,
                                                   const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  // Below this a segment is a point (m^2): far under any cloth edge.
  constexpr double kPointLength2 = 1e-24;
  double s = 0.0, t = 0.0;
  if (a <= kPointLength2 && e <= kPointLength2) {
    s = t = 0.0;
  } else if (a <= kPointLength2) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kPointLength2) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denominator = a * e - b * b;  // >= 0; 0 when parallel
      // Parallel within rounding: s = 0, as the clamped pair below then gives.
      s = denominator > 1e-12 * a * e ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return {s, t, p0 + s * d1, q0 + t * d2};
}

}  // namespace drapelab
