#!/usr/bin/env bash
# Seed 004 ch. 13's robot teams (Fig. 13.3): 1-3 robots x the three strategies, in the thesis's
# open-field simulation conditions A-D (Table 8.1: wind 0.2 / 0.9 m/s, release 5 / 10 % of the
# pump, here 500 and 1000 units as in scripts/levy-benchmark.sh) and on the nine test maps
# (cluttered, which the thesis did not do). Configurations: individualist with 1 (a robot alone),
# 2 and 3 robots; cooperative and collaborative with 2 and 3.
#
#   scripts/team-benchmark.sh [RUNS] [OUT] [all|open-field|test-maps]
#   scripts/team_table.py OUT                  # the tables and box plots of docs/validation.md
#
# Open field: the 10 x 4 m arena of scripts/levy_maps.py (10 maps, a source 1 m from the inlet at
# a random y, five starts 8 m downwind at random y, taken in turn), RUNS runs per map (default 2),
# the physics model with an unknown release rate (--release-scale 0.25,2), in the thesis's world.
# Test maps: the first 5 sources of each, one run each (45 runs a configuration, within 20
# minutes on 2 cores for all seven), the physics model, the faithful world and the fast MOX
# sensor (as the methods' comparison). The team starts side by side about the
# run's start (Scenario::team_starts). OUT/wall.txt has each setting's wall time.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
runs=${1:-2}
out=${2:-out/teams}
part=${3:-all}
plumekit=${PLUMEKIT:-./build/plumekit}
configs="individualist:1 individualist:2 individualist:3 cooperative:2 cooperative:3
collaborative:2 collaborative:3"
mkdir -p "$out"
wall="$out/wall.txt"
if [[ -e $wall ]] && ! grep -q '^team benchmark' "$wall"; then
  echo "team-benchmark.sh: $wall exists and was not written by this script" >&2
  exit 2
fi
[[ -e $wall ]] || echo "team benchmark: wall time per setting, 2 cores" >"$wall"
run_configs() {  # SETTING MAP_DIR EVALUATE_FLAGS...
  local setting=$1 maps=$2
  shift 2
  local start
  start=$(date +%s)
  for config in $configs; do
    IFS=: read -r strategy robots <<<"$config"
    "$plumekit" evaluate --map-dir "$maps" --robots "$robots" --team "$strategy" \
      --protocol thesis --threads 0 --out "$out/$setting/$strategy-$robots" "$@" >/dev/null
  done
  echo "$setting: $(($(date +%s) - start)) s" | tee -a "$wall"
}
if [[ $part != test-maps ]]; then
  for condition in A:0.2:500 B:0.2:1000 C:0.9:500 D:0.9:1000; do
    IFS=: read -r name speed rate <<<"$condition"
    maps="$out/maps/$name"
    [[ -d $maps ]] || /usr/bin/python3 scripts/levy_maps.py "$maps" "$speed" crosswind >/dev/null
    run_configs "$name" "$maps" --runs "$runs" --world thesis --plume-model physics \
      --release-rate "$rate" --release-scale 0.25,2
  done
fi
if [[ $part != open-field ]]; then
  run_configs test-maps data/test-maps --runs 1 --sources 5 --plume-model physics \
    --gas-sensor mox-fast
fi
