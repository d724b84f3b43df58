#!/usr/bin/env bash
# Seed 004 ch. 16's benchmark, STE against adaptive Levy taxis (Fig. 16.5; methods/README.md,
# "Against STE"): scripts/levy-benchmark.sh with 3 runs per map, then its table.
#   results/levy-taxis/make.sh [OUT]
cd "$(dirname "$0")/../.."
source results/make-lib.sh "${1:-}"
bash scripts/levy-benchmark.sh 3 "$out"
/usr/bin/python3 scripts/levy_table.py "$out" >"$out/table.md"
