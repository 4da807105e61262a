// orient3d with a static floating-point filter and an exact GMP integer fallback (see
// orient3d.hpp). Built with -ffp-contract=off (engine/CMakeLists.txt): the error bound assumes
// every product and sum is rounded on its own, which a fused multiply-add would break.
#include "metrics/orient3d.hpp"

#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace drapelab {
namespace {

// Shewchuk's bound for the determinant below, computed from rounded differences (Shewchuk 1997,
// "Adaptive precision floating-point arithmetic and fast robust geometric predicates",
// o3derrboundA): |rounded - exact| <= (7 + 56 eps) eps * permanent with eps = 2^-53, the unit
// round-off of a double.
constexpr double kEpsilon = 0x1p-53;
constexpr double kErrorBoundFactor = (7.0 + 56.0 * kEpsilon) * kEpsilon;
// The bound ignores underflow: with a permanent this small, products may have lost bits to
// subnormal rounding, so the exact stage decides. Cloth coordinates never come near it.
constexpr double kSmallestTrustedPermanent = 1e-250;

// GMP integers kept by each thread for the exact stage: the twelve scaled coordinates, the nine
// differences, a product and the sum.
struct ExactScratch {
  mpz_t value[12], difference[9], product, sum;
  ExactScratch() {
    for (mpz_t& z : value) mpz_init2(z, 128);
    for (mpz_t& z : difference) mpz_init2(z, 128);
    mpz_init2(product, 256);
    mpz_init2(sum, 384);
  }
  ~ExactScratch() {
    for (mpz_t& z : value) mpz_clear(z);
    for (mpz_t& z : difference) mpz_clear(z);
    mpz_clear(product);
    mpz_clear(sum);
  }
  ExactScratch(const ExactScratch&) = delete;
  ExactScratch& operator=(const ExactScratch&) = delete;
};

}  // namespace

std::optional<int> orient3d_filtered(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double determinant =
      adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  // Not finite (overflow) or too small to trust: undecided. Comparisons with NaN are false.
  if (!(permanent >= kSmallestTrustedPermanent) || !std::isfinite(permanent)) return std::nullopt;
  const double bound = kErrorBoundFactor * permanent;
  if (determinant > bound) return 1;
  if (-determinant > bound) return -1;
  return std::nullopt;
}

int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  // Every finite double is m 2^e with m a whole number below 2^53. Scaled by 2^-emin (the least e
  // of the twelve), every coordinate is a whole number, and the determinant's sign is that of the
  // scaled one (a positive factor 2^(3 emin) apart), computed exactly with GMP's integers. Their
  // storage is the thread's own and kept from call to call: after the first calls nothing is
  // allocated (rationals allocated and reduced by their gcd at every operation, most of a metric
  // pass on a flat cloth, whose coplanar points all reach this stage).
  const double coordinate[12] = {a.x(), a.y(), a.z(), b.x(), b.y(), b.z(),
                                 c.x(), c.y(), c.z(), d.x(), d.y(), d.z()};
  long mantissa[12];
  int exponent[12];
  int least = std::numeric_limits<int>::max();
  for (int k = 0; k < 12; ++k) {
    int e = 0;
    const double fraction = std::frexp(coordinate[k], &e);  // in [0.5, 1), or 0
    mantissa[k] = static_cast<long>(std::ldexp(fraction, 53));
    exponent[k] = e - 53;
    if (mantissa[k] != 0) least = std::min(least, exponent[k]);
  }
  thread_local ExactScratch scratch;
  for (int k = 0; k < 12; ++k) {
    mpz_set_si(scratch.value[k], mantissa[k]);
    if (mantissa[k] != 0)
      mpz_mul_2exp(scratch.value[k], scratch.value[k],
                   static_cast<mp_bitcnt_t>(exponent[k] - least));
  }
  // Differences from d: a - d, b - d, c - d, each x, y, z.
  mpz_t* v = scratch.value;
  mpz_t* dd = scratch.difference;
  for (int row = 0; row < 3; ++row)
    for (int axis = 0; axis < 3; ++axis)
      mpz_sub(dd[3 * row + axis], v[3 * row + axis], v[9 + axis]);
  // adz (bdx cdy - cdx bdy) + bdz (cdx ady - adx cdy) + cdz (adx bdy - bdx ady).
  const auto x = [&](int row) { return dd[3 * row]; };
  const auto y = [&](int row) { return dd[3 * row + 1]; };
  const auto z = [&](int row) { return dd[3 * row + 2]; };
  mpz_set_ui(scratch.sum, 0);
  for (int row = 0; row < 3; ++row) {
    const int next = (row + 1) % 3, last = (row + 2) % 3;
    mpz_mul(scratch.product, x(next), y(last));
    mpz_submul(scratch.product, x(last), y(next));
    mpz_addmul(scratch.sum, z(row), scratch.product);
  }
  return mpz_sgn(scratch.sum);
}

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  if (const std::optional<int> sign = orient3d_filtered(a, b, c, d)) return *sign;
  // Four points sharing one coordinate lie in a plane of constant x, y or z: exactly 0. A sheet
  // lying flat (a grid falling in a plane of constant y) would otherwise send every pair of its
  // edges and triangles to the exact stage only to get that 0.
  for (int axis = 0; axis < 3; ++axis)
    if (d[axis] == a[axis] && d[axis] == b[axis] && d[axis] == c[axis]) return 0;
  return orient3d_exact(a, b, c, d);
}

}  // namespace drapelab
