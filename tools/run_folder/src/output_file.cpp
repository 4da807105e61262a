// Files written through one descriptor, with located errors and rollback (output_file.hpp).
#include "drapelab/run_folder/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

namespace drapelab::run_folder {
namespace {

std::error_code last_error() { return {errno, std::generic_category()}; }

}  // namespace

WriteError::WriteError(const std::filesystem::path& path, std::error_code error)
    : std::runtime_error("cannot write " + path.string() + ": " + error.message()),
      path_(path),
      error_(error) {}

OutputFile::OutputFile(const std::filesystem::path& path) : path_(path) {
  descriptor_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (descriptor_ < 0) throw WriteError(path_, last_error());
}

OutputFile::~OutputFile() {
  if (descriptor_ >= 0) ::close(descriptor_);
}

void OutputFile::append(std::string_view bytes) {
  write_at(size_, bytes);
  size_ += static_cast<std::int64_t>(bytes.size());
}

void OutputFile::overwrite(std::int64_t offset, std::string_view bytes) { write_at(offset, bytes); }

void OutputFile::write_at(std::int64_t offset, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t written = ::pwrite(descriptor_, bytes.data(), bytes.size(), offset);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0)
      throw WriteError(
          path_, written < 0 ? last_error() : std::make_error_code(std::errc::no_space_on_device));
    offset += written;
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
}

bool OutputFile::rollback() noexcept {
  if (::ftruncate(descriptor_, committed_) != 0) return false;
  size_ = committed_;
  return true;
}

void write_whole_file(const std::filesystem::path& path, std::string_view text) {
  try {
    OutputFile file(path);
    file.append(text);
  } catch (const WriteError&) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    throw;
  }
}

}  // namespace drapelab::run_folder
