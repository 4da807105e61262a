// The adaptive substeps' shape bound on plain arrays (shape_bound_loops.hpp). Built without
// contraction into fused multiply-adds: the same bits on every CPU.
#include "integrators/shape_bound_loops.hpp"

#include <algorithm>
#include <cmath>

#include "integrators/particle_loops.hpp"

namespace drapelab::kernels {
namespace {

// Particles per chunk of the per-particle pass: their two summed tensors (12 rows) stay in L1
// between the gather and the eigenvalue loop.
constexpr std::int64_t kBoundChunk = 256;

// Written without branches (selects instead), so that the loop over a chunk's particles vectorises;
// every select keeps the value the branching form would have, so the bits are those of that form.
inline double largest_eigenvalue(double a, double b, double c, double d, double e, double f) {
  // With q the mean eigenvalue and B = (A - q I) / p scaled to unit spread, the eigenvalues are
  // q + 2 p t for the roots t of 4 t^3 - 3 t = det(B) / 2 = r (cos 3 phi = 4 cos^3 phi - 3 cos phi,
  // so t = cos(acos(r) / 3) is the largest). Without trigonometric functions: at t = 1/2 + s the
  // cubic is 6 s^2 + 4 s^3 = 1 + r, so 1/2 + sqrt((1 + r) / 6) (and 1) lie above the root, and
  // Newton's method on this cubic, convex above its largest root, descends to it from there.
  const double off = d * d + e * e + f * f;
  const double q = (a + b + c) / 3.0;
  const double spread = (a - q) * (a - q) + (b - q) * (b - q) + (c - q) * (c - q) + 2.0 * off;
  const bool isotropic = spread <= 0.0;  // a multiple of the identity: q is the eigenvalue
  const double p = std::sqrt(isotropic ? 1.0 : spread / 6.0);
  // det(B) = det(A - q I) / p^3: one division instead of scaling each entry.
  const double sa = a - q, sb = b - q, sc = c - q;
  const double shifted_det = sa * (sb * sc - f * f) - d * (d * sc - f * e) + e * (d * f - sb * e);
  const double r = std::clamp(0.5 * shifted_det / (p * p * p), -1.0, 1.0);
  double t = std::min(1.0, 0.5 + std::sqrt((1.0 + r) / 6.0));
  for (int k = 0; k < 3;
       ++k) {  // three steps reach the root to about 1e-10 relative from this start
    const double excess = 4.0 * t * t * t - 3.0 * t - r;  // > 0 above the root
    const double slope = 12.0 * t * t - 3.0;              // > 0 for t > 1/2
    // At the root, to rounding, t stays: this step and every later one leave it as it is.
    const bool descend = excess > 0.0 && slope > 0.0;
    t = descend ? t - excess / (descend ? slope : 1.0) : t;
  }
  const double largest = isotropic ? q : q + 2.0 * p * t;
  return isotropic ? q : largest + 1e-9 * std::abs(largest);
}

// One spring's share of its particles' tensors at separation d = x_a - x_b (m): u u^T (xx, yy, zz,
// xy, xz, yz) and ks split into the part on u u^T and the part on I (N/m), with a = max(0, 1 - l0 /
// l). A spring of zero length has no direction: its "u u^T" is the identity, so it counts as stiff
// and damped in every direction (across = 0 puts its whole ks there).
struct SpringTerms {
  double uu[6];
  double along, isotropic;  // N/m
};
inline SpringTerms spring_terms(double dx, double dy, double dz, double rest, double ks) {
  const double squared = dx * dx + dy * dy + dz * dz;  // m^2
  const bool has_direction = squared > 0.0;
  const double inverse_length = has_direction ? 1.0 / std::sqrt(squared) : 0.0;  // 1/m
  const double ux = dx * inverse_length, uy = dy * inverse_length, uz = dz * inverse_length;
  const double across = has_direction ? std::max(0.0, 1.0 - rest * inverse_length) : 0.0;
  return {{has_direction ? ux * ux : 1.0, has_direction ? uy * uy : 1.0,
           has_direction ? uz * uz : 1.0, ux * uy, ux * uz, uy * uz},
          ks * (1.0 - across),
          ks * across};
}

// The rates of a chunk's particles from their summed tensors t (12 rows: S_i in N/m, then D_i in
// N*s/m) and inverse masses w (1/kg, 0 when pinned: a pinned particle bounds nothing), into the
// running maxima, in a vectorised loop over the chunk.
inline void chunk_rate_maxima(const double (&t)[12][kBoundChunk], const double* w,
                              std::int64_t count, double contact_stiffness, double contact_damping,
                              double& stiffness_rate, double& damping_rate) {
  double stiffness_max = stiffness_rate, damping_max = damping_rate;
#pragma omp simd reduction(max : stiffness_max, damping_max)
  for (std::int64_t j = 0; j < count; ++j) {
    const double stiffness =
        largest_eigenvalue(t[0][j], t[1][j], t[2][j], t[3][j], t[4][j], t[5][j]);
    const double damping =
        largest_eigenvalue(t[6][j], t[7][j], t[8][j], t[9][j], t[10][j], t[11][j]);
    stiffness_max =
        std::max(stiffness_max, w[j] == 0.0 ? 0.0 : (2.0 * stiffness + contact_stiffness) * w[j]);
    damping_max =
        std::max(damping_max, w[j] == 0.0 ? 0.0 : (2.0 * damping + contact_damping) * w[j]);
  }
  stiffness_rate = stiffness_max;
  damping_rate = damping_max;
}

}  // namespace

double largest_symmetric_eigenvalue(double a, double b, double c, double d, double e, double f) {
  return largest_eigenvalue(a, b, c, d, e, f);
}

ShapeRates shape_rate_maxima(std::int64_t n, IncidentSprings adjacency, SpringArrays s,
                             const double* inverse_mass, const double* x, double contact_stiffness,
                             double contact_damping, std::int64_t spring_count, double* terms) {
  // terms: 8 rows of spring_count values: the spring's u u^T (xx, yy, zz, xy, xz, yz), then ks (1 -
  // a) and ks a (N/m), a = max(0, 1 - l0 / l): the parts of ks on u u^T and on I.
  double* const uu[6] = {terms,
                         terms + spring_count,
                         terms + 2 * spring_count,
                         terms + 3 * spring_count,
                         terms + 4 * spring_count,
                         terms + 5 * spring_count};
  double* const along = terms + 6 * spring_count;
  double* const isotropic = terms + 7 * spring_count;
  double stiffness_rate = 0.0, damping_rate = 0.0;  // 1/s^2, 1/s
  const bool parallel = n >= kParallelParticles;
#pragma omp parallel if (parallel)
  {
    // 1. Each spring's direction and split stiffness, once, in a vectorised loop over the springs.
#pragma omp for simd schedule(simd : static)
    for (std::int64_t e = 0; e < spring_count; ++e) {
      const std::int64_t a = s.v0[e], b = s.v1[e];
      const SpringTerms terms_e =
          spring_terms(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1],
                       x[3 * a + 2] - x[3 * b + 2], s.rest_length[e], s.ks[e]);
      for (int c = 0; c < 6; ++c) uu[c][e] = terms_e.uu[c];
      along[e] = terms_e.along;
      isotropic[e] = terms_e.isotropic;
    }
    // 2. Chunk by chunk, each particle sums its own springs (no writes to shared sums, one order),
    // then the largest eigenvalues of its two tensors, in a vectorised loop over the chunk's
    // particles.
    const std::int64_t chunks = (n + kBoundChunk - 1) / kBoundChunk;
#pragma omp for schedule(static) reduction(max : stiffness_rate, damping_rate)
    for (std::int64_t chunk = 0; chunk < chunks; ++chunk) {
      const std::int64_t begin = chunk * kBoundChunk,
                         count = std::min(n, begin + kBoundChunk) - begin;
      double t[12][kBoundChunk];  // S_i (xx, yy, zz, xy, xz, yz) in N/m, then D_i in N*s/m
      for (std::int64_t j = 0; j < count; ++j) {
        double sum[12] = {};
        for (std::int64_t k = adjacency.first[begin + j]; k < adjacency.first[begin + j + 1]; ++k) {
          const std::int32_t e = adjacency.incident[k];
          for (int c = 0; c < 6; ++c) {
            const double on_identity = c < 3 ? isotropic[e] : 0.0;  // N/m
            sum[c] += along[e] * uu[c][e] + on_identity;
            sum[6 + c] += s.kd[e] * uu[c][e];
          }
        }
        for (int c = 0; c < 12; ++c) t[c][j] = sum[c];
      }
      chunk_rate_maxima(t, inverse_mass + begin, count, contact_stiffness, contact_damping,
                        stiffness_rate, damping_rate);
    }
  }
  return {stiffness_rate, damping_rate};
}

ShapeRates family_shape_rate_maxima(std::int64_t n, const std::vector<SpringFamily>& families,
                                    const double* inverse_mass, const double* x,
                                    double contact_stiffness, double contact_damping) {
  double stiffness_rate = 0.0, damping_rate = 0.0;  // 1/s^2, 1/s
  const std::int64_t chunks = (n + kBoundChunk - 1) / kBoundChunk;
#pragma omp parallel for schedule(static) \
    reduction(max                         \
              : stiffness_rate, damping_rate) if (n >= kParallelParticles)
  for (std::int64_t chunk = 0; chunk < chunks; ++chunk) {
    const std::int64_t begin = chunk * kBoundChunk,
                       count = std::min(n, begin + kBoundChunk) - begin;
    double t[12][kBoundChunk] = {};  // S_i (xx, yy, zz, xy, xz, yz) in N/m, then D_i in N*s/m
    // Particle i adds the terms of a spring at separation d (m; either sign: the terms are even in
    // d).
    const auto add_terms = [&t](std::int64_t j, double dx, double dy, double dz, double rest,
                                double ks, double kd) {
      const SpringTerms terms = spring_terms(dx, dy, dz, rest, ks);
      t[0][j] += terms.along * terms.uu[0] + terms.isotropic;
      t[1][j] += terms.along * terms.uu[1] + terms.isotropic;
      t[2][j] += terms.along * terms.uu[2] + terms.isotropic;
      t[3][j] += terms.along * terms.uu[3];
      t[4][j] += terms.along * terms.uu[4];
      t[5][j] += terms.along * terms.uu[5];
      for (int c = 0; c < 6; ++c) t[6 + c][j] += kd * terms.uu[c];
    };
    const std::int64_t end = begin + count;
    for (const SpringFamily& family : families) {
      const std::int64_t o = family.offset;
      const double* rest = family.rest.data();
      const double* ks = family.ks.data();
      const double* kd = family.kd.data();
      // Particle i starts slot i's spring (i, i + o), which exists only for i + o < n, and ends
      // slot i - o's, only for i >= o; an empty slot within those ranges has ks = kd = 0 and adds
      // exact zeros (for finite positions: a NaN one spreads to its slot partners, and the health
      // check then stops the run).
      const std::int64_t starts_end = std::min(end, n - o);
#pragma omp simd
      for (std::int64_t i = begin; i < starts_end; ++i)
        add_terms(i - begin, x[3 * i] - x[3 * (i + o)], x[3 * i + 1] - x[3 * (i + o) + 1],
                  x[3 * i + 2] - x[3 * (i + o) + 2], rest[i], ks[i], kd[i]);
      const std::int64_t ends_begin = std::max(begin, o);
#pragma omp simd
      for (std::int64_t i = ends_begin; i < end; ++i)
        add_terms(i - begin, x[3 * (i - o)] - x[3 * i], x[3 * (i - o) + 1] - x[3 * i + 1],
                  x[3 * (i - o) + 2] - x[3 * i + 2], rest[i - o], ks[i - o], kd[i - o]);
    }
    chunk_rate_maxima(t, inverse_mass + begin, count, contact_stiffness, contact_damping,
                      stiffness_rate, damping_rate);
  }
  return {stiffness_rate, damping_rate};
}

}  // namespace drapelab::kernels
