// libFuzzer target: the OBJ reader and the mesh cloth builder (fuzz_inputs.hpp).
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto broken = drapelab::fuzz::read_obj_input({reinterpret_cast<const char*>(data), size});
  if (broken) {
    std::fprintf(stderr, "fuzz_obj_reader: %s\n", broken->c_str());
    std::abort();  // libFuzzer saves the input as a crash
  }
  return 0;
}
