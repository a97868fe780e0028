#pragma once
// The contract between tumble::Cvode and a user's system y' = f(t, y), y in R^n, without SUNDIALS:
// the Eigen views a system's callbacks receive (ConstVectorMap, VectorMap, MatrixMap; BandMatrixMap
// is in core/band_matrix.hpp), the required concept CvodeSystem (a size and a right-hand side) and
// the optional members, detected at compile time: a dense or band Jacobian, a projection onto a
// constraint manifold, root functions (events) with their directions and action, an action after
// each return, and a GMRES preconditioner. What a system does not provide costs nothing.
//
// A system written against this header (and integrate/errors.hpp for RecoverableError) needs no
// SUNDIALS include; integrate/cvode.hpp integrates it.
//
// \warning The state views handed to callbacks are only valid during the call.
// \warning If on_root() or on_step() changes y it must return true: the integrator then restarts
//          CVODE from the changed state (CVodeReInit). A change without `true` is overwritten.

#include <concepts>
#include <ranges>
#include <span>
#include <type_traits>

#include <Eigen/Core>

#include "tumble/core/band_matrix.hpp"

namespace tumble {

/// Read-only view of a CVODE vector (y, f(t, y), ...) inside a callback.
using ConstVectorMap = Eigen::Map<const Eigen::VectorXd>;
/// Writable view of a CVODE vector (ydot, a correction, root values, ...) inside a callback.
using VectorMap = Eigen::Map<Eigen::VectorXd>;
/// Writable column-major view of CVODE's dense Jacobian matrix.
using MatrixMap = Eigen::Map<Eigen::MatrixXd>;

// clang-format off
/// The required interface of a system y' = f(t, y):
///   int size() const;                                      // n, fixed for the system's life
///   void rhs(double t, ConstVectorMap y, VectorMap ydot);  // ydot = f(t, y)
/// rhs() may throw RecoverableError to make CVODE retry with a smaller step.
template <class S>
concept CvodeSystem = requires(std::remove_cvref_t<S>& s, const std::remove_cvref_t<S>& cs,
                               double t, ConstVectorMap y, VectorMap ydot) {
  { cs.size() } -> std::convertible_to<int>;
  s.rhs(t, y, ydot);
};

/// Optional: the dense Jacobian J = df/dy at (t, y), fy = f(t, y). J arrives zeroed.
/// Used with the BDF dense linear solver (otherwise CVODE's difference quotients).
template <class S>
concept CvodeHasJacobian = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                    ConstVectorMap fy, MatrixMap jac) {
  s.jacobian(t, y, fy, jac);
};

/// Optional: the same into CVODE's band matrix (BandMatrixMap: write only entries in_band(i, j)),
/// used with the BDF band linear solver. A system may provide both, or one template for both.
template <class S>
concept CvodeHasBandJacobian = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                        ConstVectorMap fy, BandMatrixMap jac) {
  s.jacobian(t, y, fy, jac);
};

/// Optional: projection onto the constraint manifold after each step (CVodeSetProjFn, BDF only).
/// Write into corr the correction that puts y + corr on the manifold; err (size 0 when error
/// projection is off) is the local error estimate, to be replaced by its projection. epsProj is
/// the tolerance (WRMS norm of the update) for an iterative projection.
template <class S>
concept CvodeHasProjection = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                      VectorMap corr, double eps, VectorMap err) {
  s.project(t, y, corr, eps, err);
};

/// Optional: root functions g_i(t, y), i < root_count(), whose zeros CVODE locates (events).
template <class S>
concept CvodeHasRoots = requires(std::remove_cvref_t<S>& s, const std::remove_cvref_t<S>& cs,
                                 double t, ConstVectorMap y, VectorMap g) {
  { cs.root_count() } -> std::convertible_to<int>;
  s.roots(t, y, g);
};

/// Optional: the direction of the zero crossings to report, one int per root function:
/// +1 only increasing g_i, -1 only decreasing, 0 both (the default).
template <class S>
concept CvodeHasRootDirections = requires(const std::remove_cvref_t<S>& cs) {
  { cs.root_directions() } -> std::ranges::input_range;
};

/// Optional: the action at a root. which[i] is +1 (g_i crossed upward), -1 (downward) or 0.
/// The system may change y; it returns true when it did, so that CVODE is reinitialized.
template <class S>
concept CvodeHasRootAction = requires(std::remove_cvref_t<S>& s, double t, VectorMap y,
                                      std::span<const int> which) {
  { s.on_root(t, y, which) } -> std::convertible_to<bool>;
};

/// Optional: called whenever advance() or step() returns (at the output time, after each
/// internal step, at roots after on_root). The system may change y (e.g. switch the chart of an
/// orientation parameterization) and returns true when it did, to reinitialize CVODE.
template <class S>
concept CvodeHasStepAction = requires(std::remove_cvref_t<S>& s, double t, VectorMap y) {
  { s.on_step(t, y) } -> std::convertible_to<bool>;
};

/// Optional: a preconditioner P ~ I - gamma J for GMRES (CVodeSetPreconditioner).
///   bool precondition_setup(t, y, fy, jacobian_ok, gamma): prepare P; jacobian_ok says that
///        saved Jacobian data may be reused; return true when Jacobian data was recomputed.
///   void precondition_solve(t, y, fy, r, z, gamma, delta, lr): solve P z = r (to the tolerance
///        delta if iterative; lr is 1 for the left, 2 for the right preconditioner).
template <class S>
concept CvodeHasPreconditioner = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                          ConstVectorMap fy, ConstVectorMap r, VectorMap z,
                                          bool jok, double gamma, double delta, int lr) {
  { s.precondition_setup(t, y, fy, jok, gamma) } -> std::convertible_to<bool>;
  s.precondition_solve(t, y, fy, r, z, gamma, delta, lr);
};
// clang-format on

}  // namespace tumble
