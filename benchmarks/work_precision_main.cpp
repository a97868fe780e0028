// tumble_bench: the work-precision driver, the main job of the README.
//
//   tumble_bench [--full] [--out DIR] [--reps N] [--outputs N] [--problems a,b,...]
//                [--no-scaling] [--no-plots] [--python PATH]
//
// For each problem with a known answer (work_precision_problems.cpp) it sweeps the tolerance
// rtol = atol = 1e-3 ... 1e-13 for tumble with every parameterization and CVODE's Adams and BDF,
// and, as references in the same run, the hand-written Euler-parameter right-hand side in the
// same CVODE setup (the floor for CVODE), fixed-step RK4 (a sweep of step sizes) and Pinocchio's
// aba in the same CVODE setup (when installed). Each configuration is timed as the best of several
// runs; errors are measured against the reference at every output time. Then the scaling study
// (work_precision_scaling.cpp). It prints one progress line per measurement, a summary with the
// targets of issue 4 (met or missed), and writes one CSV per problem, scaling.csv, summary.txt and
// (with matplotlib) PNG work-precision diagrams into the output folder, which it names at the
// start and at the end.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>
#include <sundials/sundials_config.h>

#include "work_precision.hpp"

#ifndef TUMBLE_BENCH_DEFAULT_OUT
#define TUMBLE_BENCH_DEFAULT_OUT "benchmark-results"
#endif
#ifndef TUMBLE_BENCH_PLOT_SCRIPT
#define TUMBLE_BENCH_PLOT_SCRIPT "plot_work_precision.py"
#endif
#ifndef TUMBLE_BENCH_PLOT_PYTHON
#define TUMBLE_BENCH_PLOT_PYTHON "python3"
#endif
#ifndef TUMBLE_BENCH_BUILD_TYPE
#define TUMBLE_BENCH_BUILD_TYPE "unknown"
#endif
#ifndef TUMBLE_BENCH_CXX_FLAGS
#define TUMBLE_BENCH_CXX_FLAGS "unknown"
#endif
// The per-step micro-benchmarks (Google Benchmark) and their summary script: tumble_bench runs
// them first, so that the main job's table has the ratios of the core assembly too.
#ifndef TUMBLE_BENCH_MICRO
#define TUMBLE_BENCH_MICRO ""
#endif
#ifndef TUMBLE_BENCH_MICRO_SCRIPT
#define TUMBLE_BENCH_MICRO_SCRIPT ""
#endif

namespace tumble::bench {
namespace {

// ---- options -----------------------------------------------------------------------------------

struct Options {
  bool full = false;
  std::string out = TUMBLE_BENCH_DEFAULT_OUT;
  int reps = 3;
  int outputs = 200;
  std::set<std::string> problems;    // empty: all
  std::vector<std::string> methods;  // empty: all; else method labels containing one of these
  std::vector<double> tolerances;    // empty: the default sweep
  bool scaling = true;
  bool plots = true;
  bool micro = true;
  bool exact_jacobian = true;  // tumble with BDF: the scene's Jacobian, or difference quotients
  TimeBase clock = TimeBase::wall;
  std::string python = TUMBLE_BENCH_PLOT_PYTHON;
};

void usage() {
  std::printf(
      "tumble_bench: tumble's work-precision benchmark (run time against error) and scaling "
      "study.\n\n"
      "  --full            every parameterization (16), and the scaling study up to N = 10,000\n"
      "                    (default: the quick run, 6 parameterizations, N up to 1,000)\n"
      "  --out DIR         where to write CSV, PNG and summary.txt (default: %s)\n"
      "  --reps N          timed runs per configuration, the best is kept (default: 3)\n"
      "  --outputs N       output times per problem at which errors are measured (default: 200)\n"
      "  --problems LIST   comma-separated subset of: tumbling,spinner,gravity_offset,stiff_top\n"
      "  --methods LIST    only methods whose label contains one of these comma-separated\n"
      "                    strings (e.g. 'EulerParameters adams,hand-written,RK4')\n"
      "  --tolerances LIST comma-separated CVODE tolerances (default: 1e-3,1e-4,...,1e-13)\n"
      "  --no-scaling      skip the scaling study\n"
      "  --clock wall|cpu  the clock of the report: wall (steady_clock, the default) or the\n"
      "                    thread's CPU time, which leaves out waiting for a core on a busy\n"
      "                    machine (the CSVs always have both)\n"
      "  --no-plots        write CSV only\n"
      "  --no-micro        skip the per-step micro-benchmarks (tumble_micro) at the start\n"
      "  --difference-quotients\n"
      "                    tumble with BDF: CVODE's difference-quotient Jacobian instead of the\n"
      "                    scene's exact one (to measure what the exact Jacobian changes)\n"
      "  --python PATH     the Python with matplotlib for the plots (default: %s)\n",
      TUMBLE_BENCH_DEFAULT_OUT, TUMBLE_BENCH_PLOT_PYTHON);
}

std::optional<Options> parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        throw std::invalid_argument(a + " needs a value");
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      usage();
      return std::nullopt;
    } else if (a == "--full") {
      o.full = true;
    } else if (a == "--quick") {
      o.full = false;
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--reps") {
      o.reps = std::max(1, std::stoi(value()));
    } else if (a == "--outputs") {
      o.outputs = std::max(2, std::stoi(value()));
    } else if (a == "--problems") {
      std::stringstream ss(value());
      std::string item;
      while (std::getline(ss, item, ',')) {
        if (!item.empty()) {
          o.problems.insert(item);
        }
      }
    } else if (a == "--methods") {
      std::stringstream ss(value());
      std::string item;
      while (std::getline(ss, item, ',')) {
        if (!item.empty()) {
          o.methods.push_back(item);
        }
      }
    } else if (a == "--tolerances") {
      std::stringstream ss(value());
      std::string item;
      while (std::getline(ss, item, ',')) {
        if (!item.empty()) {
          o.tolerances.push_back(std::stod(item));
        }
      }
    } else if (a == "--no-scaling") {
      o.scaling = false;
    } else if (a == "--clock") {
      const std::string c = value();
      if (c == "wall") {
        o.clock = TimeBase::wall;
      } else if (c == "cpu") {
        o.clock = TimeBase::cpu;
      } else {
        throw std::invalid_argument("--clock takes wall or cpu (got '" + c + "')");
      }
    } else if (a == "--no-plots") {
      o.plots = false;
    } else if (a == "--no-micro") {
      o.micro = false;
    } else if (a == "--difference-quotients") {
      o.exact_jacobian = false;
    } else if (a == "--python") {
      o.python = value();
    } else {
      throw std::invalid_argument("unknown option '" + a + "' (see --help)");
    }
  }
  return o;
}

// ---- formatting --------------------------------------------------------------------------------

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string sci(double x) {
  if (std::isnan(x)) {
    return "nan";
  }
  return fmt("%.1e", x);
}

std::string duration(double s) {
  if (!std::isfinite(s)) {
    return "-";
  }
  if (s < 1e-6) {
    return fmt("%.1f ns", s * 1e9);
  }
  if (s < 1e-3) {
    return fmt("%.1f us", s * 1e6);
  }
  if (s < 1.0) {
    return fmt("%.2f ms", s * 1e3);
  }
  return fmt("%.2f s", s);
}

std::string pad(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : s + std::string(width - s.size(), ' ');
}
std::string lpad(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) {
    return s;
  }
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"') {
      q += '"';
    }
    q += ch == '\n' ? ' ' : ch;
  }
  return q + "\"";
}

std::string num(double x) {
  if (std::isnan(x)) {
    return "";
  }
  return fmt("%.6g", x);
}

// ---- the sweep ---------------------------------------------------------------------------------

const std::vector<double> kTolerances = {1e-3, 1e-4,  1e-5,  1e-6,  1e-7, 1e-8,
                                         1e-9, 1e-10, 1e-11, 1e-12, 1e-13};

enum class Family { tumble, handwritten, pinocchio, rk4 };

const char* family_name(Family f) {
  switch (f) {
    case Family::tumble:
      return "tumble";
    case Family::handwritten:
      return "hand-written";
    case Family::pinocchio:
      return "pinocchio";
    case Family::rk4:
      return "rk4";
  }
  return "?";
}

/// One measurement to make.
struct Job {
  const Problem* problem = nullptr;
  Family family = Family::tumble;
  const Parameterization* param = nullptr;  // tumble only
  Scheme scheme = Scheme::adams;
  double tol = 0;    // CVODE methods
  int substeps = 0;  // RK4: steps per output interval
  [[nodiscard]] std::string method() const {
    switch (family) {
      case Family::tumble:
        return "tumble " + param->name + " " + scheme_name(scheme);
      case Family::handwritten:
        return std::string("hand-written EP ") + scheme_name(scheme);
      case Family::pinocchio:
        return std::string("Pinocchio aba ") + scheme_name(scheme);
      case Family::rk4:
        return "RK4 fixed step";
    }
    return "?";
  }
  [[nodiscard]] std::string setting() const {
    if (family == Family::rk4) {
      const double dt = problem->times.front();
      return "h=" + sci(dt / substeps);
    }
    return "tol=" + sci(tol);
  }
};

/// A finished measurement.
struct Row {
  Job job;
  Run run;
  Errors errors;
};

/// The RK4 step counts per output interval for problem p: powers of two from 1 until the step
/// times the largest rate |omega0| is below 1e-3 rad (where RK4's error is near the round-off
/// floor on these problems).
std::vector<int> rk4_substeps(const Problem& p) {
  const double dt = p.times.front();
  const double rate = p.omega0.norm();
  std::vector<int> list;
  for (int s = 1; s <= (1 << 16); s *= 2) {
    list.push_back(s);
    if (dt / s * rate < 1e-3) {
      break;
    }
  }
  return list;
}

std::string line_result(const Row& r) {
  if (!r.run.ok) {
    return "FAILED: " + r.run.error;
  }
  std::string s = duration(r.run.seconds) + ", max attitude error " + sci(r.errors.max_attitude);
  s += ", " + std::to_string(r.run.steps) + " steps";
  if (r.run.chart_switches > 0) {
    s += ", " + std::to_string(r.run.chart_switches) + " chart switches";
  }
  return s;
}

void write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "problem,method,family,parameterization,scheme,tol,rtol,atol,rk4_substeps,rk4_step_s,ok,"
       "error_message,time_s,time_median_s,wall_time_s,cpu_time_s,reps,final_attitude_error_rad,"
       "max_attitude_error_rad,max_centroid_error_m,max_omega_error_rad_s,energy_drift,"
       "momentum_drift,steps,rhs_evals,linear_rhs_evals,jacobian_evals,error_test_failures,"
       "convergence_failures,reinits,chart_switches,constraint_drift\n";
  for (const Row& r : rows) {
    const Job& j = r.job;
    const bool cv = j.family != Family::rk4;
    f << csv_quote(j.problem->id) << ',' << csv_quote(j.method()) << ',' << family_name(j.family)
      << ',' << csv_quote(j.family == Family::tumble ? j.param->name : "EulerParameters") << ','
      << scheme_name(j.scheme) << ',' << (cv ? num(j.tol) : "") << ',' << (cv ? num(j.tol) : "")
      << ',' << (cv ? num(j.tol) : "") << ',' << (cv ? "" : std::to_string(j.substeps)) << ','
      << (cv ? "" : num(j.problem->times.front() / j.substeps)) << ',' << (r.run.ok ? 1 : 0) << ','
      << csv_quote(r.run.error) << ',' << num(r.run.seconds) << ',' << num(r.run.seconds_median)
      << ',' << num(r.run.wall_seconds) << ',' << num(r.run.cpu_seconds) << ',' << r.run.reps << ','
      << num(r.errors.final_attitude) << ',' << num(r.errors.max_attitude) << ','
      << num(r.errors.max_centroid) << ',' << num(r.errors.max_omega) << ','
      << num(r.errors.energy_drift) << ',' << num(r.errors.momentum_drift) << ',' << r.run.steps
      << ',' << r.run.rhs_evals << ',' << r.run.linear_rhs_evals << ',' << r.run.jacobian_evals
      << ',' << r.run.error_test_failures << ',' << r.run.convergence_failures << ','
      << r.run.reinits << ',' << r.run.chart_switches << ',' << num(r.run.constraint_drift) << '\n';
  }
}

void write_scaling_csv(const std::string& path, const std::vector<ScalingRow>& rows) {
  std::ofstream f(path);
  f << "bodies,measurement,seconds,seconds_per_body,calls,rhs_evals,jacobian_evals,"
       "linear_iterations,ok,error_message\n";
  for (const ScalingRow& r : rows) {
    f << r.bodies << ',' << r.what << ',' << num(r.seconds) << ',' << num(r.per_body) << ','
      << r.calls << ',' << r.rhs_evals << ',' << r.jacobian_evals << ',' << r.linear_iterations
      << ',' << (r.ok ? 1 : 0) << ',' << csv_quote(r.error) << '\n';
  }
}

// ---- work-precision curves and the time at a given error ----------------------------------------

struct Point {
  double error;
  double time;
};

/// The time a method needs to reach `target` (max attitude error), read off its work-precision
/// curve: the Pareto front of its runs (each kept point is faster than every more accurate one),
/// with log(time) interpolated linearly in log(error) between the two points that bracket the
/// target. When even the cheapest run is more accurate than the target, its time (an upper bound)
/// and `bound` = true; when no run reaches the target, nullopt.
struct TimeAt {
  double time = std::numeric_limits<double>::quiet_NaN();
  bool bound = false;
};

std::optional<TimeAt> time_at(std::vector<Point> points, double target) {
  std::erase_if(points, [](const Point& p) {
    return !(std::isfinite(p.error) && p.error > 0 && std::isfinite(p.time));
  });
  if (points.empty()) {
    return std::nullopt;
  }
  std::sort(points.begin(), points.end(),
            [](const Point& a, const Point& b) { return a.time < b.time; });
  std::vector<Point> front;
  for (const Point& p : points) {
    if (front.empty() || p.error < front.back().error) {
      front.push_back(p);
    }
  }
  if (target >= front.front().error) {
    return TimeAt{front.front().time, true};
  }
  if (target < front.back().error) {
    return std::nullopt;
  }
  for (std::size_t i = 0; i + 1 < front.size(); ++i) {
    const Point& a = front[i];
    const Point& b = front[i + 1];
    if (target <= a.error && target >= b.error) {
      const double s = std::log(target / a.error) / std::log(b.error / a.error);
      return TimeAt{std::exp(std::log(a.time) + s * std::log(b.time / a.time)), false};
    }
  }
  return std::nullopt;
}

/// The curves of one problem: method label -> points, in the order the methods were run.
struct Curves {
  std::vector<std::string> order;
  std::map<std::string, std::vector<Point>> points;
  std::map<std::string, Family> family;
  std::map<std::string, double> best_error;
  std::map<std::string, long> switches_at_tightest;
};

Curves curves_of(const std::vector<Row>& rows) {
  Curves c;
  for (const Row& r : rows) {
    const std::string m = r.job.method();
    if (!c.points.contains(m)) {
      c.order.push_back(m);
      c.family[m] = r.job.family;
      c.best_error[m] = std::numeric_limits<double>::infinity();
    }
    c.points[m];
    if (r.run.ok && std::isfinite(r.errors.max_attitude)) {
      c.points[m].push_back({r.errors.max_attitude, r.run.seconds});
      c.best_error[m] = std::min(c.best_error[m], r.errors.max_attitude);
      c.switches_at_tightest[m] = r.run.chart_switches;
    }
  }
  return c;
}

/// The fastest method of a family at a target error.
struct Best {
  std::string method;
  TimeAt at;
};

std::optional<Best> fastest(const Curves& c, Family f, double target) {
  std::optional<Best> best;
  for (const std::string& m : c.order) {
    if (c.family.at(m) != f) {
      continue;
    }
    const auto t = time_at(c.points.at(m), target);
    if (t && (!best || t->time < best->at.time)) {
      best = Best{m, *t};
    }
  }
  return best;
}

std::string time_cell(const std::optional<TimeAt>& t) {
  if (!t) {
    return "-";
  }
  // (appended, not "<" + duration(...): GCC 12 warns falsely on operator+(const char*, string&&))
  std::string cell = t->bound ? "<" : "";
  cell += duration(t->time);
  return cell;
}

// ---- machine description -----------------------------------------------------------------------

std::string read_first_line(const char* path, const std::string& key) {
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (key.empty() || line.rfind(key, 0) == 0) {
      const auto colon = line.find(':');
      return key.empty() || colon == std::string::npos ? line : line.substr(colon + 2);
    }
  }
  return "unknown";
}

std::string compiler() {
#if defined(__clang__)
  return std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string machine_description() {
  std::ostringstream s;
  s << "machine:   " << read_first_line("/proc/cpuinfo", "model name") << ", "
    << std::thread::hardware_concurrency() << " hardware threads available to this process\n"
    << "load:      " << read_first_line("/proc/loadavg", "")
    << " (/proc/loadavg; in a container it may count the whole host)\n"
    << "compiler:  " << compiler() << ", build type " << TUMBLE_BENCH_BUILD_TYPE << ", flags "
    << TUMBLE_BENCH_CXX_FLAGS << "\n"
    << "libraries: SUNDIALS " << SUNDIALS_VERSION << ", Eigen " << EIGEN_WORLD_VERSION << '.'
    << EIGEN_MAJOR_VERSION << '.' << EIGEN_MINOR_VERSION << ", " << pinocchio_description() << "\n";
#ifndef NDEBUG
  s << "WARNING:   assertions are on (no NDEBUG): configure with -DCMAKE_BUILD_TYPE=Release for "
       "meaningful times\n";
#endif
  return s.str();
}

// ---- the stiff top's reference
// --------------------------------------------------------------------

/// The stiff top has no closed form. Its reference integrates tumble's equations of the same
/// body and loads in long double with fixed-step RK4 (h = 5 us, 200,000 steps over 1 s: far
/// below both the spring's period, 6.3 ms, and the spin's, 42 ms), independent of CVODE and of
/// double rounding; its own error is estimated by Richardson's rule against h = 10 us.
/// (A CVODE run at rtol 1e-14 is no reference here: BDF and Adams at 1e-14 differ by 1e-9 rad.)
void make_stiff_reference(Problem& p) {
  constexpr double step = 5e-6;
  const int substeps = std::max(1, static_cast<int>(std::lround(p.times.front() / step)));
  p.reference = stiff_top_reference(p, substeps, p.reference_uncertainty);
  p.reference_note = "tumble's equations in long double, fixed-step RK4 with h = " +
                     sci(p.times.front() / substeps) +
                     " s and quaternion projection; Richardson error estimate " +
                     sci(p.reference_uncertainty) + " rad";
}

// ---- the summary
// ---------------------------------------------------------------------------------

const std::vector<double> kTargetErrors = {1e-3, 1e-6, 1e-9};

std::string problem_table(const Problem& p, const Curves& c) {
  std::ostringstream s;
  s << "\n" << p.id << ": " << p.title << "\n";
  s << "  reference: " << p.reference_note << "\n";
  const std::vector<double> errs = {1e-3, 1e-6, 1e-9, 1e-11};
  s << "  " << pad("method", 38) << lpad("best err", 10);
  for (double e : errs) {
    s << lpad("t(" + sci(e) + ")", 12);
  }
  s << lpad("switches", 10) << "\n";
  for (const std::string& m : c.order) {
    s << "  " << pad(m, 38) << lpad(sci(c.best_error.at(m)), 10);
    for (double e : errs) {
      s << lpad(time_cell(time_at(c.points.at(m), e)), 12);
    }
    const auto sw = c.switches_at_tightest.find(m);
    s << lpad(sw == c.switches_at_tightest.end() ? "-" : std::to_string(sw->second), 10) << "\n";
  }
  s << "  (t(e): time to reach max attitude error e, interpolated on the method's log-log "
       "work-precision curve;\n   '<' = its cheapest run is already more accurate; '-' = not "
       "reached; switches: chart switches at the tightest setting)\n";
  return s.str();
}

struct Verdict {
  std::string name;
  std::string measured;
  std::string target;
  std::string status;
};

std::string verdict_table(const std::vector<Verdict>& v) {
  std::size_t w0 = 6, w1 = 8, w2 = 6;
  for (const Verdict& x : v) {
    w0 = std::max(w0, x.name.size());
    w1 = std::max(w1, x.measured.size());
    w2 = std::max(w2, x.target.size());
  }
  std::ostringstream s;
  s << "  " << pad("target", w0) << "  " << pad("measured", w1) << "  " << pad("goal", w2)
    << "  status\n";
  s << "  " << std::string(w0 + w1 + w2 + 14, '-') << "\n";
  for (const Verdict& x : v) {
    s << "  " << pad(x.name, w0) << "  " << pad(x.measured, w1) << "  " << pad(x.target, w2) << "  "
      << x.status << "\n";
  }
  return s.str();
}

/// The typical timing noise: the median over repetitions of (median / best - 1).
double timing_noise(const std::vector<Row>& rows) {
  std::vector<double> r;
  for (const Row& x : rows) {
    if (x.run.ok && x.run.reps >= 3 && x.run.seconds > 0) {
      r.push_back(x.run.seconds_median / x.run.seconds - 1.0);
    }
  }
  if (r.empty()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2), r.end());
  return r[r.size() / 2];
}

void ratio_verdicts(std::vector<Verdict>& out, const Curves& c, const std::vector<Row>& rows) {
  // 1. accuracy
  double best = std::numeric_limits<double>::infinity();
  std::string best_method;
  std::string best_setting;
  for (const Row& r : rows) {
    if (r.job.family == Family::tumble && r.run.ok && r.errors.max_attitude < best) {
      best = r.errors.max_attitude;
      best_method = r.job.method();
      best_setting = r.job.setting();
    }
  }
  out.push_back({"tumbling: tumble's best max attitude error",
                 sci(best) + " rad (" + best_method + ", " + best_setting + ")", "<= 1e-11",
                 best <= 1e-11 ? "met" : "MISSED"});
  const double noise = timing_noise(rows);
  // 2. against the hand-written floor, Pinocchio and RK4
  for (double e : kTargetErrors) {
    const auto t = fastest(c, Family::tumble, e);
    const auto floor = fastest(c, Family::handwritten, e);
    const std::string at = " at error " + sci(e);
    if (!t) {
      out.push_back(
          {"tumble vs hand-written floor" + at, "tumble does not reach it", "<= 1.00x", "MISSED"});
      continue;
    }
    const std::string who = " (" + t->method + " " + duration(t->at.time) + ")";
    if (floor) {
      const double ratio = t->at.time / floor->at.time;
      std::string status = ratio <= 1.0 ? "met" : "MISSED";
      if (ratio > 1.0 && ratio - 1.0 <= noise) {
        status += " (within the timing noise, " + fmt("%.0f%%", 100 * noise) + ")";
      }
      out.push_back({"tumble vs hand-written floor" + at,
                     fmt("%.2fx the floor", ratio) + who + " vs " + floor->method + " " +
                         duration(floor->at.time),
                     "<= 1.00x", status});
    }
    const auto pin = fastest(c, Family::pinocchio, e);
    if (!pinocchio_available()) {
      out.push_back(
          {"Pinocchio-in-CVODE / tumble" + at, "n/a: Pinocchio not installed", ">= 1.5x", "n/a"});
    } else if (pin) {
      const double ratio = pin->at.time / t->at.time;
      out.push_back({"Pinocchio-in-CVODE / tumble" + at,
                     fmt("%.2fx", ratio) + " (" + pin->method + " " + duration(pin->at.time) + ")",
                     ">= 1.5x", ratio >= 1.5 ? "met" : "MISSED"});
    } else {
      out.push_back(
          {"Pinocchio-in-CVODE / tumble" + at, "Pinocchio does not reach it", ">= 1.5x", "met"});
    }
    const auto rk = fastest(c, Family::rk4, e);
    if (rk) {
      const double ratio = rk->at.time / t->at.time;
      out.push_back({"fixed-step RK4 / tumble" + at,
                     fmt("%.2fx", ratio) + " (RK4 " + time_cell(rk->at) + ")", ">= 1.5x",
                     ratio >= 1.5 ? "met" : "MISSED"});
    } else {
      out.push_back({"fixed-step RK4 / tumble" + at, "RK4 does not reach it", ">= 1.5x", "met"});
    }
  }
}

/// Least-squares slope of log(y) against log(x).
double loglog_slope(const std::vector<std::pair<double, double>>& xy) {
  if (xy.size() < 2) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : xy) {
    const double lx = std::log(x), ly = std::log(y);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double n = static_cast<double>(xy.size());
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::string scaling_table(const std::vector<ScalingRow>& rows, std::vector<Verdict>& verdicts) {
  std::ostringstream s;
  std::set<int> sizes;
  for (const ScalingRow& r : rows) {
    sizes.insert(r.bodies);
  }
  s << "\nscaling: a chain of N Euler-parameter bodies joined by spring-dampers (BDF at rtol "
       "1e-6, atol 1e-8)\n";
  s << "  " << lpad("N", 6) << lpad("rhs/body", 12) << lpad("dense/step", 13)
    << lpad("band/step", 13) << lpad("band-dq/step", 14) << lpad("gmres/step", 13)
    << lpad("band/body", 12) << lpad("gmres/body", 12) << "\n";
  auto find = [&](int n, const std::string& k) -> const ScalingRow* {
    for (const ScalingRow& r : rows) {
      if (r.bodies == n && r.what == k && r.ok) {
        return &r;
      }
    }
    return nullptr;
  };
  for (int n : sizes) {
    auto cell = [&](const std::string& k, bool per_body) {
      const ScalingRow* r = find(n, k);
      return r ? duration(per_body ? r->per_body : r->seconds) : std::string("-");
    };
    s << "  " << lpad(std::to_string(n), 6) << lpad(cell("rhs", true), 12)
      << lpad(cell("bdf-dense", false), 13) << lpad(cell("bdf-band", false), 13)
      << lpad(cell("bdf-band-dq", false), 14) << lpad(cell("bdf-gmres", false), 13)
      << lpad(cell("bdf-band", true), 12) << lpad(cell("bdf-gmres", true), 12) << "\n";
  }
  // rhs per body: flat within 1.2x
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  int n_lo = 0, n_hi = 0;
  for (int n : sizes) {
    if (const ScalingRow* r = find(n, "rhs")) {
      if (r->per_body < lo) {
        lo = r->per_body;
        n_lo = n;
      }
      if (r->per_body > hi) {
        hi = r->per_body;
        n_hi = n;
      }
    }
  }
  if (hi > 0) {
    const double ratio = hi / lo;
    verdicts.push_back({"rhs cost per body, max/min over N",
                        fmt("%.2fx", ratio) + " (max " + duration(hi) +
                            " at N=" + std::to_string(n_hi) + ", min " + duration(lo) +
                            " at N=" + std::to_string(n_lo) + ")",
                        "<= 1.2x", ratio <= 1.2 ? "met" : "MISSED"});
  }
  // BDF step cost: log-log slope over N >= 100 (where the per-body work dominates CVODE's
  // fixed per-step overhead), or over all sizes when fewer than two are that large.
  for (const std::string k : {"bdf-band", "bdf-gmres", "bdf-dense"}) {
    std::vector<std::pair<double, double>> all, large;
    for (int n : sizes) {
      if (const ScalingRow* r = find(n, k)) {
        all.emplace_back(n, r->seconds);
        if (n >= 100) {
          large.emplace_back(n, r->seconds);
        }
      }
    }
    const auto& fit = large.size() >= 2 ? large : all;
    if (fit.size() < 2) {
      continue;
    }
    const double slope = loglog_slope(fit);
    const std::string range = "N=" + std::to_string(static_cast<int>(fit.front().first)) + ".." +
                              std::to_string(static_cast<int>(fit.back().first));
    if (k == "bdf-dense") {
      verdicts.push_back({"BDF step cost growth, dense LU (for comparison)",
                          "slope " + fmt("%.2f", slope) + " (" + range + ")",
                          "(superlinear expected)", "info"});
    } else {
      verdicts.push_back(
          {"BDF step cost growth, " + std::string(k == "bdf-band" ? "band LU" : "GMRES"),
           "slope " + fmt("%.2f", slope) + " (" + range + ", log-log fit)", "~1 (<= 1.2)",
           slope <= 1.2 ? "met" : "MISSED"});
    }
  }
  s << "  (per step: construction of the integrator plus the first steps, divided by the steps; "
       "dense only up to\n   the N where it is feasible; dense and band with the scene's exact "
       "Jacobian, band-dq with CVODE's\n   banded difference quotients)\n";
  return s.str();
}

// ---- plots
// ---------------------------------------------------------------------------------------

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) {
    if (ch == '\'') {
      q += "'\\''";
    } else {
      q += ch;
    }
  }
  return q + "'";
}

void plot(const Options& o, const std::string& out) {
  const std::string script = TUMBLE_BENCH_PLOT_SCRIPT;
  if (!std::filesystem::exists(script)) {
    std::printf("plots: skipped, the script %s is not there\n", script.c_str());
    return;
  }
  const std::string check = shell_quote(o.python) + " -c 'import matplotlib' >/dev/null 2>&1";
  if (std::system(check.c_str()) != 0) {
    std::printf("plots: skipped, matplotlib is not available to %s (install python3-matplotlib, or "
                "pass --python); the CSVs are written\n",
                o.python.c_str());
    return;
  }
  const std::string cmd =
      shell_quote(o.python) + " " + shell_quote(script) + " " + shell_quote(out);
  std::fflush(stdout);
  if (std::system(cmd.c_str()) != 0) {
    std::printf("plots: %s failed (the CSVs are written)\n", cmd.c_str());
  }
}

/// Runs tumble_micro through summarize_micro.py (the short list that the ratios need) and returns
/// its table, or a line that says why it was skipped. The JSON and the table go to `out`.
std::string micro_summary(const Options& o, const std::string& out) {
  const std::string micro = TUMBLE_BENCH_MICRO, script = TUMBLE_BENCH_MICRO_SCRIPT;
  if (micro.empty() || !std::filesystem::exists(micro)) {
    return "per-step micro-benchmarks: skipped (tumble_micro was not built: Google Benchmark "
           "missing?)\n";
  }
  if (script.empty() || !std::filesystem::exists(script)) {
    return "per-step micro-benchmarks: skipped (summarize_micro.py not found)\n";
  }
  const std::string table = out + "/micro_summary.txt";
  const std::string cmd = shell_quote(o.python) + " " + shell_quote(script) + " --run " +
                          shell_quote(micro) + " --quick --out " +
                          shell_quote(out + "/micro.json") + " > " + shell_quote(table);
  std::fflush(stdout);
  if (std::system(cmd.c_str()) != 0) {
    return "per-step micro-benchmarks: FAILED (" + cmd + ")\n";
  }
  std::ifstream f(table);
  std::stringstream text;
  text << f.rdbuf();
  return text.str();
}

// ---- main
// ----------------------------------------------------------------------------------------

int counter = 0;
int total = 0;

void progress_prefix(const std::string& text) {
  ++counter;
  std::printf("[%d/%d] %s ... ", counter, total, text.c_str());
  std::fflush(stdout);
}

void scaling_done(const ScalingRow& r) {
  if (!r.ok) {
    std::printf("FAILED: %s\n", r.error.c_str());
  } else if (r.what == "rhs") {
    std::printf("%s per right-hand side, %s per body\n", duration(r.seconds).c_str(),
                duration(r.per_body).c_str());
  } else {
    std::string gmres;
    if (r.what == "bdf-gmres") {
      gmres = ", " + std::to_string(r.linear_iterations) + " GMRES iterations";
    }
    std::printf("%s per step (%ld steps, %ld right-hand sides, %ld Jacobians%s)\n",
                duration(r.seconds).c_str(), r.calls, r.rhs_evals, r.jacobian_evals, gmres.c_str());
  }
  std::fflush(stdout);
}

int run(const Options& o) {
  const auto start = Clock::now();
  namespace fs = std::filesystem;
  const fs::path out = fs::absolute(o.out);
  fs::create_directories(out);
  const std::string machine =
      machine_description() + "times:     " +
      (o.clock == TimeBase::wall ? "wall clock (std::chrono::steady_clock)"
                                 : "thread CPU time (CLOCK_THREAD_CPUTIME_ID; --clock cpu)") +
      ", best of " + std::to_string(o.reps) +
      " runs (1 when the first takes > 1 s); the CSVs have both clocks\n";
  std::printf("tumble_bench: %s run; results go to %s\n%s\n", o.full ? "full" : "quick",
              out.string().c_str(), machine.c_str());

  std::vector<Parameterization> params;
  add_parameterizations_a(params);
  add_parameterizations_b(params);
  std::erase_if(params, [&](const Parameterization& p) { return !o.full && !p.quick; });

  std::vector<Problem> problems = make_problems(o.outputs);
  std::erase_if(problems, [&](const Problem& p) {
    return !o.problems.empty() && !o.problems.contains(p.id);
  });

  // The plan.
  const std::vector<double>& tolerances = o.tolerances.empty() ? kTolerances : o.tolerances;
  std::vector<Job> jobs;
  for (const Problem& p : problems) {
    for (const Parameterization& par : params) {
      for (Scheme s : {Scheme::adams, Scheme::bdf}) {
        for (double tol : tolerances) {
          jobs.push_back({&p, Family::tumble, &par, s, tol, 0});
        }
      }
    }
    if (!p.exact) {
      continue;  // the references below need a closed-form problem (no spring)
    }
    for (Scheme s : {Scheme::adams, Scheme::bdf}) {
      for (double tol : tolerances) {
        jobs.push_back({&p, Family::handwritten, nullptr, s, tol, 0});
      }
    }
    if (pinocchio_available()) {
      for (Scheme s : {Scheme::adams, Scheme::bdf}) {
        for (double tol : tolerances) {
          jobs.push_back({&p, Family::pinocchio, nullptr, s, tol, 0});
        }
      }
    }
    for (int sub : rk4_substeps(p)) {
      jobs.push_back({&p, Family::rk4, nullptr, Scheme::rk4, 0, sub});
    }
  }
  std::erase_if(jobs, [&](const Job& j) {
    if (o.methods.empty()) {
      return false;
    }
    const std::string m = j.method();
    return std::none_of(o.methods.begin(), o.methods.end(),
                        [&](const std::string& s) { return m.find(s) != std::string::npos; });
  });
  ScalingPlan plan;
  if (o.full) {
    plan.rhs_sizes = {1, 3, 10, 30, 100, 300, 1000, 3000, 10000};
    plan.bdf_sizes = {1, 3, 10, 30, 100, 300, 1000, 3000, 10000};
    plan.dense_limit = 200;
    plan.bdf_sizes.insert(std::lower_bound(plan.bdf_sizes.begin(), plan.bdf_sizes.end(), 200), 200);
  } else {
    plan.rhs_sizes = {1, 3, 10, 30, 100, 300, 1000};
    plan.bdf_sizes = {1, 3, 10, 30, 100, 300, 1000};
    plan.dense_limit = 100;
  }
  plan.reps = o.reps;
  plan.base = o.clock;
  bool stiff = false;
  for (const Problem& p : problems) {
    stiff = stiff || !p.exact;
  }
  total = static_cast<int>(jobs.size()) + (stiff ? 1 : 0) + (o.micro ? 1 : 0) +
          (o.scaling ? scaling_measurements(plan) : 0);

  std::string micro_text;
  if (o.micro) {
    progress_prefix("per-step micro-benchmarks (tumble_micro, the ratios' short list)");
    const auto t0 = Clock::now();
    micro_text = micro_summary(o, out.string());
    std::printf("%s\n", duration(seconds_since(t0)).c_str());
  }

  const Timing timing{.reps = o.reps, .base = o.clock, .slow_run = 1.0};
  std::string summary;
  std::vector<Verdict> verdicts;
  for (Problem& p : problems) {
    if (!p.exact) {
      progress_prefix("reference for " + p.id + " (long double RK4, h = 5 us and 10 us)");
      const auto t0 = Clock::now();
      make_stiff_reference(p);
      std::printf("%s, uncertainty %s rad\n", duration(seconds_since(t0)).c_str(),
                  sci(p.reference_uncertainty).c_str());
    }
    std::vector<Row> rows;
    for (const Job& j : jobs) {
      if (j.problem != &p) {
        continue;
      }
      progress_prefix(p.id + " " + j.method() + " " + j.setting());
      Row r{j, {}, {}};
      switch (j.family) {
        case Family::tumble:
          r.run = j.param->run(p, {j.scheme, j.tol, o.exact_jacobian}, timing);
          break;
        case Family::handwritten:
          r.run = run_handwritten(p, {j.scheme, j.tol}, timing);
          break;
        case Family::pinocchio:
          r.run = run_pinocchio(p, {j.scheme, j.tol}, timing);
          break;
        case Family::rk4:
          r.run = run_rk4(p, j.substeps, timing);
          break;
      }
      r.errors = evaluate(p, r.run);
      r.run.samples.clear();
      r.run.samples.shrink_to_fit();
      std::printf("%s\n", line_result(r).c_str());
      std::fflush(stdout);
      rows.push_back(std::move(r));
    }
    const std::string csv = (out / ("work_precision_" + p.id + ".csv")).string();
    write_csv(csv, rows);
    const Curves c = curves_of(rows);
    summary += problem_table(p, c);
    if (p.kind == ProblemKind::tumbling) {
      ratio_verdicts(verdicts, c, rows);
      const double noise = timing_noise(rows);
      summary += "  timing noise on this problem (median over runs of median/best - 1): " +
                 fmt("%.1f%%", 100 * noise) + "\n";
    }
  }

  {
    std::ofstream f(out / "problems.csv");
    f << "id,title,reference,reference_uncertainty_rad\n";
    for (const Problem& p : problems) {
      f << csv_quote(p.id) << ',' << csv_quote(p.title) << ',' << csv_quote(p.reference_note) << ','
        << num(p.reference_uncertainty) << '\n';
    }
  }

  if (o.scaling) {
    const ScalingProgress progress{.start = &progress_prefix, .done = &scaling_done};
    const std::vector<ScalingRow> rows = run_scaling(plan, progress);
    write_scaling_csv((out / "scaling.csv").string(), rows);
    summary += scaling_table(rows, verdicts);
  }

  const double elapsed = seconds_since(start);
  std::ostringstream text;
  text << "\n================================ tumble_bench summary "
          "================================\n"
       << machine;
  if (!micro_text.empty()) {
    text << "\nper-step cost of the core assembly (tumble_micro; CPU ns per call, median of 3 "
            "repetitions):\n"
         << micro_text;
  }
  text << summary;
  if (!verdicts.empty()) {
    text << "\ntargets of issue 4 (measured in this run):\n" << verdict_table(verdicts);
  }
  text << "\nrun time " << fmt("%.0f s", elapsed) << " (" << (o.full ? "full" : "quick")
       << " run); results in " << out.string() << "\n";
  std::printf("%s", text.str().c_str());
  {
    std::ofstream f(out / "summary.txt");
    f << text.str();
  }
  if (o.plots) {
    plot(o, out.string());
  }
  std::printf("wrote: %s/{work_precision_*.csv,scaling.csv,summary.txt%s}\n", out.string().c_str(),
              o.plots ? ",*.png" : "");
  return 0;
}

}  // namespace
}  // namespace tumble::bench

int main(int argc, char** argv) {
  try {
    const auto options = tumble::bench::parse(argc, argv);
    if (!options) {
      return 0;
    }
    return tumble::bench::run(*options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tumble_bench: %s\n", e.what());
    return 1;
  }
}
