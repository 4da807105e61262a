#!/usr/bin/env bash
# Starts and stops a private one-node Slurm cluster (munged, slurmctld, slurmd on this machine) for
# the tests of `drapelab sweep --engine slurm`. It needs no systemd, no cgroups, no accounting
# database, and leaves /etc/slurm and /etc/munge alone: everything lives in one state directory.
# Uses sudo for the daemons when not root (slurmd must be root to run jobs as the submitting user).
#
# Usage: tools/slurm-local.sh start | stop | status
#   start   starts the cluster (or finds it running) and waits until its node is idle (1 s or so;
#           gives up after 60 s, showing the ends of the logs). Prints exactly one line on stdout,
#             export SLURM_CONF=<state directory>/slurm.conf
#           which points sbatch, squeue, scancel and sinfo at the cluster; everything else goes to
#           stderr. In a script with set -e:
#             slurm_env=$(tools/slurm-local.sh start)   # a failed start stops the script here,
#             eval "$slurm_env"                         # not so with eval "$(...)"
#   stop    cancels the cluster's jobs and stops its three daemons (pid files in the state
#           directory); touches no other process or Slurm.
#   status  exits 0 if the cluster is running, 1 if not.
# Exits 2 if a program is missing (run tools/install-deps.sh), 1 if the cluster does not start.
#
# State directory: $DRAPELAB_SLURM_DIR, default /tmp/drapelab-slurm, owned by root:
#   slurm.conf, munge/ (key, socket), run/ (pid files), spool/ (emptied at every start),
#   log/munged.log, log/slurmctld.log, log/slurmd.log (the previous run's as *.log.prev)
# Ports: slurmctld on $DRAPELAB_SLURM_PORT (default 6817), slurmd on the next one.
set -euo pipefail

usage="usage: tools/slurm-local.sh start | stop | status"
command=${1:-}
case "$command" in
  start | stop | status) ;;
  *) echo "$usage" >&2; exit 2 ;;
esac

# Only the export line of `start` may reach stdout (callers eval it); fd 3 keeps the real stdout.
exec 3>&1 1>&2

dir=${DRAPELAB_SLURM_DIR:-/tmp/drapelab-slurm}
dir=$(realpath -m "$dir")  # absolute: slurm.conf and the daemons' command lines name it
conf=$dir/slurm.conf
port=${DRAPELAB_SLURM_PORT:-6817}
export SLURM_CONF=$conf

# The daemons live in /usr/sbin, which is not on a normal user's PATH on Debian.
find_program() {
  local name=$1 path
  path=$(PATH=$PATH:/usr/local/sbin:/usr/sbin:/sbin command -v "$name" || true)
  if [[ -z "$path" ]]; then
    echo "slurm-local: $name is missing; run tools/install-deps.sh" >&2
    exit 2
  fi
  echo "$path"
}
munged=$(find_program munged)
slurmctld=$(find_program slurmctld)
slurmd=$(find_program slurmd)
find_program sbatch >/dev/null
for client in sinfo squeue scancel scontrol; do
  find_program "$client" >/dev/null
done

# status reads only /proc and asks the controller, so it needs no sudo.
as_root=()
if [[ $(id -u) -ne 0 && "$command" != status ]]; then
  if ! command -v sudo >/dev/null; then
    echo "slurm-local: the Slurm daemons run as root; run this script as root or install sudo" >&2
    exit 1
  fi
  as_root=(sudo)
fi

# pid of a daemon we started, if it is still running. A pid file left by a daemon killed with -9
# may name a reused pid, so the process must also have the right name and our state directory on
# its command line.
daemon_pid() {
  local name=$1 pid cmdline
  pid=$(cat "$dir/run/$name.pid" 2>/dev/null || true)
  [[ "$pid" =~ ^[0-9]+$ ]] || return 1
  [[ "$(cat "/proc/$pid/comm" 2>/dev/null)" == "$name" ]] || return 1
  cmdline=$(tr '\0' ' ' 2>/dev/null <"/proc/$pid/cmdline") || return 1
  [[ "$cmdline" == *"$dir/"* ]] || return 1
  echo "$pid"
}

daemons_up() {
  daemon_pid munged >/dev/null && daemon_pid slurmctld >/dev/null && daemon_pid slurmd >/dev/null
}

# A zombie is not alive: PID 1 of a container need not reap the daemons' orphans promptly.
process_alive() {
  local state
  state=$(awk '{ print $3 }' "/proc/$1/stat" 2>/dev/null || true)
  [[ -n "$state" && "$state" != Z ]]
}

# SIGTERM to all three at once, then SIGKILL to any still there after 5 s (a slurmd that cannot
# reach its controller does not exit on SIGTERM). No state needs saving: the next start empties it.
stop_daemons() {
  local name pid pids=() i alive
  for name in slurmd slurmctld munged; do
    pid=$(daemon_pid "$name") || continue
    pids+=("$pid")
    "${as_root[@]}" kill -TERM "$pid" 2>/dev/null || true
  done
  for ((i = 0; i < 50; i++)); do
    alive=0
    for pid in ${pids[@]+"${pids[@]}"}; do
      if process_alive "$pid"; then alive=1; fi
    done
    ((alive)) || return 0
    sleep 0.1
  done
  for pid in "${pids[@]}"; do
    if process_alive "$pid"; then
      echo "slurm-local: $(cat "/proc/$pid/comm" 2>/dev/null) (pid $pid) ignored SIGTERM;" \
        "killing it" >&2
      "${as_root[@]}" kill -KILL "$pid" 2>/dev/null || true
    fi
  done
}

# Stopping slurmd leaves its jobs' processes running (slurmd is meant to be restartable under
# them), and the next start empties the spool they use, so the cluster's own jobs are cancelled
# first. Only this cluster's controller is asked (SLURM_CONF), so no other Slurm is touched.
# Without a slurmd the controller cannot end them (they would stay COMPLETING): kill_orphan_steps
# does.
cancel_jobs() {
  local jobs i
  if ! daemon_pid slurmd >/dev/null || ! daemon_pid slurmctld >/dev/null ||
    ! scontrol ping >/dev/null 2>&1; then
    return 0
  fi
  jobs=$(squeue -h -o %A 2>/dev/null | sort -u | tr '\n' ' ' || true)
  [[ -n "${jobs// /}" ]] || return 0
  echo "slurm-local: cancelling the jobs still in the cluster: $jobs" >&2
  # shellcheck disable=SC2086  # one argument per job id
  "${as_root[@]}" env SLURM_CONF="$conf" scancel $jobs || true
  # KillWait is 2 s; wait for the jobs' processes to be gone before slurmd goes.
  for ((i = 0; i < 100; i++)); do
    [[ -z "$(squeue -h -o %A 2>/dev/null)" ]] && return 0
    sleep 0.1
  done
  echo "slurm-local: some jobs were still ending after 10 s: $(squeue -h -o %A | tr '\n' ' ')" >&2
}

# Job steps of a slurmd that died (killed with -9, or stopped while its controller was gone) keep
# running their jobs' processes. They are found by their working directory: slurmd works in the
# directory of its log file, here $dir/log, and each slurmstepd it starts inherits that. Each is
# killed with all its descendants (the batch script and whatever it started).
kill_orphan_steps() {
  local comm name pid steps=() tree
  # A process may end between the glob and the read: its files are then gone. Redirections apply
  # left to right, so stderr goes to /dev/null before the file is opened, or bash's own "No such
  # file or directory" for the failed open would still reach the terminal.
  for comm in /proc/[0-9]*/comm; do
    read -r name 2>/dev/null <"$comm" || continue
    [[ "$name" == slurmstepd ]] || continue
    pid=${comm#/proc/}
    pid=${pid%/comm}
    if [[ "$("${as_root[@]}" readlink "/proc/$pid/cwd" 2>/dev/null)" == "$dir/log" ]]; then
      steps+=("$pid")
    fi
  done
  ((${#steps[@]} > 0)) || return 0
  # pid and parent pid of every process, from /proc (procps may be missing in a container); the
  # name in parentheses may contain spaces, so the fields are counted after its closing one.
  tree=$({ cat /proc/[0-9]*/stat 2>/dev/null || true; } | awk -v roots="${steps[*]}" '
    { rest = $0; sub(/.*\) /, "", rest); split(rest, field, " "); parent[$1] = field[2] }
    END {
      n = split(roots, root, " ")
      for (i = 1; i <= n; i++) keep[root[i]] = 1
      do {
        changed = 0
        for (p in parent) if (!(p in keep) && (parent[p] in keep)) { keep[p] = 1; changed = 1 }
      } while (changed)
      for (p in keep) printf "%s ", p
    }')
  echo "slurm-local: killing the job steps left by an earlier slurmd: ${steps[*]}" >&2
  # shellcheck disable=SC2086  # one argument per pid
  "${as_root[@]}" kill -KILL $tree 2>/dev/null || true
}

stop_all() {
  cancel_jobs
  stop_daemons
  kill_orphan_steps
}

# Runs a daemon (which forks into the background) with no file descriptor of ours but stdin, stdout
# and stderr: munged keeps every other descriptor open for its whole life, so fd 3, the stdout of
# `$(tools/slurm-local.sh start)`, would keep that command substitution waiting forever. (sudo
# closes them by itself; without sudo nothing does.) The daemons then set stdin, stdout and stderr
# to /dev/null; what they print before that is an early error the caller should see.
launch() {
  (
    for fd in "/proc/$BASHPID/fd"/*; do
      fd=${fd##*/}
      if ((fd > 2)); then eval "exec $fd>&-" 2>/dev/null || true; fi
    done
    exec "${as_root[@]}" "$@"
  )
}

show_logs() {
  local log
  for log in munged slurmctld slurmd; do
    echo "--- last lines of $dir/log/$log.log" >&2
    "${as_root[@]}" tail -n 15 "$dir/log/$log.log" >&2 2>/dev/null || echo "(no log)" >&2
  done
}

node_name() {
  # The node and the controller are this machine under its short hostname (slurmctld insists that
  # its own name is the SlurmctldHost). NodeAddr=127.0.0.1 means the name needs no resolving, but
  # Slurm still looks it up in places, so fall back to localhost if it does not resolve.
  local name
  name=$(hostname -s 2>/dev/null || true)
  if [[ -n "$name" ]] && getent hosts "$name" >/dev/null; then
    echo "$name"
  else
    echo localhost
  fi
}

write_conf() {
  local node=$1 cpus memory_mb
  cpus=$(nproc)
  # slurmd drains a node that has less memory than configured; claim 90 % of what it has.
  memory_mb=$(awk '/^MemTotal:/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
  "${as_root[@]}" tee "$conf" >/dev/null <<EOF
# Written by tools/slurm-local.sh on every start; edits are lost.
ClusterName=drapelab
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
# The daemons run as root (slurmd must be, to run each job as the user who submitted it).
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
# Our own munged and key: the system one is not started without systemd, and /etc/munge stays as is.
AuthInfo=socket=$dir/munge/munge.socket.2
StateSaveLocation=$dir/spool/slurmctld
SlurmdSpoolDir=$dir/spool/slurmd
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No systemd and no cgroup delegation in containers: track job processes through /proc, bind
# nothing, gather no usage, keep no accounting.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
MailProg=/bin/true
# One CPU per array task by default, so the tasks of a sweep run side by side, nproc at a time.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
# Strict priority order suffices for one node. Pending jobs are started by the controller's
# background pass, once a second: sched_interval=1 (default 60 s) and batch_sched_delay=0 (default
# 3 s) let every pass start batch jobs. Measured: a task starts within about 1 s of its submission
# or of a CPU becoming free; the first job after a start waits until the controller is about 3 s
# old.
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1,batch_sched_delay=0
# Array indices 0..1000.
MaxArraySize=1001
MaxJobCount=10000
# squeue drops a job as soon as it ends; its final state and exit code stay in scontrol show job
# (and squeue -t all) until it is purged, MinJobAge seconds later rounded up to the controller's
# purge pass: 2 to about 12 s here, not 5 minutes. After that, squeue -j <id> exits 1 with
# "Invalid job id specified". 2 s is the smallest value the manual recommends.
MinJobAge=2
# scancel: SIGTERM, then SIGKILL 2 s later (default 30 s).
KillWait=2
InactiveLimit=0
Waittime=0
# A node that was DOWN (e.g. slurmd restarted or killed) is idle again once its slurmd registers.
ReturnToService=2
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

# The logs are kept; the daemons that did start are stopped, so that the next start is clean.
start_failed() {
  echo "slurm-local: $1" >&2
  show_logs
  stop_all
  echo "slurm-local: the cluster did not start; logs in $dir/log" >&2
  exit 1
}

# The two ports must be free: another Slurm (or an earlier cluster whose state directory was
# deleted) would make slurmctld or slurmd exit with "Address already in use".
check_ports() {
  local p
  for p in "$port" "$((port + 1))"; do
    if (exec 4<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then
      echo "slurm-local: port $p is in use (another Slurm?); set DRAPELAB_SLURM_PORT to another" \
        "port for slurmctld (slurmd uses the next one)" >&2
      exit 1
    fi
  done
}

start() {
  local node munge_key log state deadline grace name
  # A controller slow to answer is no reason to restart the cluster under running jobs: if the
  # three daemons are up, the cluster is.
  if daemons_up; then
    echo "slurm-local: already running ($conf)" >&2
    echo "export SLURM_CONF=$conf" >&3
    return 0
  fi
  # Whatever is left of an earlier run (a daemon still up while another died) goes first.
  stop_all
  check_ports

  node=$(node_name)
  "${as_root[@]}" install -d -m 0755 -o root -g root "$dir" "$dir/munge" "$dir/run" "$dir/log"
  # Jobs, node states and job ids of an earlier run (possibly killed with -9) would be recovered
  # from the spool and can keep the node down or drained: every start begins empty.
  "${as_root[@]}" rm -rf "$dir/spool" "$dir/munge/munge.socket.2" "$dir/munge/munge.socket.2.lock"
  "${as_root[@]}" rm -f "$dir/run/munged.pid" "$dir/run/slurmctld.pid" "$dir/run/slurmd.pid"
  "${as_root[@]}" install -d -m 0755 -o root -g root "$dir/spool" "$dir/spool/slurmctld" \
    "$dir/spool/slurmd"
  for log in munged slurmctld slurmd; do
    if [[ -e "$dir/log/$log.log" ]]; then
      "${as_root[@]}" mv -f "$dir/log/$log.log" "$dir/log/$log.log.prev"
    fi
  done
  write_conf "$node"

  munge_key=$dir/munge/munge.key
  if ! "${as_root[@]}" test -s "$munge_key"; then
    echo "slurm-local: creating the munge key $munge_key" >&2
    # shellcheck disable=SC2016  # $1 is expanded by that sh
    "${as_root[@]}" sh -c 'umask 077 && head -c 1024 /dev/urandom >"$1"' sh "$munge_key"
  fi

  echo "slurm-local: starting munged, slurmctld and slurmd (node $node, state in $dir)" >&2
  # --force: munged refuses a socket or key below a directory owned by anyone but root (say a
  # DRAPELAB_SLURM_DIR in a home directory); the cluster is private, so warnings are enough.
  launch "$munged" --force --socket="$dir/munge/munge.socket.2" --key-file="$munge_key" \
    --seed-file="$dir/munge/munged.seed" --pid-file="$dir/run/munged.pid" \
    --log-file="$dir/log/munged.log" || start_failed "munged did not start"
  launch "$slurmctld" -f "$conf" || start_failed "slurmctld did not start"
  launch "$slurmd" -f "$conf" -N "$node" || start_failed "slurmd did not start"

  # slurmctld and slurmd fork at once and report errors only in their logs: wait for the node to
  # be idle. A client waits up to MessageTimeout (10 s) for an answer, hence the timeout on sinfo.
  deadline=$((SECONDS + 60))
  grace=$((SECONDS + 3))
  while ((SECONDS < deadline)); do
    state=$(timeout 3 sinfo -h -N -n "$node" -o %T 2>/dev/null || true)
    if [[ "$state" == "idle" ]]; then
      echo "slurm-local: running; node $node idle with $(nproc) CPUs" >&2
      echo "export SLURM_CONF=$conf" >&3
      return 0
    fi
    # A daemon that exited will not come back: no need to wait the whole minute. (Its pid file
    # may not be written in the first moments.)
    if ((SECONDS >= grace)); then
      for name in munged slurmctld slurmd; do
        daemon_pid "$name" >/dev/null || start_failed "$name exited during start"
      done
    fi
    sleep 0.1
  done
  start_failed "the node was not idle within 60 s (its state: ${state:-no answer from slurmctld})"
}

case "$command" in
  start)
    start
    ;;
  stop)
    if ! daemon_pid munged >/dev/null && ! daemon_pid slurmctld >/dev/null &&
      ! daemon_pid slurmd >/dev/null; then
      kill_orphan_steps
      echo "slurm-local: not running" >&2
      exit 0
    fi
    stop_all
    echo "slurm-local: stopped" >&2
    ;;
  status)
    if daemons_up && scontrol ping >/dev/null 2>&1; then
      echo "slurm-local: running ($conf)" >&2
      exit 0
    fi
    echo "slurm-local: not running" >&2
    exit 1
    ;;
esac
