// tumble_bench, study (e): Exudyn's implicit solvers on the IFToMM mechanisms, when `import
// exudyn` works in the Python found at configure time (`pip install exudyn`; peers/peers.cmake
// finds it, and main/tumble_bench.cmake defines TUMBLE_BENCH_EXUDYN_PYTHON and
// TUMBLE_BENCH_EXUDYN_SCRIPT for this file only). Without it the functions below return no rows
// and start nothing.
//
// Exudyn is a Python package over a C++ core with no C or C++ interface of its own, so each
// problem runs in a Python process of its own: this file writes the problem's data (from tumble's
// own problem: mechanisms.hpp's BarPendulum, PlanarLinkage, SpatialLinkage for A04 and the open
// chain, FlyballGovernor for A05), the output times, the ladder of steps and tumble's Timing to a
// JSON file, runs peers/exudyn_mechanisms.py on it, and reads back, for each run, its times,
// counters and what the problem measures. The script builds the model in Exudyn (its top comment
// describes the models and settings), times only exu.SolveDynamic and writes the tracked point at
// each output (A01, A04, the chain) or the links' absolute angles at each output (A02, A03); the
// error is computed here, by the very object that measures tumble's rows. A failure of the script
// (a Python error, a missing module) is reported on stderr and gives no rows; a run that Exudyn
// fails (Newton diverging at a coarse step) is a failed row.
//
// The rows: method "Exudyn GeneralizedAlpha" (index-3 generalized-alpha, spectral radius 0.9)
// and "Exudyn TrapezoidalIndex2" (the trapezoidal rule with the constraints differentiated once),
// tol empty (a fixed step), the note the step; steps, Newton iterations (rhs_evals: one residual
// each) and Jacobians as Exudyn counts them; |C| the largest distance apart of the points that a
// joint holds together, at the end.

#include <functional>
#include <string>
#include <vector>

#include "common/bench.hpp"
#include "mechanisms/mechanisms.hpp"

#if defined(TUMBLE_BENCH_EXUDYN_PYTHON) && defined(TUMBLE_BENCH_EXUDYN_SCRIPT)

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <Eigen/Core>
#include <unistd.h>

#include "common/format.hpp"
#include "mechanisms/track.hpp"

namespace tumble::bench {
namespace {

/// The part of the JSON input every problem shares: its id, the outputs, the ladder and timing.
std::string common_json(const char* problem, const std::vector<double>& times,
                        const std::vector<int>& ladder, const Timing& timing) {
  std::ostringstream os;
  os.precision(17);
  os << "\"problem\": \"" << problem << "\", \"times\": [";
  for (std::size_t k = 0; k < times.size(); ++k) {
    os << (k ? ", " : "") << times[k];
  }
  os << "], \"ladder\": [";
  for (std::size_t k = 0; k < ladder.size(); ++k) {
    os << (k ? ", " : "") << ladder[k];
  }
  // A ladder stops after a run slower than `budget` (s): its finer steps would take longer.
  os << "], \"solvers\": [\"GeneralizedAlpha\", \"TrapezoidalIndex2\"], \"reps\": " << timing.reps
     << ", \"slow_run\": " << timing.slow_run << ", \"clock\": \""
     << (timing.base == TimeBase::cpu ? "cpu" : "wall") << "\", \"budget\": 2.0";
  return os.str();
}

std::string json(const Eigen::Ref<const Eigen::VectorXd>& v) {
  std::ostringstream os;
  os.precision(17);
  os << '[';
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    os << (i ? ", " : "") << v[i];
  }
  os << ']';
  return os.str();
}

std::string json_matrix(const Eigen::Matrix3d& m) {
  // Appended in place: GCC 12 at -O3 warns (-Wrestrict, a false positive) on "[" + string&&.
  std::string out = "[";
  for (int r = 0; r < 3; ++r) {
    out += r > 0 ? ", " : "";
    out += json(m.row(r).transpose());
  }
  out += ']';
  return out;
}

/// `s` as one word for /bin/sh.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (const char c : s) {
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return q + "'";
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream is(line);
  for (std::string f; std::getline(is, f, '\t');) {
    fields.push_back(f);
  }
  return fields;
}

std::vector<double> numbers(const std::string& list) {
  std::vector<double> v;
  std::istringstream is(list);
  for (std::string f; std::getline(is, f, ',');) {
    v.push_back(std::stod(f));
  }
  return v;
}

/// One run's line: its row without the error (the caller measures it).
MechanismRow parse_run(const std::vector<std::string>& f, const Timing& timing) {
  if (f.size() < 11) {  // the message, the last field, is often empty
    throw std::runtime_error("a malformed run line");
  }
  MechanismRow r;
  r.method = "Exudyn " + f[1];
  r.tol = std::numeric_limits<double>::quiet_NaN();  // a fixed step, no tolerance
  r.note = "h = " + sci(std::stod(f[3])) + " s, " + f[2] + " steps per output";
  r.run.ok = f[4] == "1";
  r.run.error = f.size() > 11 ? f[11] : "";
  r.run.steps = std::stol(f[5]);
  r.run.rhs_evals = std::stol(f[6]);  // Newton iterations, one residual each
  r.run.jacobian_evals = std::stol(f[7]);
  r.run.constraint_drift = std::stod(f[8]);
  const std::vector<double> walls = numbers(f[9]), cpus = numbers(f[10]);
  std::vector<double> seconds = timing.base == TimeBase::cpu ? cpus : walls;
  if (r.run.ok && !seconds.empty()) {
    r.run.wall_seconds = *std::min_element(walls.begin(), walls.end());
    r.run.cpu_seconds = *std::min_element(cpus.begin(), cpus.end());
    r.run.seconds = *std::min_element(seconds.begin(), seconds.end());
  }
  finish_timing(r.run, seconds);
  return r;
}

/// Runs the script on `input` (the JSON object's members) and returns its output's lines; no
/// lines, and a message on stderr, when it failed.
std::vector<std::vector<std::string>> run_script(const std::string& id, const std::string& input) {
  namespace fs = std::filesystem;
  const std::string stem = "tumble_bench_exudyn_" + std::to_string(::getpid()) + "_" + id;
  const fs::path in = fs::temp_directory_path() / (stem + ".json");
  const fs::path out = fs::temp_directory_path() / (stem + ".txt");
  std::vector<std::vector<std::string>> lines;
  try {
    std::ofstream(in) << "{" << input << "}\n";
    // Exudyn prints on stdout (its banners, a failed run's notice): not into the report.
    const std::string command = quoted(TUMBLE_BENCH_EXUDYN_PYTHON) + " " +
                                quoted(TUMBLE_BENCH_EXUDYN_SCRIPT) + " " + quoted(in.string()) +
                                " " + quoted(out.string()) + " > /dev/null";
    std::fflush(nullptr);
    const int status = std::system(command.c_str());
    std::ifstream file(out);
    bool complete = false;
    for (std::string line; std::getline(file, line);) {
      complete = line == "end";
      lines.push_back(split(line));
    }
    if (status != 0 || !complete) {
      throw std::runtime_error("the script failed (status " + std::to_string(status) +
                               "; its messages above)");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tumble_bench: Exudyn on %s: %s; no Exudyn rows\n", id.c_str(), e.what());
    lines.clear();
  }
  std::error_code ignored;
  fs::remove(in, ignored);
  fs::remove(out, ignored);
  return lines;
}

/// The rows of a problem whose runs report a tracked point: measured by `track`.
std::vector<MechanismRow> point_rows(const std::string& id, const std::string& input,
                                     PointTrackError& track, const Timing& timing) {
  std::vector<MechanismRow> rows;
  try {
    for (const std::vector<std::string>& f : run_script(id, input)) {
      if (f.front() == "run") {
        if (!rows.empty() && rows.back().run.ok) {
          rows.back().error = track.measure();
        }
        rows.push_back(parse_run(f, timing));
      } else if (f.front() == "point" && f.size() == 5) {
        track.record(std::stoul(f[1]),
                     Eigen::Vector3d(std::stod(f[2]), std::stod(f[3]), std::stod(f[4])));
      }
    }
    if (!rows.empty() && rows.back().run.ok) {
      rows.back().error = track.measure();
    }
  } catch (const std::exception& e) {  // std::stod and friends on a damaged file
    std::fprintf(stderr, "tumble_bench: Exudyn on %s: unreadable output (%s); no Exudyn rows\n",
                 id.c_str(), e.what());
    rows.clear();
  }
  track.measure();  // clears what a failed run recorded
  return rows;
}

/// The "spatial" member of the JSON input: the linkage `l` as the script's spatial() reads it.
std::string spatial_json(const SpatialLinkage& l, bool redundant) {
  std::ostringstream os;
  os.precision(17);
  os << "\"spatial\": {\"bodies\": [";
  for (std::size_t i = 0; i < l.bodies.size(); ++i) {
    const SpatialLinkage::Body& b = l.bodies[i];
    os << (i ? ", " : "") << "{\"centroid\": " << json(b.centroid)
       << ", \"rotation\": " << json_matrix(b.rotation) << ", \"mass\": " << b.mass
       << ", \"inertia\": " << json_matrix(b.inertia) << ", \"velocity\": " << json(b.velocity)
       << ", \"omega\": " << json(b.omega) << "}";
  }
  os << "], \"hinges\": [";
  for (std::size_t i = 0; i < l.hinges.size(); ++i) {
    const SpatialLinkage::Hinge& h = l.hinges[i];
    os << (i ? ", " : "") << "{\"a\": " << h.a << ", \"b\": " << h.b << ", \"at\": " << json(h.at)
       << ", \"axis\": " << json(h.axis) << "}";
  }
  os << "], \"gravity\": " << json(l.gravity) << ", \"track\": {\"body\": " << l.track_body
     << ", \"point\": " << json(l.track_point)
     << "}, \"redundant\": " << (redundant ? "true" : "false") << "}";
  return os.str();
}

/// Steps per output interval, doubling from `from` to `to`.
std::vector<int> doubling(int from, int to) {
  std::vector<int> ladder;
  for (int n = from; n <= to; n *= 2) {
    ladder.push_back(n);
  }
  return ladder;
}

}  // namespace

bool exudyn_available() { return true; }

std::vector<MechanismRow> exudyn_a01_rows(const BarPendulum& p, const std::vector<double>& times,
                                          PointTrackError& bob, const Timing& timing) {
  std::ostringstream os;
  os.precision(17);
  os << common_json("a01", times, doubling(4, 8192), timing)
     << ", \"pendulum\": {\"mass\": " << p.mass << ", \"inertia\": " << p.inertia
     << ", \"pivot\": " << json(p.pivot) << ", \"start\": " << json(p.start)
     << ", \"gravity\": " << json(p.gravity) << "}";
  return point_rows("a01", os.str(), bob, timing);
}

std::vector<MechanismRow> exudyn_a04_rows(const SpatialLinkage& l, const std::vector<double>& times,
                                          PointTrackError& p3, const Timing& timing) {
  return point_rows(
      "a04", common_json("a04", times, doubling(1, 1024), timing) + ", " + spatial_json(l, true),
      p3, timing);
}

std::vector<MechanismRow> exudyn_a05_rows(const FlyballGovernor& g,
                                          const std::vector<double>& times, PointTrackError& slider,
                                          const Timing& timing) {
  std::ostringstream os;
  os.precision(17);
  os << common_json("a05", times, doubling(1, 1024), timing)
     << ", \"flyball\": {\"gravity\": " << g.gravity << ", \"shaft_mass\": " << g.shaft_mass
     << ", \"shaft_length\": " << g.shaft_length << ", \"shaft_inertia\": " << json(g.shaft_inertia)
     << ", \"slider_mass\": " << g.slider_mass << ", \"slider_inertia\": " << g.slider_inertia
     << ", \"rod_mass\": " << g.rod_mass << ", \"rod_length\": " << g.rod_length
     << ", \"rod_centroid\": " << g.rod_centroid << ", \"rod_axial\": " << g.rod_axial
     << ", \"rod_transverse\": " << g.rod_transverse << ", \"offset\": " << g.offset
     << ", \"top\": " << g.top << ", \"stiffness\": " << g.stiffness
     << ", \"damping\": " << g.damping << ", \"rest_length\": " << g.rest_length
     << ", \"s0\": " << g.s0 << ", \"alpha\": " << g.alpha << ", \"spin\": " << g.spin << "}";
  return point_rows("a05", os.str(), slider, timing);
}

std::vector<MechanismRow> exudyn_chain_rows(const SpatialLinkage& l,
                                            const std::vector<double>& times, PointTrackError& tip,
                                            const Timing& timing) {
  return point_rows(
      "chain",
      common_json("chain", times, doubling(1, 1024), timing) + ", " + spatial_json(l, false), tip,
      timing);
}

std::vector<MechanismRow> exudyn_planar_rows(const std::string& id, const PlanarLinkage& m,
                                             const std::vector<double>& times,
                                             const PlanarMeasure& measure, const Timing& timing) {
  std::ostringstream os;
  os.precision(17);
  os << common_json(id.c_str(), times, doubling(1, 1024), timing) << ", \"linkage\": {\"links\": [";
  for (std::size_t i = 0; i < m.links.size(); ++i) {
    const PlanarLinkage::Link& k = m.links[i];
    os << (i ? ", " : "") << "{\"parent\": " << k.parent << ", \"hinge\": " << json(k.hinge)
       << ", \"centroid\": " << json(k.centroid) << ", \"angle\": " << k.angle
       << ", \"mass\": " << k.mass << ", \"inertia\": " << k.inertia << ", \"rate\": " << k.rate
       << "}";
  }
  os << "], \"loops\": [";
  for (std::size_t i = 0; i < m.loops.size(); ++i) {
    os << (i ? ", " : "") << "{\"a\": " << m.loops[i].a << ", \"b\": " << m.loops[i].b
       << ", \"at\": " << json(m.loops[i].at) << "}";
  }
  os << "], \"gravity\": " << json(m.gravity) << ", \"spring_link\": " << m.spring_link
     << ", \"spring_on_link\": " << json(m.spring_on_link)
     << ", \"spring_on_ground\": " << json(m.spring_on_ground) << ", \"stiffness\": " << m.stiffness
     << ", \"rest_length\": " << m.rest_length << ", \"motor_link\": " << m.motor_link
     << ", \"torque\": " << m.torque << "}";
  // The links' absolute angles at every output (NaN: not written) of the run being read.
  const std::vector<double> unset(m.links.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<std::vector<double>> angles(times.size(), unset);
  const auto measure_run = [&](MechanismRow& row) {
    const bool complete = std::none_of(angles.begin(), angles.end(), [](const auto& at) {
      return std::any_of(at.begin(), at.end(), [](double a) { return std::isnan(a); });
    });
    if (row.run.ok && complete) {
      row.error = measure(angles);
    }
    std::fill(angles.begin(), angles.end(), unset);
  };
  std::vector<MechanismRow> rows;
  try {
    for (const std::vector<std::string>& f : run_script(id, os.str())) {
      if (f.front() == "run") {
        if (!rows.empty()) {
          measure_run(rows.back());
        }
        rows.push_back(parse_run(f, timing));
      } else if (f.front() == "angles" && f.size() == m.links.size() + 2) {
        const std::size_t k = std::stoul(f[1]);
        for (std::size_t i = 0; k < angles.size() && i < m.links.size(); ++i) {
          angles[k][i] = std::stod(f[i + 2]);
        }
      }
    }
    if (!rows.empty()) {
      measure_run(rows.back());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tumble_bench: Exudyn on %s: unreadable output (%s); no Exudyn rows\n",
                 id.c_str(), e.what());
    rows.clear();
  }
  return rows;
}

}  // namespace tumble::bench

#else

namespace tumble::bench {

bool exudyn_available() { return false; }

std::vector<MechanismRow> exudyn_a01_rows(const BarPendulum& /*p*/,
                                          const std::vector<double>& /*times*/,
                                          PointTrackError& /*bob*/, const Timing& /*timing*/) {
  return {};
}
std::vector<MechanismRow> exudyn_a04_rows(const SpatialLinkage& /*l*/,
                                          const std::vector<double>& /*times*/,
                                          PointTrackError& /*p3*/, const Timing& /*timing*/) {
  return {};
}
std::vector<MechanismRow> exudyn_a05_rows(const FlyballGovernor& /*g*/,
                                          const std::vector<double>& /*times*/,
                                          PointTrackError& /*slider*/, const Timing& /*timing*/) {
  return {};
}
std::vector<MechanismRow> exudyn_planar_rows(const std::string& /*id*/, const PlanarLinkage& /*m*/,
                                             const std::vector<double>& /*times*/,
                                             const PlanarMeasure& /*measure*/,
                                             const Timing& /*timing*/) {
  return {};
}
std::vector<MechanismRow> exudyn_chain_rows(const SpatialLinkage& /*l*/,
                                            const std::vector<double>& /*times*/,
                                            PointTrackError& /*tip*/, const Timing& /*timing*/) {
  return {};
}

}  // namespace tumble::bench

#endif
