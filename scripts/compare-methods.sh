#!/usr/bin/env bash
# Issue 20's comparison: every localization method on the nine test maps and on random buildings,
# in the faithful world with the fast MOX sensor (as ste/results/faithful), one `evaluate` folder
# per method and map set under OUT (default out/compare). The test maps come first, all methods,
# so that their wall time (the issue's 30 minutes on 2 cores) is measured without the buildings.
#
#   scripts/compare-methods.sh [RUNS] [OUT] [all|test-maps|buildings]
#                          # RUNS per source on the test maps (default 3); which part (all)
#
# The buildings (20 random ones, seed 1001, 7-30 m a side) take the first source of each map, one
# run, 0.1 m flow cells, and --max-steps 100 for the methods other than STE: their own budget, two
# stops per square metre, would be up to 1,650 stops of 5 s on the largest (STE stops at 50
# samples, or one per 10 m^2 of floor beyond 500 m^2).
#   scripts/methods_table.py OUT/test-maps/* ; scripts/methods_table.py OUT/buildings/*
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
out=${2:-out/compare}
part=${3:-all}
plumekit=${PLUMEKIT:-./build/plumekit}
methods=(ste sweeping surge-cast zigzag pseudo-gradient pf-gradient pf-sweep apf)
evaluate() {
  local m=$1 maps=$2 dest=$3
  shift 3
  local extra=()
  if [[ $m == ste ]]; then
    extra=(--plume-model physics)
  elif [[ $dest != */test-maps ]]; then
    extra=(--max-steps 100)
  fi
  "$plumekit" evaluate --map-dir "$maps" --method "$m" "${extra[@]}" --gas-sensor mox-fast \
    --threads 0 --out "$dest/$m" "$@"
}
wall="$out/test-maps/wall.txt"
if [[ $part != buildings ]]; then
  # wall.txt is this script's own line; any other file of that name is left alone.
  if [[ -e $wall ]] && ! grep -q '^test maps, all methods: ' "$wall"; then
    echo "compare-methods.sh: $wall exists and was not written by this script" >&2
    exit 2
  fi
  start=$(date +%s)
  for m in "${methods[@]}"; do evaluate "$m" data/test-maps "$out/test-maps" --runs "$runs"; done
  echo "test maps, all methods: $(($(date +%s) - start)) s wall" | tee "$wall"
fi
if [[ $part != test-maps ]]; then
  [[ -d "$out/buildings-maps" ]] ||
    "$plumekit" maps random --families building --count 20 --seed 1001 --sources 3 \
      --out "$out/buildings-maps"
  for m in "${methods[@]}"; do
    evaluate "$m" "$out/buildings-maps" "$out/buildings" --runs 1 --sources 1 --cell 0.1
  done
fi
