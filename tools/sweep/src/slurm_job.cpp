#include "drapelab/sweep/slurm_job.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "drapelab/run_folder/csv.hpp"
#include "drapelab/runner/run_scene.hpp"

namespace drapelab::sweep {

namespace fs = std::filesystem;

namespace {

// A word for bash: single-quoted, with each ' written as '\''.
std::string bash_word(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

CommandOutput run_command(const std::vector<std::string>& arguments) {
  CommandOutput output;
  int pipe_ends[2];
  if (::pipe2(pipe_ends, O_CLOEXEC) != 0) {
    output.text = std::string("cannot make a pipe: ") + std::strerror(errno);
    return output;
  }
  ChildLaunch launch;
  launch.program = arguments.at(0);
  launch.search_path = true;
  launch.arguments = arguments;
  launch.output_descriptor = pipe_ends[1];
  std::string error;
  const std::optional<pid_t> pid = spawn_child(launch, &error);
  ::close(pipe_ends[1]);
  if (!pid) {
    ::close(pipe_ends[0]);
    output.text = error;
    return output;
  }
  output.started = true;
  char buffer[4096];
  for (;;) {
    const ssize_t got = ::read(pipe_ends[0], buffer, sizeof buffer);
    if (got > 0)
      output.text.append(buffer, static_cast<std::size_t>(got));
    else if (got == 0 || errno != EINTR)
      break;
  }
  ::close(pipe_ends[0]);
  int status = 0;
  while (::waitpid(*pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) output.exit_code = WEXITSTATUS(status);
  while (!output.text.empty() && (output.text.back() == '\n' || output.text.back() == ' '))
    output.text.pop_back();
  return output;
}

std::optional<std::string> missing_slurm_command() {
  const char* path = std::getenv("PATH");
  const std::string directories = path ? path : "";
  for (const std::string command : {"sbatch", "squeue", "scancel"}) {
    bool found = false;
    std::size_t begin = 0;
    while (!found && begin <= directories.size()) {
      std::size_t end = directories.find(':', begin);
      if (end == std::string::npos) end = directories.size();
      const std::string directory = directories.substr(begin, end - begin);
      const fs::path candidate = fs::path(directory.empty() ? "." : directory) / command;
      found = ::access(candidate.c_str(), X_OK) == 0;
      begin = end + 1;
    }
    if (!found) return command;
  }
  return std::nullopt;
}

fs::path slurm_folder(const fs::path& sweep) { return sweep / "slurm"; }
fs::path task_script_path(const fs::path& sweep) { return slurm_folder(sweep) / "task.sh"; }
fs::path task_status_path(const fs::path& sweep, std::size_t index) {
  return slurm_folder(sweep) / "status" / (std::to_string(index) + ".txt");
}

std::string task_script(const fs::path& sweep, const fs::path& workdir,
                        const std::vector<SlurmTask>& tasks) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
       "# One combination of a drapelab sweep per Slurm array task (written by drapelab sweep\n"
       "# --engine slurm). The status file is written last, whole, by a rename: the sweep reads a\n"
       "# task as finished only once it exists.\n"
       "cd "
    << bash_word(workdir.string())
    << " || exit 1\n"
       "export OMP_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"\n"
       "case \"$SLURM_ARRAY_TASK_ID\" in\n";
  for (const auto& task : tasks) {
    s << "  " << task.index << ")\n    log=" << bash_word(task.log.string()) << "\n    set --";
    for (const auto& argument : task.arguments) s << " " << bash_word(argument);
    s << " ;;\n";
  }
  s << "  *) echo \"drapelab sweep: no combination $SLURM_ARRAY_TASK_ID\" >&2; exit 1 ;;\n"
       "esac\n"
       "status_dir="
    << bash_word((slurm_folder(sweep) / "status").string())
    << "\n"
       // scancel and the time limit send SIGTERM to every process of the task: drapelab run stops
       // after its current step with valid files, and the script, told only to note it, goes on
       // to write the status once the run has ended.
       "stopped=0\n"
       "trap 'stopped=1' TERM\n"
       "started=$(date +%s.%N)\n"
       "\"$@\" >\"$log\" 2>&1 &\n"
       "child=$!\n"
       // wait returns early when a trapped signal arrives: wait again until the run has ended.
       "while :; do wait \"$child\"; code=$?; kill -0 \"$child\" 2>/dev/null || break; done\n"
       "ended=$(date +%s.%N)\n"
       "status=\"$status_dir/$SLURM_ARRAY_TASK_ID.txt\"\n"
       "printf 'exit_code=%s\\nstarted=%s\\nended=%s\\nstopped_by_slurm=%s\\n' \"$code\" "
       "\"$started\" \"$ended\" \"$stopped\" >\"$status.partial\"\n"
       "mv -f \"$status.partial\" \"$status\"\n"
       "exit \"$code\"\n";
  return s.str();
}

std::string array_ranges(const std::vector<std::size_t>& indices) {
  std::string text;
  for (std::size_t k = 0; k < indices.size();) {
    std::size_t end = k;
    while (end + 1 < indices.size() && indices[end + 1] == indices[end] + 1) ++end;
    text += (text.empty() ? "" : ",") + std::to_string(indices[k]);
    if (end > k) text += "-" + std::to_string(indices[end]);
    k = end + 1;
  }
  return text;
}

std::vector<std::string> sbatch_arguments(const SlurmOptions& options, const std::string& job_name,
                                          const fs::path& sweep,
                                          const std::vector<std::size_t>& indices) {
  std::string array = array_ranges(indices);
  if (options.most_running > 0) array += "%" + std::to_string(options.most_running);
  std::vector<std::string> arguments{"--parsable", "--job-name=" + job_name, "--array=" + array,
                                     "--cpus-per-task=" + std::to_string(options.cpus_per_task),
                                     "--output=" + (slurm_folder(sweep) / "task_%a.out").string()};
  if (!options.partition.empty()) arguments.push_back("--partition=" + options.partition);
  if (!options.time_limit.empty()) arguments.push_back("--time=" + options.time_limit);
  // Last before the script, so that they can override any option above.
  arguments.insert(arguments.end(), options.extra.begin(), options.extra.end());
  arguments.push_back(task_script_path(sweep).string());
  return arguments;
}

std::optional<std::string> submit_array(const std::vector<std::string>& sbatch_args,
                                        std::string* error) {
  std::vector<std::string> command{"sbatch"};
  command.insert(command.end(), sbatch_args.begin(), sbatch_args.end());
  const CommandOutput output = run_command(command);
  if (!output.started) {
    *error = output.text + " (Slurm's sbatch must be on PATH)";
    return std::nullopt;
  }
  // --parsable prints "jobid" or "jobid;cluster" on the last line.
  const std::string last = output.text.substr(output.text.find_last_of('\n') + 1);
  const std::string id = last.substr(0, last.find(';'));
  const bool numeric = !id.empty() && id.find_first_not_of("0123456789") == std::string::npos;
  if (output.exit_code != 0 || !numeric) {
    *error = "sbatch failed" +
             (output.exit_code > 0 ? " (exit code " + std::to_string(output.exit_code) + ")"
                                   : std::string()) +
             ": " + (output.text.empty() ? "no output" : output.text);
    return std::nullopt;
  }
  return id;
}

std::optional<std::set<std::size_t>> queued_tasks(const std::string& job_id, std::string* error) {
  // -r: one line per array task (pending ones too); %K: the task's array index.
  const CommandOutput output =
      run_command({"squeue", "--noheader", "--array", "--jobs=" + job_id, "--format=%K"});
  std::set<std::size_t> tasks;
  if (!output.started || output.exit_code != 0) {
    // A job that has left the controller's memory altogether is "Invalid job id": none queued.
    if (output.started && output.text.find("Invalid job id") != std::string::npos) return tasks;
    *error = "squeue failed: " + output.text;
    return std::nullopt;
  }
  std::istringstream lines(output.text);
  std::string line;
  while (std::getline(lines, line)) {
    const auto value = run_folder::parse_number(line);
    if (value && *value >= 0) tasks.insert(static_cast<std::size_t>(*value));
  }
  return tasks;
}

bool cancel_job(const std::string& job_id, std::string* error) {
  const CommandOutput output = run_command({"scancel", job_id});
  if (output.started && output.exit_code == 0) return true;
  *error = "scancel " + job_id + " failed: " + output.text;
  return false;
}

std::optional<TaskEnd> read_task_end(const fs::path& status_file) {
  std::ifstream in(status_file);
  if (!in) return std::nullopt;
  std::optional<double> code, started, ended, stopped;
  std::string line;
  while (std::getline(in, line)) {
    const auto equals = line.find('=');
    if (equals == std::string::npos) continue;
    const std::string key = line.substr(0, equals);
    const auto value = run_folder::parse_number(line.substr(equals + 1));
    if (key == "exit_code") code = value;
    if (key == "started") started = value;
    if (key == "ended") ended = value;
    if (key == "stopped_by_slurm") stopped = value;
  }
  if (!code || !started || !ended || !stopped) return std::nullopt;
  TaskEnd end;
  const int exit_code = static_cast<int>(*code);
  // bash reports a command killed by signal N as 128 + N. drapelab run's own exit codes are 0, 1,
  // 2 and 130 (interrupted), so any other code above 128 is a signal.
  if (exit_code > 128 && exit_code != runner::kExitInterrupted) {
    end.exit.exited = false;
    end.exit.signal = exit_code - 128;
  } else {
    end.exit.exited = true;
    end.exit.code = exit_code;
  }
  end.wall_seconds = *ended - *started;
  end.stopped_by_slurm = *stopped != 0.0;
  return end;
}

}  // namespace drapelab::sweep
