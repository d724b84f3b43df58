#!/bin/bash
# Submits a split run to Slurm: an array of N parts, then the merge, which starts only when every
# part has succeeded. Prints the two job ids ("ARRAY_JOB MERGE_JOB").
#   scripts/scaleout/submit.sh dataset|evaluate N WORK [plumekit flags...]
# Extra sbatch options go in $SBATCH_OPTIONS (e.g. "--partition=cpu --cpus-per-task=4");
# $PLUMEKIT names the program (default: plumekit on the PATH of the jobs).
set -euo pipefail
if [ $# -lt 3 ] || { [ "$1" != dataset ] && [ "$1" != evaluate ]; }; then
  echo "usage: $0 dataset|evaluate N WORK [plumekit flags...]" >&2
  exit 2
fi
kind=$1 n=$2 work=$3
shift 3
case $n in '' | *[!0-9]* | 0) echo "$0: N must be a whole number from 1, got '$n'" >&2; exit 2 ;; esac
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work/logs"
# shellcheck disable=SC2086  # SBATCH_OPTIONS is a list of options
parts=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array="0-$((n - 1))" \
  --output="$work/logs/%x-%A_%a.out" "$here/$kind-part.sbatch" "$work" "$@")
parts=${parts%%;*}  # "JOBID;CLUSTER" on a multi-cluster system
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} --dependency="afterok:$parts" --kill-on-invalid-dep=yes \
  --output="$work/logs/%x-%j.out" "$here/$kind-merge.sbatch" "$work")
echo "${parts} ${merge%%;*}"
