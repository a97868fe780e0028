#pragma once
// Owning handles for MuJoCo's model, data and spec (std::unique_ptr deleters), shared by the
// benchmarks that call MuJoCo (peers/mujoco_micro.cpp, peers/mujoco_work_precision.cpp).

#include <mujoco/mujoco.h>

namespace tumble::bench {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
struct SpecDeleter {
  void operator()(mjSpec* s) const { mj_deleteSpec(s); }
};

}  // namespace tumble::bench
