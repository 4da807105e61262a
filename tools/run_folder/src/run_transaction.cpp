// A run folder written as a transaction (run_transaction.hpp).
#include "drapelab/run_folder/run_transaction.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <sstream>
#include <system_error>

#include "drapelab/run_folder/files.hpp"
#include "drapelab/run_folder/output_file.hpp"

namespace drapelab::run_folder {
namespace {

namespace fs = std::filesystem;

constexpr const char* kReserveFile = ".drapelab-reserve";
// Room kept for summary.json and the manifest after the disk fills up: a summary takes about
// 2 KB per solver.
constexpr off_t kReserveBytes = 256 * 1024;  // bytes

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

// Every regular file under `root`, relative to it, '/'-separated, sorted.
std::set<std::string> files_under(const fs::path& root) {
  std::set<std::string> files;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it)
    if (!it->is_directory()) files.insert(it->path().lexically_relative(root).generic_string());
  return files;
}

void write_manifest(const fs::path& folder, const std::set<std::string>& files) {
  std::string text =
      "# The files drapelab wrote into this folder, one per line; a new run replaces or removes "
      "only "
      "these.\n";
  for (const auto& file : files) text += file + "\n";
  write_file_atomically(folder / kManifestFile, text);
}

// Removes `relative` (a file drapelab wrote) from `folder`, then each parent folder it leaves
// empty.
void remove_own_file(const fs::path& folder, const std::string& relative) {
  std::error_code ignored;
  fs::path path = folder / relative;
  if (fs::is_directory(fs::symlink_status(path, ignored))) return;  // replaced by someone's folder
  fs::remove(path, ignored);
  for (path = path.parent_path(); path != folder && path.has_relative_path();
       path = path.parent_path())
    if (!fs::is_directory(path, ignored) || !fs::is_empty(path, ignored) ||
        !fs::remove(path, ignored))
      break;
}

void move_or_throw(const fs::path& from, const fs::path& to) {
  std::error_code error;
  fs::rename(from, to, error);
  if (error) throw WriteError(to, error);
}

// Moves everything in `from` into `to`, folder by folder: a file replaces the file of the same
// name; a folder that does not exist yet moves whole. summary.json moves last, so a reader that
// sees the final summary sees every other file too.
void move_tree(const fs::path& from, const fs::path& to) {
  std::error_code error;
  if (!fs::exists(to, error)) {
    move_or_throw(from, to);
    return;
  }
  if (!fs::is_directory(to, error))
    throw WriteError(to, std::make_error_code(std::errc::not_a_directory));
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(from)) entries.push_back(entry.path());
  std::stable_partition(entries.begin(), entries.end(),
                        [](const fs::path& p) { return p.filename() != kSummaryJson; });
  for (const auto& entry : entries) {
    const fs::path target = to / entry.filename();
    if (fs::is_directory(entry, error))
      move_tree(entry, target);
    else if (fs::is_directory(target, error))
      throw WriteError(target, std::make_error_code(std::errc::is_a_directory));
    else
      move_or_throw(entry, target);
  }
}

// A manifest line names a file inside the folder: relative, without "..", not a comment.
bool is_safe_relative_path(const std::string& line) {
  if (line.empty() || line[0] == '#' || line[0] == '/') return false;
  for (const auto& part : fs::path(line))
    if (part == "..") return false;
  return true;
}

bool holds_finished_run(const fs::path& folder) {
  return read_file(folder / kSummaryJson).find("\"state\": \"finished\"") != std::string::npos;
}

}  // namespace

std::set<std::string> read_manifest(const fs::path& folder) {
  std::set<std::string> files;
  std::istringstream lines(read_file(folder / kManifestFile));
  for (std::string line; std::getline(lines, line);)
    if (is_safe_relative_path(line)) files.insert(line);
  return files;
}

std::optional<std::string> add_to_manifest(const fs::path& folder,
                                           const std::vector<fs::path>& files) {
  std::error_code error;
  if (!fs::exists(folder / kManifestFile, error)) return std::nullopt;
  auto lock = FolderLock::acquire(folder);
  if (auto* refusal = std::get_if<std::string>(&lock)) return *refusal;
  std::set<std::string> recorded = read_manifest(folder);
  const fs::path base = fs::weakly_canonical(folder, error);
  for (const auto& file : files) {
    const std::string inside =
        fs::weakly_canonical(file, error).lexically_relative(base).generic_string();
    if (!error && is_safe_relative_path(inside)) recorded.insert(inside);
  }
  try {
    write_manifest(folder, recorded);
  } catch (const WriteError& failure) {
    return std::string(failure.what());
  }
  return std::nullopt;
}

std::optional<std::string> remove_run_folder(const fs::path& folder) {
  std::error_code error;
  if (!fs::exists(folder / kManifestFile, error)) return std::nullopt;
  {
    auto lock = FolderLock::acquire(folder);
    if (auto* refusal = std::get_if<std::string>(&lock)) return *refusal;
    for (const auto& file : read_manifest(folder)) remove_own_file(folder, file);
    for (const auto& entry : fs::directory_iterator(folder, error))
      if (starts_with(entry.path().filename().string(), kStagingPrefix))
        fs::remove_all(entry.path(), error);
    fs::remove(folder / kManifestFile, error);
  }  // the lock file goes with the lock
  if (fs::is_empty(folder, error)) fs::remove(folder, error);
  return std::nullopt;
}

bool is_bookkeeping_name(const std::string& name) {
  return name == kLockFile || name == kManifestFile ||
         name == std::string(kManifestFile) + ".partial" || starts_with(name, kStagingPrefix);
}

std::variant<std::unique_ptr<RunTransaction>, std::string> RunTransaction::open(
    const fs::path& folder, const std::string& resolved_scene, bool force) {
  std::error_code error;
  if (fs::exists(folder, error) && !fs::is_directory(folder, error))
    return folder.string() + " exists and is not a folder; choose another --out";
  fs::create_directories(folder, error);
  if (error || !fs::is_directory(folder))
    return "cannot create the output folder " + folder.string() + ": " + error.message();

  std::unique_ptr<RunTransaction> run(new RunTransaction());
  run->folder_ = folder;
  auto lock = FolderLock::acquire(folder);
  if (auto* refusal = std::get_if<std::string>(&lock)) return *refusal;
  run->lock_ = std::move(std::get<std::unique_ptr<FolderLock>>(lock));

  bool has_other_files = false;
  std::vector<fs::path> stale_staging;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (starts_with(name, kStagingPrefix))
      stale_staging.push_back(entry.path());
    else if (!is_bookkeeping_name(name))
      has_other_files = true;
  }
  if (error) return "cannot read the output folder " + folder.string() + ": " + error.message();
  if (has_other_files && !force) {
    if (!fs::exists(folder / kResolvedYaml))
      return folder.string() +
             " is not empty and holds no drapelab run; choose an empty or new --out folder, or "
             "add --force to write the run beside its files";
    if (read_file(folder / kResolvedYaml) != resolved_scene)
      return folder.string() +
             " holds a different run (its resolved.yaml differs); add --force to replace it, or "
             "choose another --out";
  }
  // The lock is ours, so no live run owns these: they are left by runs that were killed.
  for (const auto& stale : stale_staging) {
    fs::remove_all(stale, error);
    run->notes_.push_back("removed " + stale.string() + ", left by a run that was killed");
  }

  run->staging_ = folder / (kStagingPrefix + std::to_string(::getpid()));
  fs::create_directory(run->staging_, error);
  if (error) return "cannot write into " + folder.string() + ": " + error.message();
  const fs::path reserve = run->staging_ / kReserveFile;
  const int fd = ::open(reserve.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int reserved = fd < 0 ? errno : ::posix_fallocate(fd, 0, kReserveBytes);
  if (fd >= 0) ::close(fd);
  if (reserved != 0) {
    fs::remove_all(run->staging_, error);
    return "cannot write into " + folder.string() + ": " +
           std::error_code(reserved, std::generic_category()).message();
  }
  return run;
}

RunTransaction::~RunTransaction() = default;

void RunTransaction::release_reserve() noexcept {
  std::error_code ignored;
  fs::remove(staging_ / kReserveFile, ignored);
}

fs::path RunTransaction::commit(bool complete) {
  release_reserve();
  const std::set<std::string> previous = read_manifest(folder_);
  const std::set<std::string> staged = files_under(staging_);
  std::set<std::string> recorded;
  std::set<std::string> to_remove;
  fs::path destination = folder_;
  std::string prefix;  // of the staged files' paths in the manifest
  if (!complete && holds_finished_run(folder_)) {
    prefix = std::string(kInterruptedFolder) + "/";
    destination = folder_ / kInterruptedFolder;
    std::error_code error;
    const bool ours = std::any_of(previous.begin(), previous.end(),
                                  [&](const std::string& f) { return starts_with(f, prefix); });
    if (fs::exists(destination, error) && !ours) {  // someone else's folder of that name
      const std::string name = std::string(kInterruptedFolder) + "_" + std::to_string(::getpid());
      prefix = name + "/";
      destination = folder_ / name;
    }
    for (const auto& file : previous)
      (starts_with(file, prefix) ? to_remove : recorded).insert(file);
  } else {
    to_remove = previous;
  }
  for (const auto& file : staged) {
    recorded.insert(prefix + file);
    to_remove.erase(prefix + file);  // replaced by the move, not removed first
  }
  for (const auto& file : to_remove) remove_own_file(folder_, file);
  move_tree(staging_, destination);
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  write_manifest(folder_, recorded);
  committed_ = true;
  return destination;
}

}  // namespace drapelab::run_folder
