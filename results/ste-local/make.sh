#!/usr/bin/env bash
# Seed 004 ch. 12's local framework against the global one (Figs. 12.4, 12.7; docs/validation.md,
# "The local framework against the thesis"): scripts/local-benchmark.sh with 2 runs per map,
# then its table and box plots.
#   results/ste-local/make.sh [OUT]      # BUDGETS="7 9" for some budgets only
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
bash scripts/local-benchmark.sh 2 "$out"
/usr/bin/python3 scripts/local_table.py "$out" "$out" >"$out/table.md"
