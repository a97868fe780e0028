// tumble_micro: the per-call benchmarks (micro/micro.cpp) of the rotation vector.

#include "micro/register.hpp"

namespace tumble::bench {

void register_rotation_vector() { register_all<RotationVector>(); }

}  // namespace tumble::bench
