// tumble_bench: the CSV files it writes, one row per measurement, every number it has (the
// terminal tables show a few of them), and the one it reads back (the micro-benchmark times).
//   work_precision_<problem>.csv  every run of the sweep: setting, both clocks, errors, invariants'
//                                 drift, CVODE's counters, chart switches
//   scaling.csv                   cost per right-hand side and per BDF step against N
//   ensemble.csv                  the ensemble study: each timed ensemble (threads, ranks, runs,
//                                 median and best time, runs/s), then its tolerance and errors,
//                                 memory and allocations as named values
//   problems.csv                  each problem's title and how its reference was obtained
//   mechanism_<problem>.csv       study (e): every run of a mechanism (method, tolerance, both
//                                 clocks, the problem's error, |C| at the end, counters)
//   mechanisms.csv                each mechanism's title, error measure and reference
// main/plot.py draws the PNG diagrams from them.

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/format.hpp"
#include "main/driver.hpp"

namespace tumble::bench {

void write_runs_csv(const std::filesystem::path& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "problem,method,family,parameterization,scheme,tol,rtol,atol,rk4_substeps,rk4_step_s,ok,"
       "error_message,time_s,time_median_s,wall_time_s,cpu_time_s,reps,final_attitude_error_rad,"
       "max_attitude_error_rad,max_centroid_error_m,max_omega_error_rad_s,energy_drift,"
       "momentum_drift,steps,rhs_evals,linear_rhs_evals,jacobian_evals,error_test_failures,"
       "convergence_failures,reinits,chart_switches,constraint_drift\n";
  for (const Row& r : rows) {
    const Job& j = r.job;
    const bool cv = !j.fixed_step();
    f << csv_quote(j.problem->id) << ',' << csv_quote(j.method()) << ','
      << csv_quote(j.method_entry->family) << ',' << csv_quote(j.method_entry->parameterization)
      << ',' << scheme_name(j.scheme) << ',' << (cv ? num(j.tol) : "") << ','
      << (cv ? num(j.tol) : "") << ',' << (cv ? num(j.tol) : "") << ','
      << (cv ? "" : std::to_string(j.substeps)) << ','
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

void write_mechanism_csv(const std::filesystem::path& path, const MechanismResult& r) {
  std::ofstream f(path);
  f << "problem,method,tol,rtol,atol,ok,error_message,time_s,time_median_s,wall_time_s,"
       "cpu_time_s,reps,error,constraint_residual_end,steps,rhs_evals,jacobian_evals,"
       "rejected_steps,convergence_failures,methods_chosen,relaxed_steps\n";
  for (const MechanismRow& x : r.rows) {
    f << csv_quote(r.id) << ',' << csv_quote(x.method) << ',' << num(x.tol) << ',' << num(x.tol)
      << ',' << num(x.tol) << ',' << (x.run.ok ? 1 : 0) << ',' << csv_quote(x.run.error) << ','
      << num(x.run.seconds) << ',' << num(x.run.seconds_median) << ',' << num(x.run.wall_seconds)
      << ',' << num(x.run.cpu_seconds) << ',' << x.run.reps << ',' << num(x.error) << ','
      << num(x.run.constraint_drift) << ',' << x.run.steps << ',' << x.run.rhs_evals << ','
      << x.run.jacobian_evals << ',' << x.run.error_test_failures << ','
      << x.run.convergence_failures << ',' << csv_quote(x.note) << ',' << x.run.relaxed_steps
      << '\n';
  }
}

void write_mechanisms_csv(const std::filesystem::path& path,
                          const std::vector<MechanismResult>& results) {
  std::ofstream f(path);
  f << "id,title,error_measure,reference\n";
  for (const MechanismResult& r : results) {
    f << csv_quote(r.id) << ',' << csv_quote(r.title) << ',' << csv_quote(r.measure) << ','
      << csv_quote(r.reference) << '\n';
  }
}

void write_scaling_csv(const std::filesystem::path& path, const std::vector<ScalingRow>& rows) {
  std::ofstream f(path);
  f << "bodies,measurement,seconds,seconds_per_body,calls,rhs_evals,jacobian_evals,"
       "linear_iterations,ok,error_message\n";
  for (const ScalingRow& r : rows) {
    f << r.bodies << ',' << r.what << ',' << num(r.seconds) << ',' << num(r.per_body) << ','
      << r.calls << ',' << r.rhs_evals << ',' << r.jacobian_evals << ',' << r.linear_iterations
      << ',' << (r.ok ? 1 : 0) << ',' << csv_quote(r.error) << '\n';
  }
}

void write_ensemble_csv(const std::filesystem::path& path, const EnsembleResult& r) {
  std::ofstream f(path);
  f << "measurement,label,threads,ranks,runs,reps,median_s,best_s,per_run_s,runs_per_s,"
       "cores,cpu_per_run_s,extrapolated,ok,note\n";
  for (const EnsembleRow& x : r.rows) {
    f << x.what << ',' << csv_quote(x.label) << ',' << x.threads << ',' << x.ranks << ',' << x.runs
      << ',' << x.reps << ',' << num(x.seconds) << ',' << num(x.best) << ',' << num(x.per_run())
      << ',' << num(x.rate()) << ',' << num(x.cores) << ',' << num(x.cpu_per_run) << ','
      << (x.extrapolated ? 1 : 0) << ',' << (x.ok ? 1 : 0) << ',' << csv_quote(x.note) << '\n';
  }
  // The rest as name,value rows under the same columns: the name in `measurement`, the value in
  // `note`.
  const auto value = [&](const std::string& name, const std::string& v) {
    f << name << ",,,,,,,,,,,,,1," << csv_quote(v) << '\n';
  };
  for (const EnsembleRow& x : r.rows) {  // each call of a row, in order (s)
    if (x.what.rfind("threads", 0) == 0) {
      std::string list;
      for (const double c : x.calls) {
        if (!list.empty()) {
          list += ' ';
        }
        list += num(c);
      }
      std::string name = "call_seconds_";
      name += x.what;
      name += '_';
      name += std::to_string(x.threads);
      value(name, list);
    }
  }
  value("tolerance", num(r.tol));
  value("nominal_attitude_error_rad", num(r.nominal_error));
  value("sample_max_attitude_error_rad", num(r.sample_error));
  value("nominal_steps", std::to_string(r.nominal_steps));
  value("nominal_rhs_evals", std::to_string(r.nominal_rhs));
  value("result_bytes_per_run", std::to_string(r.result_bytes));
  for (const EnsembleResult::Peak& p : r.fold_peaks) {
    value("fold_peak_rss_growth_kb_" + std::to_string(p.runs), std::to_string(p.kilobytes));
  }
  value("operator_new_per_run_short", std::to_string(r.allocations_short));
  value("operator_new_per_run_long", std::to_string(r.allocations_long));
  value("steps_short", std::to_string(r.steps_short));
  value("steps_long", std::to_string(r.steps_long));
  value("operator_new_per_integrator", std::to_string(r.allocations_new));
  value("mpi_results_bitwise_equal", r.mpi_same ? "1" : "0");
  value("mpi_note", r.mpi_note);
  value("memory_note", r.memory_note);
}

void write_problems_csv(const std::filesystem::path& path, const std::vector<Problem>& problems) {
  std::ofstream f(path);
  f << "id,title,reference,reference_uncertainty_rad\n";
  for (const Problem& p : problems) {
    f << csv_quote(p.id) << ',' << csv_quote(p.title) << ',' << csv_quote(p.reference_note) << ','
      << num(p.reference_uncertainty) << '\n';
  }
}

MicroTimes read_micro_csv(const std::filesystem::path& path) {
  MicroTimes times;
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);  // the header
  while (std::getline(f, line)) {
    const auto comma = line.rfind(',');
    if (comma == std::string::npos) {
      continue;
    }
    try {
      times[line.substr(0, comma)] = std::stod(line.substr(comma + 1));
    } catch (const std::exception&) {
      // a malformed line: left out of the table
    }
  }
  return times;
}

}  // namespace tumble::bench
