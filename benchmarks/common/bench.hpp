#pragma once
// tumble_bench, the work-precision driver: what its translation units share.
//
// A *problem* is a rigid-body motion with a known answer at a set of output times (the exact
// solution, or a reference integration where there is none). A *method* integrates it and
// records, at every output time, the attitude R, the body angular velocity omega and the position
// and velocity of the body's reference point (a Sample); the driver compares them with the
// problem's reference samples. Every method is timed the same way: the best of several runs of
// the integrator's construction plus the integration over all output times (what a user pays),
// on the wall clock (std::chrono::steady_clock) and, beside it, on the thread's CPU-time clock;
// building the problem's data is not timed.
//
// Methods: one list (work_precision/methods.cpp), one entry per method, each a Method below:
//  - tumble: a Scene of one RigidBody<P> integrated by SceneIntegrator (CVODE Adams or BDF), for
//    every orientation parameterization P (work_precision/tumble.hpp), in the state form
//    [q; qdot] and, for a few P, [q; v; omega]; and the same scenes under OdeintIntegrator
//    (Boost.Odeint's Fehlberg 7(8) and Dormand-Prince 5(4), work_precision/tumble_d.cpp);
//  - floors, every one on a right-hand side written by hand: the Euler-parameter [q; qdot] closed
//    form in tumble's CVODE setup (floors/cvode_rk4.cpp), and the first-order [p; omega]
//    form (7 states; 13 with translation and loads, floors/rhs.hpp) under CVODE,
//    ARKODE's Fehlberg 7(8) (floors/sundials.cpp) and Boost.Odeint's
//    Fehlberg 7(8) and Dormand-Prince 5 dense output (floors/odeint.cpp);
//  - fixed-step classical RK4 on the Euler-parameter equations (floors/cvode_rk4.cpp);
//  - Pinocchio's aba inside the same CVODE setup, when Pinocchio is installed
//    (peers/pinocchio_work_precision.cpp).
// Conventions are tumble's (docs/conventions.md): R maps body components to inertial ones,
// omega is in body components, quaternions are scalar first.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <time.h>

namespace tumble::bench {

using Clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Which clock the report uses (both are always recorded).
enum class TimeBase {
  wall,  ///< std::chrono::steady_clock: what a user waits (the default)
  cpu,   ///< this thread's CPU time (CLOCK_THREAD_CPUTIME_ID): leaves out the time the thread
         ///< waited for a core, so it estimates the uncontended run time on a busy machine
};

/// A stopwatch on both clocks, started at construction.
class Stopwatch {
 public:
  Stopwatch() : wall_(Clock::now()), cpu_(cpu_now()) {}
  [[nodiscard]] double wall() const { return seconds_since(wall_); }
  [[nodiscard]] double cpu() const { return cpu_now() - cpu_; }
  [[nodiscard]] double elapsed(TimeBase base) const {
    return base == TimeBase::cpu ? cpu() : wall();
  }
  /// This thread's CPU time, s (POSIX clock_gettime).
  static double cpu_now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }

 private:
  Clock::time_point wall_;
  double cpu_;
};

enum class ProblemKind {
  tumbling,        ///< torque-free asymmetric body, framed at its centroid
  minor_axis,      ///< the same body, a stable spin near its minor axis
  major_axis,      ///< the same body, a stable spin near its major axis
  spinner,         ///< the same body spinning fast about its minor axis
  gravity_offset,  ///< a body framed off its centroid, thrown under uniform gravity
  stiff_top,       ///< a spinning top held at its tip by a stiff spring-damper
};

/// Integration scheme of a method.
enum class Scheme {
  adams,   ///< CVODE Adams-Moulton
  bdf,     ///< CVODE BDF
  rk4,     ///< classical RK4, fixed step (swept over the step size, not the tolerance)
  erk78,   ///< ARKODE ERKStep, Fehlberg 7(8)
  rkf78,   ///< Boost.Odeint runge_kutta_fehlberg78, controlled
  dopri5,  ///< Boost.Odeint runge_kutta_dopri5, dense output
};

inline const char* scheme_name(Scheme s) {
  switch (s) {
    case Scheme::adams:
      return "adams";
    case Scheme::bdf:
      return "bdf";
    case Scheme::rk4:
      return "rk4";
    case Scheme::erk78:
      return "erk-f78";
    case Scheme::rkf78:
      return "rkf78";
    case Scheme::dopri5:
      return "dopri5";
  }
  return "?";
}

/// The state of the body at one output time, as every method reports it.
struct Sample {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< R, body -> inertial
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();         ///< body components, rad/s
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      ///< reference point, inertial, m
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      ///< reference point, inertial, m/s
};

/// A problem: the body, its initial state, its loads, the output times and the reference.
struct Problem {
  ProblemKind kind = ProblemKind::tumbling;
  std::string id;     ///< short name, used in file names ("tumbling")
  std::string title;  ///< one line for the report
  double t_end = 0;
  std::vector<double> times;  ///< output times in (0, t_end], increasing; the last is t_end

  // The body (SI units). Principal inertia about the centroid; the centroid sits at `centroid`
  // (body components) from the reference point, zero for a body framed at its centroid.
  double mass = 1;
  Eigen::Vector3d inertia = Eigen::Vector3d::Ones();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  bool at_centroid = true;
  // The initial state (tumble's InitialState): reference point position and velocity, R, omega.
  Eigen::Matrix3d r0 = Eigen::Matrix3d::Identity();
  Eigen::Vector3d omega0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d position0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity0 = Eigen::Vector3d::Zero();
  // Loads: uniform gravity; for the stiff top an isotropic spring-damper (zero rest length)
  // between the reference point and the inertial origin.
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  double stiffness = 0;
  double damping = 0;

  // The reference.
  std::vector<Sample> reference;  ///< at `times`
  bool exact = true;              ///< closed form (true) or a reference integration (false)
  std::string reference_note;     ///< how the reference was obtained
  /// An estimate of the reference's own attitude error (rad; 0 for a closed form): errors below
  /// a few times this are not resolved.
  double reference_uncertainty = 0;
  /// The quick run's tolerance ladder takes every `quick_stride`-th tolerance of the default one
  /// (2: every other decade) for problems whose runs are long.
  int quick_stride = 1;
};

/// The outcome of one method on one problem at one setting.
struct Run {
  bool ok = true;
  std::string error;                                         ///< why it failed, when !ok
  double seconds = std::numeric_limits<double>::infinity();  ///< best of `reps`, Timing's clock
  double seconds_median = std::numeric_limits<double>::quiet_NaN();  ///< the same clock
  double wall_seconds = std::numeric_limits<double>::infinity();     ///< best, wall clock
  double cpu_seconds = std::numeric_limits<double>::infinity();      ///< best, CPU time
  int reps = 0;
  std::vector<double> rep_seconds;  ///< every repetition's time, Timing's clock, sorted
  std::vector<Sample> samples;      ///< at Problem::times
  long steps = 0;
  long rhs_evals = 0;         ///< right-hand sides (RK4: 4 per step)
  long linear_rhs_evals = 0;  ///< right-hand sides for difference-quotient Jacobians
  long jacobian_evals = 0;
  long error_test_failures = 0;
  long convergence_failures = 0;
  long reinits = 0;  ///< CVODE restarts (chart switches restart CVODE)
  /// The explicit path's steps of a mechanism tested at a looser tolerance than asked, near a
  /// singular position (OdeintStatistics::relaxed_steps; the front door's sum).
  long relaxed_steps = 0;
  long chart_switches = 0;
  double constraint_drift = std::numeric_limits<double>::quiet_NaN();  ///< | |p| - 1 | at the end
};

/// Errors of a run against the problem's reference (all maxima over the output times).
struct Errors {
  double final_attitude = std::numeric_limits<double>::quiet_NaN();  ///< rad, at t_end
  double max_attitude = std::numeric_limits<double>::quiet_NaN();    ///< rad
  double max_centroid = std::numeric_limits<double>::quiet_NaN();    ///< m
  double max_omega = std::numeric_limits<double>::quiet_NaN();       ///< rad/s
  /// max |E(t) - E_ref(t)| / |E_ref(0)|; E_ref is the constant E(0) where energy is conserved.
  double energy_drift = std::numeric_limits<double>::quiet_NaN();
  /// max |h(t) - h_ref(t)| / |h_ref(0)|, h = R I_g omega the angular momentum about the centroid
  /// (inertial components; conserved by the torque-free body and under uniform gravity).
  double momentum_drift = std::numeric_limits<double>::quiet_NaN();
};

/// The geodesic distance between two attitudes, the angle of R_a^T R_b in [0, pi] (rad), as
/// atan2(|axial part|, (trace - 1)/2): accurate for small angles, where acos((trace - 1)/2) is not.
double geodesic_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/// Total energy T + V of the body in a sample, J.
double energy(const Problem& p, const Sample& s);
/// Angular momentum about the centroid, inertial components, kg m^2/s.
Eigen::Vector3d centroid_momentum(const Problem& p, const Sample& s);

Errors evaluate(const Problem& p, const Run& r);

/// How a run is timed: best of `reps` runs (fewer when one run is slow, see max_seconds).
struct Timing {
  int reps = 3;
  TimeBase base = TimeBase::wall;
  /// After the first run, skip further repetitions when it took longer than this (s): the run
  /// time is then far above the timer's resolution and the noise it would average out.
  double slow_run = 1.0;
  /// Fast runs: past `reps`, repeat while the runs so far add up to less than this (s), up to
  /// max_reps. The best of 3 runs of 50 us is mostly the noise of those 150 us: a preempted
  /// run, a cold cache, a frequency change. 0: exactly `reps`.
  double min_total = 0.0;
  int max_reps = 200;
  /// The work-precision sweep times each setting in this many rounds over a problem's settings
  /// (one setting's repetitions spread over the problem's whole sweep, so that a slow stretch of
  /// a shared machine lands on every method alike); each round has round()'s share.
  int rounds = 1;
  [[nodiscard]] Timing round() const {
    Timing t = *this;
    t.reps = (reps + rounds - 1) / rounds;
    t.min_total = min_total / rounds;
    t.max_reps = std::max(1, max_reps / rounds);
    t.rounds = 1;
    return t;
  }
};

/// Records one timed repetition, measured by `watch`, into `run` (the best on each clock, and
/// the times on Timing's clock for the median).
void record_time(Run& run, std::vector<double>& times, const Stopwatch& watch,
                 const Timing& timing);
/// Copies the counters of a CVODE run (tumble::CvodeStatistics, or SceneStatistics derived from
/// it) into `run`.
template <class Statistics> void record_statistics(Run& run, const Statistics& st) {
  run.steps = st.steps;
  run.rhs_evals = st.rhs_evals;
  run.linear_rhs_evals = st.linear_rhs_evals;
  run.jacobian_evals = st.jacobian_evals;
  run.error_test_failures = st.error_test_failures;
  run.convergence_failures = st.nonlinear_convergence_failures;
  run.reinits = st.reinits;
}
/// Finishes the timing record (median, reps, rep_seconds).
void finish_timing(Run& run, std::vector<double>& times);
/// Adds the repetitions of `again`, a later round of the same run, to `run`'s timing record.
void merge_timing(Run& run, const Run& again);
/// Whether another repetition should be run after `done` of them.
bool another_rep(const Timing& timing, const std::vector<double>& times);

// ---- the problems ---------------------------------------------------------------------------

/// The four problems with their output times and, for the three with a closed form, their
/// exact reference samples. The stiff top's reference is filled in by the driver (it needs an
/// integration, see make_stiff_reference in work_precision/sweep.cpp).
/// `full`: the spinner runs its 50 s (the quick run: 5 s, see make_problems).
std::vector<Problem> make_problems(int output_count, bool full);

/// The stiff top's reference (it has no closed form): tumble's equations of the same body and
/// loads in long double (RigidBody<EulerParameters, offset, long double> and its accelerations),
/// integrated by classical RK4 with `substeps` fixed steps per output interval and the quaternion
/// projected onto |p| = 1, p.pdot = 0 after every step. `uncertainty` receives the Richardson
/// estimate of its attitude error, max |angle(R_h, R_2h)| / 15 (RK4's error is O(h^4)).
std::vector<Sample> stiff_top_reference(const Problem& p, int substeps, double& uncertainty);

/// Exact samples of a torque-free / freely falling body (TorqueFreeBody for the attitude, a
/// parabola for the centroid) at the problem's output times.
std::vector<Sample> exact_samples(const Problem& p);

// ---- the methods ----------------------------------------------------------------------------

/// The setting of one run of a method: rtol = atol = tol for the adaptive ones.
struct MethodSetting {
  Scheme scheme = Scheme::adams;
  double tol = 1e-6;
  int substeps = 0;  ///< RK4: fixed steps per output interval
  /// BDF: tumble's scenes give CVODE their exact Jacobian (tumble::jacobian); false: CVODE's
  /// difference quotients (tumble_bench --difference-quotients)
  bool exact_jacobian = true;
  /// SUNDIALS' fused vector operations (CvodeOptions::fused_vector_operations); false:
  /// tumble_bench --fused-ops off, to measure what they change
  bool fused = true;
};

/// How a method runs one problem at one setting.
using MethodRunner = Run (*)(const Problem&, const MethodSetting&, const Timing&);

/// One method of the sweep: an entry of the list in work_precision/methods.cpp. Adding a method
/// (another state form of tumble's scene, another integrator on it) is adding one entry.
struct Method {
  std::string label;   ///< the report's row label, without the scheme ("EulerParameters")
  std::string family;  ///< "tumble", "floor", "peer" or "rk4": the CSV's family, the plot's style
  std::string parameterization = "EulerParameters";  ///< of the state it integrates (CSV)
  std::vector<Scheme> schemes;                       ///< one curve per scheme
  bool quick = true;  ///< in the default (quick) sweep; every method is in --full
  /// The quick run's tolerance ladder of this method takes every quick_stride-th tolerance of
  /// the problem's (1: all of them), for methods whose runs are slow; --full runs every one.
  int quick_stride = 1;
  /// Whether it can run problem p (nullptr: every problem).
  bool (*applies)(const Problem&) = nullptr;
  MethodRunner run = nullptr;
};

/// The methods, in the order of the report (work_precision/methods.cpp). tumble's are
/// instantiated in work_precision/tumble_*.cpp.
std::vector<Method> all_methods();
void add_tumble_methods_a(std::vector<Method>& list);
void add_tumble_methods_b(std::vector<Method>& list);
/// tumble on [q; v; omega] (StateForm::quasi_velocities) with CVODE (work_precision/tumble_c.cpp)
void add_tumble_methods_c(std::vector<Method>& list);
/// tumble's scenes under Boost.Odeint (OdeintIntegrator, work_precision/tumble_d.cpp; built when
/// the target tumble::odeint exists, TUMBLE_BENCH_HAVE_TUMBLE_ODEINT)
void add_tumble_methods_d(std::vector<Method>& list);
/// The eight configurations after the headline, in the second unit of tumble_d.cpp.
void add_tumble_methods_d_others(std::vector<Method>& list);

/// The hand-written Euler-parameter [q; qdot] right-hand side (14 states, tumble's state form)
/// in a plain tumble::Cvode with tumble's settings and constraint handling.
Run run_handwritten(const Problem& p, const MethodSetting& c, const Timing& timing);

/// Fixed-step classical RK4 on the Euler-parameter equations (first-order form: p and omega),
/// c.substeps steps per output interval, with the quaternion normalized after every step.
Run run_rk4(const Problem& p, const MethodSetting& c, const Timing& timing);

/// The first-order floors (floors/rhs.hpp): [p; omega] (7 states) on the
/// torque-free problems framed at the centroid, [r_g; p; v_g; omega] (13) on the others.
/// CVODE (c.scheme Adams or BDF) through tumble::Cvode, no projection:
Run run_floor_cvode(const Problem& p, const MethodSetting& c, const Timing& timing);
/// ARKODE ERKStep with the Fehlberg 7(8) table:
Run run_floor_arkode_f78(const Problem& p, const MethodSetting& c, const Timing& timing);
/// Boost.Odeint, std::array state: controlled runge_kutta_fehlberg78 in integrate_times and
/// in a plain loop over try_step, and runge_kutta_dopri5 with dense output:
Run run_floor_odeint_rkf78(const Problem& p, const MethodSetting& c, const Timing& timing);
Run run_floor_odeint_rkf78_loop(const Problem& p, const MethodSetting& c, const Timing& timing);
Run run_floor_odeint_dopri5(const Problem& p, const MethodSetting& c, const Timing& timing);

/// Pinocchio's aba in the same CVODE setup (peers/pinocchio_work_precision.cpp).
bool pinocchio_available();
std::string pinocchio_description();
Run run_pinocchio(const Problem& p, const MethodSetting& c, const Timing& timing);

/// MuJoCo's fixed-step RK4, mj_step (peers/mujoco_work_precision.cpp), swept like run_rk4.
bool mujoco_available();
Run run_mujoco(const Problem& p, const MethodSetting& c, const Timing& timing);

/// Whether a problem is one of the torque-free bodies (no load at all, attitude only).
inline bool torque_free(const Problem& p) {
  return p.kind == ProblemKind::tumbling || p.kind == ProblemKind::minor_axis ||
         p.kind == ProblemKind::major_axis || p.kind == ProblemKind::spinner;
}

/// Whether a problem has no spring (the floors with a closed form of their own: no spring).
inline bool closed_form_problem(const Problem& p) { return p.stiffness == 0; }

/// --methods: whether the method labelled `label` is chosen by `filter` (the option's strings):
/// every method when it is empty, else those whose label contains one of them.
inline bool method_chosen(const std::vector<std::string>& filter, const std::string& label) {
  return filter.empty() || std::any_of(filter.begin(), filter.end(), [&](const std::string& s) {
           return label.find(s) != std::string::npos;
         });
}

// ---- the scaling study (scaling/scaling.cpp) ------------------------------------------

struct ScalingRow {
  int bodies = 0;
  std::string what;     ///< "rhs", "bdf-dense", "bdf-band", "bdf-gmres"
  double seconds = 0;   ///< per right-hand side, or per BDF step
  double per_body = 0;  ///< seconds / bodies
  long calls = 0;       ///< right-hand sides timed, or BDF steps taken
  long rhs_evals = 0;   ///< BDF: right-hand sides, including those of the Jacobian
  long jacobian_evals = 0;
  long linear_iterations = 0;
  bool ok = true;
  std::string error;
};

struct ScalingPlan {
  std::vector<int> rhs_sizes;  ///< N for the right-hand-side cost
  std::vector<int> bdf_sizes;  ///< N for the BDF step cost (band and GMRES)
  int dense_limit = 100;       ///< the dense solver only up to this N
  int bdf_steps = 60;          ///< BDF steps timed per N
  double rhs_seconds = 0.02;   ///< time per timed batch of right-hand sides
  int rhs_batches = 5;         ///< timed batches per N, the best is kept
  int reps = 3;                ///< BDF runs per N, the best is kept
  TimeBase base = TimeBase::wall;
};

/// Progress callbacks: `start` before each measurement with a one-line description, `done`
/// after it with the result.
struct ScalingProgress {
  std::function<void(const std::string&)> start;
  std::function<void(const ScalingRow&)> done;
};

std::vector<ScalingRow> run_scaling(const ScalingPlan& plan, const ScalingProgress& progress);
/// Counts the measurements run_scaling will make (for the progress counter).
int scaling_measurements(const ScalingPlan& plan);

// ---- the ensemble study (ensembles/ensemble.cpp) ----------------------------------------

/// What the ensemble study measures and how much (ensemble_plan, work_precision/sweep.cpp).
struct EnsemblePlan {
  std::size_t runs = 2000;  ///< runs per timed ensemble: threads, serial loops, MPI ranks
  int reps = 3;             ///< timed repetitions of each, the median is reported
  /// Calls in a row of each Ensemble::integrate row, each timed and shown: a slow call cannot
  /// hide behind the median (some calls of ten were once 3-4x slower:
  /// docs/benchmarks/ensembles.md).
  int calls = 10;
  /// The large ensemble timed once on 2 threads (Ensemble::fold); its tenth is the smaller fold
  /// of the memory measurement.
  std::size_t large = 100000;
  /// The large ensemble is timed only when the 2-thread rate promises it within this many
  /// seconds; otherwise its time is extrapolated from that rate (and labelled so).
  double large_budget = 30.0;
  double target_error = 1e-6;  ///< rad: the tolerance is the loosest that reaches it
  int error_sample = 16;       ///< dispersed runs whose error is measured too (and the nominal)
  bool mpi = true;  ///< the same runs over 1 and 2 MPI ranks, when tumble_bench_mpi exists
};

/// One timed measurement of the ensemble study.
struct EnsembleRow {
  std::string what;   ///< "threads", "serial-reset", "serial-new", "mpi", "fold"
  std::string label;  ///< one line for the table
  int threads = 1;
  int ranks = 1;  ///< MPI processes (1 for the measurements inside tumble_bench)
  std::size_t runs = 0;
  int reps = 0;
  double seconds = std::numeric_limits<double>::quiet_NaN();  ///< median, wall clock
  double best = std::numeric_limits<double>::quiet_NaN();     ///< fastest repetition
  std::vector<double> calls;  ///< each repetition's wall time, s, in the order they ran
  /// The cores the measurement had: the process's CPU time (all its threads; MPI: all ranks)
  /// over the wall time, summed over the repetitions. Below the threads or ranks asked for, the
  /// machine was busy with something else.
  double cores = std::numeric_limits<double>::quiet_NaN();
  /// The process's CPU time per run (s): the cost of a run without the time spent waiting for a
  /// core, comparable between measurements when the machine is busy.
  double cpu_per_run = std::numeric_limits<double>::quiet_NaN();
  bool extrapolated = false;  ///< from a measured rate, not timed
  bool ok = true;
  std::string note;  ///< why it failed or what it means
  [[nodiscard]] double per_run() const { return seconds / static_cast<double>(runs); }
  [[nodiscard]] double rate() const { return static_cast<double>(runs) / seconds; }
};

/// Everything the study found.
struct EnsembleResult {
  double tol = std::numeric_limits<double>::quiet_NaN();            ///< rtol = atol of the runs
  double nominal_error = std::numeric_limits<double>::quiet_NaN();  ///< rad, at 50 s
  double sample_error = std::numeric_limits<double>::quiet_NaN();   ///< rad, max over the sample
  long nominal_steps = 0;
  long nominal_rhs = 0;
  std::vector<EnsembleRow> rows;
  /// Memory: bytes kept per run by Ensemble::integrate (a RunOutcome<double>), and the growth
  /// of the peak resident set (VmHWM over VmRSS before, kB) during Ensemble::fold of `runs`.
  std::size_t result_bytes = 0;
  struct Peak {
    std::size_t runs = 0;
    long kilobytes = -1;  ///< -1: not measured
  };
  std::vector<Peak> fold_peaks;
  std::string memory_note;  ///< how the peaks were measured, or why not
  /// Allocations (operator new calls) per run of a 1-thread ensemble, for runs of kEnd / 10 and
  /// of kEnd (ten times the steps), and the steps per run of each; -1: not counted.
  long allocations_short = -1;
  long allocations_long = -1;
  long steps_short = 0;
  long steps_long = 0;
  long allocations_new = -1;  ///< the same, to make one integrator
  /// The process's first 2-thread call (oneTBB starts its worker threads in it) of a few runs,
  /// and the same call again, s: the start-up the timed rows are kept clear of.
  std::size_t startup_runs = 0;
  double startup_first = std::numeric_limits<double>::quiet_NaN();
  double startup_again = std::numeric_limits<double>::quiet_NaN();
  bool mpi_same = false;  ///< MPI results bitwise those of the threads (their sum)
  std::string mpi_note;   ///< why there are no MPI rows, or ""
};

/// Calls of the global operator new (every form) while counting is on, in any thread: the
/// program's replacements (ensembles/alloc.cpp, linked with the ensemble study). Eigen's and
/// C code's allocations go through malloc and are not seen.
long allocation_count() noexcept;
void reset_allocation_count() noexcept;
void set_allocation_counting(bool on) noexcept;

/// Runs the ensemble study; `step` is called after each measurement.
EnsembleResult run_ensemble(const EnsemblePlan& plan, const std::filesystem::path& out,
                            const std::function<void()>& step);
/// The number of measurements run_ensemble makes (for the progress counter).
int ensemble_measurements(const EnsemblePlan& plan);

}  // namespace tumble::bench
