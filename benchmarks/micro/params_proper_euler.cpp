// tumble_micro: the per-call benchmarks (micro/micro.cpp) of the six proper Euler sequences.

#include "micro/register.hpp"

namespace tumble::bench {

void register_proper_euler() {
  register_all<EulerXYX, EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ>();
}

}  // namespace tumble::bench
