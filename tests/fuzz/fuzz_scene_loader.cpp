// libFuzzer target: the scene loader, from YAML text and --set overrides (fuzz_inputs.hpp).
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto broken = drapelab::fuzz::load_scene_input({reinterpret_cast<const char*>(data), size});
  if (broken) {
    std::fprintf(stderr, "fuzz_scene_loader: %s\n", broken->c_str());
    std::abort();  // libFuzzer saves the input as a crash
  }
  return 0;
}
