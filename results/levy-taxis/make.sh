#!/usr/bin/env bash
# Seed 004 ch. 16's benchmark, STE against adaptive Levy taxis (Fig. 16.5; docs/validation.md,
# "Adaptive Lévy taxis against STE"): scripts/levy-benchmark.sh with 3 runs per map, then its
# table.
#   results/levy-taxis/make.sh [OUT]
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
bash scripts/levy-benchmark.sh 3 "$out"
/usr/bin/python3 scripts/levy_table.py "$out" >"$out/table.md"
