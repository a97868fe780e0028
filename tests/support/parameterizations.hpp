#pragma once
// The parameterizations and scalar types the generic suites run over.

#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "tumble/orientation/euler_parameters.hpp"
#if __has_include("tumble/orientation/euler_angles.hpp")
#include "tumble/orientation/euler_angles.hpp"
#define TUMBLE_TEST_HAVE_EULER_ANGLES 1
#endif
#if __has_include("tumble/orientation/rodrigues.hpp")
#include "tumble/orientation/rodrigues.hpp"
#define TUMBLE_TEST_HAVE_RODRIGUES 1
#endif
#if __has_include("tumble/orientation/modified_rodrigues.hpp")
#include "tumble/orientation/modified_rodrigues.hpp"
#define TUMBLE_TEST_HAVE_MRP 1
#endif
#if __has_include("tumble/orientation/rotation_vector.hpp")
#include "tumble/orientation/rotation_vector.hpp"
#define TUMBLE_TEST_HAVE_ROTATION_VECTOR 1
#endif

namespace tumble::test {

/// Forward-mode AD scalar with a dynamic derivative vector (constants carry an empty one).
using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;

/// Every parameterization of tumble: 12 Euler sequences, Euler parameters, Gibbs, MRP and the
/// rotation vector.
using AllParameterizations = std::tuple<EulerParameters
#ifdef TUMBLE_TEST_HAVE_EULER_ANGLES
                                        ,
                                        EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX,
                                        EulerXYX, EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ
#endif
#ifdef TUMBLE_TEST_HAVE_RODRIGUES
                                        ,
                                        RodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_MRP
                                        ,
                                        ModifiedRodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_ROTATION_VECTOR
                                        ,
                                        RotationVector
#endif
                                        >;

/// The parameterizations the integration suites (tests/integrate, tests/scene) run their scene
/// types over. Compiled with TUMBLE_TEST_REPRESENTATIVE=1 (CMake's default,
/// -DTUMBLE_TEST_INTEGRATION_SET=representative), one of each family, so that every code path of
/// the scene and the integrator is still taken: Euler parameters (the constraint, projection and
/// stabilization), a Tait-Bryan and a proper Euler sequence (singular at +-pi/2 and at 0, pi: both
/// kinds of chart re-centering), Gibbs, the rotation vector (re-centering of vector charts) and
/// MRP (the shadow set). The 12 Euler sequences share one implementation, which the orientation,
/// body and chart suites test one by one whatever this set. With
/// -DTUMBLE_TEST_INTEGRATION_SET=all, all 16.
#if defined(TUMBLE_TEST_REPRESENTATIVE) && TUMBLE_TEST_REPRESENTATIVE
using IntegrationParameterizations = std::tuple<EulerParameters
#ifdef TUMBLE_TEST_HAVE_EULER_ANGLES
                                                ,
                                                EulerZYX, EulerZXZ
#endif
#ifdef TUMBLE_TEST_HAVE_RODRIGUES
                                                ,
                                                RodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_MRP
                                                ,
                                                ModifiedRodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_ROTATION_VECTOR
                                                ,
                                                RotationVector
#endif
                                                >;
#else
using IntegrationParameterizations = AllParameterizations;
#endif

/// What a sliced source's list is a slice of: the integration set in the integration suites
/// (where TUMBLE_TEST_INTEGRATION_LIST is defined by the build), AllParameterizations elsewhere.
#ifdef TUMBLE_TEST_INTEGRATION_LIST
using SlicedParameterizations = IntegrationParameterizations;
#else
using SlicedParameterizations = AllParameterizations;
#endif

// ---- slices ------------------------------------------------------------------------------------
// TUMBLE_TEST_PARAMETERIZATIONS: the parameterization list of a test source that the build
// compiles several times, each time with a part of the list (tests/CMakeLists.txt,
// tumble_add_sliced_sources). A source uses it where it would name AllParameterizations:
//
//   TEMPLATE_LIST_TEST_CASE("...", "[...]", TUMBLE_TEST_PARAMETERIZATIONS) { ... }
//
// Compiled with -DTUMBLE_TEST_SLICE=k -DTUMBLE_TEST_SLICES=n, the list is slice k of n of
// SlicedParameterizations: the types at the indices i with i % n == k (round robin, so that every
// slice gets a mix of Euler angles and the vector charts, which differ in compile time). Without
// them it is SlicedParameterizations itself, and the test names are those of an unsliced build.
//
// Why: orientation/properties and body/rigid_body instantiate their checks for every
// parameterization (properties also for every scalar type); in one translation unit each is one
// compiler process of minutes and over 4 GB, which no second core can share. Slices compile in
// parallel, each in a fraction of the memory. The slice's name is part of the Catch2 name of
// every TEMPLATE_LIST_TEST_CASE ("<name> - tumble::test::ParameterizationSlice<k> - <index>").

namespace detail_slice {
template <std::size_t K, std::size_t N, class List> struct Slice;
template <std::size_t K, std::size_t N, class... Ts> struct Slice<K, N, std::tuple<Ts...>> {
  template <std::size_t... I>
  static auto pick(std::index_sequence<I...>) -> decltype(std::tuple_cat(
      std::conditional_t<I % N == K, std::tuple<std::tuple_element_t<I, std::tuple<Ts...>>>,
                         std::tuple<>>{}...));
  using type = decltype(pick(std::index_sequence_for<Ts...>{}));
};
}  // namespace detail_slice

/// The types of List at the indices i with i % N == K.
template <std::size_t K, std::size_t N, class List>
using SliceOf = typename detail_slice::Slice<K, N, List>::type;

static_assert(std::is_same_v<SliceOf<1, 3, std::tuple<int, char, long, float, double>>,
                             std::tuple<char, double>>);

#if defined(TUMBLE_TEST_SLICE) && defined(TUMBLE_TEST_SLICES)
static_assert(TUMBLE_TEST_SLICE >= 0 && TUMBLE_TEST_SLICE < TUMBLE_TEST_SLICES,
              "TUMBLE_TEST_SLICE must be in [0, TUMBLE_TEST_SLICES)");
/// Slice K of TUMBLE_TEST_SLICES of AllParameterizations (one template argument, so that the
/// name passes through Catch2's macros, which would split it at a comma).
template <std::size_t K>
using ParameterizationSlice = SliceOf<K, TUMBLE_TEST_SLICES, SlicedParameterizations>;
/// The part of a source's own type list that this slice holds (all of it in an unsliced build).
template <class List> using ThisSlice = SliceOf<TUMBLE_TEST_SLICE, TUMBLE_TEST_SLICES, List>;
#define TUMBLE_TEST_PARAMETERIZATIONS tumble::test::ParameterizationSlice<TUMBLE_TEST_SLICE>
#define TUMBLE_TEST_PRIMARY_SLICE (TUMBLE_TEST_SLICE == 0)
#define TUMBLE_TEST_IN_SLICE(k) (TUMBLE_TEST_SLICE == (k) % TUMBLE_TEST_SLICES)
#define TUMBLE_TEST_SLICED_NAME(name) \
  TUMBLE_TEST_CAT(name, TUMBLE_TEST_CAT(_slice, TUMBLE_TEST_SLICE))
#else
template <class List> using ThisSlice = List;
#define TUMBLE_TEST_PARAMETERIZATIONS tumble::test::SlicedParameterizations
#define TUMBLE_TEST_PRIMARY_SLICE 1
#define TUMBLE_TEST_IN_SLICE(k) 1
#define TUMBLE_TEST_SLICED_NAME(name) name
#endif
// TUMBLE_TEST_PRIMARY_SLICE: true in slice 0 and in an unsliced build. A sliced source that links
// all its slices into one executable guards what is not per parameterization with it, and names
// a type list of its own (a product with AllParameterizations, say) TUMBLE_TEST_SLICED_NAME(name):
// name_slice<k>, so that the Catch2 names of the slices differ; ThisSlice<List> is its part in
// this slice: using TUMBLE_TEST_SLICED_NAME(MySlice) = tumble::test::ThisSlice<MyList>;
// TUMBLE_TEST_IN_SLICE(k): true in slice k mod n and in an unsliced build, to spread such parts
// over the slices.
#define TUMBLE_TEST_CAT2(a, b) a##b
#define TUMBLE_TEST_CAT(a, b) TUMBLE_TEST_CAT2(a, b)

}  // namespace tumble::test
