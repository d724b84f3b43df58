#!/usr/bin/env bash
# Issue 20's comparison: every localization method on the nine test maps and on random buildings,
# in the faithful world with the fast MOX sensor (as ste/results/faithful), one `evaluate` folder
# per method and map set under OUT (default out/compare).
#
#   scripts/compare-methods.sh [RUNS] [OUT]      # RUNS per source (default 3)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
out=${2:-out/compare}
plumekit=${PLUMEKIT:-./build/plumekit}
methods=(ste sweeping surge-cast zigzag pseudo-gradient pf-gradient pf-sweep apf)
common=(--runs "$runs" --gas-sensor mox-fast --threads 0)
[[ -d "$out/buildings-maps" ]] ||
  "$plumekit" maps random --families building --count 20 --seed 1001 --sources 3 \
    --out "$out/buildings-maps"
for m in "${methods[@]}"; do
  model=()
  [[ $m == ste ]] && model=(--plume-model physics)
  "$plumekit" evaluate --map-dir data/test-maps --method "$m" "${model[@]}" "${common[@]}" \
    --out "$out/test-maps/$m"
  "$plumekit" evaluate --map-dir "$out/buildings-maps" --method "$m" "${model[@]}" \
    --runs 1 --gas-sensor mox-fast --threads 0 --out "$out/buildings/$m"
done
