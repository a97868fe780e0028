#pragma once
// SUNDIALS glue for tumble::Cvode: the version differences between SUNDIALS 6 and 7 in one place,
// and small owning handles (RAII) for the SUNDIALS objects a CVODE integrator needs.
//
// Version differences handled here (SUNDIALS_VERSION_MAJOR from sundials/sundials_config.h):
//  - SUNContext_Create takes `void* comm` in 6 and `SUNComm comm` (SUN_COMM_NULL) in 7.
//  - Error messages: 6 reports them through a per-integrator handler (CVodeSetErrHandlerFn);
//    7 removed it and reports through the SUNContext's handler stack (SUNContext_PushErrHandler).
//    Either way tumble installs a handler that captures the message (see ErrorCapture) instead
//    of letting SUNDIALS print it to stderr; the message goes into the IntegrationError.
//    SUNDIALS 6 also hands warnings (e.g. "t + h = t on the next step") to that handler, so they
//    are captured too; SUNDIALS 7 sends warnings to the context's SUNLogger instead, which prints
//    them as configured (SUNLOGGER_WARNING_FILENAME; builds with SUNDIALS_LOGGING_LEVEL >= 2).
//  - Types: `realtype`/`booleantype` (deprecated in 6.x, removed in 7) versus
//    `sunrealtype`/`sunbooleantype`; tumble uses detail::sun_real / detail::sun_bool.
//
// Owning handles are std::unique_ptr with a deleter that calls the SUNDIALS destroy function, so
// nothing leaks when a constructor throws half way.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sundials/sundials_nvector.h>
#include <sundials/sundials_types.h>

#include "tumble/core/cache_line.hpp"

#if !defined(SUNDIALS_VERSION_MAJOR) || SUNDIALS_VERSION_MAJOR < 6
#error "tumble::Cvode needs SUNDIALS >= 6 (CVODE with SUNContext)"
#endif

namespace tumble::detail {

#if SUNDIALS_VERSION_MAJOR == 6 && SUNDIALS_VERSION_MINOR < 4
// sunrealtype/sunbooleantype appeared in 6.4; earlier 6.x releases only have the old names.
using sun_real = realtype;
using sun_bool = booleantype;
#else
using sun_real = sunrealtype;
using sun_bool = sunbooleantype;
#endif

// tumble views SUNDIALS vectors and matrices as Eigen::VectorXd / MatrixXd: the build of
// SUNDIALS must use double precision (the default; SUNDIALS_PRECISION=double).
static_assert(std::is_same_v<sun_real, double>,
              "tumble::Cvode needs SUNDIALS built with double precision (sunrealtype == double)");

/// Captures the last message SUNDIALS reports (error or warning) in a fixed buffer: the handler
/// runs inside C code, so it must not throw, and it does not allocate.
struct ErrorCapture {
  std::array<char, 512> message{};
  int code = 0;
  bool has_message = false;

  void capture(int error_code, const char* function, const char* msg) noexcept {
    code = error_code;
    has_message = true;
    std::snprintf(message.data(), message.size(), "%s: %s", function ? function : "CVODE",
                  msg ? msg : "(no message)");
  }
  void clear() noexcept {
    has_message = false;
    code = 0;
    message[0] = '\0';
  }

#if SUNDIALS_VERSION_MAJOR >= 7
  static void handler(int /*line*/, const char* function, const char* /*file*/, const char* msg,
                      SUNErrCode error_code, void* data, SUNContext /*ctx*/) noexcept {
    static_cast<ErrorCapture*>(data)->capture(static_cast<int>(error_code), function, msg);
  }
#else
  static void handler(int error_code, const char* /*module*/, const char* function, char* msg,
                      void* data) noexcept {
    static_cast<ErrorCapture*>(data)->capture(error_code, function, msg);
  }
#endif
};

struct ContextDeleter {
  void operator()(SUNContext ctx) const noexcept { SUNContext_Free(&ctx); }
};
struct NVectorDeleter {
  void operator()(N_Vector v) const noexcept { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const noexcept { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const noexcept { SUNLinSolFree(s); }
};
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver s) const noexcept { SUNNonlinSolFree(s); }
};
struct CvodeMemoryDeleter {
  void operator()(void* mem) const noexcept { CVodeFree(&mem); }
};

using ContextHandle = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using NVectorHandle = std::unique_ptr<std::remove_pointer_t<N_Vector>, NVectorDeleter>;
using MatrixHandle = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverHandle =
    std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using NonlinearSolverHandle =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverDeleter>;
using CvodeMemoryHandle = std::unique_ptr<void, CvodeMemoryDeleter>;

/// A SUNDIALS constructor returned null. They fail only when malloc fails (the arguments are
/// validated before), so report it as std::bad_alloc.
template <class T> T* require_allocated(T* p) {
  if (p == nullptr) {
    throw std::bad_alloc();
  }
  return p;
}

/// The clone operation of tumble's serial vectors: a serial N_Vector like w (its operations
/// included) whose data are whole cache lines of their own (core/cache_line.hpp), from
/// std::aligned_alloc, so that SUNDIALS' own destroy frees them (free()). Null when memory runs
/// out (SUNDIALS' convention for clones).
inline N_Vector clone_on_lines(N_Vector w) noexcept {
  N_Vector v = N_VCloneEmpty_Serial(w);  // w's length and operations, no data
  if (v == nullptr) {
    return nullptr;
  }
  const auto n = std::max<std::size_t>(static_cast<std::size_t>(NV_LENGTH_S(w)), 1);
  void* data = std::aligned_alloc(kCacheLine, CacheLineAllocator<sun_real>::padded(n));
  if (data == nullptr) {
    N_VDestroy_Serial(v);
    return nullptr;
  }
  NV_DATA_S(v) = static_cast<sun_real*>(data);
  NV_OWN_DATA_S(v) = SUNTRUE;
  return v;
}

/// A serial N_Vector of length n, with SUNDIALS' fused and vector-array operations enabled when
/// `fused` is true (they are off by default). CVODE clones every vector it works with (the
/// Nordsieck array, the error weights, the nonlinear solver's and projection's work vectors)
/// from the y0 given to CVodeInit, and a clone inherits the operations of the vector it was
/// cloned from: so this must be the vector handed to CVodeInit, set before that call (NVECTOR
/// serial module, "fused and vector array operations", SUNDIALS 6.x and 7.x alike). Its clone
/// operation is clone_on_lines: the data of this vector and of every clone, written at every
/// step, are cache lines of their own, never shared with another thread's integrator (SUNDIALS
/// would take them from malloc).
inline NVectorHandle make_serial_vector(sunindextype n, SUNContext ctx, bool fused) {
  const NVectorHandle empty(require_allocated(N_VNewEmpty_Serial(n, ctx)));
  empty->ops->nvclone = &clone_on_lines;
  NVectorHandle v(require_allocated(clone_on_lines(empty.get())));
  if (fused && N_VEnableFusedOps_Serial(v.get(), SUNTRUE) != 0) {
    throw std::runtime_error("tumble::Cvode: N_VEnableFusedOps_Serial failed");
  }
  return v;
}

/// A SUNContext whose errors are captured by `capture` (which must outlive the context).
inline ContextHandle make_context([[maybe_unused]] ErrorCapture& capture) {
  SUNContext ctx = nullptr;
#if SUNDIALS_VERSION_MAJOR >= 7
  if (SUNContext_Create(SUN_COMM_NULL, &ctx) != 0 || ctx == nullptr) {
    throw std::runtime_error("tumble::Cvode: SUNContext_Create failed");
  }
  ContextHandle handle(ctx);
  // Replace the default handler (which logs to stderr) by the capturing one.
  if (SUNContext_ClearErrHandlers(ctx) != 0 ||
      SUNContext_PushErrHandler(ctx, &ErrorCapture::handler, &capture) != 0) {
    throw std::runtime_error("tumble::Cvode: could not install the SUNDIALS error handler");
  }
  return handle;
#else
  if (SUNContext_Create(nullptr, &ctx) != 0 || ctx == nullptr) {
    throw std::runtime_error("tumble::Cvode: SUNContext_Create failed");
  }
  return ContextHandle(ctx);
#endif
}

/// Installs the capturing handler on a CVODE memory block where SUNDIALS 6 needs it there.
inline void install_error_handler([[maybe_unused]] void* cvode_mem,
                                  [[maybe_unused]] ErrorCapture& capture) {
#if SUNDIALS_VERSION_MAJOR < 7
  if (CVodeSetErrHandlerFn(cvode_mem, &ErrorCapture::handler, &capture) != CV_SUCCESS) {
    throw std::runtime_error("tumble::Cvode: CVodeSetErrHandlerFn failed");
  }
#endif
}

/// CVODE's name of a return flag ("CV_TOO_MUCH_WORK"). CVodeGetReturnFlagName returns a string
/// allocated with malloc that the caller frees.
inline std::string flag_name(int flag) {
  char* raw = CVodeGetReturnFlagName(static_cast<long>(flag));
  if (raw == nullptr) {
    return "CV_UNKNOWN(" + std::to_string(flag) + ")";
  }
  std::string name(raw);
  std::free(raw);  // NOLINT(cppcoreguidelines-no-malloc): allocated by SUNDIALS with malloc
  return name;
}

}  // namespace tumble::detail
