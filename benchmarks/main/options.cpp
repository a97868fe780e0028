// tumble_bench: its command line. Every option of the main job, with its default; --help
// prints them.

#include <algorithm>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "main/driver.hpp"

namespace tumble::bench {
namespace {

void usage() {
  const Timing sweep = sweep_timing(Options{});
  std::printf(
      "tumble_bench: what tumble costs and the accuracy it buys: per-call cost of the core "
      "assembly,\nrun time against error on problems with exact answers, cost per step against the "
      "number of bodies,\nruns per second of an ensemble against threads and MPI ranks.\n\n"
      "  --full            every parameterization (16), and the scaling study up to N = 10,000\n"
      "                    (default: the quick run, 6 parameterizations, N up to 1,000)\n"
      "  --out DIR         where to write CSV, PNG, summary.txt and the raw micro-benchmark "
      "output\n"
      "                    (default: %s)\n"
      "  --reps N          timed runs per configuration, the best is kept (default: %d); the\n"
      "                    work-precision runs repeat until they add up to %.0f ms (at most %d),\n"
      "                    in up to 3 rounds over each problem's settings\n"
      "  --outputs N       output times per problem at which errors are measured (default: 200)\n"
      "  --problems LIST   comma-separated subset of: tumbling,minor_axis,major_axis,spinner,\n"
      "                    gravity_offset,stiff_top,stiff_top_damped; the mechanisms\n"
      "                    a01,a02,a03,a04,a05,chain\n"
      "  --methods LIST    only methods whose label contains one of these comma-separated\n"
      "                    strings (e.g. 'EulerParameters adams,hand-written,RK4')\n"
      "  --tolerances LIST comma-separated CVODE tolerances (default: 1e-3,1e-4,...,1e-13)\n"
      "  --no-scaling      skip the scaling study\n"
      "  --no-mechanisms   skip the mechanisms' work precision (IFToMM a01-a05, chain;\n"
      "                    --problems and --methods filter it too: e.g. --problems a03 --methods\n"
      "                    BDF; a peer runs when a string names it: --methods MuJoCo,Exudyn)\n"
      "  --no-ensemble     skip the ensemble study (runs per second against threads and MPI "
      "ranks)\n"
      "  --no-mpi          the ensemble study without its MPI runs (mpiexec)\n"
      "  --ensemble-only   only the ensemble study: no micro-benchmarks, work precision, scaling,\n"
      "                    mechanisms, plots\n"
      "  --clock wall|cpu  the clock of the report: wall (steady_clock, the default) or the\n"
      "                    thread's CPU time, which leaves out waiting for a core on a busy\n"
      "                    machine (the CSVs always have both)\n"
      "  --no-plots        write CSV only\n"
      "  --no-micro        skip the per-step micro-benchmarks (tumble_micro) at the start\n"
      "  --difference-quotients\n"
      "                    tumble with BDF: CVODE's difference-quotient Jacobian instead of the\n"
      "                    scene's exact one (to measure what the exact Jacobian changes)\n"
      "  --fused-ops on|off\n"
      "                    CVODE methods: SUNDIALS' fused vector operations (default: on; off to\n"
      "                    measure what they change)\n"
      "  --python PATH     the Python with matplotlib for the plots (default: %s)\n",
      TUMBLE_BENCH_DEFAULT_OUT, sweep.reps, 1e3 * sweep.min_total, sweep.max_reps,
      TUMBLE_BENCH_PLOT_PYTHON);
}

}  // namespace

std::optional<Options> parse_options(int argc, char** argv) {
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
    } else if (a == "--no-mechanisms") {
      o.mechanisms = false;
    } else if (a == "--no-ensemble") {
      o.ensemble = false;
    } else if (a == "--no-mpi") {
      o.mpi = false;
    } else if (a == "--ensemble-only") {
      o.micro = o.work_precision = o.scaling = o.plots = o.mechanisms = false;
      o.ensemble = true;
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
    } else if (a == "--fused-ops") {
      const std::string f = value();
      if (f != "on" && f != "off") {
        throw std::invalid_argument("--fused-ops takes on or off (got '" + f + "')");
      }
      o.fused_ops = f == "on";
    } else if (a == "--python") {
      o.python = value();
    } else {
      throw std::invalid_argument("unknown option '" + a + "' (see --help)");
    }
  }
  return o;
}

}  // namespace tumble::bench
