// orient3d with a static floating-point filter and a GMP fallback (see orient3d.hpp). Built with
// -ffp-contract=off (engine/CMakeLists.txt): the error bound assumes every product and sum is
// rounded on its own, which a fused multiply-add would break.
#include "metrics/orient3d.hpp"

#include <gmpxx.h>

#include <cmath>

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

int sign_of(const mpq_class& value) {
  const int s = sgn(value);
  return (s > 0) - (s < 0);
}

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
  // A double converts to a rational exactly; so do their differences, products and sums.
  const mpq_class dx(d.x()), dy(d.y()), dz(d.z());
  const mpq_class adx = mpq_class(a.x()) - dx, ady = mpq_class(a.y()) - dy,
                  adz = mpq_class(a.z()) - dz;
  const mpq_class bdx = mpq_class(b.x()) - dx, bdy = mpq_class(b.y()) - dy,
                  bdz = mpq_class(b.z()) - dz;
  const mpq_class cdx = mpq_class(c.x()) - dx, cdy = mpq_class(c.y()) - dy,
                  cdz = mpq_class(c.z()) - dz;
  const mpq_class determinant =
      adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
  return sign_of(determinant);
}

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  if (const std::optional<int> sign = orient3d_filtered(a, b, c, d)) return *sign;
  return orient3d_exact(a, b, c, d);
}

}  // namespace drapelab
