#pragma once
// BandMatrixMap: a writable view of an n x n band matrix with upper and lower half-bandwidths
// mu and ml, stored by columns the way LAPACK and SUNDIALS do (SUNMATRIX_BAND): column j holds
// the entries i in [j - mu, j + ml] at data[j * ldim + smu + i - j], where smu >= mu is the
// stored upper bandwidth (SUNDIALS keeps smu = mu + ml for the fill-in of the LU factors).
// It has no SUNDIALS dependency, so that a system's Jacobian can be written for dense
// (Eigen::Map) and band storage alike: see detail::add_block.

#include <type_traits>

#include <Eigen/Core>

namespace tumble {

class BandMatrixMap {
 public:
  BandMatrixMap(double* data, Eigen::Index n, Eigen::Index ldim, Eigen::Index stored_upper,
                Eigen::Index upper, Eigen::Index lower) noexcept
      : data_(data), n_(n), ldim_(ldim), smu_(stored_upper), mu_(upper), ml_(lower) {}

  [[nodiscard]] Eigen::Index rows() const noexcept { return n_; }
  [[nodiscard]] Eigen::Index cols() const noexcept { return n_; }
  [[nodiscard]] Eigen::Index upper_bandwidth() const noexcept { return mu_; }
  [[nodiscard]] Eigen::Index lower_bandwidth() const noexcept { return ml_; }
  /// True when (i, j) lies in the band, i.e. is stored.
  [[nodiscard]] bool in_band(Eigen::Index i, Eigen::Index j) const noexcept {
    return i - j <= ml_ && j - i <= mu_;
  }
  /// Entry (i, j); only for in_band(i, j).
  [[nodiscard]] double& coeffRef(Eigen::Index i, Eigen::Index j) const noexcept {
    return data_[j * ldim_ + smu_ + i - j];
  }

 private:
  double* data_;
  Eigen::Index n_, ldim_, smu_, mu_, ml_;
};

namespace detail {

/// jac(r0 + i, c0 + j) += block(i, j): all of it for a dense Eigen matrix (or Map), the entries
/// inside the band for a BandMatrixMap (a band narrower than the Jacobian's own drops the rest,
/// as CVODE's banded difference quotients do), or whatever a storage with its own
/// add_block(r0, c0, block) keeps (the scene's block-diagonal preconditioner).
template <class Jac, class Derived>
void add_block(Jac& jac, Eigen::Index r0, Eigen::Index c0, const Eigen::MatrixBase<Derived>& b) {
  if constexpr (requires { jac.add_block(r0, c0, b); }) {
    jac.add_block(r0, c0, b);
  } else if constexpr (std::is_same_v<std::remove_cv_t<Jac>, BandMatrixMap>) {
    for (Eigen::Index j = 0; j < b.cols(); ++j) {
      for (Eigen::Index i = 0; i < b.rows(); ++i) {
        if (jac.in_band(r0 + i, c0 + j)) {
          jac.coeffRef(r0 + i, c0 + j) += b(i, j);
        }
      }
    }
  } else {
    jac.block(r0, c0, b.rows(), b.cols()) += b;
  }
}

}  // namespace detail
}  // namespace tumble
