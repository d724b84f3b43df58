#!/usr/bin/env bash
# Issue 20's comparison: every localization method on the nine test maps and on random buildings,
# in the faithful world with the fast MOX sensor (as results/ste-faithful), one `evaluate` folder
# per method and map set under OUT (default out/compare). All the methods run in one `evaluate`
# (--method a,b,...): each run's plume is simulated once and sampled by every method's robot, which
# reads what it would read alone (docs/design/evaluation.md, "Several methods in one world"). The test maps
# come first, so that their wall time (the issue's 30 minutes on 2 cores) is measured without the
# buildings.
#
#   scripts/compare-methods.sh [RUNS] [OUT] [all|test-maps|buildings]
#                          # RUNS per source on the test maps (default 3); which part (all)
#
# STE runs with the physics plume model (--plume-model, which the other methods ignore). The
# buildings (20 random ones, seed 1001, 7-30 m a side) take the first source of each map, one run,
# 0.1 m flow cells, and --max-steps 100 for the methods other than STE (which ignores it: it stops
# at 50 samples, or one per 10 m^2 of floor beyond 500 m^2): their own budget, two stops per
# square metre, would be up to 1,650 stops of 5 s on the largest.
#   scripts/methods_table.py OUT/test-maps/* ; scripts/methods_table.py OUT/buildings/*
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
runs=${1:-3}
out=${2:-out/compare}
part=${3:-all}
plumekit=${PLUMEKIT:-./build/plumekit}
# Issue 20's eight (`all` also has the methods added since).
methods=ste,sweeping,surge-cast,zigzag,pseudo-gradient,pf-gradient,pf-sweep,apf
evaluate() {
  "$plumekit" evaluate --method "$methods" --plume-model physics --gas-sensor mox-fast \
    --threads 0 "$@"
}
wall="$out/test-maps/wall.txt"
if [[ $part != buildings ]]; then
  # wall.txt is this script's own line; any other file of that name is left alone.
  if [[ -e $wall ]] && ! grep -q '^test maps, all methods: ' "$wall"; then
    echo "compare-methods.sh: $wall exists and was not written by this script" >&2
    exit 2
  fi
  start=$(date +%s)
  evaluate --map-dir data/test-maps --out "$out/test-maps" --runs "$runs"
  echo "test maps, all methods: $(($(date +%s) - start)) s wall" | tee "$wall"
fi
if [[ $part != test-maps ]]; then
  [[ -d "$out/buildings-maps" ]] ||
    "$plumekit" maps random --families building --count 20 --seed 1001 --sources 3 \
      --out "$out/buildings-maps"
  evaluate --map-dir "$out/buildings-maps" --out "$out/buildings" --runs 1 --sources 1 \
    --cell 0.1 --max-steps 100
fi
