// Child processes: each combination of a sweep is a `drapelab run` of its own, and each of Slurm's
// commands a program run to completion; both are started by spawn_child (posix_spawn, no shell:
// arguments go through untouched) and reaped with waitpid.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::sweep {

// How a child ended.
struct ChildExit {
  bool exited = false;  // exited normally; `code` is its exit code
  int code = 0;
  int signal = 0;  // the signal that ended it when !exited
};

// How to start a child: the one way drapelab starts a program (sweep runs and Slurm's commands
// alike). stdin reads /dev/null; stdout and stderr go together either into `log` (created or
// replaced) or, when `output_descriptor` >= 0, onto that descriptor (a pipe's write end).
struct ChildLaunch {
  std::string program;  // a path, or a name looked up on PATH with search_path
  bool search_path = false;
  std::vector<std::string> arguments;  // arguments[0]: the program's name as it sees it
  std::filesystem::path log;
  int output_descriptor = -1;
};

// Starts `launch` with SIGINT and SIGTERM reset to their default action and no signal blocked
// (the parent's Ctrl-C handler is not the child's). Returns the process id, or nothing with
// `error` set.
std::optional<pid_t> spawn_child(const ChildLaunch& launch, std::string* error);

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

}  // namespace drapelab::sweep
