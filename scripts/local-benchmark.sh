#!/usr/bin/env bash
# Seed 004 ch. 12's local framework (Algorithm 1): the sample budget sweep of Fig. 12.4 and the
# global-versus-local travelled distance of Fig. 12.7, in the thesis's simulation condition C
# (wind 0.9 m/s, release 5 %: 500 units) in a 20 x 4 m arena (scripts/levy_maps.py with LENGTH
# 20: 10 maps, a source 1 m from the inlet at a random y, five starts 8 m downwind at random y,
# taken in turn), the thesis's world. The local framework (--method ste-local) knows no map and
# no position but its odometry, which drifts by 0.02 m per square root of metre travelled (the
# thesis gives no figure); the global one is plumekit's STE with the thesis's Gaussian plume
# model (MH), the map and exact positions.
#
#   scripts/local-benchmark.sh [RUNS] [OUT]     # RUNS per map (default 2); BUDGETS="7 9" for some
#   scripts/local_table.py OUT [PNG_DIR]        # the table and box plots of docs/validation.md
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
runs=${1:-2}
out=${2:-out/local}
plumekit=${PLUMEKIT:-./build/plumekit}
maps="$out/maps"
[[ -d $maps ]] || /usr/bin/python3 scripts/levy_maps.py "$maps" 0.9 crosswind 10 1 20 >/dev/null
evaluate() {
  "$plumekit" evaluate --map-dir "${maps:?}" --runs "$runs" --world thesis --release-rate 500 \
    --protocol thesis --threads 0 "$@" >/dev/null
}
wall="$out/wall.txt"
# wall.txt is this script's own line; any other file of that name is left alone.
if [[ -e $wall ]] && ! grep -q '^local framework benchmark: ' "$wall"; then
  echo "local-benchmark.sh: $wall exists and was not written by this script" >&2
  exit 2
fi
start=$(date +%s)
budgets=${BUDGETS:-1 3 5 7 9 15 25 50}
for budget in $budgets; do
  # A budget of B_0 moves a map at most every B_0 samples: the guard grows with it (20 B_0, at
  # least the auto 160 of this arena), so that it is not what stops the larger budgets.
  steps=$((20 * budget > 160 ? 20 * budget : 160))
  evaluate --method ste-local --budget "$budget" --odometry-drift 0.02 --max-steps "$steps" \
    --out "$out/budget-$budget"
  echo "B_0 = $budget: done"
done
evaluate --plume-model gaussian --out "$out/global"
# Fig. 12.5's other half: low wind (condition A, 0.2 m/s), B_0 = 7.
low="$out/maps-low"
[[ -d $low ]] || /usr/bin/python3 scripts/levy_maps.py "$low" 0.2 crosswind 10 1 20 >/dev/null
maps=$low evaluate --method ste-local --budget 7 --odometry-drift 0.02 --max-steps 160 \
  --out "$out/low-wind"
echo "local framework benchmark: $(($(date +%s) - start)) s wall" | tee "$wall"
