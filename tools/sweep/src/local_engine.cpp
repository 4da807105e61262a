// The local engine: each combination a `drapelab run` child process of its own, up to --jobs at a
// time. Separate processes, not threads: a run that crashes or hangs takes only its own row with
// it, and every run folder is exactly what `drapelab run` writes.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>

#include "drapelab/runner/run_scene.hpp"
#include "drapelab/sweep/children.hpp"
#include "drapelab/sweep/engines.hpp"

namespace drapelab::sweep {

using namespace drapelab::runner;

namespace {

// After Ctrl-C, how long the children get to stop after their current step before SIGKILL.
constexpr std::chrono::milliseconds kStopGrace{10000};

// The child currently running one combination.
struct RunningChild {
  std::size_t index = 0;
  pid_t pid = 0;
  std::chrono::steady_clock::time_point started;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::vector<std::size_t> combinations_to_run(const SweepStart& start) {
  std::vector<std::size_t> indices;
  for (std::size_t index = 0; index < start.plan.count(); ++index)
    if (!start.validation.combination_errors[index]) indices.push_back(index);
  return indices;
}

std::vector<std::string> run_arguments(const SweepStart& start, std::size_t index,
                                       const std::string& program) {
  // The run's output goes into its log, which holds no progress lines.
  std::vector<std::string> arguments{program,
                                     "run",
                                     start.arguments.scene,
                                     "--out",
                                     start.folder.run_dir(index).string(),
                                     "--force",
                                     "--no-progress"};
  std::vector<std::string> overrides = start.arguments.overrides;
  const auto varied = start.plan.overrides(index);
  overrides.insert(overrides.end(), varied.begin(), varied.end());
  for (const auto& text : overrides) {
    arguments.emplace_back("--set");
    arguments.push_back(text);
  }
  return arguments;
}

int run_local_sweep(SweepStart& start) {
  SweepFolder& folder = start.folder;
  const int jobs = folder.record().jobs;
  const std::vector<std::size_t> queue = combinations_to_run(start);
  std::size_t next = 0;
  std::vector<RunningChild> running;
  while ((next < queue.size() || !running.empty()) && !start.interrupt.load()) {
    while (static_cast<int>(running.size()) < jobs && next < queue.size() &&
           !start.interrupt.load()) {
      const std::size_t index = queue[next++];
      std::string problem;
      ChildLaunch launch;
      launch.program = "/proc/self/exe";
      launch.arguments = run_arguments(start, index, "drapelab");
      launch.log = folder.log(index);
      const auto pid = spawn_child(launch, &problem);
      if (!pid) {
        folder.finish(unstarted_outcome(index, folder.folder(index), problem));
        continue;
      }
      running.push_back({index, *pid, std::chrono::steady_clock::now()});
    }
    bool any_ended = false;
    for (auto it = running.begin(); it != running.end();) {
      const auto ended = poll_child(it->pid);
      if (!ended) {
        ++it;
        continue;
      }
      auto outcome = finished_outcome(it->index, *ended, folder.run_dir(it->index),
                                      folder.log(it->index), folder.folder(it->index), false);
      outcome.wall_seconds = seconds_since(it->started);
      folder.finish(std::move(outcome));
      it = running.erase(it);
      any_ended = true;
    }
    folder.show_progress(running.size());
    if (!any_ended) std::this_thread::sleep_for(kChildPollPeriod);
  }

  if (start.interrupt.load()) {
    // Ctrl-C: stop the children (they keep their files valid), record them, and stop.
    std::vector<pid_t> pids;
    for (const auto& child : running) pids.push_back(child.pid);
    const auto ends = stop_children(pids, kStopGrace);
    for (std::size_t k = 0; k < running.size(); ++k) {
      const std::size_t index = running[k].index;
      auto outcome = finished_outcome(index, ends[k], folder.run_dir(index), folder.log(index),
                                      folder.folder(index), true);
      outcome.wall_seconds = seconds_since(running[k].started);
      folder.finish(std::move(outcome));
    }
    folder.set_state("interrupted");
    std::cerr << "interrupted; " << (folder.out() / "sweep.csv").string() << " holds the "
              << folder.finished().size() << " of " << start.plan.count()
              << " combinations finished\n";
    return kExitInterrupted;
  }
  folder.set_state("complete");
  return print_tally(folder, start.plan);
}

}  // namespace drapelab::sweep
