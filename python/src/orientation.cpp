// Python bindings of the orientation parameterizations (include/tumble/orientation): the
// run-time interface of parameterizations.hpp and the class tumble.Parameterization.

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <nanobind/eigen/dense.h>
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/string_view.h>
#include <nanobind/stl/vector.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "parameterizations.hpp"

namespace tumble::python {

namespace {

template <class P> class ParameterizationOf final : public Parameterization {
  using Coords = typename P::template Coords<double>;

 public:
  [[nodiscard]] std::string_view name() const override { return P::name; }
  [[nodiscard]] int size() const override { return P::size; }
  [[nodiscard]] bool has_constraint() const override { return P::has_constraint; }
  [[nodiscard]] Eigen::Matrix3d rotation(const Eigen::VectorXd& theta) const override {
    return P::rotation(Coords(theta));
  }
  [[nodiscard]] Eigen::MatrixXd G(const Eigen::VectorXd& theta) const override {
    return P::G(Coords(theta));
  }
  [[nodiscard]] Eigen::Vector3d Gdot_thetadot(const Eigen::VectorXd& theta,
                                              const Eigen::VectorXd& thetadot) const override {
    return P::Gdot_thetadot(Coords(theta), Coords(thetadot));
  }
  [[nodiscard]] Eigen::VectorXd thetadot(const Eigen::VectorXd& theta,
                                         const Eigen::Vector3d& omega) const override {
    return P::thetadot(Coords(theta), omega);
  }
  [[nodiscard]] Eigen::Vector3d omega(const Eigen::VectorXd& theta,
                                      const Eigen::VectorXd& thetadot) const override {
    return P::omega(Coords(theta), Coords(thetadot));
  }
  [[nodiscard]] Eigen::VectorXd from_rotation(const Eigen::Matrix3d& r) const override {
    return P::from_rotation(r);
  }
  [[nodiscard]] Eigen::VectorXd from_quaternion(const Eigen::Vector4d& q) const override {
    return P::from_quaternion(Eigen::Quaterniond(q(0), q(1), q(2), q(3)));  // w first
  }
  [[nodiscard]] Eigen::Vector4d to_quaternion(const Eigen::VectorXd& theta) const override {
    const Eigen::Quaterniond q = P::to_quaternion(Coords(theta));
    return {q.w(), q.x(), q.y(), q.z()};
  }
  [[nodiscard]] double singularity_distance(const Eigen::VectorXd& theta) const override {
    return P::singularity_distance(Coords(theta));
  }
  [[nodiscard]] Eigen::VectorXd canonical(const Eigen::VectorXd& theta) const override {
    return P::canonical(Coords(theta));
  }
};

template <class... P> std::vector<const Parameterization*> table(std::tuple<P...>* /*types*/) {
  static const std::tuple<ParameterizationOf<P>...> objects;  // constant, stateless
  return {&std::get<ParameterizationOf<P>>(objects)...};
}

/// R must be a rotation: orthonormal to 1e-9 with determinant +1.
Eigen::Matrix3d rotation_arg(nb::handle h) {
  const Eigen::Matrix3d r = matrix3(h, "R");
  const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > 1e-9 || r.determinant() < 0) {
    throw std::invalid_argument(
        "tumble: 'R' is not a rotation matrix (|R^T R - I| = " + std::to_string(off) +
        ", det R = " + std::to_string(r.determinant()) + "; expected orthonormal, det +1)");
  }
  return r;
}

/// q = (w, x, y, z) of norm 1 to 1e-9.
Eigen::Vector4d quaternion_arg(nb::handle h) {
  const Eigen::Vector4d q = vector(h, 4, "q");
  if (std::abs(q.norm() - 1.0) > 1e-9) {
    throw std::invalid_argument("tumble: 'q' must be a unit quaternion (w, x, y, z); its norm is " +
                                std::to_string(q.norm()));
  }
  return q;
}

}  // namespace

const std::vector<const Parameterization*>& parameterizations() {
  static const std::vector<const Parameterization*> all =
      table(static_cast<AllParameterizations*>(nullptr));
  return all;
}

const Parameterization& parameterization(std::string_view name) {
  std::string known;
  for (const Parameterization* p : parameterizations()) {
    if (p->name() == name) {
      return *p;
    }
    known += (known.empty() ? "" : ", ") + std::string(p->name());
  }
  throw std::invalid_argument("tumble: unknown parameterization '" + std::string(name) +
                              "'; known: " + known);
}

void bind_orientation(nb::module_& m) {
  using P = Parameterization;
  using namespace nb::literals;
  nb::class_<P>(m, "Parameterization",
                "An orientation parameterization (include/tumble/orientation): R(theta), G(theta) "
                "with omega = G thetadot (Eq. 1.5), the inverse map, conversions and the distance "
                "to the nearest singularity.\n\n"
                "R maps body components to inertial ones (r_F = R r_f); omega is the body's "
                "angular velocity in body components, rad/s; quaternions are scalar first "
                "(w, x, y, z); Euler angles are intrinsic sequences, rad. Get one with "
                "tumble.parameterization(name) or as tumble.EulerZYX, ...")
      .def_prop_ro(
          "name", [](const P& p) { return std::string(p.name()); },
          "The C++ name, e.g. 'EulerZYX', 'EulerParameters'.")
      .def_prop_ro("size", &P::size, "The number of coordinates: 3, or 4 for Euler parameters.")
      .def_prop_ro("has_constraint", &P::has_constraint,
                   "True for Euler parameters (|p| = 1), False otherwise.")
      .def(
          "rotation",
          [](const P& p, nb::handle theta) { return p.rotation(vector(theta, p.size(), "theta")); },
          "theta"_a, "R(theta), 3 x 3, body -> inertial (Eq. 1.1).")
      .def(
          "G", [](const P& p, nb::handle theta) { return p.G(vector(theta, p.size(), "theta")); },
          "theta"_a, "G(theta), 3 x size: omega = G thetadot (Eq. 1.5).")
      .def(
          "Gdot_thetadot",
          [](const P& p, nb::handle theta, nb::handle thetadot) {
            return p.Gdot_thetadot(vector(theta, p.size(), "theta"),
                                   vector(thetadot, p.size(), "thetadot"));
          },
          "theta"_a, "thetadot"_a, "The product Gdot thetadot of Eq. (1.10), rad/s^2.")
      .def(
          "thetadot",
          [](const P& p, nb::handle theta, nb::handle omega) {
            return p.thetadot(vector(theta, p.size(), "theta"), vector3(omega, "omega"));
          },
          "theta"_a, "omega"_a,
          "The parameter rates for the body angular velocity omega (rad/s, body components): "
          "the inverse of Eq. (1.5); for Euler parameters the rate tangent to |p| = 1.")
      .def(
          "omega",
          [](const P& p, nb::handle theta, nb::handle thetadot) {
            return p.omega(vector(theta, p.size(), "theta"),
                           vector(thetadot, p.size(), "thetadot"));
          },
          "theta"_a, "thetadot"_a, "omega = G(theta) thetadot, rad/s, body components (Eq. 1.5).")
      .def(
          "from_rotation",
          [](const P& p, nb::handle r) { return p.from_rotation(rotation_arg(r)); }, "R"_a,
          "The coordinates of the rotation matrix R (orthonormal to 1e-9, det +1, else "
          "ValueError).")
      .def(
          "from_quaternion",
          [](const P& p, nb::handle q) { return p.from_quaternion(quaternion_arg(q)); }, "q"_a,
          "The coordinates of the unit quaternion q = (w, x, y, z) (norm 1 to 1e-9, else "
          "ValueError).")
      .def(
          "to_quaternion",
          [](const P& p, nb::handle theta) {
            return p.to_quaternion(vector(theta, p.size(), "theta"));
          },
          "theta"_a, "The unit quaternion (w, x, y, z) of theta.")
      .def(
          "singularity_distance",
          [](const P& p, nb::handle theta) {
            return p.singularity_distance(vector(theta, p.size(), "theta"));
          },
          "theta"_a,
          "The angle in rad from theta to the nearest attitude where G is singular "
          "(inf for Euler parameters).")
      .def(
          "canonical",
          [](const P& p, nb::handle theta) {
            return p.canonical(vector(theta, p.size(), "theta"));
          },
          "theta"_a,
          "The canonical representative of theta's attitude (normalized quaternion, MRP "
          "shadow set, ...); theta itself where there is no choice.")
      .def(
          "convert",
          [](const P& p, nb::handle theta, const P& to) {
            // As tumble::convert: through the unit quaternion.
            return to.from_quaternion(p.to_quaternion(vector(theta, p.size(), "theta")));
          },
          "theta"_a, "to"_a,
          "theta's attitude in the parameterization `to` (through the unit quaternion, as "
          "tumble::convert).")
      .def("__repr__",
           [](const P& p) { return "tumble.parameterization('" + std::string(p.name()) + "')"; });

  m.def(
      "parameterization",
      [](const std::string& name) -> const P& { return parameterization(name); }, "name"_a,
      nb::rv_policy::reference,
      "The parameterization of this name, e.g. 'EulerZYX', 'EulerParameters', "
      "'RodriguesParameters', 'ModifiedRodriguesParameters', 'RotationVector'.");
  m.def(
      "parameterization_names",
      [] {
        std::vector<std::string> names;
        for (const P* p : parameterizations()) {
          names.emplace_back(p->name());
        }
        return names;
      },
      "The names of the 16 parameterizations: 12 Euler sequences, EulerParameters, "
      "RodriguesParameters, ModifiedRodriguesParameters, RotationVector.");
  for (const P* p : parameterizations()) {
    m.attr(std::string(p->name()).c_str()) = nb::cast(p, nb::rv_policy::reference);
  }
}

}  // namespace tumble::python
