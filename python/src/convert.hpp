#pragma once
// Conversions between Python objects and Eigen values for the bindings, with the checks that turn
// bad input into std::invalid_argument (ValueError in Python) whose message names the argument,
// the expected shape and what was given. Nothing here is on a hot loop: it runs once per call.

#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Core>
#include <nanobind/eigen/dense.h>
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

namespace tumble::python {

namespace nb = nanobind;

/// A C-contiguous float64 array on the CPU, any shape.
using InArray = nb::ndarray<const double, nb::c_contig, nb::device::cpu>;

/// A float64 C-contiguous view of `h`: the array itself when it already is one, else
/// numpy.ascontiguousarray(h, dtype=float64) (lists, tuples, integer or float32 arrays).
inline InArray as_array(nb::handle h, const char* what) {
  InArray a;
  if (nb::try_cast(h, a, false)) {
    return a;
  }
  nb::object converted;
  try {
    converted = nb::module_::import_("numpy").attr("ascontiguousarray")(h, "float64");
  } catch (const nb::python_error& e) {
    throw std::invalid_argument(std::string("tumble: '") + what +
                                "' is not an array of numbers: " + e.what());
  }
  if (!nb::try_cast(converted, a, false)) {
    throw std::invalid_argument(std::string("tumble: '") + what +
                                "' could not be read as an array of float64");
  }
  return a;
}

inline std::string shape_of(const InArray& a) {
  std::string s = "(";
  for (std::size_t i = 0; i < a.ndim(); ++i) {
    s += std::to_string(a.shape(i));
    s += a.ndim() == 1 ? "," : (i + 1 < a.ndim() ? ", " : "");
  }
  return s + ")";
}

inline void check_finite(const double* data, std::size_t n, const char* what) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(data[i])) {
      throw std::invalid_argument(std::string("tumble: '") + what +
                                  "' has a non-finite entry at flat index " + std::to_string(i) +
                                  " (" + std::to_string(data[i]) + ")");
    }
  }
}

/// A vector of exactly n finite entries.
inline Eigen::VectorXd vector(nb::handle h, Eigen::Index n, const char* what) {
  const InArray a = as_array(h, what);
  if (a.ndim() != 1 || static_cast<Eigen::Index>(a.shape(0)) != n) {
    throw std::invalid_argument(std::string("tumble: '") + what + "' must have shape (" +
                                std::to_string(n) + ",), got shape " + shape_of(a));
  }
  check_finite(a.data(), a.size(), what);
  return Eigen::Map<const Eigen::VectorXd>(a.data(), n);
}

inline Eigen::Vector3d vector3(nb::handle h, const char* what) { return vector(h, 3, what); }

/// A rows x cols matrix of finite entries (row-major in NumPy, as printed).
inline Eigen::MatrixXd matrix(nb::handle h, Eigen::Index rows, Eigen::Index cols,
                              const char* what) {
  const InArray a = as_array(h, what);
  if (a.ndim() != 2 || static_cast<Eigen::Index>(a.shape(0)) != rows ||
      static_cast<Eigen::Index>(a.shape(1)) != cols) {
    throw std::invalid_argument(std::string("tumble: '") + what + "' must have shape (" +
                                std::to_string(rows) + ", " + std::to_string(cols) +
                                "), got shape " + shape_of(a));
  }
  check_finite(a.data(), a.size(), what);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(a.data(), rows, cols);
}

inline Eigen::Matrix3d matrix3(nb::handle h, const char* what) { return matrix(h, 3, 3, what); }

/// A new NumPy float64 array of shape (n,) holding data[0, n): numpy.empty(n), filled through the
/// buffer protocol. Null, with the Python error set, if NumPy fails. Used for the small vectors of
/// RigidBody's methods: nanobind's own return of an Eigen vector wraps a heap copy in a capsule
/// and exports it with numpy.asarray, which took 1.2 us of the 1.5 us of a call of
/// RigidBody.accelerations; this takes about 0.2 us (docs/benchmarks/python.md).
inline PyObject* new_numpy_vector(const double* data, Py_ssize_t n) noexcept {
  static PyObject* empty = nullptr;  // numpy.empty, kept for the life of the process
  if (empty == nullptr) {            // the GIL is held: no race
    PyObject* numpy = PyImport_ImportModule("numpy");
    if (numpy == nullptr) {
      return nullptr;
    }
    empty = PyObject_GetAttrString(numpy, "empty");
    Py_DECREF(numpy);
    if (empty == nullptr) {
      return nullptr;
    }
  }
  PyObject* size = PyLong_FromSsize_t(n);
  if (size == nullptr) {
    return nullptr;
  }
  PyObject* array = PyObject_CallOneArg(empty, size);  // dtype float64, C order
  Py_DECREF(size);
  if (array == nullptr) {
    return nullptr;
  }
  Py_buffer view;
  if (PyObject_GetBuffer(array, &view, PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS) != 0) {
    Py_DECREF(array);
    return nullptr;
  }
  std::memcpy(view.buf, data, sizeof(double) * static_cast<std::size_t>(n));
  PyBuffer_Release(&view);
  return array;
}

/// An Eigen vector returned to Python as a new NumPy array by new_numpy_vector (the stubs show
/// the same type as for an Eigen return).
template <class V> struct NumpyVector { V value; };

template <class V> NumpyVector<V> to_numpy(V v) { return {std::move(v)}; }

}  // namespace tumble::python

namespace nanobind::detail {

template <class V> struct type_caster<tumble::python::NumpyVector<V>> {
  NB_TYPE_CASTER(tumble::python::NumpyVector<V>, make_caster<V>::Name)

  bool from_python(handle, uint8_t, cleanup_list*) noexcept { return false; }  // outputs only

  static handle from_cpp(const tumble::python::NumpyVector<V>& v, rv_policy,
                         cleanup_list*) noexcept {
    return tumble::python::new_numpy_vector(v.value.data(),
                                            static_cast<Py_ssize_t>(v.value.size()));
  }
};

}  // namespace nanobind::detail
