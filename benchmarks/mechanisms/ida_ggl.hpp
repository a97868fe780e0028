#pragma once
// tumble_bench, study (e), A05: the alternative to the library's stiff path for mechanisms,
// measured against it: a mechanism as a stabilized index-2 DAE in SUNDIALS IDA, beside CVODE's BDF
// on tumble's index-1 ODE (SceneIntegrator: the constraint solve inside every right-hand side, the
// exact Jacobian, the state projected after each step). It is a study here, not a path of the
// library: the measurement and the reasons are in docs/benchmarks/mechanisms.md (2026-12-06).
//
// The formulation (Gear, Gupta and Leimkuhler, 1985, in tumble's absolute coordinates). Unknowns
// Y = [y; lambda; mu; mu_p]: y the scene's state (per body [r; theta; v; omega], or [q; qdot]),
// lambda and mu one per constraint row, mu_p one per body in Euler parameters. Residual:
//   q' - kin(q, nu) - [dv; thetadot(theta, domega)] = 0,  [dv; domega] = sum of J_i^T mu
//                                                          (and, for Euler parameters, + p mu_p)
//   nu' - rates(q, nu; W - J^T lambda)                    = 0   (the scene's own pass 3)
//   J nu                                                  = 0   (velocity constraints)
//   C(q)                                                  = 0   (position constraints)
//   |p|^2 - 1                                             = 0   (each body in Euler parameters)
// thetadot is the inverse of omega = G(theta) thetadot (the reference chapter's Eq. 1.5), so
// C_q [dv; thetadot(., domega)] = J J^T, invertible for independent rows: mu is zero on the exact
// solution, and each step meets C = 0 and J nu = 0 to the Newton iteration's accuracy (IDA has no
// projection). The residual is the right-hand side's passes without the constraint solve: each
// evaluation is cheap, and its Jacobian is sparse (a body's rows touch only its joints' bodies and
// its couplings'), where CVODE's of the index-1 ODE is dense for a connected mechanism.
// IDA's options: the multipliers are algebraic (IDASetId), left out of the error test
// (IDASetSuppressAlg), with the tolerance below; the rest are IDA's defaults. Its Jacobian:
// difference quotients, over the pattern of the residual (probed once at a perturbed state, where
// no entry vanishes by accident), with the columns that share no row perturbed together (Curtis,
// Powell and Reid, 1974: 47 residuals for A05's 96 columns); factored by SUNDIALS' dense LU, and by
// KLU (SuiteSparse) when TUMBLE_BENCH_HAVE_KLU. Chart bases are not re-centred: a scene of Euler
// parameters (A05) has nothing to re-centre, and one with three-parameter sets is not what this
// study runs.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <ida/ida.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#if TUMBLE_BENCH_HAVE_KLU
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include "common/bench.hpp"
#include "mechanisms/mechanisms.hpp"
#include "tumble/integrate/detail/sundials.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/scene/assembly.hpp"  // body_velocities
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::bench {

/// The GGL residual of a mechanism (see the file comment).
template <class SceneT> class GglResidual {
 public:
  explicit GglResidual(const SceneT& scene, const SceneState& s0)
      : scene_(scene),
        ws_(scene),
        base_(s0.base),
        n_(static_cast<int>(scene.size())),
        m_(scene.constraint_count()),
        f_(scene.size()) {
    ws_.stabilize_constraints = false;  // |p| = 1 is a constraint of the DAE here
    scene.for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      if constexpr (Body::Param::has_constraint) {
        static_assert(std::is_same_v<typename Body::Param, EulerParameters>);
        norm_at_.push_back(e.offset + Body::n_r);
      }
    });
  }
  [[nodiscard]] int states() const { return n_; }
  /// The unknowns: the state, then lambda, mu and mu_p.
  [[nodiscard]] int size() const { return n_ + 2 * m_ + static_cast<int>(norm_at_.size()); }

  /// r = F(t, Y, Y'), each of length size().
  void operator()(double t, const double* yy, const double* yp, double* r) {
    using ConstMap = Eigen::Map<const Eigen::VectorXd>;
    const ConstMap y(yy, n_), lambda(yy + n_, m_), mu(yy + n_ + m_, m_);
    const ConstMap mu_p(yy + n_ + 2 * m_, static_cast<Eigen::Index>(norm_at_.size()));
    detail::scene_kinematics(scene_, ws_, y, std::span<const Matrix3<double>>(base_));
    detail::scene_loads(scene_, ws_, t,
                        std::make_index_sequence<std::tuple_size_v<typename SceneT::LoadTypes>>{});
    detail::joint_rows(scene_, ws_);
    JointScratch& j = ws_.joints();
    j.lambda = lambda;
    detail::add_reactions(ws_);
    scene_.for_each_entry([&](const auto& e) {
      const auto& k = ws_.kinematics(e);
      detail::entry_rates<false>(e, y, k, ws_.wrench(e.id), false, k.theta_functions, f_);
    });
    j.acc.setZero();  // per body: [dv; domega] = sum of J_i^T mu
    for (int row = 0; row < m_; ++row) {
      j.acc.col(j.joint_a[row]) += j.ja.row(row).transpose() * mu(row);
      if (j.joint_b[row] >= 0) {
        j.acc.col(j.joint_b[row]) += j.jb.row(row).transpose() * mu(row);
      }
    }
    scene_.for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      if constexpr (Body::n_r == 3) {
        f_.template segment<3>(e.offset) += j.acc.col(e.id).template head<3>();
      }
      const Eigen::Vector3d dw = j.acc.col(e.id).template tail<3>();
      const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + Body::n_r);
      f_.template segment<Body::n_theta>(e.offset + Body::n_r) += Body::Param::thetadot(th, dw);
    });
    Eigen::Map<Eigen::VectorXd> res(r, size());
    for (std::size_t b = 0; b < norm_at_.size(); ++b) {
      const Eigen::Vector4d p = y.template segment<4>(norm_at_[b]);
      f_.template segment<4>(norm_at_[b]) += p * mu_p(static_cast<Eigen::Index>(b));
      res(n_ + 2 * m_ + static_cast<Eigen::Index>(b)) = p.squaredNorm() - 1;
    }
    res.head(n_) = ConstMap(yp, n_) - f_;
    detail::body_velocities(scene_, ws_, j.nu);
    detail::joint_apply(j, j.nu, j.rhs);  // J nu
    res.segment(n_, m_) = j.rhs;
    res.segment(n_ + m_, m_) = j.c;
  }

  /// Consistent initial values at s0 (on the constraints): Y = [y0; lambda0; 0; 0] with lambda0
  /// from the library's constraint solve, Y' = [y0'; 0].
  void initial_values(const SceneState& s0, double* yy, double* yp) {
    Eigen::Map<Eigen::VectorXd> y(yy, size()), ydot(yp, size());
    y.setZero();
    ydot.setZero();
    ws_.stabilize_constraints = false;
    rhs(scene_, ws_, 0.0, s0, ydot.head(n_));
    y.head(n_) = s0.y;
    y.segment(n_, m_) = ws_.joints().lambda;
  }

 private:
  const SceneT& scene_;
  SceneWorkspace<SceneT> ws_;
  ChartBases base_;
  int n_, m_;
  Eigen::VectorXd f_;
  std::vector<int> norm_at_;  ///< where each Euler-parameter body's p starts in y
};

/// dF/dY + cj dF/dY' by difference quotients over the residual's pattern, grouped columns.
class GroupedDifferences {
 public:
  /// The pattern, probed at `y0` perturbed (a state off the solution, so that no entry is zero by
  /// accident there), and the groups (greedy: a column joins the first group it shares no row
  /// with). `differential` leading unknowns have Y' in the residual.
  template <class Residual>
  GroupedDifferences(Residual& residual, std::vector<double> y0, int differential)
      : n_(static_cast<int>(y0.size())),
        differential_(differential),
        y_(std::move(y0)),
        yp_(y_.size(), 0.0),
        r_(y_.size()),
        inc_(y_.size()) {
    for (int i = 0; i < n_; ++i) {  // deterministic, distinct perturbations
      y_[static_cast<std::size_t>(i)] += (i < differential ? 1e-2 : 1.0) * std::sin(1.0 + i);
    }
    std::vector<double> r0(y_.size()), probe = y_;
    residual(0.0, y_.data(), yp_.data(), r0.data());
    rows_.assign(y_.size(), {});
    for (int c = 0; c < n_; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      probe[cu] = y_[cu] + 1e-6;
      residual(0.0, probe.data(), yp_.data(), r_.data());
      probe[cu] = y_[cu];
      for (int i = 0; i < n_; ++i) {
        const auto iu = static_cast<std::size_t>(i);
        if (r_[iu] != r0[iu] || (i == c && i < differential)) {
          rows_[cu].push_back(i);
        }
      }
    }
    std::vector<std::vector<char>> taken;
    for (int c = 0; c < n_; ++c) {
      const auto& rows = rows_[static_cast<std::size_t>(c)];
      std::size_t g = 0;
      for (; g < groups_.size(); ++g) {
        if (std::none_of(rows.begin(), rows.end(),
                         [&](int i) { return taken[g][static_cast<std::size_t>(i)] != 0; })) {
          break;
        }
      }
      if (g == groups_.size()) {
        groups_.emplace_back();
        taken.emplace_back(y_.size(), 0);
      }
      groups_[g].push_back(c);
      for (const int i : rows) {
        taken[g][static_cast<std::size_t>(i)] = 1;
      }
    }
  }
  [[nodiscard]] const std::vector<int>& rows(int column) const {
    return rows_[static_cast<std::size_t>(column)];
  }
  [[nodiscard]] long nonzeros() const {
    long nz = 0;
    for (const auto& c : rows_) {
      nz += static_cast<long>(c.size());
    }
    return nz;
  }
  [[nodiscard]] std::size_t groups() const { return groups_.size(); }
  [[nodiscard]] long residuals() const { return residuals_; }

  /// put(i, j, value) for every entry of the pattern, at (t, Y, Y') with F(t, Y, Y') = r and the
  /// error weights ewt; the increments are IDA's own (max(sqrt(eps) |Y_j|, 1 / ewt_j)).
  template <class Residual, class Put>
  void evaluate(Residual& residual, double t, double cj, const double* yy, const double* yp,
                const double* r, const double* ewt, Put&& put) {
    y_.assign(yy, yy + n_);
    yp_.assign(yp, yp + n_);
    const double srur = std::sqrt(std::numeric_limits<double>::epsilon());
    for (const auto& group : groups_) {
      for (const int c : group) {
        const auto cu = static_cast<std::size_t>(c);
        inc_[cu] = std::max(srur * std::abs(yy[c]), 1.0 / ewt[c]);
        y_[cu] += inc_[cu];
        if (c < differential_) {
          yp_[cu] += cj * inc_[cu];  // dF/dY + cj dF/dY' in one difference
        }
      }
      residual(t, y_.data(), yp_.data(), r_.data());
      ++residuals_;
      for (const int c : group) {
        const auto cu = static_cast<std::size_t>(c);
        for (const int i : rows_[cu]) {
          put(i, c, (r_[static_cast<std::size_t>(i)] - r[i]) / inc_[cu]);
        }
        y_[cu] = yy[c];
        yp_[cu] = yp[c];
      }
    }
  }

 private:
  int n_, differential_;
  std::vector<double> y_, yp_, r_, inc_;
  std::vector<std::vector<int>> rows_;  ///< per column, ascending
  std::vector<std::vector<int>> groups_;
  long residuals_ = 0;
};

enum class IdaLinearSolver { dense, klu };

/// Whether this thread's floating-point environment flushes subnormals to zero (x86's MXCSR FTZ or
/// DAZ); false where it cannot tell.
inline bool flushes_subnormals() {
#if defined(__SSE__)
  constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
  return (_mm_getcsr() & (kFlushToZero | kDenormalsAreZero)) != 0;
#else
  return false;
#endif
}

/// The multipliers' absolute tolerance in the Newton iteration's convergence test (they are left
/// out of the error test). On A05, with the state's (rtol = atol = tol), the run at 1e-4 takes
/// 30 s (41474 steps, 20733 convergence failures) and those at 1e-8 and tighter fail at t = 0, the
/// Newton iteration failing as h is cut to 4e-15 s and below (the index-2 iteration matrix's
/// condition grows as h^-2); with 1e-6, 1e-4 and 1e-5 take 29 and 2.8 s and 1e-10 and tighter
/// fail at t = 0. With 1 (the reactions are forces and moments of 1 to 1e3 N, N m), every rung
/// runs.
inline constexpr double kMultiplierTolerance = 1.0;

namespace detail_ida {

struct IdaMemoryDeleter {
  void operator()(void* mem) const noexcept { IDAFree(&mem); }
};
using IdaMemoryHandle = std::unique_ptr<void, IdaMemoryDeleter>;

template <class SceneT> struct IdaData {
  GglResidual<SceneT>* residual;
  GroupedDifferences* jacobian;
  void* mem;
  N_Vector ewt;
  IdaLinearSolver solver;
};

template <class SceneT>
int residual(tumble::detail::sun_real t, N_Vector yy, N_Vector yp, N_Vector rr, void* data) {
  (*static_cast<IdaData<SceneT>*>(data)->residual)(t, N_VGetArrayPointer(yy),
                                                   N_VGetArrayPointer(yp), N_VGetArrayPointer(rr));
  return 0;
}

template <class SceneT>
int jacobian(tumble::detail::sun_real t, tumble::detail::sun_real cj, N_Vector yy, N_Vector yp,
             N_Vector rr, SUNMatrix jac, void* data, N_Vector /*tmp1*/, N_Vector /*tmp2*/,
             N_Vector /*tmp3*/) {
  auto& d = *static_cast<IdaData<SceneT>*>(data);
  if (IDAGetErrWeights(d.mem, d.ewt) != IDA_SUCCESS) {
    return -1;
  }
  const double* w = N_VGetArrayPointer(d.ewt);
  const double* y = N_VGetArrayPointer(yy);
  const double* p = N_VGetArrayPointer(yp);
  const double* r = N_VGetArrayPointer(rr);
#if TUMBLE_BENCH_HAVE_KLU
  if (d.solver == IdaLinearSolver::klu) {
    // Compressed columns in the pattern's order (each column's rows ascending).
    sunindextype* start = SUNSparseMatrix_IndexPointers(jac);
    sunindextype* index = SUNSparseMatrix_IndexValues(jac);
    double* value = SUNSparseMatrix_Data(jac);
    const int n = static_cast<int>(N_VGetLength(yy));
    sunindextype k = 0;
    for (int c = 0; c < n; ++c) {
      start[c] = k;
      for (const int i : d.jacobian->rows(c)) {
        index[k++] = i;
      }
    }
    start[n] = k;
    d.jacobian->evaluate(*d.residual, t, cj, y, p, r, w, [&](int i, int c, double v) {
      const auto& rows = d.jacobian->rows(c);
      value[start[c] + (std::lower_bound(rows.begin(), rows.end(), i) - rows.begin())] = v;
    });
    return 0;
  }
#endif
  SUNMatZero(jac);
  d.jacobian->evaluate(*d.residual, t, cj, y, p, r, w,
                       [&](int i, int c, double v) { SM_ELEMENT_D(jac, i, c) = v; });
  return 0;
}

inline void check(int flag, const char* what) {
  if (flag < 0) {
    throw std::runtime_error(std::string("IDA: ") + what + " failed (" + std::to_string(flag) +
                             ")");
  }
}

}  // namespace detail_ida

/// The label of a row of this study.
inline const char* ida_ggl_label(IdaLinearSolver s) {
  return s == IdaLinearSolver::klu ? "IDA GGL index 2 (KLU)" : "IDA GGL index 2 (dense LU)";
}

/// One timed run of the scene in IDA, as timed_mechanism_run times tumble's (construction and
/// integration over all outputs, best of the plan's repetitions): record(k, state) at output k.
template <class SceneT, class Record>
void ida_ggl_run(const SceneT& scene, IdaLinearSolver solver, double tol,
                 const std::vector<double>& times, const Timing& timing, Record& record,
                 MechanismRow& row) {
  namespace td = tumble::detail;
  std::vector<double> seconds;
  Run& run = row.run;
  try {
    do {
      const Stopwatch watch;
      const SceneState s0 = scene.initial_state();
      GglResidual<SceneT> residual(scene, s0);
      const int n = residual.states(), size = residual.size();
      td::ErrorCapture capture;
      const td::ContextHandle ctx = td::make_context(capture);
      const td::NVectorHandle yy(td::require_allocated(N_VNew_Serial(size, ctx.get())));
      const td::NVectorHandle yp(td::require_allocated(N_VNew_Serial(size, ctx.get())));
      const td::NVectorHandle id(td::require_allocated(N_VNew_Serial(size, ctx.get())));
      const td::NVectorHandle atol(td::require_allocated(N_VNew_Serial(size, ctx.get())));
      const td::NVectorHandle ewt(td::require_allocated(N_VNew_Serial(size, ctx.get())));
      double* y = N_VGetArrayPointer(yy.get());
      residual.initial_values(s0, y, N_VGetArrayPointer(yp.get()));
      for (int i = 0; i < size; ++i) {
        N_VGetArrayPointer(id.get())[i] = i < n ? 1.0 : 0.0;
        N_VGetArrayPointer(atol.get())[i] = i < n ? tol : kMultiplierTolerance;
      }
      GroupedDifferences jacobian(residual, std::vector<double>(y, y + size), n);
      const detail_ida::IdaMemoryHandle mem(td::require_allocated(IDACreate(ctx.get())));
      void* m = mem.get();
#if SUNDIALS_VERSION_MAJOR < 7
      detail_ida::check(IDASetErrHandlerFn(m, &td::ErrorCapture::handler, &capture),
                        "IDASetErrHandlerFn");
#endif
      detail_ida::IdaData<SceneT> data{&residual, &jacobian, m, ewt.get(), solver};
      detail_ida::check(IDAInit(m, &detail_ida::residual<SceneT>, 0.0, yy.get(), yp.get()),
                        "IDAInit");
      detail_ida::check(IDASVtolerances(m, tol, atol.get()), "IDASVtolerances");
      detail_ida::check(IDASetUserData(m, &data), "IDASetUserData");
      detail_ida::check(IDASetId(m, id.get()), "IDASetId");
      detail_ida::check(IDASetSuppressAlg(m, SUNTRUE), "IDASetSuppressAlg");
      detail_ida::check(IDASetMaxNumSteps(m, 1000000), "IDASetMaxNumSteps");
      td::MatrixHandle a;
      td::LinearSolverHandle ls;
#if TUMBLE_BENCH_HAVE_KLU
      if (solver == IdaLinearSolver::klu) {
        a.reset(td::require_allocated(
            SUNSparseMatrix(size, size, jacobian.nonzeros(), CSC_MAT, ctx.get())));
        ls.reset(td::require_allocated(SUNLinSol_KLU(yy.get(), a.get(), ctx.get())));
      }
#endif
      if (!a) {
        a.reset(td::require_allocated(SUNDenseMatrix(size, size, ctx.get())));
        ls.reset(td::require_allocated(SUNLinSol_Dense(yy.get(), a.get(), ctx.get())));
      }
      detail_ida::check(IDASetLinearSolver(m, ls.get(), a.get()), "IDASetLinearSolver");
      detail_ida::check(IDASetJacFn(m, &detail_ida::jacobian<SceneT>), "IDASetJacFn");
      SceneState x = s0;
      for (std::size_t k = 0; k < times.size(); ++k) {
        double reached = 0;
        if (IDASolve(m, times[k], &reached, yy.get(), yp.get(), IDA_NORMAL) < 0) {
          throw std::runtime_error(std::string("IDASolve stopped at t = ") +
                                   std::to_string(reached) + " s: " + capture.message.data());
        }
        x.y = Eigen::Map<const Eigen::VectorXd>(y, n);
        record(k, x);
      }
      record_time(run, seconds, watch, timing);

      long v = 0;
      IDAGetNumSteps(m, &v);
      run.steps = v;
      IDAGetNumResEvals(m, &v);
      run.rhs_evals = v;
      run.linear_rhs_evals = jacobian.residuals();
      IDAGetNumJacEvals(m, &v);
      run.jacobian_evals = v;
      IDAGetNumErrTestFails(m, &v);
      run.error_test_failures = v;
      IDAGetNumNonlinSolvConvFails(m, &v);
      run.convergence_failures = v;
      run.constraint_drift = constraint_residual(scene, x).position;
    } while (another_rep(timing, seconds));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, seconds);
  row.method = ida_ggl_label(solver);
  row.tol = tol;
  // Subnormal arithmetic costs these runs up to 2.9x on A05 (docs/benchmarks/mechanisms.md): say
  // which floating-point environment they ran in.
  row.note =
      std::string("a study, not a path of the library; subnormals ") +
      (flushes_subnormals() ? "flushed (FTZ/DAZ set in this process)" : "kept (the default)");
}

/// The study's rows: each linear solver built here (dense LU; KLU when found) at each of the
/// plan's tolerances, the error by `measure()` after each run (as mechanism_sweep; its rows join
/// the problem's as a peer's do, outside the progress count).
template <class SceneT, class Record, class Measure>
std::vector<MechanismRow> ida_ggl_rows(const MechanismPlan& plan, const SceneT& scene,
                                       const std::vector<double>& times, Record& record,
                                       Measure measure) {
  std::vector<MechanismRow> rows;
  std::vector<IdaLinearSolver> solvers{IdaLinearSolver::dense};
#if TUMBLE_BENCH_HAVE_KLU
  solvers.push_back(IdaLinearSolver::klu);
#endif
  for (const IdaLinearSolver s : solvers) {
    if (!method_chosen(plan.filter, ida_ggl_label(s))) {
      continue;
    }
    for (const double tol : plan.tolerances) {
      MechanismRow r;
      ida_ggl_run(scene, s, tol, times, plan.timing, record, r);
      r.error = measure();  // also clears what a failed run recorded
      if (!r.run.ok) {
        r.error = std::numeric_limits<double>::quiet_NaN();
      }
      rows.push_back(std::move(r));
    }
  }
  return rows;
}

}  // namespace tumble::bench
