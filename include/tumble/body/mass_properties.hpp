#pragma once
// Mass properties of a rigid body, validated on construction.
//
// Reference chapter, Eq. (1.22): the inertia tensor about the reference point c in the body
// frame, I_c = \int S(r)^T S(r) dm. The parallel axis theorem relates it to the inertia about the
// centroid g, I_c = I_g + m S(r_g)^T S(r_g) = I_g + m (|r_g|^2 I - r_g r_g^T), with r_g the
// centroid's position relative to c in body components. Units: kg, m, kg m^2 (any consistent
// set works: nothing in tumble assumes SI).

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <Eigen/Eigenvalues>

#include "tumble/body/wrench.hpp"
#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"

namespace tumble {

template <class S = double> class MassProperties {
 public:
  /// Inertia `inertia` about the centroid; the centroid at `centroid` in body components
  /// relative to the reference point (zero when the body frame sits at the centroid).
  [[nodiscard]] static MassProperties about_centroid(
      const S& mass, const Matrix3<S>& inertia, const Vector3<S>& centroid = Vector3<S>::Zero()) {
    return MassProperties(mass, inertia, centroid);
  }

  /// Inertia `inertia` about the reference point c (the body frame's origin); converted to the
  /// centroid by the parallel axis theorem, I_g = I_c - m (|r_g|^2 I - r_g r_g^T), before
  /// validation.
  /// \warning `centroid` is the centroid's POSITION r_g relative to c (m, body components), not
  ///          the first moment m r_g (kg m): for a top of mass 2 kg whose centroid is 0.1 m up its
  ///          axis, pass (0, 0, 0.1), not (0, 0, 0.2). The first moment is first_moment().
  [[nodiscard]] static MassProperties about_reference(const S& mass, const Matrix3<S>& inertia,
                                                      const Vector3<S>& centroid) {
    check_mass(mass);
    check_finite(centroid, "centroid");
    check_finite(inertia, "inertia about the reference point");
    return MassProperties(mass, inertia - parallel_axis(mass, centroid), centroid);
  }

  /// The same mass properties in another scalar type (for example Jet<N>, to differentiate),
  /// converted entry by entry and not validated again: the source was.
  template <class T>
  requires(!std::is_same_v<T, S>) explicit MassProperties(const MassProperties<T>& other)
      : mass_(S(other.mass())),
        centroid_(other.centroid().template cast<S>()),
        first_moment_(other.first_moment().template cast<S>()),
        inertia_centroid_(other.inertia_centroid().template cast<S>()),
        inertia_reference_(other.inertia_reference().template cast<S>()),
        inertia_inverse_(other.inertia_centroid_inverse().template cast<S>()),
        inertia_reference_inverse_(other.inertia_reference_inverse().template cast<S>()),
        principal_centroid_(diagonal(inertia_centroid_) && diagonal(inertia_inverse_)),
        principal_reference_(diagonal(inertia_reference_) && diagonal(inertia_reference_inverse_)),
        euler_centroid_(euler_coefficients(inertia_centroid_)),
        euler_reference_(euler_coefficients(inertia_reference_)) {}

  [[nodiscard]] const S& mass() const { return mass_; }
  /// r_g: the centroid relative to the reference point, body components.
  [[nodiscard]] const Vector3<S>& centroid() const { return centroid_; }
  /// m r_g = \int r dm, the first moment about the reference point (Eq. 1.26).
  [[nodiscard]] const Vector3<S>& first_moment() const { return first_moment_; }
  /// I_g, about the centroid, body axes.
  [[nodiscard]] const Matrix3<S>& inertia_centroid() const { return inertia_centroid_; }
  /// I_c, about the reference point, body axes (Eq. 1.22).
  [[nodiscard]] const Matrix3<S>& inertia_reference() const { return inertia_reference_; }
  /// I_g^{-1}, computed once here so the accelerations need no solve.
  [[nodiscard]] const Matrix3<S>& inertia_centroid_inverse() const { return inertia_inverse_; }
  /// I_c^{-1}, computed once here: the angular acceleration of a body held at its reference
  /// point (ReferencePoint::fixed_point) needs no solve either.
  [[nodiscard]] const Matrix3<S>& inertia_reference_inverse() const {
    return inertia_reference_inverse_;
  }
  /// Euler's equations about the centroid, the theta-rows of Eq. (1.33) in Newton-Euler form:
  /// alpha = I_g^{-1} (m - omega x I_g omega) for the moment m about the centroid and omega (body
  /// components).
  /// m = NoWrench{}: no moment, its terms left out.
  template <class Moment>
  [[nodiscard]] Vector3<S> euler_centroid(const Moment& m, Vector3<S> omega) const {
    return euler(principal_centroid_, euler_centroid_, inertia_centroid_, inertia_inverse_, m,
                 omega);
  }
  /// The same about the reference point (the theta-rows of Eq. (1.32) with rddot_oc = 0):
  /// alpha = I_c^{-1} (m - omega x I_c omega), m about c.
  template <class Moment>
  [[nodiscard]] Vector3<S> euler_reference(const Moment& m, Vector3<S> omega) const {
    return euler(principal_reference_, euler_reference_, inertia_reference_,
                 inertia_reference_inverse_, m, omega);
  }

  /// Principal moments of I_g in ascending order.
  [[nodiscard]] Vector3<double> principal_moments() const {
    return Eigen::SelfAdjointEigenSolver<Matrix3<double>>(values(inertia_centroid_),
                                                          Eigen::EigenvaluesOnly)
        .eigenvalues();
  }

  /// m (|r|^2 I - r r^T) = m S(r)^T S(r): the parallel-axis term.
  [[nodiscard]] static Matrix3<S> parallel_axis(const S& mass, const Vector3<S>& r) {
    return mass * (r.squaredNorm() * Matrix3<S>::Identity() - r * r.transpose());
  }

 private:
  MassProperties(const S& mass, const Matrix3<S>& inertia_centroid, const Vector3<S>& centroid)
      : mass_(mass), centroid_(centroid) {
    check_mass(mass);
    check_finite(centroid, "centroid");
    check_finite(inertia_centroid, "inertia about the centroid");
    inertia_centroid_ = check_inertia(inertia_centroid);
    first_moment_ = mass_ * centroid_;
    inertia_reference_ = inertia_centroid_ + parallel_axis(mass_, centroid_);
    inertia_inverse_ = inertia_centroid_.inverse();
    inertia_reference_inverse_ = inertia_reference_.inverse();
    principal_centroid_ = diagonal(inertia_centroid_) && diagonal(inertia_inverse_);
    principal_reference_ = diagonal(inertia_reference_) && diagonal(inertia_reference_inverse_);
    euler_centroid_ = euler_coefficients(inertia_centroid_);
    euler_reference_ = euler_coefficients(inertia_reference_);
    // A positive definite inertia can still be too small (or too badly scaled) for its inverse
    // to be representable, e.g. diag(1e-320, ...): reject it rather than return inf later.
    if (!detail::all_finite(inertia_inverse_) || !detail::all_finite(inertia_reference_) ||
        !detail::all_finite(inertia_reference_inverse_)) {
      throw std::invalid_argument(
          "tumble::MassProperties: the inertia tensor about the centroid is positive definite "
          "but its inverse (or the parallel-axis inertia) overflows; rescale the units");
    }
  }

  /// Euler's coefficients of a diagonal inertia i = diag(I1, I2, I3):
  /// ((I2 - I3) / I1, (I3 - I1) / I2, (I1 - I2) / I3), see euler().
  static Vector3<S> euler_coefficients(const Matrix3<S>& i) {
    return Vector3<S>((i(1, 1) - i(2, 2)) / i(0, 0), (i(2, 2) - i(0, 0)) / i(1, 1),
                      (i(0, 0) - i(1, 1)) / i(2, 2));
  }

  /// Euler's equations, alpha = i^{-1} (m - omega x i omega), for the inertia i and its inverse
  /// i_inv. When both are diagonal (`principal`: the body axes are principal axes),
  /// (omega x i omega)_1 = (I3 - I2) omega_2 omega_3 and cyclically, so that
  ///   alpha_1 = m_1 / I1 + c_1 omega_2 omega_3,   c_1 = (I2 - I3) / I1   (and cyclically),
  /// with Euler's coefficients c (euler_coefficients) computed once. Per axis that is two
  /// products and a sum on the path from omega to alpha, where i^{-1} (m - omega x i omega) has
  /// five dependent operations; an explicit integrator's stages wait on it: a torque-free body's
  /// Fehlberg 7(8) run took 1.17-1.21 times the hand-written floor's time against 1.24-1.28
  /// (docs/benchmarks/floors.md, 2026-12-02, seventeenth session). It also rounds no worse:
  /// I3 - I2 is formed once from the moments instead of as the difference of the products
  /// I3 omega_3 omega_2 and I2 omega_2 omega_3, which cancel when two moments are close. On 24
  /// tumbling bodies (Fehlberg 7(8), 50 s, the best of tol 1e-10 to 1e-13 against a long-double
  /// reference) the attitude errors had the same median to 3 % (2.64e-12 against 2.56e-12 rad).
  /// m = NoWrench{}: the same with m = 0, to the bit but for the sign of a zero. omega is a copy
  /// (here and in euler_centroid, euler_reference): GCC 12 may leave Eigen's 3 x 3 products out of
  /// line, and a reference passed to one would make the caller's kinematics escape to memory (the
  /// scene's right-hand side then kept them on the stack: docs/benchmarks/floors.md, 2026-12-05).
  template <class Moment>
  [[gnu::always_inline]] static Vector3<S> euler(bool principal, const Vector3<S>& c,
                                                 const Matrix3<S>& i, const Matrix3<S>& i_inv,
                                                 const Moment& m, const Vector3<S> omega) {
    constexpr bool loaded = !std::is_same_v<Moment, NoWrench>;
    if (principal) {
      if constexpr (loaded) {
        return Vector3<S>(i_inv(0, 0) * m(0) + c(0) * omega(1) * omega(2),
                          i_inv(1, 1) * m(1) + c(1) * omega(2) * omega(0),
                          i_inv(2, 2) * m(2) + c(2) * omega(0) * omega(1));
      } else {
        return Vector3<S>(c(0) * omega(1) * omega(2), c(1) * omega(2) * omega(0),
                          c(2) * omega(0) * omega(1));
      }
    }
    const Vector3<S> h = i * omega;
    Vector3<S> mc = -omega.cross(h);  // m - omega x h, exactly: a - b is a + (-b)
    if constexpr (loaded) {
      mc += m;
    }
    return i_inv.lazyProduct(mc);
  }

  static bool diagonal(const Matrix3<S>& m) {
    return detail::value(m(0, 1)) == 0 && detail::value(m(0, 2)) == 0 &&
           detail::value(m(1, 0)) == 0 && detail::value(m(1, 2)) == 0 &&
           detail::value(m(2, 0)) == 0 && detail::value(m(2, 1)) == 0;
  }

  static Matrix3<double> values(const Matrix3<S>& m) {
    Matrix3<double> v;
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        v(i, j) = static_cast<double>(detail::value(m(i, j)));
      }
    }
    return v;
  }

  static void check_mass(const S& mass) {
    const auto m = detail::value(mass);
    if (!detail::isfinite(mass) || !(m > 0)) {
      std::ostringstream os;
      os << "tumble::MassProperties: the mass must be positive and finite, got " << m;
      throw std::invalid_argument(os.str());
    }
  }

  template <class Derived>
  static void check_finite(const Eigen::MatrixBase<Derived>& x, const char* what) {
    if (!detail::all_finite(x)) {
      throw std::invalid_argument(std::string("tumble::MassProperties: the ") + what +
                                  " has a non-finite entry");
    }
  }

  /// Symmetric (to rounding), positive definite, principal moments obeying the triangle
  /// inequality I1 + I2 >= I3 (equality: a plane lamina or a thin rod). Returns the
  /// symmetrized matrix.
  static Matrix3<S> check_inertia(const Matrix3<S>& inertia) {
    const Matrix3<double> v = values(inertia);
    const double scale = v.cwiseAbs().maxCoeff();
    const double eps = std::numeric_limits<decltype(detail::value(S()))>::epsilon();
    const double tol = 64 * static_cast<double>(eps) * scale;
    const double asym = (v - v.transpose()).cwiseAbs().maxCoeff();
    if (asym > tol) {
      std::ostringstream os;
      os << "tumble::MassProperties: the inertia tensor is not symmetric (largest |I_ij - I_ji| "
         << "= " << asym << ", scale " << scale << ")";
      throw std::invalid_argument(os.str());
    }
    const Vector3<double> ev =
        Eigen::SelfAdjointEigenSolver<Matrix3<double>>(v, Eigen::EigenvaluesOnly).eigenvalues();
    if (!(ev(0) > tol)) {
      std::ostringstream os;
      os << "tumble::MassProperties: the inertia tensor about the centroid is not positive "
         << "definite (principal moments " << ev(0) << ", " << ev(1) << ", " << ev(2) << ")";
      throw std::invalid_argument(os.str());
    }
    if (ev(0) + ev(1) < ev(2) - tol) {
      std::ostringstream os;
      os << "tumble::MassProperties: the principal moments " << ev(0) << ", " << ev(1) << ", "
         << ev(2) << " violate the triangle inequality (" << ev(0) << " + " << ev(1) << " < "
         << ev(2) << "): no mass distribution has this inertia";
      throw std::invalid_argument(os.str());
    }
    return S(0.5) * (inertia + inertia.transpose());
  }

  S mass_;
  Vector3<S> centroid_;
  Vector3<S> first_moment_;
  Matrix3<S> inertia_centroid_;
  Matrix3<S> inertia_reference_;
  Matrix3<S> inertia_inverse_;
  Matrix3<S> inertia_reference_inverse_;
  bool principal_centroid_ = false;   ///< I_g and its inverse are diagonal
  bool principal_reference_ = false;  ///< I_c and its inverse are diagonal
  Vector3<S> euler_centroid_;         ///< Euler's coefficients of I_g (used when principal)
  Vector3<S> euler_reference_;        ///< Euler's coefficients of I_c (used when principal)
};

}  // namespace tumble
