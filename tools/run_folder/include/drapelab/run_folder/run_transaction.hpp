// A run folder written as a transaction (docs/outputs.md, "How a run folder is written"). The run
// writes into a private staging folder, FOLDER/.drapelab-run-PID/, and its files move into FOLDER
// when it ends, so results already in FOLDER stay whole until new ones exist. The folder's manifest
// (FOLDER/.drapelab-manifest) lists every file drapelab wrote there: a new run replaces or removes
// only those, never a file someone else put in the folder. One writer at a time (folder_lock.hpp).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "drapelab/run_folder/folder_lock.hpp"

namespace drapelab::run_folder {

inline constexpr const char* kManifestFile = ".drapelab-manifest";
inline constexpr const char* kStagingPrefix = ".drapelab-run-";
// Where an incomplete run goes when the folder already holds a finished one, so that Ctrl-C on a
// re-run never replaces complete results with fewer frames.
inline constexpr const char* kInterruptedFolder = "interrupted_run";

// The files drapelab wrote into `folder` (paths relative to it, '/'-separated); empty when the
// folder has no manifest.
std::set<std::string> read_manifest(const std::filesystem::path& folder);
// Records files another verb wrote (render/'s frames, report.html) in the manifest of the run
// folder they describe, so that the next run into the folder removes them with the run they show.
// Files outside the folder are the user's own and are left out. Takes the folder's lock; returns
// why not when it cannot (a run is writing there) or the manifest cannot be written. A folder
// without a manifest is left as it is.
std::optional<std::string> add_to_manifest(const std::filesystem::path& folder,
                                           const std::vector<std::filesystem::path>& files);
// Removes a run folder drapelab wrote: the files its manifest lists, its bookkeeping, then the
// folder itself and any folder left empty. Files someone else put there stay, and so does the
// folder that holds them. Returns why not when a run holds its lock. A folder without a manifest is
// left as it is.
std::optional<std::string> remove_run_folder(const std::filesystem::path& folder);
// True for the names drapelab keeps for itself in a run folder (lock, manifest, staging folders).
bool is_bookkeeping_name(const std::string& name);

class RunTransaction {
 public:
  // Opens a transaction on `folder`: creates it if needed, takes its lock, checks that it may be
  // used, and creates the staging folder. Returns the transaction, or the message of a refusal
  // (exit 2): the path is a file, another run holds the lock, the folder cannot be written, or it
  // holds other files or a different run and `force` is not given. A folder holding this very run
  // (the same resolved scene) is refreshed without `force`.
  static std::variant<std::unique_ptr<RunTransaction>, std::string> open(
      const std::filesystem::path& folder, const std::string& resolved_scene, bool force);
  ~RunTransaction();  // releases the lock; a staging folder never committed stays for inspection

  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& folder() const { return folder_; }
  // What happened to earlier leftovers (a killed run's staging folder), for the log.
  const std::vector<std::string>& notes() const { return notes_; }

  // Gives back the space held in reserve since open(), so that after a write error (disk full) the
  // run can still write its summary and manifest.
  void release_reserve() noexcept;

  // Moves the staged files into place and records them in the manifest. A complete run (finished or
  // stopped unstable) replaces the previous run's files; an incomplete one (interrupted, or stopped
  // by a write error) does too unless the folder holds a finished run, in which case it goes to
  // FOLDER/interrupted_run/. Returns the folder the run's files are in. Throws WriteError.
  std::filesystem::path commit(bool complete);

 private:
  RunTransaction() = default;
  std::filesystem::path folder_;
  std::filesystem::path staging_;
  std::unique_ptr<FolderLock> lock_;
  std::vector<std::string> notes_;
  bool committed_ = false;
};

}  // namespace drapelab::run_folder
