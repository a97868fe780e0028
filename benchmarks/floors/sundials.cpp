// tumble_bench: integrator floors on the hand-written first-order right-hand side
// (floors/rhs.hpp), with SUNDIALS:
//  - CVODE (Adams or BDF) through tumble::Cvode, the same wrapper and settings as tumble's scenes
//    (rtol = atol = tol, fused vector operations as set), on [p; omega] (7 states) or
//    [r_g; p; v_g; omega] (13); no projection, no stabilization: |p| is normalized at output;
//  - ARKODE's explicit Runge-Kutta stepper (ERKStep) with the Fehlberg 7(8) table
//    (ARKODE_FEHLBERG_13_7_8), called directly through SUNDIALS' C interface.
// What each shows: how fast the integrator itself runs on the problem when the state is the
// cheapest one, beside tumble on its own state.

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <arkode/arkode.h>
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>

#include "floors/rhs.hpp"
#include "tumble/cvode.hpp"

namespace tumble::bench {
namespace {

// ---- CVODE -----------------------------------------------------------------------------------

template <int N> struct FloorCvodeSystem {
  const FloorRhs<N>* f;
  [[nodiscard]] int size() const { return N; }
  void rhs(double /*t*/, ConstVectorMap y, VectorMap yd) const { (*f)(y.data(), yd.data()); }
};

template <int N> Run cvode_floor(const Problem& p, const MethodSetting& c, const Timing& timing) {
  Run run;
  run.samples.resize(p.times.size());
  const FloorRhs<N> f(p);
  const std::array<double, N> x0 = f.initial(p);
  const Eigen::VectorXd y0 = Eigen::Map<const Eigen::Matrix<double, N, 1>>(x0.data());
  CvodeOptions o;
  o.method = c.scheme == Scheme::bdf ? CvodeMethod::bdf : CvodeMethod::adams;
  o.rtol = c.tol;
  o.atol = c.tol;
  o.fused_vector_operations = c.fused;
  std::vector<double> times;
  try {
    do {
      f.evals = 0;
      const Stopwatch watch;
      Cvode<FloorCvodeSystem<N>> cvode(FloorCvodeSystem<N>{&f}, 0.0, y0, o);
      std::size_t k = 0;
      cvode.integrate(p.times,
                      [&](double, ConstVectorMap y) { run.samples[k++] = f.sample(p, y.data()); });
      record_time(run, times, watch, timing);
      record_statistics(run, cvode.statistics());
      run.constraint_drift = FloorRhs<N>::drift(cvode.state().data());
    } while (another_rep(timing, times));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, times);
  return run;
}

// ---- ARKODE ERKStep, Fehlberg 7(8) -------------------------------------------------------------

#if SUNDIALS_VERSION_MAJOR > 7 || (SUNDIALS_VERSION_MAJOR == 7 && SUNDIALS_VERSION_MINOR >= 1)
#define TUMBLE_BENCH_ARKODE_GENERIC \
  1  // 7.1 moved the common calls to ARKode* (ERKStep* deprecated)
#else
#define TUMBLE_BENCH_ARKODE_GENERIC 0
#endif

struct ArkodeFree {
  void operator()(void* mem) const noexcept {
#if TUMBLE_BENCH_ARKODE_GENERIC
    ARKodeFree(&mem);
#else
    ERKStepFree(&mem);
#endif
  }
};

template <int N> int arkode_rhs(detail::sun_real /*t*/, N_Vector y, N_Vector yd, void* data) {
  (*static_cast<const FloorRhs<N>*>(data))(N_VGetArrayPointer(y), N_VGetArrayPointer(yd));
  return 0;
}

void arkode_check(int flag, const char* call) {
  if (flag < 0) {
    throw std::runtime_error(std::string("ARKODE: ") + call + " failed with flag " +
                             std::to_string(flag));
  }
}

template <int N> Run arkode_floor(const Problem& p, const MethodSetting& c, const Timing& timing) {
  Run run;
  run.samples.resize(p.times.size());
  const FloorRhs<N> f(p);
  const std::array<double, N> x0 = f.initial(p);
  std::vector<double> times;
  try {
    do {
      f.evals = 0;
      const Stopwatch watch;
      const detail::ContextHandle ctx = [] {
        SUNContext raw = nullptr;
#if SUNDIALS_VERSION_MAJOR >= 7
        arkode_check(SUNContext_Create(SUN_COMM_NULL, &raw), "SUNContext_Create");
#else
        arkode_check(SUNContext_Create(nullptr, &raw), "SUNContext_Create");
#endif
        return detail::ContextHandle(raw);
      }();
      detail::NVectorHandle y = detail::make_serial_vector(N, ctx.get(), c.fused);
      std::copy(x0.begin(), x0.end(), N_VGetArrayPointer(y.get()));
      std::unique_ptr<void, ArkodeFree> mem(
          detail::require_allocated(ERKStepCreate(&arkode_rhs<N>, 0.0, y.get(), ctx.get())));
      void* m = mem.get();
      // A failure is recorded in the run (and its CSV row), not printed: SUNDIALS 6 prints
      // through the integrator's error file, 7 through the context's handlers.
#if SUNDIALS_VERSION_MAJOR >= 7
      arkode_check(SUNContext_ClearErrHandlers(ctx.get()), "SUNContext_ClearErrHandlers");
#else
      arkode_check(ERKStepSetErrFile(m, nullptr), "ERKStepSetErrFile");
#endif
      arkode_check(ERKStepSetTableNum(m, ARKODE_FEHLBERG_13_7_8), "ERKStepSetTableNum");
#if TUMBLE_BENCH_ARKODE_GENERIC
      arkode_check(ARKodeSStolerances(m, c.tol, c.tol), "ARKodeSStolerances");
      arkode_check(ARKodeSetUserData(m, const_cast<FloorRhs<N>*>(&f)), "ARKodeSetUserData");
      arkode_check(ARKodeSetMaxNumSteps(m, 10'000'000), "ARKodeSetMaxNumSteps");
#else
      arkode_check(ERKStepSStolerances(m, c.tol, c.tol), "ERKStepSStolerances");
      arkode_check(ERKStepSetUserData(m, const_cast<FloorRhs<N>*>(&f)), "ERKStepSetUserData");
      arkode_check(ERKStepSetMaxNumSteps(m, 10'000'000), "ERKStepSetMaxNumSteps");
#endif
      for (std::size_t k = 0; k < p.times.size(); ++k) {
        detail::sun_real t = 0;
#if TUMBLE_BENCH_ARKODE_GENERIC
        arkode_check(ARKodeEvolve(m, p.times[k], y.get(), &t, ARK_NORMAL), "ARKodeEvolve");
#else
        arkode_check(ERKStepEvolve(m, p.times[k], y.get(), &t, ARK_NORMAL), "ERKStepEvolve");
#endif
        run.samples[k] = f.sample(p, N_VGetArrayPointer(y.get()));
      }
      record_time(run, times, watch, timing);
      long steps = 0, fails = 0;
#if TUMBLE_BENCH_ARKODE_GENERIC
      arkode_check(ARKodeGetNumSteps(m, &steps), "ARKodeGetNumSteps");
      arkode_check(ARKodeGetNumErrTestFails(m, &fails), "ARKodeGetNumErrTestFails");
#else
      arkode_check(ERKStepGetNumSteps(m, &steps), "ERKStepGetNumSteps");
      arkode_check(ERKStepGetNumErrTestFails(m, &fails), "ERKStepGetNumErrTestFails");
#endif
      run.steps = steps;
      run.error_test_failures = fails;
      run.rhs_evals = f.evals;
      run.constraint_drift = FloorRhs<N>::drift(N_VGetArrayPointer(y.get()));
    } while (another_rep(timing, times));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, times);
  return run;
}

/// The 7-state form where the problem allows it, else the 13-state one.
template <template <int> class Runner>
Run dispatch(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return FloorRhs<7>::fits(p) ? Runner<7>::run(p, c, timing) : Runner<13>::run(p, c, timing);
}
template <int N> struct CvodeRunner {
  static Run run(const Problem& p, const MethodSetting& c, const Timing& t) {
    return cvode_floor<N>(p, c, t);
  }
};
template <int N> struct ArkodeRunner {
  static Run run(const Problem& p, const MethodSetting& c, const Timing& t) {
    return arkode_floor<N>(p, c, t);
  }
};

}  // namespace

Run run_floor_cvode(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return dispatch<CvodeRunner>(p, c, timing);
}

Run run_floor_arkode_f78(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return dispatch<ArkodeRunner>(p, c, timing);
}

}  // namespace tumble::bench
