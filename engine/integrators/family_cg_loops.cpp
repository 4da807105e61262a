// Backward Euler's matrix-free solve for spring families (family_cg_loops.hpp). Every loop runs
// over fixed blocks of particles (each thread one contiguous run, core/thread_blocks.hpp's
// for_each_block); a product is two passes, the slot terms B_s (p_a - p_b) of every family and then
// each particle's gather of its slots, so no two threads ever write one value.
#include "integrators/family_cg_loops.hpp"

#include <algorithm>
#include <cmath>

#include "integrators/coupling_product.hpp"
#include "integrators/particle_loops.hpp"

namespace drapelab::kernels {
namespace {

// Particles per block. Fixed, never derived from the thread count, so every sum runs in the same
// order.
constexpr std::int64_t kBlock = 512;

// The CG's vectors (FamilySystem::vector_row): solution, residual, preconditioned residual, search
// direction and its product with A; the sixth holds the unpacked velocity during the assembly and
// the right-hand side at the start of the solve.
enum Vector : int {
  kSolution = 0,
  kResidual,
  kPreconditioned,
  kDirection,
  kProduct,
  kScratch,
  kCount
};

// Three rows of one vector.
struct Rows {
  double* c[3];
};

Rows rows(FamilySystem& s, int which) {
  return {{s.vector_row(which, 0), s.vector_row(which, 1), s.vector_row(which, 2)}};
}

struct BlockRange {
  std::int64_t begin, end;
};

BlockRange block_range(const FamilySystem& s, std::int64_t block) {
  return {block * kBlock, std::min(s.particles, (block + 1) * kBlock)};
}

std::int64_t block_count(const FamilySystem& s) { return (s.particles + kBlock - 1) / kBlock; }
bool threaded(const FamilySystem& s) { return s.particles >= kParallelParticles; }

// The per-block partial sums of one pass, added in block order.
double sum_partials(const FamilySystem& s, int column) {
  double total = 0.0;
  for (std::int64_t block = 0; block < block_count(s); ++block)
    total += s.partials[2 * block + column];
  return total;
}

// Slot terms t_f = B_f (p(i) - p(i + offset)) of every family, for the slots of one block.
void slot_terms(FamilySystem& s, const Rows& p, BlockRange range) {
  for (std::size_t f = 0; f < s.offsets.size(); ++f) {
    const std::int64_t o = s.offsets[f];
    const double* ux = s.spring_row(f, 0);
    const double* uy = s.spring_row(f, 1);
    const double* uz = s.spring_row(f, 2);
    const double* a = s.spring_row(f, 3);
    const double* b = s.spring_row(f, 4);
    double* tx = s.term_row(f, 0);
    double* ty = s.term_row(f, 1);
    double* tz = s.term_row(f, 2);
    const double *px = p.c[0], *py = p.c[1], *pz = p.c[2];
#pragma omp simd
    for (std::int64_t i = range.begin; i < range.end; ++i) {
      const double dx = px[i] - px[i + o], dy = py[i] - py[i + o], dz = pz[i] - pz[i + o];
      const double along = a[i] * (ux[i] * dx + uy[i] * dy + uz[i] * dz);
      tx[i] = along * ux[i] + b[i] * dx;
      ty[i] = along * uy[i] + b[i] * dy;
      tz[i] = along * uz[i] + b[i] * dz;
    }
  }
}

// out(i) = sum over families, in order, of t_f(i) - t_f(i - offset), for the particles of one
// block.
void gather_terms(FamilySystem& s, BlockRange range, const Rows& out) {
  for (int c = 0; c < 3; ++c) std::fill(out.c[c] + range.begin, out.c[c] + range.end, 0.0);
  for (std::size_t f = 0; f < s.offsets.size(); ++f) {
    const std::int64_t o = s.offsets[f];
    for (int c = 0; c < 3; ++c) {
      const double* t = s.term_row(f, c);
      double* y = out.c[c];
#pragma omp simd
      for (std::int64_t i = range.begin; i < range.end; ++i) y[i] += t[i] - t[i - o];
    }
  }
}

// y(i) = body_i p(i) + the gathered slot terms, masked, for the particles of one range (the slot
// terms of every slot they read must be computed).
void finish_product(FamilySystem& s, const Rows& p, const Rows& y, BlockRange range) {
  gather_terms(s, range, y);
  const double *xx = s.body_row(0), *yy = s.body_row(1), *zz = s.body_row(2);
  const double *xy = s.body_row(3), *xz = s.body_row(4), *yz = s.body_row(5);
  const double* free = s.free.data();
#pragma omp simd
  for (std::int64_t i = range.begin; i < range.end; ++i) {
    const double px = p.c[0][i], py = p.c[1][i], pz = p.c[2][i];
    y.c[0][i] = free[i] * (y.c[0][i] + xx[i] * px + xy[i] * py + xz[i] * pz);
    y.c[1][i] = free[i] * (y.c[1][i] + xy[i] * px + yy[i] * py + yz[i] * pz);
    y.c[2][i] = free[i] * (y.c[2][i] + xz[i] * px + yz[i] * py + zz[i] * pz);
  }
}

double dot(const Rows& a, const Rows& b, BlockRange range) {
  double sum = 0.0;
#pragma omp simd reduction(+ : sum)
  for (std::int64_t i = range.begin; i < range.end; ++i)
    sum += a.c[0][i] * b.c[0][i] + a.c[1][i] * b.c[1][i] + a.c[2][i] * b.c[2][i];
  return sum;
}

// y = A p over every particle; returns p . y (summed per block, then in block order).
// One parallel region: each thread walks its own run of blocks, computing a block's slot terms and
// then its particles' products while the terms are in cache. Particle i reads slots i and i -
// offset; only the first `padding` particles of a run read slots of the previous thread's run, so
// they wait for the barrier. The dot products then go per block, over values that are final.
double product(FamilySystem& s, int p_index, int y_index) {
  const Rows p = rows(s, p_index), y = rows(s, y_index);
  const std::int64_t blocks = block_count(s);
#pragma omp parallel if (threaded(s))
  {
    const ThreadRun run = thread_run(blocks, kBlock, s.particles, s.padding);
    for (std::int64_t block = run.first_block; block < run.end_block; ++block) {
      const BlockRange range = block_range(s, block);
      slot_terms(s, p, range);
      const std::int64_t begin = std::max(range.begin, run.deferred_end);
      if (begin < range.end) finish_product(s, p, y, {begin, range.end});
    }
#pragma omp barrier
    for (std::int64_t begin = run.begin; begin < run.deferred_end; begin += kBlock)
      finish_product(s, p, y, {begin, std::min(run.deferred_end, begin + kBlock)});
    for (std::int64_t block = run.first_block; block < run.end_block; ++block)
      s.partials[2 * block] = dot(p, y, block_range(s, block));
  }
  const double springs_and_bodies = sum_partials(s, 0);
  if (s.couplings.empty()) return springs_and_bodies;
  return springs_and_bodies + add_coupling_products(
                                  s.couplings, s.free.data(),
                                  [&](std::int32_t j, int c) { return p.c[c][j]; },
                                  [&](std::int32_t j, int c) -> double& { return y.c[c][j]; });
}

// z = inverse-block r for the particles of one range; returns r . z over them.
double precondition(FamilySystem& s, const Rows& r, const Rows& z, BlockRange range) {
  const double *xx = s.inverse_row(0), *yy = s.inverse_row(1), *zz = s.inverse_row(2);
  const double *xy = s.inverse_row(3), *xz = s.inverse_row(4), *yz = s.inverse_row(5);
  double dot = 0.0;
#pragma omp simd reduction(+ : dot)
  for (std::int64_t i = range.begin; i < range.end; ++i) {
    const double rx = r.c[0][i], ry = r.c[1][i], rz = r.c[2][i];
    z.c[0][i] = xx[i] * rx + xy[i] * ry + xz[i] * rz;
    z.c[1][i] = xy[i] * rx + yy[i] * ry + yz[i] * rz;
    z.c[2][i] = xz[i] * rx + yz[i] * ry + zz[i] * rz;
    dot += rx * z.c[0][i] + ry * z.c[1][i] + rz * z.c[2][i];
  }
  return dot;
}

double squared_norm(const Rows& r, BlockRange range) { return dot(r, r, range); }

// Packed 3 x n (x0 y0 z0 x1 ...) to three rows, times the free mask, and back.
void unpack(const FamilySystem& s, const double* packed, const Rows& out, BlockRange range) {
  for (std::int64_t i = range.begin; i < range.end; ++i)
    for (int c = 0; c < 3; ++c) out.c[c][i] = s.free[i] * packed[3 * i + c];
}
void pack(const Rows& in, double* packed, BlockRange range) {
  for (std::int64_t i = range.begin; i < range.end; ++i)
    for (int c = 0; c < 3; ++c) packed[3 * i + c] = in.c[c][i];
}

}  // namespace

void FamilySystem::resize(std::int64_t particle_count, const std::vector<SpringFamily>& families) {
  particles = particle_count;
  offsets.clear();
  padding = 0;
  for (const SpringFamily& family : families) {
    offsets.push_back(family.offset);
    padding = std::max<std::int64_t>(padding, family.offset);
  }
  const std::size_t slots = static_cast<std::size_t>(padding + particles);
  springs.assign(5 * offsets.size() * slots, 0.0);
  terms.assign(3 * offsets.size() * slots, 0.0);
  vectors.assign(3 * kCount * slots, 0.0);
  body.assign(6 * static_cast<std::size_t>(particles), 0.0);
  inverse.assign(6 * static_cast<std::size_t>(particles), 0.0);
  free.assign(static_cast<std::size_t>(particles), 1.0);
  partials.assign(2 * static_cast<std::size_t>((particles + kBlock - 1) / kBlock), 0.0);
}

void assemble_family_system(const double* x, const double* v, const double* mass,
                            const double* free, const std::vector<SpringFamily>& families, double h,
                            double air, FamilySystem& s, double* spring_stiffness_velocity) {
  std::copy(free, free + s.particles, s.free.begin());
  // Positions and velocities as rows (velocities unmasked: a pinned particle's is zero anyway).
  const Rows position = rows(s, kSolution), velocity = rows(s, kScratch);
  for_each_block(block_count(s), threaded(s), [&](std::int64_t block) {
    const BlockRange range = block_range(s, block);
    for (std::int64_t i = range.begin; i < range.end; ++i)
      for (int c = 0; c < 3; ++c) {
        position.c[c][i] = x[3 * i + c];
        velocity.c[c][i] = v[3 * i + c];
      }
  });
  const double h2 = h * h;
  for_each_block(block_count(s), threaded(s), [&](std::int64_t block) {
    const BlockRange range = block_range(s, block);
    for (std::size_t f = 0; f < families.size(); ++f) {
      const SpringFamily& family = families[f];
      const std::int64_t o = family.offset;
      const double *rest = family.rest.data(), *ks = family.ks.data(), *kd = family.kd.data();
      double *ux = s.spring_row(f, 0), *uy = s.spring_row(f, 1), *uz = s.spring_row(f, 2);
      double *a = s.spring_row(f, 3), *b = s.spring_row(f, 4);
      double *tx = s.term_row(f, 0), *ty = s.term_row(f, 1), *tz = s.term_row(f, 2);
      const double *px = position.c[0], *py = position.c[1], *pz = position.c[2];
      const double *vx = velocity.c[0], *vy = velocity.c[1], *vz = velocity.c[2];
#pragma omp simd
      for (std::int64_t i = range.begin; i < range.end; ++i) {
        const double dx = px[i] - px[i + o], dy = py[i] - py[i + o], dz = pz[i] - pz[i + o];
        const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
        // A zero-length spring has no direction and no Jacobian (spring_jacobian.hpp).
        const double inverse = length > 0.0 ? 1.0 / length : 0.0;
        const double live = length > 0.0 ? 1.0 : 0.0;
        const double tau = std::max(0.0, 1.0 - rest[i] * inverse);
        const double stiff_along = live * h2 * ks[i] * (1.0 - tau);  // kg
        const double across = live * h2 * ks[i] * tau;               // kg
        ux[i] = dx * inverse;
        uy[i] = dy * inverse;
        uz[i] = dz * inverse;
        a[i] = stiff_along + live * h * kd[i];
        b[i] = across;
        // The stiffness part of B times the relative velocity: -h^2 K (v_a - v_b) on particle a.
        const double wx = vx[i] - vx[i + o], wy = vy[i] - vy[i + o], wz = vz[i] - vz[i + o];
        const double along = stiff_along * (ux[i] * wx + uy[i] * wy + uz[i] * wz);
        tx[i] = along * ux[i] + across * wx;
        ty[i] = along * uy[i] + across * wy;
        tz[i] = along * uz[i] + across * wz;
      }
    }
  });
  const Rows gathered = rows(s, kProduct);
  for_each_block(block_count(s), threaded(s), [&](std::int64_t block) {
    const BlockRange range = block_range(s, block);
    gather_terms(s, range, gathered);
    pack(gathered, spring_stiffness_velocity, range);
    for (std::int64_t i = range.begin; i < range.end; ++i) {
      const double diagonal = s.free[i] != 0.0 ? mass[i] * (1.0 + h * air) : 1.0;
      s.body_row(0)[i] = s.body_row(1)[i] = s.body_row(2)[i] = diagonal;
      s.body_row(3)[i] = s.body_row(4)[i] = s.body_row(5)[i] = 0.0;
    }
  });
}

void invert_diagonal_blocks(FamilySystem& s) {
  for_each_block(block_count(s), threaded(s), [&](std::int64_t block) {
    const BlockRange range = block_range(s, block);
    double* inverse[6];
    const double* body[6];
    for (int e = 0; e < 6; ++e) {
      inverse[e] = s.inverse_row(e);
      body[e] = s.body_row(e);
    }
    for (std::int64_t i = range.begin; i < range.end; ++i) {
      double m[6];  // xx, yy, zz, xy, xz, yz
      for (int e = 0; e < 6; ++e) m[e] = body[e][i];
      // Each spring's B on both of its particles: slot i (first particle) and slot i - offset
      // (second).
      for (std::size_t f = 0; f < s.offsets.size(); ++f) {
        const std::int64_t o = s.offsets[f];
        for (const std::int64_t slot : {i, i - o}) {
          const double ux = s.spring_row(f, 0)[slot], uy = s.spring_row(f, 1)[slot],
                       uz = s.spring_row(f, 2)[slot];
          const double a = s.spring_row(f, 3)[slot], b = s.spring_row(f, 4)[slot];
          m[0] += a * ux * ux + b;
          m[1] += a * uy * uy + b;
          m[2] += a * uz * uz + b;
          m[3] += a * ux * uy;
          m[4] += a * ux * uz;
          m[5] += a * uy * uz;
        }
      }
      // The inverse of a symmetric 3x3 block by its cofactors.
      const double c_xx = m[1] * m[2] - m[5] * m[5], c_xy = m[4] * m[5] - m[3] * m[2],
                   c_xz = m[3] * m[5] - m[4] * m[1];
      const double c_yy = m[0] * m[2] - m[4] * m[4], c_yz = m[3] * m[4] - m[0] * m[5],
                   c_zz = m[0] * m[1] - m[3] * m[3];
      const double determinant = m[0] * c_xx + m[3] * c_xy + m[4] * c_xz;
      const double scale = s.free[i] / determinant;  // 0 for a pinned particle
      inverse[0][i] = scale * c_xx;
      inverse[1][i] = scale * c_yy;
      inverse[2][i] = scale * c_zz;
      inverse[3][i] = scale * c_xy;
      inverse[4][i] = scale * c_xz;
      inverse[5][i] = scale * c_yz;
    }
  });
}

void apply_family_system(FamilySystem& s, const double* p, double* y) {
  const Rows direction = rows(s, kDirection), result = rows(s, kProduct);
  for_each_block(block_count(s), threaded(s),
                 [&](std::int64_t block) { unpack(s, p, direction, block_range(s, block)); });
  product(s, kDirection, kProduct);
  for_each_block(block_count(s), threaded(s),
                 [&](std::int64_t block) { pack(result, y, block_range(s, block)); });
}

FamilySolveResult solve_family_system(FamilySystem& s, const double* b, double* x, double tolerance,
                                      int max_iterations) {
  const Rows solution = rows(s, kSolution), residual = rows(s, kResidual),
             preconditioned = rows(s, kPreconditioned);
  const Rows direction = rows(s, kDirection), product_rows = rows(s, kProduct),
             rhs = rows(s, kScratch);
  const std::int64_t blocks = block_count(s);
  const bool parallel = threaded(s);
  FamilySolveResult result;

  // r = b - A x for the initial guess; |b|^2.
  for_each_block(blocks, parallel, [&](std::int64_t block) {
    const BlockRange range = block_range(s, block);
    unpack(s, x, solution, range);
    unpack(s, b, rhs, range);
    s.partials[2 * block + 1] = squared_norm(rhs, range);
  });
  const double rhs_norm2 = sum_partials(s, 1);
  if (rhs_norm2 == 0.0) {
    std::fill(x, x + 3 * s.particles, 0.0);
    result.converged = true;
    return result;
  }
  const double threshold = std::max(tolerance * tolerance * rhs_norm2, 1e-300);
  product(s, kSolution, kProduct);
  for_each_block(blocks, parallel, [&](std::int64_t block) {
    const BlockRange range = block_range(s, block);
    for (int c = 0; c < 3; ++c)
      for (std::int64_t i = range.begin; i < range.end; ++i)
        residual.c[c][i] = rhs.c[c][i] - product_rows.c[c][i];
    s.partials[2 * block] = precondition(s, residual, direction, range);
    s.partials[2 * block + 1] = squared_norm(residual, range);
  });
  double rz = sum_partials(s, 0);
  double residual_norm2 = sum_partials(s, 1);

  int iteration = 0;
  if (residual_norm2 >= threshold) {
    while (iteration < max_iterations) {
      const double alpha = rz / product(s, kDirection, kProduct);
      // x += alpha p, r -= alpha q, z = P r, and the two sums for the stopping test and beta.
      for_each_block(blocks, parallel, [&](std::int64_t block) {
        const BlockRange range = block_range(s, block);
        for (int c = 0; c < 3; ++c) {
          double *xs = solution.c[c], *rs = residual.c[c];
          const double *ps = direction.c[c], *qs = product_rows.c[c];
#pragma omp simd
          for (std::int64_t i = range.begin; i < range.end; ++i) {
            xs[i] += alpha * ps[i];
            rs[i] -= alpha * qs[i];
          }
        }
        s.partials[2 * block] = precondition(s, residual, preconditioned, range);
        s.partials[2 * block + 1] = squared_norm(residual, range);
      });
      residual_norm2 = sum_partials(s, 1);
      if (residual_norm2 < threshold) break;
      const double rz_new = sum_partials(s, 0);
      const double beta = rz_new / rz;
      rz = rz_new;
      for_each_block(blocks, parallel, [&](std::int64_t block) {
        const BlockRange range = block_range(s, block);
        for (int c = 0; c < 3; ++c) {
          double* ps = direction.c[c];
          const double* zs = preconditioned.c[c];
#pragma omp simd
          for (std::int64_t i = range.begin; i < range.end; ++i) ps[i] = zs[i] + beta * ps[i];
        }
      });
      ++iteration;
    }
  }
  for_each_block(blocks, parallel,
                 [&](std::int64_t block) { pack(solution, x, block_range(s, block)); });
  result.iterations = iteration;
  result.relative_residual = std::sqrt(residual_norm2 / rhs_norm2);
  result.converged = residual_norm2 < threshold;
  return result;
}

}  // namespace drapelab::kernels
