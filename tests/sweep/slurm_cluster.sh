#!/usr/bin/env bash
# slurm_cluster.sh - start or stop a private one-node Slurm cluster for a test.
#
# Usage:
#   slurm_cluster.sh start DIR   # DIR: a fresh temporary folder owned by the test
#   slurm_cluster.sh stop DIR
#
# `start` runs munged, slurmctld and slurmd (as root) with every file they use
# (munge key, sockets, slurm.conf, state, spool, pid and log files) inside DIR,
# waits until the node is idle, and prints as its last stdout line
#   SLURM_CONF=DIR/slurm.conf
# With that variable exported, sbatch/squeue/scontrol/sinfo talk to this cluster.
# The daemons listen on two free TCP ports (not 6817/6818) and are reached on
# 127.0.0.1. There is no accounting (sacct does not work); finished jobs stay
# visible to `scontrol -o show job ID` (JobState=..., ExitCode=code:signal)
# for MinJobAge (600 s). A job whose afterok dependency failed is cancelled
# (DependencyParameters=kill_invalid_depend) instead of pending forever.
#
# `stop` cancels the cluster's jobs and ends the processes that `start` left
# in DIR (checked by pid file and command line, never by name). It is safe to
# run twice, or after a failed or partial start.
#
# Needs: Debian 12 (bookworm) packages slurm-wlm and munge (installed with
# apt-get when missing), root, and a DIR path of at most 80 characters (unix
# socket paths are limited to 108 bytes).
#
# Exit codes: 0 ok, 77 skipped (prints `SKIP: <reason>` on stdout),
#             1 failure (message on stderr; start stops whatever it started).

set -uo pipefail

readonly PROG=${0##*/}
readonly READY_TIMEOUT=30   # seconds to wait for the node to become idle
readonly STOP_TIMEOUT=15    # seconds to wait for a daemon to exit on SIGTERM
readonly MAX_DIR_LEN=80
DIR=""

# ---------------------------------------------------------------- messages

log() { echo "$PROG: $*" >&2; }

skip() {
    echo "SKIP: $*"
    exit 77
}

# Stops what was started, shows the daemons' log tails and exits 1.
fail() {
    log "error: $*"
    show_log_tails
    stop_cluster
    exit 1
}

show_log_tails() {
    local f
    for f in "$DIR"/log/*; do
        [[ -s $f ]] || continue
        echo "---- last lines of $f ----" >&2
        tail -n 15 "$f" >&2
    done
}

# ---------------------------------------------------------------- packages

have_tools() {
    local tool
    for tool in sbatch sinfo scontrol squeue scancel slurmctld slurmd munged munge unmunge; do
        command -v "$tool" >/dev/null || return 1
    done
}

apt_install() {
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
        slurm-wlm munge
}

ensure_packages() {
    have_tools && return 0
    command -v apt-get >/dev/null || skip "slurm-wlm/munge are not installed and there is no apt-get"
    log "installing slurm-wlm and munge"
    if ! apt_install >"$DIR/log/apt.log" 2>&1; then
        DEBIAN_FRONTEND=noninteractive apt-get update >>"$DIR/log/apt.log" 2>&1
        apt_install >>"$DIR/log/apt.log" 2>&1 || fail "apt-get install slurm-wlm munge failed"
    fi
    have_tools || fail "slurm tools still missing after installing slurm-wlm and munge"
}

# ---------------------------------------------------------------- processes

# Writes the pid of a daemon we launched, NAME.pid in DIR/pids.
record_pid() { echo "$2" >"$DIR/pids/$1.pid"; }

# Prints the recorded pid of NAME if that process is alive and is ours
# (its command line mentions DIR: the daemon's options, or for a moment after
# launch, before the exec, this script's own "start DIR"); else nothing.
our_pid() {
    local file="$DIR/pids/$1.pid" pid cmd
    [[ -r $file ]] || return 0
    pid=$(<"$file")
    [[ $pid =~ ^[0-9]+$ ]] || return 0
    cmd=" $({ tr '\0' ' ' <"/proc/$pid/cmdline"; } 2>/dev/null)"
    [[ $cmd == *[=\ ]"$DIR/"* || $cmd == *" $DIR " ]] && echo "$pid"
    return 0
}

# Sends SIGTERM to the PIDs at once (each daemon takes ~2 s to exit), waits
# up to STOP_TIMEOUT s for all of them, then SIGKILLs the rest.
end_processes() {
    local pid i alive
    (($# > 0)) || return 0
    kill -TERM "$@" 2>/dev/null
    for ((i = 0; i < STOP_TIMEOUT * 10; i++)); do
        alive=()
        for pid in "$@"; do kill -0 "$pid" 2>/dev/null && alive+=("$pid"); done
        ((${#alive[@]} > 0)) || return 0
        sleep 0.1
    done
    log "pids ${alive[*]} ignored SIGTERM; sending SIGKILL"
    kill -KILL "${alive[@]}" 2>/dev/null
    sleep 0.2
}

# Pids of slurmstepd processes spawned by this cluster's slurmd: slurmd runs
# with SLURM_CONF=DIR/slurm.conf in its environment and they inherit it.
our_stepds() {
    local env_file pid
    for env_file in /proc/[0-9]*/environ; do
        pid=${env_file#/proc/}
        pid=${pid%/environ}
        [[ $(cat "/proc/$pid/comm" 2>/dev/null) == slurmstepd ]] || continue
        [[ $'\n'$({ tr '\0' '\n' <"$env_file"; } 2>/dev/null)$'\n' == \
            *$'\n'"SLURM_CONF=$DIR/slurm.conf"$'\n'* ]] && echo "$pid"
    done
}

# Prints PID's descendants (children first found, then theirs).
descendants() {
    local child
    for child in $(ps -o pid= --ppid "$1" 2>/dev/null); do
        echo "$child"
        descendants "$child"
    done
}

# Last resort for steps that outlived scancel (e.g. slurmctld had died):
# ends each slurmstepd of this cluster together with the job processes under it.
end_stepds() {
    local stepd pid
    for stepd in $(our_stepds); do
        for pid in $(descendants "$stepd") "$stepd"; do
            kill -KILL "$pid" 2>/dev/null
        done
    done
}

# Launches NAME (a command line) in its own session, detached from our stdio,
# and records its pid.
launch() {
    local name=$1
    shift
    setsid "$@" </dev/null >>"$DIR/log/$name.out" 2>&1 &
    record_pid "$name" "$!"
}

# ---------------------------------------------------------------- ports

# Local TCP ports in use (any state), one per line, from /proc/net/tcp{,6}.
used_ports() {
    local f
    for f in /proc/net/tcp /proc/net/tcp6; do
        [[ -r $f ]] || continue
        while read -r _ local_addr _; do
            [[ $local_addr == *:* ]] && echo $((16#${local_addr##*:}))
        done <"$f"
    done
}

# Prints N distinct free ports below the ephemeral range.
free_ports() {
    local n=$1 used port found=()
    used=" $(used_ports | tr '\n' ' ') "
    while ((${#found[@]} < n)); do
        port=$((20000 + RANDOM % 12000))
        [[ $used == *" $port "* ]] && continue
        used+="$port "
        found+=("$port")
    done
    echo "${found[@]}"
}

# ---------------------------------------------------------------- munge

start_munge() {
    local d="$DIR/munge"
    mkdir -m 0755 "$d" || fail "cannot create $d"
    dd if=/dev/urandom of="$d/munge.key" bs=1 count=1024 status=none ||
        fail "could not write the munge key"
    chmod 0400 "$d/munge.key"
    # --force: accept a socket directory whose parents (e.g. /tmp, a build
    # tree) munged would otherwise call insecure. In --foreground mode munged
    # logs to stderr, which launch() sends to log/munged.out.
    launch munged munged --foreground --force \
        --socket="$d/munge.socket" --key-file="$d/munge.key" \
        --pid-file="$d/munged.pid" --seed-file="$d/munged.seed"
    wait_for "munged" munge_works 10 || fail "munged did not start"
}

munge_works() {
    munge --socket="$DIR/munge/munge.socket" -n 2>/dev/null |
        unmunge --socket="$DIR/munge/munge.socket" >/dev/null 2>&1
}

# ---------------------------------------------------------------- slurm

# Prints "CPUs=.. Boards=.. ... RealMemory=.." for this machine.
node_hardware() {
    slurmd -C 2>/dev/null | head -n 1 | sed -E 's/^NodeName=[^ ]+ //'
}

write_slurm_conf() {
    local host=$1 ctld_port=$2 slurmd_port=$3 hw
    hw=$(node_hardware)
    [[ $hw == *CPUs=* && $hw == *RealMemory=* ]] || fail "slurmd -C gave no hardware line"
    cat >"$DIR/slurm.conf" <<EOF
# Generated by $PROG for a one-node test cluster; everything lives in $DIR.
ClusterName=inimtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge/munge.socket
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/run/slurmctld.pid
SlurmdPidFile=$DIR/run/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$DIR/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=600
DependencyParameters=kill_invalid_depend
KillWait=5
InactiveLimit=0
SlurmdTimeout=60
MailProg=/bin/true
NodeName=$host NodeAddr=127.0.0.1 NodeHostname=$host $hw State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
    : >"$DIR/plugstack.conf"
}

start_slurm() {
    local host=$1
    export SLURM_CONF="$DIR/slurm.conf"
    launch slurmctld slurmctld -D -i -f "$SLURM_CONF"
    wait_for "slurmctld" ctld_answers 15 || fail "slurmctld did not answer"
    launch slurmd slurmd -D -N "$host" -f "$SLURM_CONF"
    wait_for "the node to be idle" node_idle "$READY_TIMEOUT" ||
        fail "node $host not idle after ${READY_TIMEOUT}s (state: $(sinfo -h -o %T 2>&1))"
}

ctld_answers() {
    [[ -n $(our_pid slurmctld) ]] || fail "slurmctld exited"
    [[ $(scontrol ping 2>/dev/null) == *"is UP"* ]]
}

node_idle() {
    [[ -n $(our_pid slurmd) ]] || fail "slurmd exited"
    [[ $(sinfo -h -o %T 2>/dev/null) == idle ]]
}

# wait_for WHAT CHECK SECONDS: polls CHECK every 0.2 s.
wait_for() {
    local what=$1 check=$2 secs=$3 i
    for ((i = 0; i < secs * 5; i++)); do
        "$check" && return 0
        sleep 0.2
    done
    log "timed out after ${secs}s waiting for $what"
    return 1
}

# ---------------------------------------------------------------- start/stop

# The daemons run as root (SlurmUser=root) and apt-get needs root too.
require_root() {
    [[ $EUID -eq 0 ]] && return 0
    have_tools || skip "slurm-wlm/munge are not installed and we are not root"
    skip "munged/slurmctld/slurmd must run as root here"
}

check_dir() {
    [[ -n $DIR ]] || usage
    [[ ${#DIR} -le $MAX_DIR_LEN ]] ||
        { log "DIR is longer than $MAX_DIR_LEN characters (unix socket limit): $DIR"; exit 1; }
}

start_cluster() {
    local host ctld_port slurmd_port
    require_root
    mkdir -p "$DIR" || { log "cannot create $DIR"; exit 1; }
    DIR=$(cd "$DIR" && pwd -P)
    check_dir
    [[ -z $(our_pid slurmctld)$(our_pid slurmd)$(our_pid munged) ]] ||
        { log "a cluster is already running in $DIR"; exit 1; }
    [[ ! -e $DIR/pids ]] ||
        { log "$DIR was used by an earlier start: give a fresh DIR"; exit 1; }
    mkdir -p "$DIR"/{log,pids,run,state,spool} || { log "cannot write in $DIR"; exit 1; }
    trap 'fail "interrupted"' INT TERM HUP
    ensure_packages
    host=$(hostname -s) || fail "hostname -s failed"
    read -r ctld_port slurmd_port <<<"$(free_ports 2)"
    start_munge
    write_slurm_conf "$host" "$ctld_port" "$slurmd_port"
    start_slurm "$host"
    trap - INT TERM HUP
    echo "SLURM_CONF=$DIR/slurm.conf"
}

# Cancels all jobs while slurmctld is still up, so their steps end cleanly.
cancel_jobs() {
    local ids i
    [[ -n $(our_pid slurmctld) && -r $DIR/slurm.conf ]] || return 0
    # %F: the array's job id (or the plain job id), so no "1_[2-3]" forms.
    mapfile -t ids < <(SLURM_CONF="$DIR/slurm.conf" timeout 10 squeue -h -o %F 2>/dev/null | sort -u)
    ((${#ids[@]} > 0)) || return 0
    SLURM_CONF="$DIR/slurm.conf" timeout 10 scancel "${ids[@]}" 2>/dev/null
    for ((i = 0; i < 50; i++)); do
        [[ -z $(our_stepds) ]] && return 0
        sleep 0.2
    done
}

stop_cluster() {
    local name pid pids=()
    [[ -d $DIR/pids ]] || return 0
    cancel_jobs
    end_stepds
    for name in slurmd slurmctld munged; do
        pid=$(our_pid "$name")
        [[ -n $pid ]] && pids+=("$pid")
    done
    end_processes "${pids[@]}"
    rm -f "$DIR"/pids/*.pid
    return 0
}

usage() {
    echo "usage: $PROG start|stop DIR" >&2
    exit 1
}

main() {
    [[ $# -eq 2 ]] || usage
    DIR=$2
    case $1 in
    start) start_cluster ;;
    stop)
        [[ -d $DIR ]] || exit 0
        DIR=$(cd "$DIR" && pwd -P)
        stop_cluster
        ;;
    *) usage ;;
    esac
}

main "$@"
