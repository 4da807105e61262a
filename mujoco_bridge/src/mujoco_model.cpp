// MJCF text turned into a MuJoCo model (mujoco_model.hpp).
#include "mujoco_model.hpp"

#include <cstring>
#include <mutex>
#include <stdexcept>

namespace drapelab::mujoco {
namespace {

// MuJoCo prints its warnings to stdout by default; every one the solver cares about (a full
// contact buffer, a non-finite state) is counted in mjData::warning and reported from there.
void ignore_warning(const char*) {}

}  // namespace

ModelPointer compile_mjcf(const std::string& xml) {
  static std::once_flag quiet;
  std::call_once(quiet, [] { mju_user_warning = &ignore_warning; });
  // The file system holds 2,000 file names of 1 kB: 2 MB, too large for the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "drapelab_scene.xml";
  if (xml.size() > static_cast<std::size_t>(INT32_MAX))
    throw std::runtime_error("the MuJoCo model's text is over 2 GB");
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo's virtual file system refused the model's text");
  const int file = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[file], xml.data(), xml.size());
  char error[1024] = "";
  ModelPointer model(mj_loadXML(name, vfs.get(), error, sizeof error));
  mj_deleteVFS(vfs.get());
  if (!model) throw std::runtime_error(std::string("MuJoCo refused the model: ") + error);
  return model;
}

}  // namespace drapelab::mujoco
