// tumble_bench: the report, the text it prints (and copies to summary.txt):
//   the header  what is measured, on which machine and build, how it is timed, how long it takes;
//   (a)         ns per call of the core assembly per parameterization, beside the baselines and
//               the peers that were built (tumble_micro's medians);
//   (b)         per problem and method, the time to reach a maximum attitude error of 1e-3, 1e-6,
//               1e-9 and 1e-11 rad, read off the method's tolerance sweep (time_at below), and the
//               best error the sweep reached;
//   (c)         the cost of a right-hand side and of a BDF step against the number of bodies, with
//               the log-log slope;
//   (d)         runs per second of an ensemble against threads and MPI processes, the per-run cost
//               against serial loops, memory and allocations per run, against their targets;
//   (e)         per mechanism (IFToMM A01-A05) and method (tumble's integrators, MuJoCo's and
//               Exudyn's when installed), the time to reach an error of 1e-3, 1e-6, 1e-9 in the
//               problem's own measure (time_at, as in (b)), the best error and the constraint
//               residual |C| at the end of the most accurate run.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <sundials/sundials_config.h>

#include "common/format.hpp"
#include "main/driver.hpp"

#ifndef TUMBLE_BENCH_BUILD_TYPE
#define TUMBLE_BENCH_BUILD_TYPE "unknown"
#endif
#ifndef TUMBLE_BENCH_CXX_FLAGS
#define TUMBLE_BENCH_CXX_FLAGS "unknown"
#endif

namespace tumble::bench {
namespace {

// ---- the header --------------------------------------------------------------------------------

std::string first_line(const char* path, const std::string& key) {
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

/// `text` broken at spaces into lines of at most 100 columns, continued with `indent`.
std::string wrap(const std::string& text, const std::string& indent) {
  constexpr std::size_t width = 100;
  std::string out, line;
  std::size_t pos = 0;
  while (pos < text.size()) {
    auto next = text.find(' ', pos + 1);
    if (next == std::string::npos) {
      next = text.size();
    }
    const std::string word = text.substr(pos, next - pos);
    if (line.size() + word.size() > width && line.size() > indent.size() + 1) {
      out += line + "\n";
      line = indent + word.substr(word.front() == ' ' ? 1 : 0);
    } else {
      line += word;
    }
    pos = next;
  }
  return out + line + "\n";
}

}  // namespace

// ---- (b), (e): time to reach an error, read off a sweep -----------------------------------------

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

namespace {

/// The row label of a method, without its scheme: tumble's rows are named by parameterization.
std::string method_label(const Job& j) {
  // the long names of the Rodrigues sets, shortened (the quasi form's label adds " quasi")
  const std::pair<std::string, std::string> shorter[] = {
      {"ModifiedRodriguesParameters", "ModifiedRodrigues"},
      {"RodriguesParameters", "Rodrigues (Gibbs)"}};
  const std::string& l = j.method_entry->label;
  for (const auto& [from, to] : shorter) {
    if (l.starts_with(from)) {
      return to + l.substr(from.size());
    }
  }
  return l;
}

const std::vector<double> kErrors = {1e-3, 1e-6, 1e-9, 1e-11};

// ---- (c): slopes -------------------------------------------------------------------------------

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

}  // namespace

std::string header_text(const Options& o, const std::filesystem::path& out, int runs) {
  std::string load = first_line("/proc/loadavg", "");
  load = load.substr(0, load.find(' ', load.find(' ', load.find(' ') + 1) + 1));
  // Calibrated on a 2-core machine (2026-12-05, the quick run in 177 s): about 0.036 s per run of
  // the sweep on average (1930 runs in 70 s), 10 s of micro-benchmarks, 11 s (quick) of scaling,
  // 18 s (quick) of ensembles, 61 s (quick) of mechanisms (A05 alone 39 s), 6 s of
  // plots; --full's studies at the ratios to the quick ones of the 2026-11-25 calibration.
  const double estimate = 0.036 * runs + (o.micro ? 10.0 : 0.0) +
                          (o.scaling ? (o.full ? 90.0 : 11.0) : 0.0) +
                          (o.ensemble ? (o.full ? 55.0 : 18.0) : 0.0) +
                          (o.mechanisms ? (o.full ? 115.0 : 61.0) : 0.0) + (o.plots ? 6.0 : 0.0);
  std::ostringstream s;
  s << "tumble_bench (" << (o.full ? "full" : "quick")
    << " run): what tumble's rigid-body dynamics cost and the accuracy they buy\n"
    << "  measures  (a) ns per call of the core assembly, (b) run time to reach an attitude error "
       "on\n"
    << "            problems with exact answers, (c) cost per step against the number of bodies,\n"
    << "            (d) runs per second of an ensemble against threads and MPI processes,\n"
    << "            (e) run time to reach an error on IFToMM mechanisms (A01-A05)\n"
    << "  machine   " << first_line("/proc/cpuinfo", "model name") << ", "
    << std::thread::hardware_concurrency() << " hardware threads, load " << load << "\n"
    << "  build     " << compiler() << ", " << TUMBLE_BENCH_BUILD_TYPE << " ("
    << TUMBLE_BENCH_CXX_FLAGS << "); SUNDIALS " << SUNDIALS_VERSION << ", Eigen "
    << EIGEN_WORLD_VERSION << '.' << EIGEN_MAJOR_VERSION << '.' << EIGEN_MINOR_VERSION << "\n";
  std::vector<std::string> peers;
  if (pinocchio_available()) {
    peers.push_back(pinocchio_description());
  }
  if (mujoco_available()) {
    peers.push_back("MuJoCo (mj_step: RK4; implicitfast on A05)");
  }
  if (exudyn_available()) {
    peers.push_back("Exudyn (SolveDynamic, implicit; mechanisms only)");
  }
  for (std::size_t i = 0; i < peers.size(); ++i) {
    s << (i == 0 ? "  peers     " : "; ") << peers[i] << (i + 1 == peers.size() ? "\n" : "");
  }
  const Timing sweep = sweep_timing(o);
  s << "  timing    " << (o.clock == TimeBase::wall ? "wall clock" : "thread CPU time")
    << ", best of " << sweep.reps << " runs per setting (of up to " << sweep.max_reps
    << " while they fill less than " << fmt("%.0f", 1e3 * sweep.min_total) << " ms), in "
    << sweep.rounds << " rounds over each problem's settings; this run: about "
    << fmt("%.0f", std::max(10.0, 10 * std::round(estimate / 10)))
    << " s on an idle 2-core machine\n"
    << "  results   " << out.string() << "\n";
#ifndef NDEBUG
  s << "  WARNING   assertions are on (no NDEBUG): configure with -DCMAKE_BUILD_TYPE=Release\n";
#endif
  return s.str();
}

namespace {

/// A mechanism's cost against its number of bodies: tumble_micro's hinged chain (micro/chain.cpp),
/// a right-hand side (the banded constraint solve included) and a projection onto the constraints,
/// per call and per body, with the log-log slope of the cost per call from 100 bodies on.
std::string chain_table(const MicroTimes& ns) {
  const std::vector<std::pair<std::string, std::string>> cols = {
      {"chain_rhs", "rhs"}, {"chain_projection", "projection"}};
  std::vector<int> sizes;
  for (int n = 1; n <= 10000; n *= 10) {
    if (ns.contains("chain_rhs/" + std::to_string(n)) ||
        ns.contains("chain_projection/" + std::to_string(n))) {
      sizes.push_back(n);
    }
  }
  if (sizes.empty()) {
    return "";
  }
  std::ostringstream s;
  s << "  a mechanism, a chain of n links hinged end to end: CPU time of a right-hand side (the\n"
       "  banded constraint solve included) and of a projection onto the constraints\n"
    << "  " << lpad("n", 6);
  for (const auto& c : cols) {
    s << lpad(c.second, 12) << lpad("per body", 12);
  }
  s << "\n";
  std::vector<std::vector<std::pair<double, double>>> large(cols.size());  // (n, ns), n >= 100
  for (int n : sizes) {
    s << "  " << lpad(std::to_string(n), 6);
    for (std::size_t c = 0; c < cols.size(); ++c) {
      const auto it = ns.find(cols[c].first + "/" + std::to_string(n));
      const bool have = it != ns.end();
      s << lpad(have ? duration(1e-9 * it->second) : "-", 12)
        << lpad(have ? duration(1e-9 * it->second / n) : "-", 12);
      if (have && n >= 100) {
        large[c].emplace_back(n, it->second);
      }
    }
    s << "\n";
  }
  s << "  " << lpad("slope", 6);
  for (const auto& points : large) {
    const double slope = loglog_slope(points);  // NaN for fewer than two sizes
    s << lpad(std::isfinite(slope) ? fmt("%.2f", slope) : "-", 24);
  }
  s << "\n  (slope: log-log fit of the cost per call against n over n >= 100; 1 = linear)\n";
  return s.str();
}

}  // namespace

std::string micro_table(const MicroTimes& ns) {
  auto cell = [&](const std::string& name) {
    const auto it = ns.find(name);
    return lpad(it == ns.end() ? std::string("-") : fmt("%.1f", it->second), 9);
  };
  auto row = [&](const std::string& label, const std::string& c, const std::string& o,
                 const std::string& lc, const std::string& lo) {
    return "  " + pad(label, 34) + cell(c) + cell(o) + "   " + cell(lc) + cell(lo) + "\n";
  };
  std::ostringstream s;
  s << "(a) per-call cost of the core assembly, qddot of one body: CPU ns per call, median of 3\n"
    << "  " << pad("", 34) << lpad("wrench given", 18) << "   " << lpad("with 3 loads", 18) << "\n"
    << "  " << pad("", 34) << lpad("centroid", 9) << lpad("offset", 9) << "   "
    << lpad("centroid", 9) << lpad("offset", 9) << "\n";
  const char* order[] = {"EulerParameters",
                         "RodriguesParameters",
                         "ModifiedRodriguesParameters",
                         "RotationVector",
                         "EulerXYZ",
                         "EulerXZY",
                         "EulerYXZ",
                         "EulerYZX",
                         "EulerZXY",
                         "EulerZYX",
                         "EulerXYX",
                         "EulerXZX",
                         "EulerYXY",
                         "EulerYZY",
                         "EulerZXZ",
                         "EulerZYZ"};
  for (const std::string p : order) {
    if (ns.contains("qddot/" + p + "/centroid") || ns.contains("qddot_loads/" + p + "/centroid")) {
      s << row("tumble " + p, "qddot/" + p + "/centroid", "qddot/" + p + "/offset",
               "qddot_loads/" + p + "/centroid", "qddot_loads/" + p + "/offset");
    }
  }
  s << row("hand-written EP (floor)", "hand_written/EulerParameters/centroid", "",
           "hand_written_loads/EulerParameters/centroid", "");
  for (const std::string p : order) {
    if (ns.contains("dense_lu/" + p + "/centroid")) {
      s << row("dense + LU, " + p, "", "", "dense_lu/" + p + "/centroid",
               "dense_lu/" + p + "/offset");
    }
  }
  bool peers = false;
  for (const auto& [label, name] : std::vector<std::pair<std::string, std::string>>{
           {"Pinocchio aba", "pinocchio_aba/"},
           {"Pinocchio crba+nle+Cholesky", "pinocchio_crba_nle_solve/"},
           {"MuJoCo mj_forward", "mujoco_forward/"}}) {
    if (ns.contains(name + "centroid")) {
      s << row(label, name + "centroid", name + "offset", "", "");
      peers = true;
    }
  }
  s << "  (3 loads: gravity, a point force, a moment; floor: the same equations written by hand;\n"
       "   dense: the generic assembly and LU that tumble avoids"
    << (peers ? ")\n" : "; Pinocchio, MuJoCo: not installed)\n");
  s << chain_table(ns);
  return s.str();
}

std::string problem_table(const Problem& p, const std::vector<Row>& rows) {
  // label -> scheme -> points, labels in the order they were run
  std::vector<std::string> labels;
  std::map<std::string, std::map<int, std::vector<Point>>> points;
  for (const Row& r : rows) {
    const std::string label = method_label(r.job);
    if (!points.contains(label)) {
      labels.push_back(label);
    }
    const int group = r.job.scheme == Scheme::bdf ? 1 : 0;  // explicit methods: the first group
    auto& list = points[label][group];
    if (r.run.ok && std::isfinite(r.errors.max_attitude)) {
      list.push_back({r.errors.max_attitude, r.run.seconds});
    }
  }
  std::ostringstream s;
  s << wrap(p.id + ": " + p.title, "  ");
  if (!p.exact) {
    s << wrap("  reference: " + p.reference_note, "    ");
  }
  for (const std::string& label : labels) {
    std::string line = "  " + pad(label, 26);
    for (int g = 0; g < 2; ++g) {
      const auto it = points[label].find(g);
      if (it == points[label].end()) {
        line += std::string((kErrors.size() + 1) * 8, ' ');
        continue;
      }
      for (double e : kErrors) {
        const auto t = time_at(it->second, e);
        std::string cell = t && t->bound ? "<" : "";
        cell += t ? duration(t->time, true) : std::string("-");
        line += lpad(cell, 8);
      }
      double best = std::numeric_limits<double>::infinity();
      for (const Point& pt : it->second) {
        best = std::min(best, pt.error);
      }
      line += lpad(std::isfinite(best) ? sci(best) : std::string("failed"), 8);
    }
    s << line.substr(0, line.find_last_not_of(' ') + 1) << "\n";
  }
  return s.str();
}

std::string problem_table_header() {
  const std::string bar(40, '-');
  std::string s = pad("(b) work precision", 28) + " ";
  s += bar.substr(0, 5) + " Adams, explicit " + bar.substr(0, 17) + " " + bar.substr(0, 17) +
       " BDF " + bar.substr(0, 17) + "\n  " + pad("method", 26);
  for (int g = 0; g < 2; ++g) {
    for (const char* e : {"1e-3", "1e-6", "1e-9", "1e-11", "best"}) {
      s += lpad(e, 8);
    }
  }
  return s + "\n";
}

std::string problem_table_footer(TimeBase clock) {
  return std::string("  (") + (clock == TimeBase::wall ? "wall" : "CPU") +
         " time to reach a max attitude error of 1e-3, 1e-6, 1e-9, 1e-11 rad: on the runs faster "
         "than\n"
         "   any more accurate one, log(time) interpolated in log(error) between the two that "
         "bracket it;\n"
         "   '<': the cheapest run is more accurate; '-': not reached; best: the smallest error; "
         "explicit\n"
         "   methods (ARKODE, Odeint, RK4's step-size sweep) in the first group; floors: written "
         "by "
         "hand,\n"
         "   [p; w] = [p; omega], [r_g; p; v_g; omega] where the problem has translation or loads; "
         "\n"
         "   every run: work_precision_<problem>.csv)\n";
}

namespace {

const std::vector<double> kMechanismErrors = {1e-3, 1e-6, 1e-9};

}  // namespace

std::string mechanism_table_header() {
  std::string s =
      "(e) mechanisms: work precision on IFToMM problems, tumble's integrators and peers\n  ";
  s += pad("method", 26);
  for (const char* e : {"1e-3", "1e-6", "1e-9", "best", "|C| end", "runs"}) {
    s += lpad(e, 9);
  }
  return s + "\n";
}

std::string mechanism_table(const MechanismResult& r) {
  std::vector<std::string> labels;
  std::map<std::string, std::vector<const MechanismRow*>> by_method;
  for (const MechanismRow& row : r.rows) {
    if (!by_method.contains(row.method)) {
      labels.push_back(row.method);
    }
    by_method[row.method].push_back(&row);
  }
  std::ostringstream s;
  s << wrap(r.id + ": " + r.title, "  ");
  s << wrap("  error: " + r.measure, "    ");
  s << wrap("  reference: " + r.reference, "    ");
  for (const std::string& label : labels) {
    std::vector<Point> points;
    const MechanismRow* best = nullptr;
    int ok = 0;
    for (const MechanismRow* row : by_method[label]) {
      if (!row->run.ok || !std::isfinite(row->error)) {
        continue;
      }
      ++ok;
      points.push_back({row->error, row->run.seconds});
      if (best == nullptr || row->error < best->error) {
        best = row;
      }
    }
    std::string line = "  " + pad(label, 26);
    for (const double e : kMechanismErrors) {
      const auto t = time_at(points, e);
      std::string cell = t && t->bound ? "<" : "";
      cell += t ? duration(t->time, true) : std::string("-");
      line += lpad(cell, 9);
    }
    line += lpad(best ? sci(best->error) : std::string("failed"), 9);
    line += lpad(best ? sci(best->run.constraint_drift) : std::string("-"), 9);
    line += lpad(std::to_string(ok) + "/" + std::to_string(by_method[label].size()), 9);
    s << line << "\n";
    if (best != nullptr && !best->note.empty()) {
      // a peer's fixed-step rows have no tolerance: their note gives the step
      s << wrap("    (at " + (std::isnan(best->tol) ? "" : "tol " + sci(best->tol) + ": ") +
                    best->note + ")",
                "     ");
    }
  }
  return s.str();
}

std::string mechanism_table_footer(TimeBase clock) {
  return std::string("  (") + (clock == TimeBase::wall ? "wall" : "CPU") +
         " time to reach the error, read off each method's tolerance ladder as in (b); '<': the\n"
         "   cheapest run is more accurate; '-': not reached; best: the smallest error, |C| end: "
         "max |C| at\n"
         "   the end of that run; runs: those that finished of the ladder (a method is not run at "
         "tighter\n"
         "   tolerances after it failed, unless it was refused as stiff). MuJoCo's and Exudyn's "
         "rows (when\n"
         "   installed) sweep a fixed step, not a tolerance: every rung is run, and its best run's "
         "step is\n"
         "   given below it. Every run: mechanism_<problem>.csv)\n";
}

std::string scaling_table(const std::vector<ScalingRow>& rows) {
  const std::vector<std::pair<std::string, std::string>> cols = {{"rhs", "rhs/body"},
                                                                 {"bdf-dense", "dense LU"},
                                                                 {"bdf-band", "band LU"},
                                                                 {"bdf-band-dq", "band, DQ J"},
                                                                 {"bdf-gmres", "GMRES"}};
  std::set<int> sizes;
  for (const ScalingRow& r : rows) {
    sizes.insert(r.bodies);
  }
  auto find = [&](int n, const std::string& k) -> const ScalingRow* {
    for (const ScalingRow& r : rows) {
      if (r.bodies == n && r.what == k && r.ok) {
        return &r;
      }
    }
    return nullptr;
  };
  std::ostringstream s;
  s << "(c) a chain of N bodies joined by spring-dampers: cost of a right-hand side per body, and\n"
       "    of a BDF step (rtol 1e-6, atol 1e-8) per linear solver\n";
  s << "  " << lpad("N", 6);
  for (const auto& c : cols) {
    s << lpad(c.second, 12);
  }
  s << "\n";
  for (int n : sizes) {
    s << "  " << lpad(std::to_string(n), 6);
    for (const auto& c : cols) {
      const ScalingRow* r = find(n, c.first);
      s << lpad(r ? duration(c.first == "rhs" ? r->per_body : r->seconds) : "-", 12);
    }
    s << "\n";
  }
  // The slope of the cost per call (not per body) against N, over N >= 100 where the per-body
  // work dominates CVODE's fixed per-step overhead, or over every N when fewer are that large.
  s << "  " << lpad("slope", 6);
  for (const auto& c : cols) {
    std::vector<std::pair<double, double>> all, large;
    for (int n : sizes) {
      if (const ScalingRow* r = find(n, c.first)) {
        all.emplace_back(n, r->seconds);
        if (n >= 100) {
          large.emplace_back(n, r->seconds);
        }
      }
    }
    const double slope = loglog_slope(large.size() >= 2 ? large : all);
    s << lpad(std::isfinite(slope) ? fmt("%.2f", slope) : "-", 12);
  }
  s << "\n  (slope: log-log fit of the cost per call against N over N >= 100 (dense: every N it "
       "ran);\n   1 = linear; 'DQ J': CVODE's difference-quotient Jacobian, else the scene's exact "
       "one)\n";
  return s.str();
}

namespace {

/// "met" or "missed", and how.
std::string verdict(bool measured, bool met) {
  return !measured ? "not measured" : met ? "met" : "missed";
}

const EnsembleRow* find_row(const EnsembleResult& r, const std::string& what, int threads,
                            int ranks) {
  for (const EnsembleRow& x : r.rows) {
    if (x.what == what && x.threads == threads && x.ranks == ranks && x.ok) {
      return &x;
    }
  }
  return nullptr;
}

}  // namespace

std::string ensemble_table(const EnsembleResult& r, const EnsemblePlan& plan) {
  std::ostringstream s;
  s << "(d) an ensemble of the tumbling body: I = diag(1, 2, 3) kg m^2, omega0 = (0.1, 2, 0.05) "
       "rad/s\n"
       "    dispersed by up to 1 % per component, 50 s per run; MRP quasi-velocity form,\n"
       "    OdeintIntegrator<Scene, 12> Fehlberg 7(8) at rtol = atol = "
    << sci(r.tol) << " (the loosest of a half-decade\n"
    << "    ladder with attitude errors <= " << sci(plan.target_error) << " rad): error at 50 s "
    << sci(r.nominal_error) << " rad (nominal run),\n"
    << "    at most " << sci(r.sample_error) << " over " << plan.error_sample
    << " dispersed runs, against the exact solution; " << r.nominal_steps << " steps, "
    << r.nominal_rhs << " rhs per run\n";
  s << "  " << pad("runs of one scene", 44) << lpad("runs", 7) << lpad("reps", 5)
    << lpad("median", 10) << lpad("per run", 10) << lpad("runs/s", 9) << lpad("cores", 7)
    << lpad("CPU/run", 10) << "\n";
  for (const EnsembleRow& x : r.rows) {
    s << "  " << pad(x.label, 44) << lpad(std::to_string(x.runs), 7)
      << lpad(x.extrapolated ? "-" : std::to_string(x.reps), 5);
    if (x.ok) {
      s << lpad(duration(x.seconds), 10) << lpad(duration(x.per_run()), 10)
        << lpad(fmt("%.0f", x.rate()), 9) << lpad(x.extrapolated ? "-" : fmt("%.2f", x.cores), 7)
        << lpad(x.extrapolated ? "-" : duration(x.cpu_per_run), 10);
      if (!x.note.empty()) {
        s << "  (" << x.note << ")";
      }
    } else {
      s << "  FAILED: " << x.note;
    }
    s << "\n";
  }
  const EnsembleRow* t1 = find_row(r, "threads", 1, 1);
  const EnsembleRow* t2 = find_row(r, "threads", 2, 1);
  const EnsembleRow* t2new = find_row(r, "threads-new", 2, 1);
  const EnsembleRow* reset = find_row(r, "serial-reset", 1, 1);
  const EnsembleRow* fresh = find_row(r, "serial-new", 1, 1);
  const EnsembleRow* m1 = find_row(r, "mpi", 1, 1);
  const EnsembleRow* m2 = find_row(r, "mpi", 1, 2);
  const EnsembleRow* large = nullptr;
  for (const EnsembleRow& x : r.rows) {
    if (x.what == "fold" && x.runs == plan.large && x.ok) {
      large = &x;
    }
  }
  s << "  (cores: the CPU time the process had (MPI: all ranks) over the wall time; below the "
       "threads\n   or ranks asked for, the machine was busy with something else. CPU/run: that "
       "CPU time per run,\n   the cost of a run without the waits for a core)\n";
  const auto ratio = [](const EnsembleRow* a, const EnsembleRow* b) {
    return a && b ? a->seconds / b->seconds : std::numeric_limits<double>::quiet_NaN();
  };
  const double threads_up = ratio(t1, t2), ranks_up = ratio(m1, m2);
  // Every call of the 2-thread rows against the 1-thread median: the worst call decides.
  double worst_up = std::numeric_limits<double>::quiet_NaN();
  s << "  each call in a row, ms (the speed-up of each 2-thread call against the 1-thread "
       "median):\n";
  for (const EnsembleRow* x : {t1, t2, t2new}) {
    if (x == nullptr || x->calls.empty()) {
      continue;
    }
    s << "    " << pad(x->label, 44);
    for (const double c : x->calls) {
      s << fmt(" %.0f", 1e3 * c);
    }
    s << "\n";
    if (x != t1 && t1 != nullptr) {
      s << "    " << pad("", 44);
      for (const double c : x->calls) {
        const double up = t1->seconds / c;
        s << fmt(" %.2fx", up);
        worst_up = std::isnan(worst_up) ? up : std::min(worst_up, up);
      }
      s << "\n";
    }
  }
  s << "    (before them, the process's first parallel call, " << r.startup_runs
    << " runs on 2 threads, in which oneTBB starts its\n     worker threads: "
    << duration(r.startup_first) << "; the same call again: " << duration(r.startup_again) << ")\n";
  const double vs_reset = ratio(t1, reset), vs_new = ratio(t1, fresh);
  s << "  speed-up, 2 against 1: threads " << fmt("%.2fx", threads_up) << " (median; worst call "
    << fmt("%.2fx", worst_up) << "), MPI ranks " << (m2 ? fmt("%.2fx", ranks_up) : "-")
    << (m2 ? std::string(r.mpi_same ? " (results bitwise the threads')"
                                    : " (results DIFFER from the threads')")
           : " (" + r.mpi_note + ")")
    << "\n";
  const auto cpu_ratio = [](const EnsembleRow* a, const EnsembleRow* b) {
    return a && b ? a->cpu_per_run / b->cpu_per_run : std::numeric_limits<double>::quiet_NaN();
  };
  s << "  per run, the 1-thread ensemble against a serial loop: " << fmt("%.2fx", vs_reset)
    << " (one integrator reset\n    per run), " << fmt("%.2fx", vs_new)
    << " (a new one per run); in CPU time " << fmt("%.2fx", cpu_ratio(t1, reset)) << " and "
    << fmt("%.2fx", cpu_ratio(t1, fresh)) << "\n";
  s << "  memory: " << r.result_bytes
    << " B kept per run by integrate (RunOutcome<double>); peak RSS growth during fold\n"
    << "    (block 4096):";
  for (std::size_t k = 0; k < r.fold_peaks.size(); ++k) {
    const EnsembleResult::Peak& p = r.fold_peaks[k];
    s << (k == 0 ? " " : ", ")
      << (p.kilobytes >= 0 ? std::to_string(p.kilobytes) + " kB" : std::string("-")) << " for "
      << p.runs << " runs";
  }
  s << (r.memory_note.empty() ? "" : " (" + r.memory_note + ")") << "\n";
  s << "  heap: operator new calls per run " << r.allocations_short << " at 5 s (" << r.steps_short
    << " steps), " << r.allocations_long << " at 50 s (" << r.steps_long << " steps); "
    << r.allocations_new << " to make an integrator\n";

  // The targets the ensembles are held to.
  const bool per_step = r.allocations_short >= 0 && r.allocations_long >= 0;
  long peak_small = -1, peak_large = -1;
  if (r.fold_peaks.size() == 2) {
    peak_small = r.fold_peaks[0].kilobytes;
    peak_large = r.fold_peaks[1].kilobytes;
  }
  const bool peaks = peak_small >= 0 && peak_large >= 0;
  // Flat: the 10 N fold's peak growth within 1 MB (or 50 %) of the N fold's; the results of
  // 10^5 runs kept would be 10^5 x result_bytes.
  const bool flat = peaks && std::abs(peak_large - peak_small) <= std::max(1024L, peak_small / 2);
  // A speed-up says something about the ensemble only if the machine gave the 2-thread (2-rank)
  // run about two cores; on a busy machine it measures the share it got.
  const auto speed_up = [&](const EnsembleRow* one, const EnsembleRow* two, double up) {
    if (!one || !two) {
      return verdict(false, false);
    }
    if (!(two->cores >= 1.6)) {
      return "not measured (the 2-way run had " + fmt("%.2f", two->cores) + " cores)";
    }
    return verdict(true, up >= 1.8);
  };
  // Both 2-thread rows, every call: each row must have had about two cores.
  const EnsembleRow* least = t2;
  if (t2new != nullptr && (least == nullptr || t2new->cores < least->cores)) {
    least = t2new;
  }
  const auto target = [&](const std::string& what, const std::string& v) {
    s << "    " << pad(what, 46) << v << "\n";
  };
  s << "  targets:\n";
  target("threads, 2 against 1, >= 1.8x, every call", speed_up(t1, least, worst_up));
  target("MPI ranks, 2 against 1, >= 1.8x", speed_up(m1, m2, ranks_up));
  target("per run within 1.2x of a serial loop",
         verdict(t1 && reset, vs_reset <= 1.2) + " (" + fmt("%.2fx", vs_reset) + ")");
  target(
      std::to_string(plan.large) + " runs to " + sci(plan.target_error) + " in < 10 s, 2 threads",
      verdict(large != nullptr,
              large && large->seconds < 10.0 && r.sample_error <= plan.target_error) +
          (large ? " (" + duration(large->seconds) + (large->extrapolated ? ", extrapolated" : "") +
                       ")"
                 : std::string()));
  target("nothing allocated per step",
         verdict(per_step, r.allocations_short == r.allocations_long));
  target("memory grows with the results kept, not N", verdict(peaks, flat));
  return s.str();
}

}  // namespace tumble::bench
