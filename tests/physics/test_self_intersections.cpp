// The self-intersection audit: the exact orient3d predicate (its float filter and GMP stage), the
// edge-triangle crossing test, and the count over hand-made meshes with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "drapelab/self_intersections.hpp"
#include "metrics/orient3d.hpp"

namespace drapelab {
namespace {

using Eigen::Vector3d;

// A mesh built piece by piece: vertices and triangles appended, indices shifted per piece.
struct Mesh {
  std::vector<Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;

  int add_vertex(const Vector3d& p) {
    vertices.push_back(p);
    return static_cast<int>(vertices.size()) - 1;
  }
  void add_triangle(int a, int b, int c) { triangles.emplace_back(a, b, c); }
  // An nu x nv vertex grid at origin + i du + j dv, each cell split along its (i, j)-(i+1, j+1)
  // diagonal.
  void add_grid(int nu, int nv, const Vector3d& origin, const Vector3d& du, const Vector3d& dv) {
    const int first = static_cast<int>(vertices.size());
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) add_vertex(origin + i * du + j * dv);
    auto at = [&](int i, int j) { return first + j * nu + i; };
    for (int j = 0; j + 1 < nv; ++j)
      for (int i = 0; i + 1 < nu; ++i) {
        add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
  }
  Eigen::Matrix3Xd x() const {
    Eigen::Matrix3Xd out(3, static_cast<Eigen::Index>(vertices.size()));
    for (std::size_t k = 0; k < vertices.size(); ++k)
      out.col(static_cast<Eigen::Index>(k)) = vertices[k];
    return out;
  }
  Eigen::Matrix3Xi faces() const {
    Eigen::Matrix3Xi out(3, static_cast<Eigen::Index>(triangles.size()));
    for (std::size_t k = 0; k < triangles.size(); ++k)
      out.col(static_cast<Eigen::Index>(k)) = triangles[k];
    return out;
  }
  int crossings() const { return count_self_intersections(faces(), x()); }
};

// The triangle (0,0,0), (1,0,0), (0,0,1) in the plane y = 0.
void add_floor_triangle(Mesh& mesh) {
  mesh.add_triangle(mesh.add_vertex({0, 0, 0}), mesh.add_vertex({1, 0, 0}),
                    mesh.add_vertex({0, 0, 1}));
}

// ---- orient3d ---------------------------------------------------------------------------------

TEST(Orient3d, SignFollowsTheSideOfThePlane) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);  // counter-clockwise seen from +z
  EXPECT_EQ(orient3d(a, b, c, {0.2, 0.2, -1.0}), 1);
  EXPECT_EQ(orient3d(a, b, c, {0.2, 0.2, 1.0}), -1);
  EXPECT_EQ(orient3d(a, b, c, {5.0, -3.0, 0.0}), 0);
}

TEST(Orient3d, IsAntisymmetricUnderSwappingAnyTwoPoints) {
  std::mt19937 random(12);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  auto point = [&] { return Vector3d(coordinate(random), coordinate(random), coordinate(random)); };
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3d a = point(), b = point(), c = point();
    Vector3d d = point();
    if (trial % 2 == 1) {
      // Half the cases nearly coplanar: on the plane of a, b, c up to rounding, so that the
      // filter often cannot decide and the exact stage must.
      const double u = coordinate(random), v = coordinate(random);
      d = a + u * (b - a) + v * (c - a);
    }
    const int s = orient3d(a, b, c, d);
    SCOPED_TRACE(trial);
    EXPECT_EQ(orient3d(b, a, c, d), -s);
    EXPECT_EQ(orient3d(a, c, b, d), -s);
    EXPECT_EQ(orient3d(a, b, d, c), -s);
    EXPECT_EQ(orient3d(d, b, c, a), -s);
    EXPECT_EQ(orient3d(b, c, a, d), s);  // an even permutation keeps it
    EXPECT_EQ(s, orient3d_exact(a, b, c, d));
    if (const auto filtered = orient3d_filtered(a, b, c, d)) {
      EXPECT_EQ(*filtered, s);
    }
  }
}

TEST(Orient3d, FourPointsSharingACoordinateAreCoplanarAsTheExactStageSays) {
  // A flat sheet's points: in a plane of constant y (and of constant x, z), where the filter
  // cannot decide.
  for (int axis = 0; axis < 3; ++axis) {
    Vector3d a(0.1, 0.7, 0.3), b(0.9, 0.2, 0.4), c(0.3, 0.5, 0.8), d(0.6, 0.1, 0.2);
    a[axis] = b[axis] = c[axis] = d[axis] = 0.37;
    EXPECT_EQ(orient3d(a, b, c, d), 0) << axis;
    EXPECT_EQ(orient3d_exact(a, b, c, d), 0) << axis;
  }
}

// The plane x + y + z = 1 through (1,0,0), (0,1,0), (0,0,1), counter-clockwise seen from
// (1,1,1). The doubles nearest 0.1, 0.2 and 0.7 sum to exactly 1 - 2^-55 (0.7 rounds down by more
// than 0.1 and 0.2 round up), so (0.1, 0.2, 0.7) lies just below the plane: a determinant of about
// 3e-17 against an error bound of about 1e-15.
TEST(Orient3d, TheExactStageDecidesWhatTheFilterCannot) {
  const Vector3d a(1, 0, 0), b(0, 1, 0), c(0, 0, 1);
  const Vector3d just_below(0.1, 0.2, 0.7);
  EXPECT_FALSE(orient3d_filtered(a, b, c, just_below).has_value()) << "the filter must give up";
  EXPECT_EQ(orient3d(a, b, c, just_below), 1);
  EXPECT_EQ(orient3d(a, b, c, just_below), orient3d_exact(a, b, c, just_below));
  // The doubles nearest 0.3, 0.3 and 0.4 sum to exactly 1: on the plane.
  const Vector3d on_plane(0.3, 0.3, 0.4);
  EXPECT_FALSE(orient3d_filtered(a, b, c, on_plane).has_value());
  EXPECT_EQ(orient3d(a, b, c, on_plane), 0);
  // A plain double evaluation rounds the first case to 0: the sum is 1 in doubles.
  EXPECT_EQ(just_below.sum() - 1.0, 0.0);
}

// The exact stage scales every coordinate to a whole number by the least power of two among them:
// it must hold for exponents far apart, for products that overflow a double, and for subnormals.
TEST(Orient3d, TheExactStageHoldsForAnyExponent) {
  // Tiny: the permanent (about 1e-903) is below what the filter trusts.
  const double t = std::ldexp(1.0, -301);
  const Vector3d origin(0, 0, 0);
  EXPECT_FALSE(orient3d_filtered(origin, {t, 0, 0}, {0, t, 0}, {0, 0, t}).has_value());
  EXPECT_EQ(orient3d(origin, {t, 0, 0}, {0, t, 0}, {0, 0, t}), -1);
  EXPECT_EQ(orient3d(origin, {t, 0, 0}, {0, t, 0}, {0, 0, -t}), 1);
  EXPECT_EQ(orient3d(origin, {t, 0, 0}, {0, t, 0}, {5.0, 7.0, 0.0}), 0);
  // Huge and tiny together in the plane z = 0, seen from a subnormal height above and below:
  // 1e300 squared overflows, so only the exact stage can answer.
  const Vector3d a(1e300, 0, 0), b(0, 1e-300, 0), c(-1e-300, -1e300, 0);
  const double subnormal = 1e-310;
  EXPECT_FALSE(orient3d_filtered(a, b, c, {0, 0, subnormal}).has_value());
  EXPECT_EQ(orient3d(a, b, c, {0, 0, subnormal}), -1);
  EXPECT_EQ(orient3d(a, b, c, {0, 0, -subnormal}), 1);
  EXPECT_EQ(orient3d(a, b, c, {3e-310, 1e200, 0}), 0);
}

// ---- the crossing test --------------------------------------------------------------------

TEST(SegmentCrossesTriangle, NeedsStrictCrossingThroughTheInside) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 0, 1);
  EXPECT_TRUE(segment_crosses_triangle({0.2, -1, 0.2}, {0.2, 1, 0.2}, a, b, c));
  EXPECT_TRUE(segment_crosses_triangle({0.2, 1, 0.2}, {0.2, -1, 0.2}, a, c, b)) << "any order";
  EXPECT_FALSE(segment_crosses_triangle({0.8, -1, 0.8}, {0.8, 1, 0.8}, a, b, c)) << "outside";
  EXPECT_FALSE(segment_crosses_triangle({0.2, 0.1, 0.2}, {0.2, 1, 0.2}, a, b, c)) << "one side";
  EXPECT_FALSE(segment_crosses_triangle({0.2, 0, 0.2}, {0.2, 1, 0.2}, a, b, c)) << "endpoint on";
  EXPECT_FALSE(segment_crosses_triangle({0.5, -1, 0}, {0.5, 1, 0}, a, b, c)) << "through a side";
  EXPECT_FALSE(segment_crosses_triangle({0, -1, 0}, {0, 1, 0}, a, b, c)) << "through a corner";
  EXPECT_FALSE(segment_crosses_triangle({0.1, 0, 0.1}, {0.3, 0, 0.2}, a, b, c)) << "coplanar";
  EXPECT_FALSE(segment_crosses_triangle(a, {0.2, 1, 0.2}, a, b, c)) << "shares a vertex";
  // A triangle in a plane of constant x: an endpoint with that x is on it.
  const Vector3d d(0.3, 0, 0), e(0.3, 1, 0), f(0.3, 0, 1);
  EXPECT_TRUE(segment_crosses_triangle({-1, 0.2, 0.2}, {1, 0.2, 0.2}, d, e, f)) << "across x";
  EXPECT_FALSE(segment_crosses_triangle({0.3, 0.2, 0.2}, {1, 0.2, 0.2}, d, e, f)) << "on x";
  EXPECT_FALSE(segment_crosses_triangle({1, 0.2, 0.2}, {0.3, 0.2, 0.2}, d, e, f)) << "on x, q";
}

TEST(SegmentCrossesTriangle, ANearlyCoplanarEndpointIsDecidedExactly) {
  const Vector3d a(1, 0, 0), b(0, 1, 0), c(0, 0, 1);
  const Vector3d above(0.3, 0.3, 0.9);  // x + y + z = 1.5
  // Just below the plane (see Orient3d.TheExactStageDecidesWhatTheFilterCannot): a crossing,
  // through the inside at barycentric (0.1, 0.2, 0.7) and (0.2, 0.2, 0.6) on the way.
  EXPECT_TRUE(segment_crosses_triangle({0.1, 0.2, 0.7}, above, a, b, c));
  // On the plane exactly: touching, not crossing.
  EXPECT_FALSE(segment_crosses_triangle({0.3, 0.3, 0.4}, above, a, b, c));
}

// ---- counts over meshes -------------------------------------------------------------------

TEST(SelfIntersections, FlatSheetAndParallelSheetsHaveNone) {
  Mesh flat;
  flat.add_grid(6, 6, {0, 0, 0}, {0.2, 0, 0}, {0, 0, 0.2});
  EXPECT_EQ(flat.crossings(), 0);
  Mesh two = flat;
  two.add_grid(6, 6, {0.05, 0.01, 0.05}, {0.2, 0, 0}, {0, 0, 0.2});  // 1 cm above, shifted
  EXPECT_EQ(two.crossings(), 0);
}

TEST(SelfIntersections, OneEdgeThroughOneTriangle) {
  // Two triangles sharing only the origin: their intersection runs from the shared corner to
  // where the edge b1-b2 pierces the floor triangle, so exactly one edge crosses.
  Mesh mesh;
  add_floor_triangle(mesh);
  mesh.add_triangle(0, mesh.add_vertex({0.3, -0.5, 0.3}), mesh.add_vertex({0.3, 0.5, 0.3}));
  EXPECT_EQ(mesh.crossings(), 1);
}

// A 5 x 5 vertex sheet in y = 0 over [0, 1]^2 (lines at x, z = 0.25 k; diagonals z - x = const)
// and a vertical strip in z = 0.6 pushed through it: columns at x = 0.3, 0.55, 0.8, rows at
// y = -0.1 and 0.1. Along their intersection line (y = 0, z = 0.6) the crossings are, by x:
// 0.3, 0.55, 0.8 (the strip's vertical edges), 0.425 and 0.675 (its diagonals), 0.5 and 0.75 (the
// sheet's z-direction edges) and 0.35 and 0.6 (the sheet's diagonals): 9 edges.
TEST(SelfIntersections, AStripPushedThroughASheetCrossesInAKnownPattern) {
  Mesh mesh;
  mesh.add_grid(5, 5, {0, 0, 0}, {0.25, 0, 0}, {0, 0, 0.25});
  mesh.add_grid(3, 2, {0.3, -0.1, 0.6}, {0.25, 0, 0}, {0, 0.2, 0});
  EXPECT_EQ(mesh.crossings(), 9);
  // Lifted out of the sheet: none.
  Mesh apart;
  apart.add_grid(5, 5, {0, 0, 0}, {0.25, 0, 0}, {0, 0, 0.25});
  apart.add_grid(3, 2, {0.3, 0.05, 0.6}, {0.25, 0, 0}, {0, 0.2, 0});
  EXPECT_EQ(apart.crossings(), 0);
}

TEST(SelfIntersections, TouchingDoesNotCount) {
  {  // a corner of one triangle on the inside of another
    Mesh mesh;
    add_floor_triangle(mesh);
    mesh.add_triangle(mesh.add_vertex({0.2, 0, 0.2}), mesh.add_vertex({0.6, 0.5, 0.2}),
                      mesh.add_vertex({0.2, 0.5, 0.6}));
    EXPECT_EQ(mesh.crossings(), 0);
  }
  {  // an edge through the floor triangle's corner (0, 0, 0)
    Mesh mesh;
    add_floor_triangle(mesh);
    mesh.add_triangle(mesh.add_vertex({0, -0.5, 0}), mesh.add_vertex({0, 0.5, 0}),
                      mesh.add_vertex({-0.5, 0.5, -0.5}));
    EXPECT_EQ(mesh.crossings(), 0);
  }
  {  // an edge through the middle of the floor triangle's side (0.5, 0, 0)
    Mesh mesh;
    add_floor_triangle(mesh);
    mesh.add_triangle(mesh.add_vertex({0.5, -0.5, 0}), mesh.add_vertex({0.5, 0.5, 0}),
                      mesh.add_vertex({0.5, 0.5, -0.5}));
    EXPECT_EQ(mesh.crossings(), 0);
  }
}

TEST(SelfIntersections, AFoldedSheetsOwnNeighboursDoNotCount) {
  // A strip folded back over itself about z = 0.5 by 178 degrees: the two halves' triangles meet
  // only along the fold, where neighbours share its vertices.
  Mesh mesh;
  const int n = 5;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = 0.25 * i, s = 0.25 * j;  // s: distance along the strip
      const double fold = 0.5, angle = (178.0 / 180.0) * 3.141592653589793;
      if (s <= fold)
        mesh.add_vertex({x, 0, s});
      else
        mesh.add_vertex({x, (s - fold) * std::sin(angle), fold + (s - fold) * std::cos(angle)});
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int v = j * n + i;
      mesh.add_triangle(v, v + 1, v + n + 1);
      mesh.add_triangle(v, v + n + 1, v + n);
    }
  EXPECT_EQ(mesh.crossings(), 0);
  // The far half's last two rows slid 10 cm along x and its last row pushed 5 cm down, through the
  // near half: the edges between those rows cross it (at z of about 0.2, away from its grid
  // lines), while the fold's neighbours still only touch.
  Mesh pushed = mesh;
  for (int k = 3 * n; k < n * n; ++k) pushed.vertices[static_cast<std::size_t>(k)].x() += 0.1;
  for (int k = 4 * n; k < n * n; ++k) pushed.vertices[static_cast<std::size_t>(k)].y() -= 0.05;
  EXPECT_GE(pushed.crossings(), 8);
}

TEST(SelfIntersections, NonFiniteVerticesAreLeftOut) {
  Mesh mesh;
  mesh.add_grid(5, 5, {0, 0, 0}, {0.25, 0, 0}, {0, 0, 0.25});
  mesh.add_grid(3, 2, {0.3, -0.1, 0.6}, {0.25, 0, 0}, {0, 0.2, 0});
  mesh.vertices[0].x() = std::numeric_limits<double>::quiet_NaN();  // far from the strip
  EXPECT_EQ(mesh.crossings(), 9);
}

TEST(SelfIntersections, UniqueEdgesOfAGrid) {
  Mesh mesh;
  mesh.add_grid(4, 3, {0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  // 3 x 3 along x, 4 x 2 along z, one diagonal per cell (6 cells).
  EXPECT_EQ(unique_edges(mesh.faces()).size(), 9u + 8u + 6u);
}

}  // namespace
}  // namespace drapelab
