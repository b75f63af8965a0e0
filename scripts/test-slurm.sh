#!/usr/bin/env bash
# A real Slurm on this machine runs examples/slurm/study.sbatch, as a cluster would:
#   - Slurm and munge from the distribution's packages (scripts/test-slurm.sh install; needs root),
#   - a one-node cluster on 127.0.0.1: munged, slurmctld and slurmd started by hand with a generated
#     slurm.conf in a temporary folder (no systemd, no cgroups: proctrack/linuxproc, task/none),
#   - a small study (4 jobs of 256²) submitted as a job array of 2 tasks; while task 1 is part-way
#     through a job (its checkpoint written), it gets the signal of its time limit (USR1 to the batch
#     shell, as --signal=B:USR1@300 sends it): wearsim stops, the task requeues itself, starts again
#     and resumes,
#   - `wearsim study collect`, and the job files and tables compared with the same study run locally:
#     identical but for provenance and timings.
# The daemons are stopped and the folder removed on exit, so the script can be run again.
#   scripts/test-slurm.sh install          # the packages, if missing
#   scripts/test-slurm.sh PATH/TO/wearsim  # the test
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"

if [ "${1:-}" = install ]; then
    if command -v slurmctld slurmd sbatch munged >/dev/null && [ "$(command -v slurmctld slurmd sbatch munged | wc -l)" = 4 ]; then
        echo "Slurm and munge are installed: $(slurmctld -V)"
        exit 0
    fi
    packages=(slurmctld slurmd slurm-client munge)
    if [ "$(id -u)" != 0 ]; then
        echo "error: Slurm and munge are missing, and installing them needs root: apt-get install ${packages[*]}" >&2
        exit 1
    fi
    apt=(apt-get -y -q -o DPkg::Lock::Timeout=300 install --no-install-recommends)
    export DEBIAN_FRONTEND=noninteractive
    # A fresh machine has no package lists yet: update them once if the install cannot find the packages.
    "${apt[@]}" "${packages[@]}" || { apt-get -q -o DPkg::Lock::Timeout=300 update && "${apt[@]}" "${packages[@]}"; }
    echo "installed: $(slurmctld -V)"
    exit 0
fi

bin=$(realpath "${1:?usage: scripts/test-slurm.sh install | scripts/test-slurm.sh PATH/TO/wearsim}")
[ -x "$bin" ] && [ "$(basename "$bin")" = wearsim ] || { echo "error: $bin is not a wearsim binary" >&2; exit 2; }
for tool in slurmctld slurmd sbatch squeue scontrol scancel munged mungekey; do
    command -v "$tool" >/dev/null || { echo "error: $tool not found: run scripts/test-slurm.sh install" >&2; exit 2; }
done

work=$(mktemp -d /tmp/wearsim-slurm.XXXXXX)
chmod 711 "$work" # munged wants its socket's folder searchable by all
export SLURM_CONF="$work/slurm.conf"
started=$SECONDS
say() { printf '  [%3ds] %s\n' "$((SECONDS - started))" "$*"; }
stop_daemons() {
    local status=$?
    # Jobs first (a failed run may leave some), then the daemons this script started.
    if [ -n "${array:-}" ]; then scancel "$array" 2>/dev/null || true; fi
    for daemon in slurmd slurmctld munged; do
        if [ -f "$work/$daemon.pid" ]; then kill "$(cat "$work/$daemon.pid")" 2>/dev/null || true; fi
    done
    if [ "$status" != 0 ]; then
        for log in "$work"/*.log; do
            [ -f "$log" ] && { echo "---- $log (last lines)"; tail -n 40 "$log"; }
        done
    fi
    sleep 1
    rm -rf "$work"
}
trap stop_daemons EXIT

# munge: the credentials of slurmctld and slurmd; its own key and socket, in the temporary folder.
mungekey --create --keyfile="$work/munge.key" --bits=1024
munged --socket="$work/munge.socket" --key-file="$work/munge.key" --pid-file="$work/munged.pid" \
    --log-file="$work/munged.log" --seed-file="$work/munged.seed"

# Two free ports on the loopback for slurmctld and slurmd.
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s:
    x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
host=$(hostname -s)
mkdir -p "$work/state" "$work/spool"
cat >"$SLURM_CONF" <<EOF
# A one-node cluster on this machine, for scripts/test-slurm.sh.
ClusterName=wearsimtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
# cred_expire: a requeued job may start again after this many seconds (default 120).
AuthInfo=socket=$work/munge.socket,cred_expire=10
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
KillWait=30
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld
slurmd
for _ in $(seq 60); do
    [ "$(sinfo -h -o %t 2>/dev/null)" = idle ] && break
    sleep 0.5
done
[ "$(sinfo -h -o %t)" = idle ] || { echo "error: the node did not come up: $(sinfo -h -o '%t %E')" >&2; exit 1; }
say "Slurm $(sinfo -V | cut -d' ' -f2) up: node $host, $(nproc) CPUs, partition test"

# 2 surface pairs × 2 loads = 4 jobs of 160 steps at 256², both 𝒢 in each.
cat >"$work/study.toml" <<'EOF'
units = "reduced"
[surface]
grid = 256
length = 1.0
hurst = 0.7
lambda_lower = 0.03125
lambda_upper = 0.25
rms_height = 0.005
seed = [1, 2]
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.25e-6, 1.0e-6]
[sliding]
loads = [5e-4, 1e-3]
distance = 1.0
running_in = 0.5
EOF

# The reference: the same study on this machine, alongside the Slurm run.
"$bin" --threads 1 study run "$work/study.toml" --out "$work/local" --jobs 1 --quiet >"$work/local.log" 2>&1 &
local_pid=$!

# The array as a user submits it, with the cores and memory of this machine's node and
# checkpoints every second so that the interruption falls after one.
export PATH="$(dirname "$bin"):$PATH"
array=$(sbatch --parsable --array=1-2 --cpus-per-task=1 --mem=500M --time=10 --chdir="$work" \
    --output="$work/task-%a.log" examples/slurm/study.sbatch "$work/study.toml" "$work/slurm" --checkpoint-every 1s)
say "submitted examples/slurm/study.sbatch as array $array (tasks 1-2; shard 1 holds jobs 0 and 2)"

state() { squeue -h -j "$1" -o %T 2>/dev/null || true; }
deadline=$((SECONDS + 120))
checkpoint=""
while [ -z "$checkpoint" ]; do
    [ "$SECONDS" -lt "$deadline" ] || { echo "error: task 1 wrote no checkpoint in 120 s" >&2; exit 1; }
    for job in 000000 000002; do
        if [ -f "$work/slurm/jobs/job-$job.checkpoint" ] && [ ! -f "$work/slurm/jobs/job-$job.json" ]; then
            checkpoint="job-$job"
        fi
    done
    sleep 0.1
done
[ "$(state "${array}_1")" = RUNNING ] || { echo "error: task 1 is $(state "${array}_1"), not running" >&2; exit 1; }
scancel --batch --signal=USR1 "${array}_1"
say "task 1 running $checkpoint with a checkpoint on disk: sent it USR1, the time-limit signal"

# It stops, requeues itself and waits out cred_expire; the job stays unfinished meanwhile.
deadline=$((SECONDS + 60))
until grep -q "requeueing the task" "$work/task-1.log" 2>/dev/null; do
    [ "$SECONDS" -lt "$deadline" ] || { echo "error: task 1 did not requeue itself" >&2; exit 1; }
    sleep 0.2
done
[ ! -f "$work/slurm/jobs/$checkpoint.json" ] && [ -f "$work/slurm/jobs/$checkpoint.checkpoint" ] ||
    { echo "error: $checkpoint finished or lost its checkpoint although stopped part-way" >&2; exit 1; }
# Stopped, not killed: its claims released and no temporary file left (task 2 works beside it).
stopped=$(grep -o "exit status [0-9]*" "$work/task-1.log" | head -n 1)
left=$(ls -A "$work/slurm/jobs" | grep -E 'job-00000[02].*\.(claim|tmp)$' || true)
if [ "$stopped" = "exit status 137" ] || [ -n "$left" ]; then
    echo "error: wearsim did not stop cleanly ($stopped; left: ${left:-nothing})" >&2
    exit 1
fi
say "task 1 stopped part-way through $checkpoint ($stopped, checkpoint kept, claims released) and requeued itself"

deadline=$((SECONDS + 150))
while [ -n "$(squeue -h -j "$array" 2>/dev/null)" ]; do
    [ "$SECONDS" -lt "$deadline" ] || { echo "error: the array did not finish in 150 s: $(squeue -j "$array")" >&2; exit 1; }
    sleep 0.5
done
restarts=$(scontrol show job "${array}_1" | grep -o 'Restarts=[0-9]*' | cut -d= -f2)
[ "$restarts" = 1 ] || { echo "error: task 1 restarted ${restarts:-?} times, expected 1" >&2; exit 1; }
grep -q "start 2" "$work/task-1.log" || { echo "error: no second start of task 1 in its log" >&2; exit 1; }
for a in 1 2; do
    grep -q "computed .* jobs" "$work/task-$a.log" || { echo "error: task $a did not finish its shard" >&2; exit 1; }
done
say "array done: task 1 started twice (Restarts=$restarts), task 2 once"

wait "$local_pid" || { cat "$work/local.log" >&2; echo "error: the local run failed" >&2; exit 1; }
"$bin" study collect "$work/slurm" >/dev/null
"$bin" study collect "$work/local" >/dev/null
python3 - "$work/slurm" "$work/local" <<'PY'
import json, sys
from pathlib import Path

slurm, local = map(Path, sys.argv[1:])
names = sorted(p.name for p in (local / "jobs").iterdir())
assert names == sorted(p.name for p in (slurm / "jobs").iterdir()), "the study folders hold different files"
assert [n for n in names if n.endswith(".json")] == [f"job-{i:06}.json" for i in range(4)], names


def results(path):
    job = json.loads(path.read_text())
    job.pop("provenance")  # the command line and date
    job.pop("seconds")  # the wall time
    job.pop("checksum")  # over the whole file, the two above included
    return job


for name in names:
    assert results(slurm / "jobs" / name) == results(local / "jobs" / name), f"{name} differs"
for table in ("results.csv", "results_aggregated.csv", "results.units.json"):
    assert (slurm / table).read_bytes() == (local / table).read_bytes(), f"{table} differs"
print(f"  the Slurm run equals the local one: {len(names)} job files (all but provenance, timing and the checksum over them), "
      "results.csv, results_aggregated.csv, results.units.json")
PY
say "Slurm test passed"
