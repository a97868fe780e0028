#pragma once
// tumble_bench, study (e): work precision on the IFToMM multibody benchmark problems (group A),
// mechanisms of rigid bodies and joints, each with a reference independent of tumble's run:
//   a01  the simple pendulum (A01): the closed form in Jacobi's sn (tests/support/pendulum.hpp)
//   a02  the N-four-bar (A02), N = 2, through its singular positions: a second model in the
//        cranks' angle (tests/joint/n_four_bar_reference.hpp)
//   a03  Andrews' squeezing mechanism (A03): a second model in the Test Set's seven joint angles,
//        integrated in long double (tests/joint/andrews_reference.hpp)
//   a04  Bricard's mechanism (A04), redundant: no closed form, a run at tight tolerance of its
//        non-redundant twin (examples/bricard.cpp), stated as such
//   a05  the stiff flyball governor (A05): a second model in four minimal coordinates
//        (tests/joint/flyball_reference.hpp); MuJoCo and Exudyn run it
//   chain an open spatial chain of six rods on hinges about axes not all parallel, from the
//        ground, swinging under gravity: a second model in the six joint angles (recursive
//        Newton-Euler), integrated in long double (tests/joint/chain_reference.hpp)
// Each problem's scene type is instantiated in a translation unit of its own
// (mechanisms/<problem>.cpp; the compiler's memory stays within CI's budget per process), which
// runs tumble's integrators over a tolerance ladder with the same output times:
//   the front door tumble::integrate (AutoIntegrator: it chooses the method),
//   OdeintIntegrator with Fehlberg 7(8), explicit,
//   SceneIntegrator, CVODE's BDF with the scene's exact Jacobian.
// On A05, when SUNDIALS' IDA is found, the rows of a study join them: the stabilized index-2
// formulation in IDA (mechanisms/ida_ggl.hpp), measured as the alternative to BDF for stiff
// mechanisms.
// Each run is timed as the single-body study's are (construction and integration over all output
// times, best of Timing::reps; common/bench.hpp), its error measured against the reference by the
// problem's own measure, and the constraint residual |C| taken at its end. The report
// (main/report.cpp, mechanism_table) reads the time to reach 1e-3, 1e-6, 1e-9 off each method's
// ladder with the same interpolation as the single-body tables (time_at).
//
// Peers: MuJoCo's fixed-step RK4 (peers/mujoco_mechanisms.cpp, when installed) runs each problem
// from an MJCF model of its own, over the same output times, and is measured by the same code
// against the same reference (the problem's .cpp hands it both, see the declarations at the end);
// its rows join MechanismResult::rows with the peer's name as the method. Exudyn's implicit
// solvers (peers/exudyn_mechanisms.cpp and .py, when `import exudyn` works in the Python found at
// configure time) run each problem in the same way, in absolute coordinates, from the same data.
// On the open chain, Pinocchio's articulated-body algorithm (peers/pinocchio_mechanisms.cpp, when
// Pinocchio's headers are found) runs in Boost.Odeint's Fehlberg 7(8) over the plan's tolerances,
// as a Pinocchio user integrates it.

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

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
  std::vector<std::string> filter;  ///< --methods: empty, all; else labels containing one
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

/// Whether the plan runs the peer named `peer` ("MuJoCo", "Exudyn"): --methods empty, or one of
/// its strings within the peer's name or holding it ("--methods MuJoCo", "--methods 'MuJoCo RK4
/// (stiffest)'"). Its rows are then filtered by label as tumble's are (keep_wanted).
bool runs_peer(const MechanismPlan& plan, const std::string& peer);
/// Drops the rows whose method label contains none of the plan's --methods strings.
void keep_wanted(const MechanismPlan& plan, std::vector<MechanismRow>& rows);

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
MechanismResult run_mechanism_a02(const MechanismPlan& plan, const std::function<void()>& step);
MechanismResult run_mechanism_a03(const MechanismPlan& plan, const std::function<void()>& step);
MechanismResult run_mechanism_a04(const MechanismPlan& plan, const std::function<void()>& step);
MechanismResult run_mechanism_a05(const MechanismPlan& plan, const std::function<void()>& step);
MechanismResult run_mechanism_chain(const MechanismPlan& plan, const std::function<void()>& step);

// ---- peers (peers/mujoco_mechanisms.cpp, peers/exudyn_mechanisms.cpp, and on the chain
// peers/pinocchio_mechanisms.cpp): no rows when the peer is not installed -----------------------

class PointTrackError;  // mechanisms/track.hpp

/// A planar linkage of hinges about z as the peers build it (A03, filled by mechanisms/andrews.cpp
/// from the example's data; A02, by mechanisms/four_bar.cpp): an open tree of links from the
/// ground, the hinges that close its loops, uniform gravity in the plane, and optionally a spring
/// to the ground and a constant torque. Positions are in the world (x, y) in the starting
/// configuration; each link turns at its `rate` there (A03 starts at rest), and the rates must
/// close the loops (the peers take them as they are).
struct PlanarLinkage {
  struct Link {
    int parent = -1;           ///< the link it hangs from in the tree (its index); -1: ground
    Eigen::Vector2d hinge;     ///< its hinge to the parent (m)
    Eigen::Vector2d centroid;  ///< (m)
    double angle = 0;          ///< its absolute angle about z at the start (rad)
    double mass = 0;           ///< kg
    double inertia = 0;        ///< about z at the centroid (kg m^2)
    double rate = 0;           ///< its absolute angular rate about z at the start (rad/s)
  };
  struct Loop {  ///< a hinge closing a loop between links a and b (b = -1: the ground)
    int a = 0, b = 0;
    Eigen::Vector2d at;  ///< (m)
  };
  std::vector<Link> links;
  std::vector<Loop> loops;
  Eigen::Vector2d gravity = Eigen::Vector2d::Zero();  ///< on every link (m/s^2)
  /// A linear spring from a point of link `spring_link` to a point of the ground; none when the
  /// stiffness is 0.
  int spring_link = 0;
  Eigen::Vector2d spring_on_link = Eigen::Vector2d::Zero();    ///< (m)
  Eigen::Vector2d spring_on_ground = Eigen::Vector2d::Zero();  ///< (m)
  double stiffness = 0, rest_length = 0;                       ///< N/m, m
  /// A constant torque about z on link `motor_link`; none when it is 0.
  int motor_link = 0;
  double torque = 0;  ///< N m
};

/// A planar linkage's error measure, shared by tumble's runs and the peers': `angles[k][i]`,
/// link i's absolute angle about z at output k (rad, followed over the turns), gives the run's
/// error. Every output is there (a run that did not reach one is not measured).
using PlanarMeasure = std::function<double(const std::vector<std::vector<double>>& angles)>;

/// A01 as the peers build it (filled by mechanisms/pendulum.cpp with the data of its scene): a
/// bob, a ball framed at its centroid, on a massless bar with spherical ends from a fixed pivot,
/// released at rest under uniform gravity.
struct BarPendulum {
  double mass = 0;                        ///< kg
  double inertia = 0;                     ///< the ball's, about any centroidal axis (kg m^2)
  Eigen::Vector3d pivot, start, gravity;  ///< the bar's length is |start - pivot| (m, m/s^2)
};

/// A spatial linkage of rigid bodies and hinges as the peers build it, under uniform gravity:
/// A04 (filled by mechanisms/bricard.cpp from the example's scene), at rest at the start, and the
/// open chain (mechanisms/chain.cpp, from the second model's start), moving. Hinge i < n (n
/// bodies) holds body a = i to its parent b < i (or the ground), so these hinges are a tree; a
/// further hinge (A04's sixth) closes a loop.
struct SpatialLinkage {
  struct Body {
    Eigen::Vector3d centroid;                            ///< (m), where the body frame sits
    Eigen::Matrix3d rotation;                            ///< body frame -> world at the start
    double mass = 0;                                     ///< kg
    Eigen::Matrix3d inertia;                             ///< about the centroid, body axes (kg m^2)
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< the centroid's at the start (m/s)
    Eigen::Vector3d omega = Eigen::Vector3d::Zero();     ///< world axes, at the start (rad/s)
  };
  struct Hinge {  ///< between bodies a and b (b = -1: the ground)
    int a = 0, b = -1;
    Eigen::Vector3d at, axis;  ///< in the world at the start (m; a unit vector)
    double rate = 0;           ///< (omega_a - omega_b) . axis at the start (rad/s)
  };
  std::vector<Body> bodies;
  std::vector<Hinge> hinges;
  Eigen::Vector3d gravity;      ///< m/s^2
  int track_body = 0;           ///< the point whose track is measured: on this body,
  Eigen::Vector3d track_point;  ///< at this point of its frame (m)
};

/// A05 as the peers build it (filled by mechanisms/flyball.cpp from examples/flyball.cpp's data),
/// z up: the shaft hinged to the ground about z at the origin, the slider on it along z (turning
/// with it), two rods, each with its ball one rigid body, hinged to the shaft's top at
/// (+-offset, 0, top) about y and pointing outward and down, and a spring-damper from each rod's
/// midpoint to the slider's point (+-offset, 0, s). All turn rigidly about z at the start.
struct FlyballGovernor {
  double gravity = 0;                                     ///< along -z (m/s^2)
  double shaft_mass = 0, shaft_length = 0;                ///< kg, m (the shaft from z = 0 up)
  Eigen::Vector3d shaft_inertia;                          ///< about its centroid (kg m^2)
  double slider_mass = 0, slider_inertia = 0;             ///< kg; about any centroidal axis
  double rod_mass = 0, rod_length = 0, rod_centroid = 0;  ///< kg, m, m from its hinge
  double rod_axial = 0, rod_transverse = 0;  ///< about its centroid, along and across (kg m^2)
  double offset = 0, top = 0;                ///< the hinges off the axis and their height (m)
  double stiffness = 0, damping = 0, rest_length = 0;  ///< N/m, N s/m, m
  double s0 = 0, alpha = 0, spin = 0;  ///< the slider's height, the rods' angle below the
                                       ///< horizontal, the spin at t = 0 (m, rad, rad/s)
};

/// MuJoCo's fixed-step RK4 (mj_step, integrator="RK4") over a ladder of steps per output
/// interval, each run timed as tumble's are (best of timing.reps, the model's construction not
/// timed) and measured by the problem's own measure:
/// A01: the bob's track at `times`, measured by `bob` (its closed-form reference);
std::vector<MechanismRow> mujoco_a01_rows(const std::vector<double>& times, PointTrackError& bob,
                                          const Timing& timing);
/// A02, A03: the linkage `m` of problem `id` ("a03": the model's name) over `times`, the links'
/// absolute angles at every output (the hinge angles summed along the tree) measured by `measure`.
std::vector<MechanismRow> mujoco_planar_rows(const std::string& id, const PlanarLinkage& m,
                                             const std::vector<double>& times,
                                             const PlanarMeasure& measure, const Timing& timing);

/// A05: the governor `g` over `times`, the slider's height (as (s, 0, 0)) measured by `slider`;
/// MuJoCo's RK4 and its implicitfast integrator (the dampers' forces implicit in the step).
std::vector<MechanismRow> mujoco_a05_rows(const FlyballGovernor& g,
                                          const std::vector<double>& times, PointTrackError& slider,
                                          const Timing& timing);

/// A04 and the open chain: the linkage `l` over `times`, its tracked point measured by `track`.
/// Hinges 0 to n - 1 (n bodies) are the tree, MuJoCo's hinge joints: hinge i holds body i to a
/// parent < i or the ground (std::invalid_argument otherwise), with the rate `l` gives it at the
/// start; any further hinge closes a loop (A04's sixth), as two <connect>s on its axis, run with
/// MuJoCo's default softness and with the stiffest setting at the step.
std::vector<MechanismRow> mujoco_spatial_rows(const SpatialLinkage& l,
                                              const std::vector<double>& times,
                                              PointTrackError& track, const Timing& timing);

/// Pinocchio's aba on the open chain `l` (as MuJoCo's rows take it), q' = v, v' = aba(q, v, 0)
/// integrated by Boost.Odeint's controlled Fehlberg 7(8) at rtol = atol = each of `tolerances`
/// (integrate_times over `times`), timed as tumble's rows (peers/pinocchio_mechanisms.cpp): the
/// tracked point at `times`, measured by `tip`. No rows without Pinocchio; a linkage that is not
/// such a chain gives one failed row.
std::vector<MechanismRow> pinocchio_chain_rows(const SpatialLinkage& l,
                                               const std::vector<double>& times,
                                               const std::vector<double>& tolerances,
                                               PointTrackError& tip, const Timing& timing);

/// Whether Exudyn's rows run (the Python found at configure time imports exudyn).
bool exudyn_available();
/// Exudyn's implicit solvers (generalized-alpha, index 3, and the trapezoidal rule, index 2) over
/// a ladder of fixed steps per output interval, each run timed inside the Python script
/// (exu.SolveDynamic only, best of timing.reps) and measured by the problem's own measure, as
/// MuJoCo's rows are:
/// A01: the pendulum `p`, the bob's track at `times` measured by `bob`;
std::vector<MechanismRow> exudyn_a01_rows(const BarPendulum& p, const std::vector<double>& times,
                                          PointTrackError& bob, const Timing& timing);
/// A04: the linkage `l`, its tracked point at `times` measured by `p3`;
std::vector<MechanismRow> exudyn_a04_rows(const SpatialLinkage& l, const std::vector<double>& times,
                                          PointTrackError& p3, const Timing& timing);
/// A05: the governor `g` (its slider's height written as (s, 0, 0)), measured by `slider`.
std::vector<MechanismRow> exudyn_a05_rows(const FlyballGovernor& g,
                                          const std::vector<double>& times, PointTrackError& slider,
                                          const Timing& timing);
/// the open chain: the linkage `l` (moving at the start, not redundant), its tracked point at
/// `times` measured by `tip`;
std::vector<MechanismRow> exudyn_chain_rows(const SpatialLinkage& l,
                                            const std::vector<double>& times, PointTrackError& tip,
                                            const Timing& timing);
/// A02, A03: the linkage `m` of problem `id` over `times`, the links' absolute angles at every
/// output measured by `measure`.
std::vector<MechanismRow> exudyn_planar_rows(const std::string& id, const PlanarLinkage& m,
                                             const std::vector<double>& times,
                                             const PlanarMeasure& measure, const Timing& timing);

}  // namespace tumble::bench
