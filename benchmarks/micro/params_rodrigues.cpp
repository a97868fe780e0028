// tumble_micro: the per-call benchmarks (micro/micro.cpp) of Rodrigues (Gibbs) and modified
// Rodrigues parameters.

#include "micro/register.hpp"

namespace tumble::bench {

void register_rodrigues() { register_all<RodriguesParameters, ModifiedRodriguesParameters>(); }

}  // namespace tumble::bench
