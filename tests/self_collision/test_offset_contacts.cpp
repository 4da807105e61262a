// Offset geometric contact's parts alone: the barrier energy's continuity and derivatives, the
// closest points of the plain-array kernels against the Eigen ones, the feasible-region admission
// (a flat sheet has no contacts, two sheets one above the other do), the conservative bounds
// against a brute-force search, and the same detection on one and two threads.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "core/offset_barrier.hpp"
#include "core/offset_contact_arrays.hpp"
#include "core/proximity.hpp"
#include "drapelab/grid_cloth.hpp"
#include "drapelab/loop_threads.hpp"
#include "layered_cloth.hpp"
#include "self_collision/cloth_topology.hpp"
#include "self_collision/offset_contacts.hpp"

namespace drapelab {
namespace {

TEST(OffsetBarrier, IsZeroBeyondTheOffsetAndGrowsWithoutBoundAsTheGapCloses) {
  const OffsetBarrier g{0.004, 500.0};
  EXPECT_EQ(g.energy(0.004), 0.0);
  EXPECT_EQ(g.slope(0.005), 0.0);
  EXPECT_EQ(g.curvature(0.0041), 0.0);
  // Logarithmic: 190 times the energy at 1 mm at 1e-100 m.
  EXPECT_GT(g.energy(1e-100), 100.0 * g.energy(0.001));
  double last = 0.0;
  for (double d = 0.0039; d > 1e-12; d *= 0.5) {
    EXPECT_GT(g.energy(d), last);
    EXPECT_LT(g.slope(d), 0.0);
    EXPECT_GT(g.curvature(d), 0.0);
    last = g.energy(d);
  }
}

TEST(OffsetBarrier, ItsValueSlopeAndCurvatureAreContinuousAtTheSwitch) {
  const OffsetBarrier g{0.003, 2000.0};
  const double tau = g.switch_distance(), e = 1e-12;
  EXPECT_NEAR(g.energy(tau - e), g.energy(tau + e), 1e-8 * g.energy(tau));
  EXPECT_NEAR(g.slope(tau - e), g.slope(tau + e), 1e-6 * std::abs(g.slope(tau)));
  EXPECT_NEAR(g.curvature(tau - e), g.curvature(tau + e), 1e-6 * g.curvature(tau));
}

TEST(OffsetBarrier, ItsSlopeAndCurvatureMatchFiniteDifferences) {
  const OffsetBarrier g{0.005, 800.0};
  for (const double d : {1e-5, 4e-4, 0.0012, 0.0024, 0.0026, 0.0031, 0.0049}) {
    const double step = 1e-9 * d;
    EXPECT_NEAR(g.slope(d), (g.energy(d + step) - g.energy(d - step)) / (2 * step),
                1e-5 * std::abs(g.slope(d)))
        << d;
    EXPECT_NEAR(g.curvature(d), (g.slope(d + step) - g.slope(d - step)) / (2 * step),
                1e-5 * g.curvature(d))
        << d;
  }
}

// The plain kernels' closest points are the Eigen ones (core/proximity.hpp) at random shapes.
TEST(OffsetContactArrays, ClosestPointsMatchTheEigenOnes) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto point = [&] { return Eigen::Vector3d(unit(random), unit(random), unit(random)); };
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d p = point(), a = point(), b = point(), c = point(), q = point();
    const PointTriangleProximity near = closest_point_on_triangle(p, a, b, c);
    double w[3];
    offset_contact::triangle_weights(p.data(), a.data(), b.data(), c.data(), w);
    EXPECT_LT((w[0] * a + w[1] * b + w[2] * c - near.closest).norm(), 1e-12) << trial;
    const SegmentProximity pair = closest_points_of_segments(p, q, a, b);
    double s = 0.0, t = 0.0;
    offset_contact::segment_pair_parameters(p.data(), q.data(), a.data(), b.data(), s, t);
    const double gap = ((p + s * (q - p)) - (a + t * (b - a))).norm();
    EXPECT_NEAR(gap, (pair.on_first - pair.on_second).norm(), 1e-12) << trial;
  }
}

GridClothSpec flat_sheet(int n, double y) {
  GridClothSpec spec;
  spec.size = {0.4, 0.4};
  spec.nx = spec.ny = n;
  spec.plane = GridPlane::xz;
  spec.center = {0.0, y, 0.0};
  spec.mass = 0.05;
  spec.thickness = 0.004;
  return spec;
}

SelfCollisionSettings self_settings(double thickness) {
  SelfCollisionSettings s;
  s.enabled = true;
  s.thickness = thickness;
  s.stiffness = 500.0;
  return s;
}

// A flat sheet's particles lie 0.7 of an edge from their neighbours' far edges: with a thickness
// of 0.6 of an edge, mesh distance alone would make each of them a contact, the feasible regions
// none.
TEST(OffsetContacts, AFlatSheetHasNoContactsHoweverThickItsLayer) {
  const ClothModel model = build_grid_cloth(flat_sheet(17, 1.0));
  const double edge = 0.4 / 16;
  OffsetContacts contacts(model, self_settings(0.6 * edge));
  contacts.detect(model.rest_positions, Eigen::Vector3d::Zero());
  EXPECT_EQ(contacts.contact_count(), 0);
  // Each particle's bound is set by its own neighbourhood: 0.45 of the nearest untouched primitive,
  // at most 0.7 of an edge away.
  for (const double bound : contacts.bounds()) {
    EXPECT_GT(bound, 0.45 * 0.5 * edge);
    EXPECT_LE(bound, 0.45 * 0.71 * edge);
  }
}

// Two sheets 2 mm apart with a 3 mm offset: every particle of the upper one over the lower's
// inside is in contact with a face of it.
TEST(OffsetContacts, TwoSheetsOneAboveTheOtherAreInContactAcrossTheirFaces) {
  const ClothModel model = fixtures::stacked_cloth({flat_sheet(9, 1.0), flat_sheet(9, 1.002)});
  OffsetContacts contacts(model, self_settings(0.003));
  Eigen::Matrix3Xd x = model.rest_positions;
  // The upper sheet shifted by a third of a cell, so its particles lie over the lower's faces.
  x.rightCols(81).colwise() += Eigen::Vector3d(0.4 / 24, 0.0, 0.4 / 48);
  contacts.detect(x, Eigen::Vector3d::Zero());
  EXPECT_GE(contacts.contact_count(), 49);  // at least the upper sheet's inner particles
  const OffsetContactArrays arrays = contacts.arrays();
  for (std::int64_t c = 0; c < arrays.count; ++c) {
    const std::int32_t* p = arrays.particle + 4 * c;
    const bool upper0 = p[0] >= 81;
    // A contact joins the two sheets, never one sheet to itself.
    if (arrays.kind[c] == SelfContactKind::edge_edge) continue;
    for (int s = 1; s < 4; ++s) {
      if (p[s] >= 0) {
        EXPECT_NE(p[s] >= 81, upper0);
      }
    }
  }
  // The bounds keep every particle within 0.45 of the 2 mm gap.
  for (const double bound : contacts.bounds()) EXPECT_LE(bound, 0.45 * 0.002 + 1e-12);
}

// The bounds against a brute-force search: 0.45 of the smallest distance between a primitive the
// particle belongs to and any primitive it does not touch, up to the reach.
TEST(OffsetContacts, BoundsMatchABruteForceSearch) {
  GridClothSpec spec = flat_sheet(9, 1.0);
  ClothModel model = build_grid_cloth(spec);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Crumpled: each particle moved by up to a cell in every direction.
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int i = 0; i < x.cols(); ++i)
    x.col(i) += 0.05 * Eigen::Vector3d(unit(random), unit(random), unit(random));
  OffsetContacts contacts(model, self_settings(0.01));
  contacts.detect(x, Eigen::Vector3d::Zero());
  const ClothTopology topology(model);
  const Eigen::Matrix3Xi& tri = model.triangles;
  std::vector<double> nearest(static_cast<std::size_t>(x.cols()), contacts.reach());
  for (int p = 0; p < x.cols(); ++p)
    for (int t = 0; t < tri.cols(); ++t) {
      if (topology.is_corner(p, t)) continue;
      const double d = (x.col(p) - closest_point_on_triangle(x.col(p), x.col(tri(0, t)),
                                                             x.col(tri(1, t)), x.col(tri(2, t)))
                                       .closest)
                           .norm();
      for (const int q : {p, tri(0, t), tri(1, t), tri(2, t)}) nearest[q] = std::min(nearest[q], d);
    }
  const auto& edges = topology.edges();
  for (std::size_t a = 0; a < edges.size(); ++a)
    for (std::size_t b = a + 1; b < edges.size(); ++b) {
      const auto& e = edges[a];
      const auto& f = edges[b];
      if (e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1]) continue;
      const SegmentProximity near =
          closest_points_of_segments(x.col(e[0]), x.col(e[1]), x.col(f[0]), x.col(f[1]));
      const double d = (near.on_first - near.on_second).norm();
      for (const int q : {e[0], e[1], f[0], f[1]}) nearest[q] = std::min(nearest[q], d);
    }
  for (int p = 0; p < x.cols(); ++p)
    EXPECT_NEAR(contacts.bounds()[p], kConservativeBoundFraction * nearest[p], 1e-12) << p;
}

// The same contacts, in the same order, and the same bounds on one thread and on two.
TEST(OffsetContacts, DetectionIsTheSameOnOneAndTwoThreads) {
  GridClothSpec spec = flat_sheet(41, 1.0);
  ClothModel model = build_grid_cloth(spec);
  std::mt19937 random(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::Matrix3Xd x = model.rest_positions;
  for (int i = 0; i < x.cols(); ++i) x(1, i) += 0.02 * unit(random);  // a rumpled sheet
  // Folded over itself: the far half turned onto the near one, 3 mm above it.
  for (int i = 0; i < x.cols(); ++i)
    if (x(0, i) > 0.0) {
      x(0, i) = -x(0, i);
      x(1, i) = 1.003 + 0.2 * (1.0 - x(1, i));
    }
  const auto detect = [&](int threads) {
    kernels::set_thread_count(threads);
    OffsetContacts contacts(model, self_settings(0.004));
    contacts.detect(x, Eigen::Vector3d::Zero());
    const OffsetContactArrays a = contacts.arrays();
    std::vector<std::int32_t> particles(a.particle, a.particle + 4 * a.count);
    return std::make_pair(particles, contacts.bounds());
  };
  const auto one = detect(1);
  const auto two = detect(2);
  kernels::set_thread_count(2);
  EXPECT_GT(one.first.size(), 0u);
  EXPECT_EQ(one.first, two.first);
  EXPECT_EQ(one.second, two.second);
}

}  // namespace
}  // namespace drapelab
