// drapelab view: runs the interactive viewer, drapelab-view, which lives beside this program (it
// links a windowing GL library, which drapelab, linking Mesa's offscreen GL for render, cannot).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "verbs.hpp"

namespace drapelab::cli {

int view_verb(int argc, char** argv) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path viewer = self.parent_path() / "drapelab-view";
  if (error || !std::filesystem::exists(viewer)) {
    std::cerr << "error: drapelab view needs " << viewer.string()
              << " beside drapelab; build it (cmake --build build) with the viewer's packages "
                 "(bash tools/install-deps.sh)\n";
    return kExitBadInput;
  }
  std::vector<std::string> arguments = {viewer.string()};
  for (int k = 2; k < argc; ++k) arguments.emplace_back(argv[k]);  // after "drapelab view"
  std::vector<char*> pointers;
  for (std::string& argument : arguments) pointers.push_back(argument.data());
  pointers.push_back(nullptr);
  execv(viewer.c_str(), pointers.data());
  std::cerr << "error: cannot run " << viewer.string() << ": " << std::strerror(errno) << "\n";
  return kExitBadInput;
}

}  // namespace drapelab::cli
