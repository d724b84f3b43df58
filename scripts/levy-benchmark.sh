#!/usr/bin/env bash
# Seed 004 ch. 16's benchmark (Fig. 16.5): STE against adaptive Lévy taxis in the open 10 x 4 m
# arena, conditions A-D of Table 8.1 (wind 0.2 / 0.9 m/s, release 5 / 10 % of the pump, here 500
# and 1000 units: the ratio the thesis gives, at plumekit's nominal), starting (a) inside the
# plume, 8 m downwind of the source, or (b) at a random crosswind position 8 m downwind. Every
# run ends on entering 0.5 m of the source (ch. 15) or when STE declares; the metric is the
# travelled distance. STE runs with the physics model and an unknown release rate (--release-scale
# 0.25,2), both methods in one plume per run (evaluate --method ste,levy-taxis), in plumekit's
# thesis-style world (steady flow, uniform meander).
#
#   scripts/levy-benchmark.sh [RUNS] [OUT]     # RUNS per map (default 3), 10 maps per setting
#   scripts/levy_table.py OUT                  # the table of docs/validation.md
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
runs=${1:-3}
out=${2:-out/levy}
plumekit=${PLUMEKIT:-./build/plumekit}
for condition in A:0.2:500 B:0.2:1000 C:0.9:500 D:0.9:1000; do
  IFS=: read -r name speed rate <<<"$condition"
  for start in plume crosswind; do
    maps="$out/maps/$name-$start"
    [[ -d $maps ]] || /usr/bin/python3 scripts/levy_maps.py "$maps" "$speed" "$start"
    "$plumekit" evaluate --map-dir "$maps" --method ste,levy-taxis --runs "$runs" \
      --world thesis --protocol thesis --plume-model physics --release-rate "$rate" --release-scale 0.25,2 \
      --success-radius 0.5 --threads 0 --out "$out/$name-$start" >/dev/null
    echo "condition $name ($speed m/s, release $rate), start $start: done"
  done
done
