// Backward Euler's assembled matrix plus the couplings of contacts between particles
// (coupling.hpp), as one operator for Eigen's conjugate gradient. The couplings join particles
// that no spring joins, so they have no place in the sparse matrix's fixed pattern; their diagonal
// blocks are in the matrix, and this operator adds their off-diagonal products (Eigen's
// matrix-free solver interface: a type with rows(), cols() and a product, and a Jacobi
// preconditioner that reads the sparse matrix's diagonal).
#pragma once

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "integrators/coupling.hpp"
#include "integrators/coupling_product.hpp"

namespace drapelab {
class CoupledMatrix;
}

namespace Eigen::internal {
template <>
struct traits<drapelab::CoupledMatrix> : public traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace drapelab {

class CoupledMatrix : public Eigen::EigenBase<CoupledMatrix> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum {
    ColsAtCompileTime = Eigen::Dynamic,
    MaxColsAtCompileTime = Eigen::Dynamic,
    IsRowMajor = false
  };

  CoupledMatrix(const Eigen::SparseMatrix<double>& matrix,
                const std::vector<kernels::Coupling>& couplings, const std::vector<double>& free)
      : matrix_(&matrix), couplings_(&couplings), free_(&free) {}

  Eigen::Index rows() const { return matrix_->rows(); }
  Eigen::Index cols() const { return matrix_->cols(); }
  const Eigen::SparseMatrix<double>& matrix() const { return *matrix_; }

  template <typename Rhs>
  Eigen::Product<CoupledMatrix, Rhs, Eigen::AliasFreeProduct> operator*(
      const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<CoupledMatrix, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

  // y += alpha (the couplings' off-diagonal blocks) p, for packed 3N vectors (the product is
  // linear in p, so alpha scales p).
  template <typename P, typename Y>
  void add_couplings(const P& p, Y& y, double alpha) const {
    if (couplings_->empty()) return;
    kernels::add_coupling_products(
        *couplings_, free_->data(),
        [&](std::int32_t j, int c) { return alpha * (*free_)[j] * p(3 * j + c); },
        [&](std::int32_t j, int c) -> double& { return y.coeffRef(3 * j + c); });
  }

 private:
  const Eigen::SparseMatrix<double>* matrix_;
  const std::vector<kernels::Coupling>* couplings_;
  const std::vector<double>* free_;  // 1 for a particle that moves, 0 for a pinned one
};

// Jacobi preconditioning from the sparse matrix's diagonal (which holds the couplings' diagonal
// blocks), as Eigen's DiagonalPreconditioner does for a plain sparse matrix.
class CoupledJacobiPreconditioner {
 public:
  CoupledJacobiPreconditioner() = default;
  template <typename MatrixType>
  explicit CoupledJacobiPreconditioner(const MatrixType& matrix) {
    compute(matrix);
  }
  CoupledJacobiPreconditioner& analyzePattern(const CoupledMatrix&) { return *this; }
  CoupledJacobiPreconditioner& factorize(const CoupledMatrix& matrix) {
    const Eigen::VectorXd diagonal = matrix.matrix().diagonal();
    inverse_ = diagonal.unaryExpr([](double d) { return d != 0.0 ? 1.0 / d : 1.0; });
    return *this;
  }
  CoupledJacobiPreconditioner& compute(const CoupledMatrix& matrix) { return factorize(matrix); }
  template <typename Rhs>
  Eigen::VectorXd solve(const Eigen::MatrixBase<Rhs>& b) const {
    return inverse_.cwiseProduct(b.derived());
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  Eigen::VectorXd inverse_;  // 1/kg
};

}  // namespace drapelab

namespace Eigen::internal {
// The product Eigen's conjugate gradient asks for: the sparse matrix's, then the couplings'.
template <typename Rhs>
struct generic_product_impl<drapelab::CoupledMatrix, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<drapelab::CoupledMatrix, Rhs,
                                generic_product_impl<drapelab::CoupledMatrix, Rhs>> {
  using Scalar = typename Product<drapelab::CoupledMatrix, Rhs>::Scalar;
  template <typename Dest>
  static void scaleAndAddTo(Dest& dst, const drapelab::CoupledMatrix& lhs, const Rhs& rhs,
                            const Scalar& alpha) {
    dst.noalias() += alpha * lhs.matrix() * rhs;
    lhs.add_couplings(rhs, dst, alpha);
  }
};
}  // namespace Eigen::internal
