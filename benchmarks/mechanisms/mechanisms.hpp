#pragma once
// tumble_bench, study (e): work precision on the IFToMM multibody benchmark problems (group A),
// mechanisms of rigid bodies and joints, each with a reference independent of tumble's run:
//   a01  the simple pendulum (A01): the closed form in Jacobi's sn (tests/support/pendulum.hpp)
//   a03  Andrews' squeezing mechanism (A03): a second model in the Test Set's seven joint angles,
//        integrated in long double (tests/joint/andrews_reference.hpp)
//   a04  Bricard's mechanism (A04), redundant: no closed form, a run at tight tolerance of its
//        non-redundant twin (examples/bricard.cpp), stated as such
// Each problem's scene type is instantiated in a translation unit of its own
// (mechanisms/<problem>.cpp; the compiler's memory stays within CI's budget per process), which
// runs tumble's integrators over a tolerance ladder with the same output times:
//   the front door tumble::integrate (AutoIntegrator: it chooses the method),
//   OdeintIntegrator with Fehlberg 7(8), explicit,
//   SceneIntegrator, CVODE's BDF with the scene's exact Jacobian.
// Each run is timed as the single-body study's are (construction and integration over all output
// times, best of Timing::reps; common/bench.hpp), its error measured against the reference by the
// problem's own measure, and the constraint residual |C| taken at its end. The report
// (main/report.cpp, mechanism_table) reads the time to reach 1e-3, 1e-6, 1e-9 off each method's
// ladder with the same interpolation as the single-body tables (time_at).
//
// Peers (MuJoCo, Exudyn, ...) on the same problems are not run yet: their rows would be added to
// MechanismResult::rows by a runner of their own (see the HOOK in mechanisms/study.cpp).

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common/bench.hpp"

namespace tumble::bench {

/// tumble's integrators in study (e).
enum class MechanismMethod {
  front_door,  ///< tumble::integrate / AutoIntegrator: the library chooses
  odeint_f78,  ///< OdeintIntegrator, Fehlberg 7(8)
  cvode_bdf,   ///< SceneIntegrator, CVODE BDF, exact Jacobian
};

/// The row label of a method ("tumble::integrate (auto)", ...).
const char* mechanism_method_label(MechanismMethod m);

/// What to run: the tolerance ladder (rtol = atol), the methods, the timing.
struct MechanismPlan {
  std::vector<double> tolerances;
  std::vector<MechanismMethod> methods;
  Timing timing;
};

/// One run of a method at one tolerance.
struct MechanismRow {
  std::string method;  ///< its label (a peer's rows: the peer's name)
  double tol = 0;
  Run run;  ///< time, counters; constraint_drift: max |C| at the end (m)
  double error = std::numeric_limits<double>::quiet_NaN();  ///< the problem's error measure
  std::string note;  ///< the front door: the methods it chose
};

/// A problem of study (e) and its runs.
struct MechanismResult {
  std::string id;         ///< "a01", used in the CSV's name
  std::string title;      ///< one line for the report
  std::string measure;    ///< the error measure, in words, with its unit
  std::string reference;  ///< how the reference was obtained
  std::vector<MechanismRow> rows;
};

/// A problem of study (e): its id and how to run it (one call per row: `step`).
struct MechanismProblem {
  std::string id;
  MechanismResult (*run)(const MechanismPlan&, const std::function<void()>& step);
};

/// The problems of study (e), in the order of the report (mechanisms/study.cpp).
std::vector<MechanismProblem> mechanism_problems();
/// The default tolerance ladder of study (e) (quick: fewer rungs).
std::vector<double> mechanism_tolerances(bool full);

MechanismResult run_mechanism_a01(const MechanismPlan& plan, const std::function<void()>& step);
MechanismResult run_mechanism_a03(const MechanismPlan& plan, const std::function<void()>& step);
MechanismResult run_mechanism_a04(const MechanismPlan& plan, const std::function<void()>& step);

}  // namespace tumble::bench
