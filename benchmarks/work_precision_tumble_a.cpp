// tumble_bench: tumble's runs for Euler parameters, Rodrigues (Gibbs), modified Rodrigues, the
// rotation vector and the two Euler sequences of the default sweep (ZYX, ZXZ).
// See work_precision_tumble.hpp.

#include <vector>

#include "work_precision.hpp"
#include "work_precision_tumble.hpp"

namespace tumble::bench {

void add_parameterizations_a(std::vector<Parameterization>& list) {
  list.push_back(parameterization<EulerParameters>(true));
  list.push_back(parameterization<RodriguesParameters>(true));
  list.push_back(parameterization<ModifiedRodriguesParameters>(true));
  list.push_back(parameterization<RotationVector>(true));
  list.push_back(parameterization<EulerZYX>(true));
  list.push_back(parameterization<EulerZXZ>(true));
}

}  // namespace tumble::bench
