// tumble_bench: tumble's runs in the quasi-velocity state form [q; v; omega]
// (StateForm::quasi_velocities, docs/conventions.md "State forms") with CVODE Adams and BDF (the
// scene's exact Jacobian), for Euler parameters and one three-parameter set, modified Rodrigues
// parameters (the fastest of them on the torque-free problems in [q; qdot]).
// See work_precision/tumble.hpp.

#include <vector>

#include "common/bench.hpp"
#include "work_precision/tumble.hpp"

namespace tumble::bench {

void add_tumble_methods_c(std::vector<Method>& list) {
  list.push_back(tumble_method<EulerParameters, StateForm::quasi_velocities>(true));
  list.push_back(tumble_method<ModifiedRodriguesParameters, StateForm::quasi_velocities>(true));
}

}  // namespace tumble::bench
