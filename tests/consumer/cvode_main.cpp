// Consumer check for tumble::cvode: the target must bring SUNDIALS CVODE's headers and libraries
// (6.x or 7.x). It integrates the Euler-parameter kinematics pdot = 1/2 L(p)^T omega of a body
// spinning at a constant body rate omega with CVODE (BDF, dense Newton) and compares p(t) with
// the closed form p(t) = p0 (x) (cos(|w| t / 2), w / |w| sin(|w| t / 2)) (Hamilton product,
// computed with Eigen::Quaternion). Exit status 0 when the error is within the tolerances' reach.

#include <cmath>
#include <cstdio>
#include <type_traits>

#include <Eigen/Geometry>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "tumble/orientation/euler_parameters.hpp"

static_assert(std::is_same_v<sunrealtype, double>, "this check assumes SUNDIALS in double");

namespace {

const Eigen::Vector3d kOmega(0.4, -0.7, 1.1);  // body angular velocity, rad/s

int rhs(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* /*user_data*/) {
  const Eigen::Map<const Eigen::Vector4d> p(N_VGetArrayPointer(y));
  Eigen::Map<Eigen::Vector4d>(N_VGetArrayPointer(ydot)) =
      tumble::EulerParameters::thetadot(Eigen::Vector4d(p), kOmega);
  return 0;
}

}  // namespace

int main() {
  SUNContext ctx = nullptr;
#if SUNDIALS_VERSION_MAJOR >= 7
  if (SUNContext_Create(SUN_COMM_NULL, &ctx) != 0) return 1;
#else
  if (SUNContext_Create(nullptr, &ctx) != 0) return 1;
#endif
  const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.8, Eigen::Vector3d(0.0, 0.6, 0.8)));
  N_Vector y = N_VNew_Serial(4, ctx);
  Eigen::Map<Eigen::Vector4d>(N_VGetArrayPointer(y)) = tumble::EulerParameters::from_quaternion(q0);

  void* cvode = CVodeCreate(CV_BDF, ctx);
  SUNMatrix a = SUNDenseMatrix(4, 4, ctx);
  SUNLinearSolver ls = SUNLinSol_Dense(y, a, ctx);
  const double rtol = 1e-10, atol = 1e-12;
  int flag = CVodeInit(cvode, rhs, 0.0, y);
  if (flag == CV_SUCCESS) flag = CVodeSStolerances(cvode, rtol, atol);
  if (flag == CV_SUCCESS) flag = CVodeSetLinearSolver(cvode, ls, a);
  const double t_end = 10.0;
  sunrealtype t = 0.0;
  if (flag == CV_SUCCESS) flag = CVode(cvode, t_end, y, &t, CV_NORMAL);

  const double w = kOmega.norm();
  const Eigen::Vector3d axis = kOmega / w;
  const Eigen::Quaterniond q_exact = q0 * Eigen::Quaterniond(Eigen::AngleAxisd(w * t_end, axis));
  const Eigen::Vector4d p = Eigen::Map<const Eigen::Vector4d>(N_VGetArrayPointer(y));
  const double error = (p - tumble::EulerParameters::from_quaternion(q_exact)).norm();
  long steps = 0;
  CVodeGetNumSteps(cvode, &steps);

  CVodeFree(&cvode);
  SUNLinSolFree(ls);
  SUNMatDestroy(a);
  N_VDestroy(y);
  SUNContext_Free(&ctx);

  // BDF's global error grows over the run; 1e-6 is far above what rtol = 1e-10 gives over about
  // two revolutions and far below anything a wrong right-hand side or a wrong link would give.
  const bool ok = flag == CV_SUCCESS && t == t_end && error < 1e-6;
  std::printf("consumer_cvode: SUNDIALS %s, flag %d, %ld steps, |p(t) - p_exact(t)| = %.3e  %s\n",
              SUNDIALS_VERSION, flag, steps, error, ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
