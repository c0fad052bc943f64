#!/usr/bin/env bash
# Proves the cluster path on a real Slurm: installs the build into a scratch prefix, starts munged, slurmctld and
# slurmd on localhost (Debian's munge and slurm-wlm, configured here, nothing read from /etc/slurm or /etc/munge),
# submits examples/batch/slurm-array.sbatch as an array of 3 tasks against the installed inkgraph, and checks that
# each task rendered exactly its share (list positions p with p mod 3 = its index), that the shares are disjoint and
# cover the list, and that every picture is byte-identical to the same script run locally as one batch of the
# whole list. Everything lives in one scratch folder; the daemons are stopped and the folder removed on any exit.
# Usage: single-node-slurm.sh BUILD_DIR
# Runs as root or as any user with a name (the daemons then run as that user, as SlurmUser and SlurmdUser).
set -euo pipefail

[ $# -eq 1 ] || { echo "usage: $0 BUILD_DIR" >&2; exit 2; }
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "$1" && pwd)
tasks=3
size=256x256

fail() { echo "single-node-slurm: FAIL: $*" >&2; exit 1; }

for tool in mungekey munged slurmctld slurmd sbatch sinfo squeue scontrol scancel cmake cmp; do
    command -v "$tool" > /dev/null ||
        fail "'$tool' is not installed (scripts/install-deps.sh installs Debian's slurm-wlm and munge)"
done
user=$(id -un 2> /dev/null) || fail "the user id $(id -u) has no name; Slurm's SlurmUser needs one"

# A Slurm job around this test (or a user's Slurm settings) must not steer the Slurm started here, and the installed
# program must find its own shaders and modules, not a developer's override.
while read -r name; do
    unset "$name"
done < <(compgen -e | grep -E '^(SLURM|SBATCH|SALLOC|SRUN|SQUEUE|SINFO|SCONTROL)_' || true)
unset INKGRAPH_SHADER_DIR INKGRAPH_IMAGEIO_MODULE

tmp=$(mktemp -d "${TMPDIR:-/tmp}/inkgraph-slurm.XXXXXX")
chmod 700 "$tmp"
conf=$tmp/slurm.conf
socket=$tmp/munge/munge.socket
# A Unix socket's path holds at most 107 bytes.
if [ ${#socket} -gt 100 ]; then
    rm -rf "$tmp"
    fail "the scratch folder's path is too long for munge's socket: '$socket' (set TMPDIR to a shorter folder)"
fi

# Every process started here (the daemons, the job steps and the job itself) carries SLURM_CONF=$conf in its
# environment, which no other process on the machine has: that is how the teardown finds what is left, by pid. The
# daemons are started with it directly (not through this function) so that $! is the daemon itself.
with_conf() { SLURM_CONF=$conf "$@"; }
munged_pid='' slurmctld_pid='' slurmd_pid='' sbatch_pid='' job=''

process_state() { # R, S, Z, ...; empty once the process is gone
    local stat
    stat=$(cat "/proc/$1/stat" 2> /dev/null) || return 0
    stat=${stat##*) }
    echo "${stat%% *}"
}
stop_daemon() { # pid, name: SIGTERM, 10 s to exit, then SIGKILL; reaped either way
    local pid=$1 name=$2 state
    [ -n "$pid" ] || return 0
    kill -TERM "$pid" 2> /dev/null || true
    for _ in $(seq 100); do
        state=$(process_state "$pid")
        [ -z "$state" ] || [ "$state" = Z ] && break
        sleep 0.1
    done
    state=$(process_state "$pid")
    if [ -n "$state" ] && [ "$state" != Z ]; then
        echo "single-node-slurm: $name (pid $pid) did not stop in 10 s; killing it" >&2
        kill -KILL "$pid" 2> /dev/null || true
    fi
    wait "$pid" 2> /dev/null || true
}
our_leftovers() { # pids of the processes whose environment holds our SLURM_CONF
    grep -lszxF "SLURM_CONF=$conf" /proc/[0-9]*/environ | sed -e 's|^/proc/||' -e 's|/environ$||' || true
}
teardown() {
    local status=$? pids=()
    trap - EXIT INT TERM
    set +e # tear down everything, whatever fails on the way
    stop_daemon "$sbatch_pid" sbatch
    job=$(grep -m1 -E '^[0-9]+$' "$tmp/sbatch.out" 2> /dev/null || true)
    # Slurm's commands retry a controller that is gone for a long time (Ctrl-C stops the daemons too): ask only a
    # live one, briefly.
    if [ -n "$job" ] && [ -n "$slurmctld_pid" ] && alive "$slurmctld_pid" && alive "$slurmd_pid"; then
        with_conf timeout 5 scancel "$job" 2> /dev/null || true
        for _ in $(seq 100); do # the tasks' steps end before slurmd does
            [ -z "$(with_conf timeout 5 squeue -h -j "$job" -o %i 2> /dev/null)" ] && break
            sleep 0.1
        done
    fi
    stop_daemon "$slurmd_pid" slurmd
    stop_daemon "$slurmctld_pid" slurmctld
    stop_daemon "$munged_pid" munged
    for _ in $(seq 50); do # a job step finishing after slurmd stopped
        mapfile -t pids < <(our_leftovers)
        [ ${#pids[@]} -eq 0 ] && break
        sleep 0.1
    done
    if [ ${#pids[@]} -ne 0 ]; then
        echo "single-node-slurm: killing what is left of this test: ${pids[*]}" >&2
        kill -KILL "${pids[@]}" 2> /dev/null || true
    fi
    rm -rf "$tmp"
    exit "$status"
}
trap teardown EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

show_logs() { # the job's task logs and the daemons' logs, for a failure
    local log
    for log in "$tmp"/job/*.log "$tmp"/log/munged.out "$tmp"/log/*.log; do
        [ -f "$log" ] || continue
        echo "----- $log" >&2
        tail -n 60 "$log" >&2
    done
}
wait_for() { # seconds, what, command...: polls the command every 0.1 s until it succeeds
    local seconds=$1 what=$2
    shift 2
    for _ in $(seq $((seconds * 10))); do
        "$@" && return 0
        sleep 0.1
    done
    show_logs
    fail "$what did not happen in $seconds s"
}
alive() { [ -n "$(process_state "$1")" ] && [ "$(process_state "$1")" != Z ]; }

# 1. The program under test, installed as a user would: the component runtime, what the Debian package holds.
cmake --install "$build" --prefix "$tmp/prefix" --component runtime > "$tmp/install.log" 2>&1 ||
    { cat "$tmp/install.log" >&2; fail "cmake --install '$build' failed"; }
inkgraph=$tmp/prefix/bin/inkgraph
[ -x "$inkgraph" ] || fail "cmake --install '$build' installed no bin/inkgraph under '$tmp/prefix'"

# 2. munge, with its own key, socket, pid and seed files; in the foreground it logs to its stderr (log/munged.out).
mkdir -m 700 "$tmp/munge" "$tmp/log" "$tmp/state" "$tmp/spool" "$tmp/job"
mungekey --create --keyfile="$tmp/munge/munge.key" > /dev/null
chmod 400 "$tmp/munge/munge.key"
# --force: munged otherwise refuses a socket in a folder that not everyone may enter (this one is 0700).
SLURM_CONF=$conf munged --foreground --force --key-file="$tmp/munge/munge.key" --socket="$socket" \
    --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" \
    > "$tmp/log/munged.out" 2>&1 &
munged_pid=$!
munge_ready() {
    alive "$munged_pid" || { show_logs; fail "munged exited"; }
    [ -S "$socket" ]
}
wait_for 10 "munged listening on '$socket'" munge_ready

# 3. slurm.conf: this machine as its only node, every file in the scratch folder, ports nothing listens on.
hardware=$(SLURM_CONF=/dev/null slurmd -C | grep -m1 '^NodeName=') || fail "'slurmd -C' printed no NodeName line"
node=${hardware%% *}
node=${node#NodeName=}
memory=$(sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' <<< "$hardware")
task_memory=1024 # MiB: a 256x256 still of the largest bundled model peaks at about 300 MiB (docs/batch.md)
[ "${memory:-0}" -ge "$task_memory" ] || fail "this machine has ${memory:-no} MiB of memory; a task asks $task_memory"
listening=$(awk 'NR > 1 && $4 == "0A" { split($2, a, ":"); print a[2] }' /proc/net/tcp /proc/net/tcp6 2> /dev/null ||
    true)
free_port() { ! grep -qx "$(printf '%04X' "$1")" <<< "$listening"; }
controller_port=
for _ in $(seq 100); do
    port=$((20000 + RANDOM % 20000 * 2))
    free_port "$port" && free_port $((port + 1)) && { controller_port=$port; break; }
done
[ -n "$controller_port" ] || fail "found no two free TCP ports next to each other between 20000 and 60000"
cat > "$conf" << EOF
ClusterName=inkgraph-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$controller_port
SlurmdPort=$((controller_port + 1))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/log/slurmctld.pid
SlurmdPidFile=$tmp/log/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
PlugStackConfig=$tmp/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
# Quick turns for a test: the next array task starts as soon as one ends (not up to 3 s later), job records are never
# purged (sbatch --wait then polls every 2 s, not at 2, 10 and 42 s), a cancelled task is killed 1 s after SIGTERM.
SchedulerParameters=batch_sched_delay=0
MinJobAge=0
KillWait=1
$hardware NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=inkgraph Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
: > "$tmp/plugstack.conf"

# 4. The controller and the node daemon, in the foreground of their own background jobs.
SLURM_CONF=$conf slurmctld -D > "$tmp/log/slurmctld.out" 2>&1 &
slurmctld_pid=$!
SLURM_CONF=$conf slurmd -D > "$tmp/log/slurmd.out" 2>&1 &
slurmd_pid=$!
node_idle() {
    alive "$slurmctld_pid" || { show_logs; fail "slurmctld exited"; }
    alive "$slurmd_pid" || { show_logs; fail "slurmd exited"; }
    [ "$(with_conf sinfo -h -n "$node" -o %T 2> /dev/null)" = idle ]
}
wait_for 30 "node '$node' idle in sinfo" node_idle

# 5. The array job, as docs/batch.md submits it, with a small size. Slurm opens --output before the script runs.
# In the background and waited for, so that a signal to this script is handled at once.
SLURM_CONF=$conf INKGRAPH=$inkgraph OUT=$tmp/slurm-out SIZE=$size timeout 90 \
    sbatch --parsable --array=0-$((tasks - 1)) --cpus-per-task=1 --mem=${task_memory}M --time=5 --chdir="$root" \
    --output="$tmp/job/%A_%a.log" --wait "$root/examples/batch/slurm-array.sbatch" > "$tmp/sbatch.out" 2>&1 &
sbatch_pid=$!
sbatch_status=0
wait "$sbatch_pid" || sbatch_status=$?
sbatch_pid=
if [ "$sbatch_status" -ne 0 ]; then
    cat "$tmp/sbatch.out" >&2
    show_logs
    fail "the array job failed (sbatch --wait exited with $sbatch_status; 124: not finished in 90 s)"
fi
job=$(grep -m1 -E '^[0-9]+$' "$tmp/sbatch.out") || fail "sbatch printed no job id: $(cat "$tmp/sbatch.out")"

# 6. The same script locally as one batch: one task of one, --shard 0/1, the whole list in one process.
(cd "$root" && SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_COUNT=1 SLURM_CPUS_PER_TASK=1 \
    INKGRAPH="$inkgraph" OUT="$tmp/local-out" SIZE=$size timeout 120 bash examples/batch/slurm-array.sbatch) \
    > "$tmp/local.log" 2>&1 || { cat "$tmp/local.log" >&2; fail "the local batch failed"; }

# 7. The checks. The list's models, as inkgraph reads the file: trimmed, blank lines and comments skipped.
mapfile -t models < <(sed -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' "$root/examples/batch/models.txt" |
    grep -v -e '^$' -e '^#')
count=${#models[@]}
[ "$count" -ge "$tasks" ] || fail "examples/batch/models.txt lists $count models, fewer than the $tasks tasks"
output_name() { # list position from 1 -> {index}-{name}: the index zero-padded to the list's width
    local model=${models[$1 - 1]##*/}
    printf '%0*d-%s' "${#count}" "$1" "${model%.*}"
}
failures=0
check() { echo "single-node-slurm: FAIL: $*" >&2; failures=$((failures + 1)); }
grep -q "rendered $count of $count models (shard 0/1 of $count)" "$tmp/local.log" ||
    check "the local batch did not render the whole list in one process: $(tail -n 1 "$tmp/local.log")"
declare -A renderer=()
for task in $(seq 0 $((tasks - 1))); do
    log=$tmp/job/${job}_$task.log
    [ -f "$log" ] || { check "task $task wrote no log '$log'"; continue; }
    # What the task rendered, from its own progress lines: [i/n] 'model' -> '$OUT/{index}-{name}.png'.
    mapfile -t wrote < <(sed -n "s|^inkgraph: \[[0-9]*/[0-9]*\] '.*' -> '$tmp/slurm-out/\(.*\)\.png':.*|\1|p" "$log")
    expected=()
    for position in $(seq $((task + 1)) "$tasks" "$count"); do expected+=("$(output_name "$position")"); done
    [ "${wrote[*]}" = "${expected[*]}" ] ||
        check "task $task rendered [${wrote[*]}], not its share p mod $tasks = $task: [${expected[*]}]"
    grep -q "rendered ${#expected[@]} of ${#expected[@]} models (shard $task/$tasks of $count)" "$log" ||
        check "task $task's summary is not that of shard $task/$tasks: $(tail -n 1 "$log")"
    for name in "${wrote[@]}"; do
        [ -z "${renderer[$name]:-}" ] || check "'$name' rendered by task ${renderer[$name]} and by task $task"
        renderer[$name]=$task
    done
done
for position in $(seq "$count"); do
    name=$(output_name "$position")
    [ -n "${renderer[$name]:-}" ] || check "no task rendered list position $position ('${models[$position - 1]}')"
    stats=$tmp/slurm-out/$name.json
    if ! grep -q "\"model\": \"${models[$position - 1]}\"" "$stats" 2> /dev/null ||
        ! grep -q "\"position\": $position," "$stats"; then
        check "'$stats' is not the --stats of list position $position ('${models[$position - 1]}')"
    fi
    [ -s "$tmp/local-out/$name.png" ] || { check "the local batch wrote no '$name.png'"; continue; }
    cmp -s "$tmp/slurm-out/$name.png" "$tmp/local-out/$name.png" ||
        check "'$name.png' from the array job differs from the local batch's"
done
pictures=$(find "$tmp/slurm-out" -name '*.png' | wc -l)
[ "$pictures" -eq "$count" ] || check "the array job wrote $pictures pictures for $count models"
if [ "$failures" -ne 0 ]; then
    show_logs
    fail "$failures checks failed"
fi
echo "single-node-slurm: job $job on node '$node': $tasks tasks rendered disjoint shares covering the $count models," \
    "each picture byte-identical to the local batch's"
