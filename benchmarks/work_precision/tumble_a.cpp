// tumble_bench: tumble's runs for Euler parameters, Rodrigues (Gibbs), modified Rodrigues, the
// rotation vector and the two Euler sequences of the default sweep (ZYX, ZXZ).
// See work_precision/tumble.hpp.

#include <vector>

#include "common/bench.hpp"
#include "work_precision/tumble.hpp"

namespace tumble::bench {

void add_tumble_methods_a(std::vector<Method>& list) {
  list.push_back(tumble_method<EulerParameters>(true));
  list.push_back(tumble_method<RodriguesParameters>(true));
  list.push_back(tumble_method<ModifiedRodriguesParameters>(true));
  list.push_back(tumble_method<RotationVector>(true));
  list.push_back(tumble_method<EulerZYX>(true));
  list.push_back(tumble_method<EulerZXZ>(true));
}

}  // namespace tumble::bench
