// tumble_bench: tumble's runs for the other ten Euler sequences (in the --full sweep only).
// See work_precision_tumble.hpp.

#include <vector>

#include "work_precision.hpp"
#include "work_precision_tumble.hpp"

namespace tumble::bench {

void add_parameterizations_b(std::vector<Parameterization>& list) {
  // Tait-Bryan (ZYX is in work_precision_tumble_a.cpp)
  list.push_back(parameterization<EulerXYZ>(false));
  list.push_back(parameterization<EulerXZY>(false));
  list.push_back(parameterization<EulerYXZ>(false));
  list.push_back(parameterization<EulerYZX>(false));
  list.push_back(parameterization<EulerZXY>(false));
  // proper Euler (ZXZ is in work_precision_tumble_a.cpp)
  list.push_back(parameterization<EulerXYX>(false));
  list.push_back(parameterization<EulerXZX>(false));
  list.push_back(parameterization<EulerYXY>(false));
  list.push_back(parameterization<EulerYZY>(false));
  list.push_back(parameterization<EulerZYZ>(false));
}

}  // namespace tumble::bench
