#!/bin/bash
# The GNU parallel equivalent of submit.sh: the N parts, JOBS at a time (default: one per core;
# --sshlogin in $PARALLEL_OPTIONS spreads them over machines that share WORK), then the merge,
# only when every part has succeeded.
#   scripts/scaleout/parallel.sh dataset|evaluate N WORK [plumekit flags...]
set -euo pipefail
if [ $# -lt 3 ] || { [ "$1" != dataset ] && [ "$1" != evaluate ]; }; then
  echo "usage: $0 dataset|evaluate N WORK [plumekit flags...]" >&2
  exit 2
fi
kind=$1 n=$2 work=$3
shift 3
case $n in '' | *[!0-9]* | 0) echo "$0: N must be a whole number from 1, got '$n'" >&2; exit 2 ;; esac
plumekit=${PLUMEKIT:-plumekit}
command=(evaluate)
[ "$kind" = dataset ] && command=(dataset generate)
mkdir -p "$work/$kind-parts"
# --quote keeps each flag one argument; --halt now,fail=1: one failed part stops the others and
# the merge does not run.
# shellcheck disable=SC2086  # PARALLEL_OPTIONS is a list of options
parallel --quote --halt now,fail=1 --jobs "${JOBS:-0}" ${PARALLEL_OPTIONS:-} \
  "$plumekit" "${command[@]}" --shard "{}/$n" --threads 1 --out "$work/$kind-parts/part-{}" "$@" \
  ::: $(seq 0 $((n - 1)))
if [ "$kind" = dataset ]; then
  "$plumekit" dataset merge "$work"/dataset-parts/part-* --out "$work/dataset"
else
  "$plumekit" evaluate merge "$work"/evaluate-parts/part-* --out "$work/evaluation"
fi
