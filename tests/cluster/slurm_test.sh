#!/bin/bash
# The Slurm path of the experiment workflow, for real: starts a single-node Slurm on this
# machine (Debian's slurm-wlm and munge, a slurm.conf generated from `slurmd -C`), runs
# tests/harness/test_snakemake.py with Snakemake submitting every job through
# experiments/profiles/slurm, and stops what it started. Prints each step's time.
#   tests/cluster/slurm_test.sh BUILD_DIR     (as root: it starts daemons; `make cluster-test`)
# Slurm's state, logs and config live in BUILD_DIR/cluster/, nothing under /etc/slurm.
set -euo pipefail

build=$(realpath "${1:-build}")
repo=$(cd "$(dirname "$0")/../.." && pwd)
work="$build/cluster"
host=$(hostname -s)
started_munge=""

step_start=$(date +%s.%N)
step() {  # prints the time the previous step took, then names the next
    local now
    now=$(date +%s.%N)
    awk -v name="$current" -v now="$now" -v start="$step_start" \
        'BEGIN { printf "[cluster-test] %-30s %7.1f s\n", name, now - start }'
    step_start=$now
    current=$1
}

cleanup() {
    [ -n "${SLURM_CONF:-}" ] && scontrol shutdown >/dev/null 2>&1 || true
    sleep 1
    if [ -n "$started_munge" ] && [ -s /run/munge/munged.pid ]; then
        kill "$(cat /run/munge/munged.pid)" 2>/dev/null || true
    fi
}
trap cleanup EXIT

[ "$(id -u)" = 0 ] || { echo "cluster-test: run as root (it starts munged, slurmctld and slurmd)" >&2; exit 2; }

current="munge"
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    [ -s /etc/munge/munge.key ] || mungekey --create
    chown munge:munge /etc/munge/munge.key && chmod 0400 /etc/munge/munge.key
    install -d -o munge -g munge -m 0755 /run/munge
    runuser -u munge -- /usr/sbin/munged
    started_munge=1
    munge -n | unmunge >/dev/null
fi

step "slurm.conf and daemons"
rm -rf "$work" && mkdir -p "$work"/{state,spool,log}
node=$(slurmd -C | head -1)  # NodeName=<host> CPUs=... RealMemory=...
cat >"$work/slurm.conf" <<EOF
ClusterName=local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/affinity
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
DefMemPerCPU=1000
MpiDefault=none
ReturnToService=2
MinJobAge=86400
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$work/slurm.conf"
slurmctld -i -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
    state=$(sinfo -h -o %T 2>/dev/null || true)
    [ "$state" = idle ] && break
    [ "$state" = down ] || [ "$state" = "down*" ] && scontrol update nodename="$host" state=resume
    sleep 1
done
[ "$state" = idle ] || { echo "cluster-test: the node is '$state', not idle; see $work/log" >&2; exit 1; }

wait_for() {  # waits up to a minute for job $1 to end; fails unless it completed
    local state=""
    for _ in $(seq 60); do
        state=$(scontrol -o show job "$1" | grep -o 'JobState=[A-Z]*' | cut -d= -f2)
        [ "$state" = COMPLETED ] && return 0
        case "$state" in FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY) break ;; esac
        sleep 1
    done
    echo "cluster-test: job $1 is $state; see $work/log" >&2
    exit 1
}

step "sbatch smoke test"
wait_for "$(sbatch --parsable -o "$work/log/smoke-%j.out" --wrap hostname)"

# The Snakefile's workaround for Snakemake 7.21 on Slurm 22.05 (srun_cpus): a job step that
# srun starts inside a job of several CPUs gets them all only through SRUN_CPUS_PER_TASK.
step "srun inside a job of all CPUs"
cpus=$(nproc)
job=$(sbatch --parsable -c "$cpus" --export=ALL,SRUN_CPUS_PER_TASK="$cpus" \
      -o "$work/log/srun-%j.out" --wrap "srun -n1 --cpu-bind=q nproc")  # Snakemake's srun
wait_for "$job"
got=$(tail -1 "$work/log/srun-$job.out")
[ "$got" = "$cpus" ] || { echo "cluster-test: srun's step got $got CPUs of $cpus" >&2; exit 1; }

step "tiny experiment through Slurm"
export USER=${USER:-root}  # Snakemake 7.21's Slurm executor reads it
RENDERER_BINARY="$build/bin/renderer" METRICS_BINARY="$build/bin/metrics" \
SNAKEMAKE_TEST_PROFILE="$repo/experiments/profiles/slurm" \
    /usr/bin/python3 -m unittest discover -s "$repo/tests/harness" -p test_snakemake.py
jobs=$(scontrol -o show jobs | grep -c 'JobState=COMPLETED' || true)
echo "[cluster-test] Slurm completed $jobs jobs, the workflow's and the 2 checks'"

step "done"
