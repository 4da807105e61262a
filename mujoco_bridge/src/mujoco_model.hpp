// MuJoCo's model and data with their owners, and MJCF text turned into a model without a file.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

namespace drapelab::mujoco {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPointer = std::unique_ptr<mjModel, ModelDeleter>;
using DataPointer = std::unique_ptr<mjData, DataDeleter>;

// Compiles MJCF text held in memory (through MuJoCo's virtual file system). Throws
// std::runtime_error with MuJoCo's own message when it refuses the model. MuJoCo's warnings are
// silenced process-wide: the solver reads its data's warning counters after every step instead.
ModelPointer compile_mjcf(const std::string& xml);

}  // namespace drapelab::mujoco
