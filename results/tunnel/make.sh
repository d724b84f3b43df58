#!/usr/bin/env bash
# Seed 004's 3-D systems in the wind tunnel (Figs. 11.3, 17.4, 17.8; docs/validation.md, "The 3-D
# systems against the thesis"): scripts/tunnel-benchmark.sh with 20 runs each, then its tables
# and box plots, and the two committed median runs.
#   results/tunnel/make.sh [OUT]
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
bash scripts/tunnel-benchmark.sh 20 "$out"
/usr/bin/python3 scripts/tunnel_table.py "$out" "$out" >"$out/table.md"
cp "$out/ste-3d/C/trajectory-median.png" "$out/ste-3d-C-median.png"
cp "$out/trackers/E/surge-spiral/trajectory-median.png" "$out/surge-spiral-E-median.png"
