// tumble_bench, study (e): the list of its problems and methods, and its default tolerance
// ladder. The problems' runs are in mechanisms/<problem>.cpp, one translation unit each, built
// when tumble::odeint exists (TUMBLE_BENCH_HAVE_TUMBLE_ODEINT: the front door and
// OdeintIntegrator need it).

#include <algorithm>
#include <string>
#include <vector>

#include "mechanisms/mechanisms.hpp"

namespace tumble::bench {

const char* mechanism_method_label(MechanismMethod m) {
  switch (m) {
    case MechanismMethod::front_door:
      return "tumble::integrate (auto)";
    case MechanismMethod::odeint_f78:
      return "OdeintIntegrator F78";
    case MechanismMethod::cvode_bdf:
      return "SceneIntegrator BDF";
  }
  return "?";
}

std::vector<MechanismProblem> mechanism_problems() {
  // HOOK for peers: a peer's runs of the same problem append rows to the MechanismResult with
  // the peer's name as `method`, the same output times and the same error measure (the problem's
  // .cpp hands them over); the table and the CSV take them as they are. MuJoCo's RK4 does so
  // (peers/mujoco_mechanisms.cpp), and Exudyn's implicit solvers (peers/exudyn_mechanisms.cpp,
  // a Python process on peers/exudyn_mechanisms.py), each when installed; on the open chain,
  // Pinocchio's aba in Boost.Odeint too (peers/pinocchio_mechanisms.cpp).
#if TUMBLE_BENCH_HAVE_TUMBLE_ODEINT
  return {{"a01", &run_mechanism_a01},
          {"a02", &run_mechanism_a02},
          {"a03", &run_mechanism_a03},
          {"a04", &run_mechanism_a04},
          {"a05", &run_mechanism_a05},
          {"chain", &run_mechanism_chain}};  // after the IFToMM problems: not one of them
#else
  return {};  // the problems' runs need tumble::odeint (Boost >= 1.74): not built
#endif
}

#if !TUMBLE_BENCH_HAVE_TUMBLE_ODEINT
bool exudyn_available() { return false; }  // peers/exudyn_mechanisms.cpp is not built
#endif

bool runs_peer(const MechanismPlan& plan, const std::string& peer) {
  return plan.filter.empty() ||
         std::any_of(plan.filter.begin(), plan.filter.end(), [&](const std::string& f) {
           return peer.find(f) != std::string::npos || f.find(peer) != std::string::npos;
         });
}

void keep_wanted(const MechanismPlan& plan, std::vector<MechanismRow>& rows) {
  std::erase_if(rows, [&](const MechanismRow& r) { return !method_chosen(plan.filter, r.method); });
}

std::vector<double> mechanism_tolerances(bool full) {
  if (full) {
    return {1e-4, 3e-5, 1e-5,  3e-6,  1e-6,  3e-7,  1e-7,  3e-8, 1e-8,
            3e-9, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11, 3e-12, 1e-12};
  }
  return {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
}

}  // namespace tumble::bench
