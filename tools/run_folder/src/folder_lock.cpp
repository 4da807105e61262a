// One writer per run folder (folder_lock.hpp).
#include "drapelab/run_folder/folder_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>

namespace drapelab::run_folder {
namespace {

std::string os_error() { return std::error_code(errno, std::generic_category()).message(); }

// The pid another writer left in the lock file ("" when unreadable).
std::string holder_pid(int descriptor) {
  char text[32] = {};
  const ssize_t got = ::pread(descriptor, text, sizeof text - 1, 0);
  std::string pid(text, got > 0 ? static_cast<std::size_t>(got) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid;
}

}  // namespace

std::optional<std::string> lock_holder(const std::filesystem::path& folder) {
  const int fd = ::open((folder / kLockFile).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  // A shared lock is refused while a writer holds its exclusive one; it is dropped at once.
  std::optional<std::string> holder;
  if (::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK) holder = holder_pid(fd);
  ::close(fd);
  return holder;
}

std::variant<std::unique_ptr<FolderLock>, std::string> FolderLock::acquire(
    const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / kLockFile;
  // A holder removes the file just before it lets go, so a lock taken on a file that `path` does
  // not name any more is stale: try again on the file it names.
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return "cannot write into " + folder.string() + ": " + os_error();
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const bool held = errno == EWOULDBLOCK;
      const std::string reason = held ? holder_pid(fd) : os_error();
      ::close(fd);
      if (!held) return "cannot lock " + path.string() + ": " + reason;
      return folder.string() + " is being written by another drapelab run (pid " +
             (reason.empty() ? std::string("unknown") : reason) +
             "); wait for it to end, or choose another --out";
    }
    struct stat held_file {};
    struct stat at_path {};
    if (::fstat(fd, &held_file) != 0 || ::stat(path.c_str(), &at_path) != 0 ||
        held_file.st_ino != at_path.st_ino || held_file.st_dev != at_path.st_dev) {
      ::close(fd);
      continue;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
      const std::string reason = os_error();
      ::unlink(path.c_str());
      ::close(fd);
      return "cannot write " + path.string() + ": " + reason;
    }
    return std::unique_ptr<FolderLock>(new FolderLock(path, fd));
  }
  return "cannot lock " + path.string() + ": it keeps changing; is another run starting there?";
}

FolderLock::~FolderLock() {
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace drapelab::run_folder
