// Reading a whole input file (a scene, an OBJ mesh) only when it is a regular file of bounded size:
// a device such as /dev/zero, a pipe or a huge file would otherwise be read until memory runs out.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace drapelab {

inline constexpr std::uintmax_t kMaxInputFileBytes = 64u << 20;  // bytes (64 MB)

struct BoundedFile {
  bool ok = false;
  std::string text;   // the file's bytes when ok
  std::string error;  // why not: "is not a regular file ...", "is 70000000 bytes; at most ..."
};

// The bytes of `path`, or why they are not read. The size is checked before reading and again while
// reading, in case the file grows.
inline BoundedFile read_bounded_file(const std::filesystem::path& path,
                                     std::uintmax_t max_bytes = kMaxInputFileBytes) {
  BoundedFile file;
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) {
    file.error = "cannot be read (no such file)";
    return file;
  }
  if (std::filesystem::is_directory(status)) {
    file.error = "is a folder, not a file";
    return file;
  }
  if (!std::filesystem::is_regular_file(status)) {
    file.error = "is not a regular file (a device, pipe or socket); only regular files are read";
    return file;
  }
  const std::string limit =
      std::to_string(max_bytes) + " bytes (" + std::to_string(max_bytes >> 20) + " MB) are read";
  const auto bytes = std::filesystem::file_size(path, error);
  if (!error && bytes > max_bytes) {
    file.error = "is " + std::to_string(bytes) + " bytes; at most " + limit;
    return file;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    file.error = "cannot be read (permission denied)";
    return file;
  }
  if (!error) file.text.reserve(static_cast<std::size_t>(bytes));
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    file.text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (file.text.size() > max_bytes) {
      file.text.clear();
      file.error =
          "grew beyond " + std::to_string(max_bytes) + " bytes while read; at most " + limit;
      return file;
    }
  }
  if (in.bad()) {
    file.text.clear();
    file.error = "cannot be read (an input error)";
    return file;
  }
  file.ok = true;
  return file;
}

}  // namespace drapelab
