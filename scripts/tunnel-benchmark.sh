#!/usr/bin/env bash
# Seed 004's 3-D systems in its wind tunnel (`plumekit evaluate tunnel`; docs/methods.md, "The 3-D
# tunnel"):
#   - Fig. 11.3: the 3-D STE in the thesis's simulation conditions A-D (Table 8.1: wind 0.2 / 0.9
#     m/s, release 5 / 10 %, here 500 / 1000 units m^3/s) in the 10 x 4 x 2 m tunnel, RUNS runs
#     each (the thesis ran 10), and condition D again with the thesis's likelihood alone
#     (--sigma-rel 0);
#   - Figs. 17.4 and 17.8: the 3-D surge-spiral and the 2-D surge-cast baseline in set-ups A-H
#     (Table 17.1: wind 0.2 / 0.9 m/s, release low / high = 500 / 1000, threshold 0.7 / 0.9) in
#     the 20 x 4 x 2 m tunnel (ch. 5.1's first arena), starting 10 m downwind, RUNS runs each
#     (the thesis ran 20).
#
#   scripts/tunnel-benchmark.sh [RUNS] [OUT]    # RUNS default 20; OUT default out/tunnel
#   scripts/tunnel_table.py OUT [PNG_DIR]       # the tables and box plots of docs/validation.md
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
runs=${1:-20}
out=${2:-out/tunnel}
plumekit=${PLUMEKIT:-./build/plumekit}
wall="$out/wall.txt"
# wall.txt is this script's own line; any other file of that name is left alone.
if [[ -e $wall ]] && ! grep -q '^tunnel benchmark: ' "$wall"; then
  echo "tunnel-benchmark.sh: $wall exists and was not written by this script" >&2
  exit 2
fi
evaluate() {
  "$plumekit" evaluate tunnel --runs "$runs" --threads 0 "$@" >/dev/null
}
start=$(date +%s)
for condition in A:0.2:500 B:0.2:1000 C:0.9:500 D:0.9:1000; do
  IFS=: read -r name speed rate <<<"$condition"
  evaluate --method ste-3d --wind-speed "$speed" --release-rate "$rate" --out "$out/ste-3d/$name"
done
evaluate --method ste-3d --wind-speed 0.9 --release-rate 1000 --sigma-rel 0 \
  --out "$out/ste-3d/D-thesis-likelihood"
ste=$(($(date +%s) - start))
echo "3-D STE: $ste s"
for setup in A:0.2:500:0.7 B:0.2:500:0.9 C:0.2:1000:0.7 D:0.2:1000:0.9 \
  E:0.9:500:0.7 F:0.9:500:0.9 G:0.9:1000:0.7 H:0.9:1000:0.9; do
  IFS=: read -r name speed rate threshold <<<"$setup"
  evaluate --method surge-spiral,surge-cast-2d --tunnel 20,4,2 --wind-speed "$speed" \
    --release-rate "$rate" --threshold "$threshold" --out "$out/trackers/$name"
  echo "set-up $name: done"
done
echo "tunnel benchmark: $(($(date +%s) - start)) s wall (3-D STE $ste s)" | tee "$wall"
