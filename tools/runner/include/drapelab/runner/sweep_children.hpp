// Child processes of a sweep: each combination is a `drapelab run` of its own, started with
// posix_spawn (no shell: arguments go through untouched) and reaped with waitpid.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::runner {

// How a child ended.
struct ChildExit {
  bool exited = false;  // exited normally; `code` is its exit code
  int code = 0;
  int signal = 0;  // the signal that ended it when !exited
};

// Starts `arguments` (arguments[0] is the program's name as it sees it) running `program`, with
// stdin from /dev/null and stdout and stderr into `log` (created or replaced). SIGINT and SIGTERM
// are reset to their default action and no signal is blocked in the child. Returns the process id,
// or nothing with `error` set.
std::optional<pid_t> spawn_child(const std::string& program,
                                 const std::vector<std::string>& arguments,
                                 const std::filesystem::path& log, std::string* error);

// Reaps `pid` if it has ended (never blocks).
std::optional<ChildExit> poll_child(pid_t pid);

// Sends SIGINT to every child (they stop after their current step and keep their files valid),
// waits up to `grace` for them, then sends SIGKILL to the rest and reaps them. Returns how each
// ended, in the order of `pids`.
std::vector<ChildExit> stop_children(const std::vector<pid_t>& pids,
                                     std::chrono::milliseconds grace);

// "signal 11 (Segmentation fault)".
std::string describe_signal(int signal);

// The path of the running executable: /proc/self/exe resolved, for messages and sweep.json (the
// children are started through /proc/self/exe itself, which stays valid even if the file on disk
// is replaced during the sweep).
std::string own_executable_path();

// How long the sweep sleeps between checks on its children and on Ctrl-C.
inline constexpr std::chrono::milliseconds kChildPollPeriod{20};

}  // namespace drapelab::runner
