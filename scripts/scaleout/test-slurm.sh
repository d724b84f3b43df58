#!/bin/bash
# Starts a real single-node Slurm (munged, slurmctld, slurmd, all in a temporary folder, on this
# machine), submits submit.sh's array jobs for a tiny dataset and a tiny evaluation, waits for
# them, and checks that the merged outputs are byte for byte those of single runs; then the same
# with parallel.sh. Everything it started is stopped on any exit.
#   sudo scripts/scaleout/test-slurm.sh            # PLUMEKIT=build/plumekit by default
# Prints SKIP and exits 0 when not root or when Slurm, munge or GNU parallel is not installed
# (scripts/install-deps.sh installs them). About a minute.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
plumekit=$(realpath "${PLUMEKIT:-$repo/build/plumekit}")

if [ "$(id -u)" != 0 ]; then
  echo "SKIP: test-slurm.sh starts Slurm and munge daemons and must run as root"
  exit 0
fi
for tool in munged mungekey slurmctld slurmd sbatch scontrol sinfo squeue scancel parallel; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool is not installed (scripts/install-deps.sh installs slurm-wlm, munge and parallel)"
    exit 0
  fi
done
[ -x "$plumekit" ] || { echo "FAIL: no plumekit program at $plumekit (set PLUMEKIT)" >&2; exit 1; }

tmp=$(mktemp -d /tmp/plumekit-slurm.XXXXXX)
pids=() jobs=()
cleanup() {
  local code=$?
  if [ ${#jobs[@]} -gt 0 ]; then  # only the jobs this test submitted, to its own Slurm
    scancel --quiet "${jobs[@]}" 2>/dev/null || true
    for _ in $(seq 50); do [ -z "$(squeue --noheader 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ $code != 0 ]; then
    echo "--- logs of the failed test (in $tmp) ---" >&2
    tail -n 20 "$tmp"/*.log "$tmp"/work-*/logs/*.out >&2 2>/dev/null || true
  fi
  rm -rf "$tmp"
  exit $code
}
trap cleanup EXIT
trap 'exit 1' INT TERM

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# --- munge: its own key and socket, nothing of the system's touched ---------------------------
mungekey --create --keyfile "$tmp/munge.key" >/dev/null
chmod 0400 "$tmp/munge.key"
# --force: munged refuses root and a world-writable /tmp otherwise.
munged --force --foreground --key-file="$tmp/munge.key" --socket="$tmp/munge.socket" \
  --pid-file="$tmp/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed" \
  >"$tmp/munged.out" 2>&1 &
pids+=($!)

# --- Slurm: one node named after this machine, 2 CPUs, no cgroups, no accounting --------------
node=$(hostname -s)
port=$((20000 + RANDOM % 20000))  # slurmctld on port, slurmd on port + 1
mkdir -p "$tmp/state" "$tmp/spool"
cat >"$tmp/slurm.conf" <<CONF
ClusterName=plumekit-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
for _ in $(seq 50); do [ -S "$tmp/munge.socket" ] && break; sleep 0.1; done
[ -S "$tmp/munge.socket" ] || fail "munged did not start ($(cat "$tmp/munged.out"))"
slurmctld -D -i -f "$SLURM_CONF" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)
state=""
for _ in $(seq 60); do
  state=$(sinfo --noheader --nodes="$node" --format=%t 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || fail "the Slurm node did not come up (state '$state'); see the logs below"
echo "slurm: node $node idle (slurmctld port $port)"

# Waits (at most $2 seconds) for job $1 to end; fails unless it COMPLETED.
wait_job() {
  local job=$1 limit=$2 state="" waited=0
  while [ $waited -lt $((limit * 2)) ]; do
    state=$(scontrol show job "$job" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1)
    case $state in
      COMPLETED) return 0 ;;
      FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | BOOT_FAIL | DEADLINE)
        fail "job $job ended $state" ;;
    esac
    sleep 0.5
    waited=$((waited + 1))
  done
  fail "job $job did not end within $limit s (state '$state')"
}

same() {  # same FILE_A FILE_B WHAT
  cmp -s "$1" "$2" || fail "$3: $1 differs from $2"
}

# --- the tiny runs, each made whole once and split -------------------------------------------
dataset_flags=(--maps 3 --sources 2 --simulator advection-diffusion --seed 1)
mkdir -p "$tmp/maps"
cp "$repo/data/test-maps/test-0-empty.json" "$repo/data/test-maps/test-4-l-shape.json" "$tmp/maps/"
evaluate_flags=(--map-dir "$tmp/maps" --sources 2 --runs 1 --plume-model gaussian --max-samples 6)
cd "$tmp"
"$plumekit" dataset generate "${dataset_flags[@]}" --threads 2 --out "$tmp/single/dataset" >/dev/null
"$plumekit" evaluate "${evaluate_flags[@]}" --threads 2 --out "$tmp/single/evaluation" >/dev/null

check_outputs() {  # check_outputs WORK HOW
  local work=$1 how=$2
  same "$work/dataset/manifest.json" "$tmp/single/dataset/manifest.json" "$how dataset"
  diff -r "$work/dataset/shards" "$tmp/single/dataset/shards" >/dev/null ||
    fail "$how dataset: the shards differ"
  for f in runs.csv summary.json boxplot-error.png boxplot-samples.png; do
    same "$work/evaluation/$f" "$tmp/single/evaluation/$f" "$how evaluation"
  done
  echo "$how: merged dataset (manifest.json, shards/) and evaluation (runs.csv, summary.json," \
    "box plots) byte-identical to single runs"
}

export PLUMEKIT=$plumekit
read -r ds_parts ds_merge < <("$here/submit.sh" dataset 3 "$tmp/work-slurm" "${dataset_flags[@]}")
read -r ev_parts ev_merge < <("$here/submit.sh" evaluate 2 "$tmp/work-slurm" "${evaluate_flags[@]}")
jobs+=("$ds_parts" "$ds_merge" "$ev_parts" "$ev_merge")
echo "slurm: dataset array $ds_parts then merge $ds_merge; evaluate array $ev_parts then merge $ev_merge"
wait_job "$ds_merge" 120
wait_job "$ev_merge" 120
for job in "$ds_parts" "$ev_parts"; do
  tasks=$(scontrol show job "$job" | grep -c "JobState=COMPLETED" || true)
  echo "slurm: array $job: $tasks tasks COMPLETED"
done
check_outputs "$tmp/work-slurm" "slurm"

JOBS=2 "$here/parallel.sh" dataset 3 "$tmp/work-parallel" "${dataset_flags[@]}" >/dev/null
JOBS=2 "$here/parallel.sh" evaluate 2 "$tmp/work-parallel" "${evaluate_flags[@]}" >/dev/null
check_outputs "$tmp/work-parallel" "parallel"
echo "PASS: test-slurm.sh"
