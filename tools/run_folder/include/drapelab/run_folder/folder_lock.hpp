// One writer per run folder: an exclusive flock(2) on FOLDER/.drapelab.lock, which holds the
// writer's pid. The kernel drops the lock when its process ends, however it ends, so a killed run
// never blocks the next one.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace drapelab::run_folder {

inline constexpr const char* kLockFile = ".drapelab.lock";

// The pid of the live process holding `folder`'s lock; nullopt when no process holds it.
std::optional<std::string> lock_holder(const std::filesystem::path& folder);

class FolderLock {
 public:
  // Locks `folder` (which must exist). Returns the lock, or a message saying why not: another
  // process holds it (naming its pid), or the folder cannot be written.
  static std::variant<std::unique_ptr<FolderLock>, std::string> acquire(
      const std::filesystem::path& folder);
  ~FolderLock();  // removes the lock file and releases the lock
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  FolderLock(std::filesystem::path path, int descriptor)
      : path_(std::move(path)), fd_(descriptor) {}
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace drapelab::run_folder
