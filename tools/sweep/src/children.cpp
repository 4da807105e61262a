#include "drapelab/sweep/children.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <thread>

extern char** environ;

namespace drapelab::sweep {

namespace {

ChildExit decode(int status) {
  ChildExit result;
  if (WIFEXITED(status)) {
    result.exited = true;
    result.code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
  }
  return result;
}

// posix_spawn's helper objects, released on every path.
struct SpawnSetup {
  posix_spawn_file_actions_t actions{};
  posix_spawnattr_t attributes{};
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
};

}  // namespace

std::optional<pid_t> spawn_child(const ChildLaunch& launch, std::string* error) {
  SpawnSetup setup;
  int code =
      posix_spawn_file_actions_addopen(&setup.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (code == 0)
    code = launch.output_descriptor >= 0
               ? posix_spawn_file_actions_adddup2(&setup.actions, launch.output_descriptor,
                                                  STDOUT_FILENO)
               : posix_spawn_file_actions_addopen(&setup.actions, STDOUT_FILENO, launch.log.c_str(),
                                                  O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (code == 0)
    code = posix_spawn_file_actions_adddup2(&setup.actions, STDOUT_FILENO, STDERR_FILENO);
  // The parent's own Ctrl-C handler is not the child's: `drapelab run` installs its own, but until
  // then the child should act on signals by default, with none blocked.
  sigset_t defaults, none;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigemptyset(&none);
  if (code == 0) code = posix_spawnattr_setsigdefault(&setup.attributes, &defaults);
  if (code == 0) code = posix_spawnattr_setsigmask(&setup.attributes, &none);
  if (code == 0)
    code = posix_spawnattr_setflags(
        &setup.attributes, static_cast<short>(POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK));
  if (code != 0) {
    *error = std::string("cannot prepare a child process: ") + std::strerror(code);
    return std::nullopt;
  }
  std::vector<char*> argv;
  for (const auto& argument : launch.arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const auto start = launch.search_path ? posix_spawnp : posix_spawn;
  code =
      start(&pid, launch.program.c_str(), &setup.actions, &setup.attributes, argv.data(), environ);
  if (code != 0) {
    *error = "cannot start " + launch.program + ": " + std::strerror(code);
    return std::nullopt;
  }
  return pid;
}

std::optional<ChildExit> poll_child(pid_t pid) {
  int status = 0;
  pid_t reaped = 0;
  do {
    reaped = ::waitpid(pid, &status, WNOHANG);
  } while (reaped < 0 && errno == EINTR);
  if (reaped == pid) return decode(status);
  if (reaped < 0) {  // not our child any more (ECHILD): report it as gone rather than wait forever
    ChildExit gone;
    gone.exited = true;
    gone.code = 127;
    return gone;
  }
  return std::nullopt;
}

std::vector<ChildExit> stop_children(const std::vector<pid_t>& pids,
                                     std::chrono::milliseconds grace) {
  std::vector<std::optional<ChildExit>> ended(pids.size());
  for (const pid_t pid : pids) ::kill(pid, SIGINT);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  bool killed = false;
  while (true) {
    bool all = true;
    for (std::size_t k = 0; k < pids.size(); ++k) {
      if (!ended[k]) ended[k] = poll_child(pids[k]);
      all = all && ended[k].has_value();
    }
    if (all) break;
    if (!killed && std::chrono::steady_clock::now() >= deadline) {
      for (std::size_t k = 0; k < pids.size(); ++k)
        if (!ended[k]) ::kill(pids[k], SIGKILL);
      killed = true;
    }
    std::this_thread::sleep_for(kChildPollPeriod);
  }
  std::vector<ChildExit> result;
  for (const auto& e : ended) result.push_back(*e);
  return result;
}

std::string describe_signal(int signal) {
  const char* name = ::strsignal(signal);
  return "signal " + std::to_string(signal) +
         (name ? " (" + std::string(name) + ")" : std::string());
}

std::string own_executable_path() {
  std::error_code ec;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("drapelab") : path.string();
}

}  // namespace drapelab::sweep
