// Python bindings of mass properties and rigid bodies: tumble.MassProperties, tumble.RigidBody.

#include "body.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <nanobind/eigen/dense.h>
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "handles.hpp"

namespace tumble::python {

std::shared_ptr<const Body> make_body(std::string_view name, ReferencePoint reference,
                                      const MassProperties<double>& mp,
                                      const Eigen::Vector3d& fixed_point) {
  (void)parameterization(name);  // the error for an unknown name, with the known ones
  if (auto b = make_euler_body(name, reference, mp, fixed_point)) {
    return b;
  }
  return make_vector_body(name, reference, mp, fixed_point);
}

ReferencePoint reference_point(const std::string& name) {
  if (name == "centroid") return ReferencePoint::centroid;
  if (name == "offset") return ReferencePoint::offset;
  if (name == "fixed_point") return ReferencePoint::fixed_point;
  throw std::invalid_argument("tumble: unknown reference point '" + name +
                              "'; known: centroid, offset, fixed_point");
}

const char* reference_name(ReferencePoint r) {
  switch (r) {
    case ReferencePoint::centroid:
      return "centroid";
    case ReferencePoint::offset:
      return "offset";
    case ReferencePoint::fixed_point:
      return "fixed_point";
  }
  return "?";
}

std::string parameterization_name(nb::handle p) {
  if (nb::isinstance<nb::str>(p)) {
    return nb::cast<std::string>(p);
  }
  const Parameterization* param = nullptr;
  if (nb::try_cast(p, param) && param != nullptr) {
    return std::string(param->name());
  }
  throw std::invalid_argument("tumble: 'parameterization' must be a name or a "
                              "tumble.Parameterization");
}

void bind_body(nb::module_& m) {
  using namespace nb::literals;
  using MP = MassProperties<double>;
  nb::class_<MP>(m, "MassProperties",
                 "Mass properties, validated: mass > 0, inertia symmetric positive definite with "
                 "the triangle inequality (SI: kg, m, kg m^2). Make them with "
                 "MassProperties.about_centroid or MassProperties.about_reference.")
      .def_static(
          "about_centroid",
          [](double mass, nb::handle inertia, nb::handle centroid) {
            return MP::about_centroid(mass, matrix3(inertia, "inertia"),
                                      vector3(centroid, "centroid"));
          },
          "mass"_a, "inertia"_a, "centroid"_a = nb::make_tuple(0.0, 0.0, 0.0),
          "Mass (kg), inertia about the centroid (3 x 3, body axes, kg m^2) and the centroid's "
          "position relative to the reference point (m, body components).")
      .def_static(
          "about_reference",
          [](double mass, nb::handle inertia, nb::handle centroid) {
            return MP::about_reference(mass, matrix3(inertia, "inertia"),
                                       vector3(centroid, "centroid"));
          },
          "mass"_a, "inertia"_a, "centroid"_a,
          "Mass (kg), inertia about the reference point c (kg m^2), converted to the centroid "
          "by the parallel axis theorem, and the centroid's POSITION r_g relative to c (m), not "
          "the first moment m r_g.")
      .def_prop_ro(
          "mass", [](const MP& p) { return p.mass(); }, "kg")
      .def_prop_ro(
          "centroid", [](const MP& p) { return Eigen::Vector3d(p.centroid()); },
          "r_g, the centroid relative to the reference point, m, body components.")
      .def_prop_ro(
          "inertia_centroid", [](const MP& p) { return Eigen::Matrix3d(p.inertia_centroid()); },
          "I_g about the centroid, body axes, kg m^2.")
      .def_prop_ro(
          "inertia_reference", [](const MP& p) { return Eigen::Matrix3d(p.inertia_reference()); },
          "I_c about the reference point, body axes, kg m^2 (Eq. 1.22).")
      .def_prop_ro(
          "principal_moments", [](const MP& p) { return p.principal_moments(); },
          "The principal moments of I_g, ascending, kg m^2.");

  nb::class_<BodyHandle>(m, "RigidBody",
                         "A rigid body of a parameterization and a reference point chosen by "
                         "name: q = [r_oc (inertial, m); theta] (theta alone for "
                         "reference='fixed_point'), qdot its rates. Wrenches: force in inertial "
                         "components (N) at the reference point, moment about it in body "
                         "components (N m).")
      .def(
          "__init__",
          [](BodyHandle* self, nb::handle param, const MP& mp, const std::string& reference,
             nb::handle fixed_point) {
            const ReferencePoint ref = reference_point(reference);
            const Eigen::Vector3d pivot = vector3(fixed_point, "fixed_point");
            if (ref != ReferencePoint::fixed_point && !pivot.isZero(0)) {
              throw std::invalid_argument(
                  "tumble.RigidBody: 'fixed_point' is only for reference='fixed_point'");
            }
            if (ref == ReferencePoint::centroid && !mp.centroid().isZero(0)) {
              throw std::invalid_argument(
                  "tumble.RigidBody: reference='centroid' needs mass properties whose centroid "
                  "is zero; use reference='offset' for a body framed away from its centroid");
            }
            new (self) BodyHandle{make_body(parameterization_name(param), ref, mp, pivot)};
          },
          "parameterization"_a, "mass_properties"_a, "reference"_a = "centroid",
          "fixed_point"_a = nb::make_tuple(0.0, 0.0, 0.0),
          "parameterization: a name ('EulerZYX', 'EulerParameters', ...) or a "
          "tumble.Parameterization; reference: 'centroid' (the frame at the centroid), 'offset' "
          "(anywhere; the coupling terms are computed) or 'fixed_point' (held at its reference "
          "point, at `fixed_point`, inertial, m).")
      .def_prop_ro(
          "parameterization",
          [](const BodyHandle& b) -> const Parameterization& { return b.body->parameterization(); },
          nb::rv_policy::reference)
      .def_prop_ro(
          "reference",
          [](const BodyHandle& b) { return std::string(reference_name(b.body->reference())); })
      .def_prop_ro("mass_properties", [](const BodyHandle& b) { return b.body->mass_properties(); })
      .def_prop_ro(
          "fixed_point", [](const BodyHandle& b) { return b.body->fixed_point(); },
          "The fixed point (inertial, m) of a body with reference='fixed_point', else 0.")
      .def_prop_ro(
          "nq", [](const BodyHandle& b) { return b.body->nq(); },
          "The size of q: 3 + size of theta, or size of theta when held at a fixed point.")
      .def(
          "mass_matrix",
          [](const BodyHandle& b, nb::handle q) {
            return b.body->mass_matrix(vector(q, b.body->nq(), "q"));
          },
          "q"_a, "M(q), nq x nq (Eq. 1.23). Singular for Euler parameters (null vector [0; p]).")
      .def(
          "centrifugal_coriolis",
          [](const BodyHandle& b, nb::handle q, nb::handle qdot) {
            const int n = b.body->nq();
            return to_numpy(
                b.body->centrifugal_coriolis(vector(q, n, "q"), vector(qdot, n, "qdot")));
          },
          "q"_a, "qdot"_a, "f_v(q, qdot), nq (Eqs. 1.26-1.27).")
      .def(
          "generalized_force",
          [](const BodyHandle& b, nb::handle q, nb::handle force, nb::handle moment) {
            return to_numpy(b.body->generalized_force(
                vector(q, b.body->nq(), "q"), vector3(force, "force"), vector3(moment, "moment")));
          },
          "q"_a, "force"_a = nb::make_tuple(0.0, 0.0, 0.0),
          "moment"_a = nb::make_tuple(0.0, 0.0, 0.0),
          "Q of the wrench (force inertial at c, N; moment about c, body, N m), Eq. (1.31).")
      .def(
          "accelerations",
          [](const BodyHandle& b, nb::handle q, nb::handle qdot, nb::handle force,
             nb::handle moment, nb::handle gen_force) {
            const int n = b.body->nq();
            const Eigen::VectorXd qv = vector(q, n, "q"), qdv = vector(qdot, n, "qdot");
            if (!gen_force.is_none()) {
              if (!force.is_none() || !moment.is_none()) {
                throw std::invalid_argument(
                    "tumble.RigidBody.accelerations: give either Q or force/moment, not both");
              }
              return to_numpy(b.body->accelerations_q(qv, qdv, vector(gen_force, n, "Q")));
            }
            const Eigen::Vector3d f =
                force.is_none() ? Eigen::Vector3d::Zero() : vector3(force, "force");
            const Eigen::Vector3d mo =
                moment.is_none() ? Eigen::Vector3d::Zero() : vector3(moment, "moment");
            return to_numpy(b.body->accelerations(qv, qdv, f, mo));
          },
          "q"_a, "qdot"_a, "force"_a = nb::none(), "moment"_a = nb::none(), "Q"_a = nb::none(),
          "qddot from M qddot = f_v + Q (Eq. 1.32), for a wrench (force inertial at c, N; moment "
          "about c, body, N m) or a generalized force Q. For Euler parameters the solution of "
          "the constrained system (p . pddot = -|pdot|^2).")
      .def(
          "kinetic_energy",
          [](const BodyHandle& b, nb::handle q, nb::handle qdot) {
            const int n = b.body->nq();
            return b.body->kinetic_energy(vector(q, n, "q"), vector(qdot, n, "qdot"));
          },
          "q"_a, "qdot"_a, "T = 1/2 qdot^T M qdot, J.")
      .def(
          "linear_momentum",
          [](const BodyHandle& b, nb::handle q, nb::handle qdot) {
            const int n = b.body->nq();
            return to_numpy(b.body->linear_momentum(vector(q, n, "q"), vector(qdot, n, "qdot")));
          },
          "q"_a, "qdot"_a, "m v_g, inertial, kg m/s.")
      .def(
          "angular_momentum",
          [](const BodyHandle& b, nb::handle q, nb::handle qdot) {
            const int n = b.body->nq();
            return to_numpy(b.body->angular_momentum(vector(q, n, "q"), vector(qdot, n, "qdot")));
          },
          "q"_a, "qdot"_a, "The angular momentum about the inertial origin, inertial, kg m^2/s.")
      .def(
          "omega",
          [](const BodyHandle& b, nb::handle q, nb::handle qdot) {
            const int n = b.body->nq();
            return to_numpy(b.body->omega(vector(q, n, "q"), vector(qdot, n, "qdot")));
          },
          "q"_a, "qdot"_a, "omega = G thetadot, rad/s, body components (Eq. 1.5).")
      .def("__repr__", [](const BodyHandle& b) {
        return "tumble.RigidBody('" + std::string(b.body->parameterization().name()) +
               "', reference='" + reference_name(b.body->reference()) + "')";
      });
}

}  // namespace tumble::python
