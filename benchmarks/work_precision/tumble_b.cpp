// tumble_bench: tumble's runs for the other ten Euler sequences (in the --full sweep only).
// See work_precision/tumble.hpp.

#include <vector>

#include "common/bench.hpp"
#include "work_precision/tumble.hpp"

namespace tumble::bench {

void add_tumble_methods_b(std::vector<Method>& list) {
  // Tait-Bryan (ZYX is in work_precision/tumble_a.cpp)
  list.push_back(tumble_method<EulerXYZ>(false));
  list.push_back(tumble_method<EulerXZY>(false));
  list.push_back(tumble_method<EulerYXZ>(false));
  list.push_back(tumble_method<EulerYZX>(false));
  list.push_back(tumble_method<EulerZXY>(false));
  // proper Euler (ZXZ is in work_precision/tumble_a.cpp)
  list.push_back(tumble_method<EulerXYX>(false));
  list.push_back(tumble_method<EulerXZX>(false));
  list.push_back(tumble_method<EulerYXY>(false));
  list.push_back(tumble_method<EulerYZY>(false));
  list.push_back(tumble_method<EulerZYZ>(false));
}

}  // namespace tumble::bench
