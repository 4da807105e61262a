// Files a run writes, with errors that say which file and which OS error (disk full, permissions,
// a name too long), and appends that can be rolled back to the last complete frame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

namespace drapelab::run_folder {

// A file could not be written: the path and the operating system's reason.
class WriteError : public std::runtime_error {
 public:
  WriteError(const std::filesystem::path& path, std::error_code error);
  const std::filesystem::path& path() const { return path_; }
  std::error_code error() const { return error_; }

 private:
  std::filesystem::path path_;
  std::error_code error_;
};

// A file written from its start, in order, through one descriptor. Every write either completes or
// throws WriteError. commit() marks the bytes written so far as complete; rollback() cuts the file
// back to the last commit, so a table or point cache stopped by a write error ends on a whole
// frame.
class OutputFile {
 public:
  explicit OutputFile(const std::filesystem::path& path);  // creates or truncates the file
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void append(std::string_view bytes);
  // Overwrites bytes already written (a header's count) without moving the end.
  void overwrite(std::int64_t offset, std::string_view bytes);
  void commit() { committed_ = size_; }
  // Cuts the file to the last commit; false (and the file left as it is) when even that fails.
  bool rollback() noexcept;
  std::int64_t size() const { return size_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  void write_at(std::int64_t offset, std::string_view bytes);  // whole, or WriteError

  std::filesystem::path path_;
  int descriptor_ = -1;
  std::int64_t size_ = 0;       // bytes
  std::int64_t committed_ = 0;  // bytes
};

// Writes `text` as the whole of `path` (no temporary): for files inside a run's private staging
// folder. A file that could not be written whole is removed before WriteError is thrown.
void write_whole_file(const std::filesystem::path& path, std::string_view text);

}  // namespace drapelab::run_folder
