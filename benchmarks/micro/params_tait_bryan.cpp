// tumble_micro: the per-call benchmarks (micro/micro.cpp) of the six Tait-Bryan sequences of Euler
// angles.

#include "micro/register.hpp"

namespace tumble::bench {

void register_tait_bryan() {
  register_all<EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX>();
}

}  // namespace tumble::bench
