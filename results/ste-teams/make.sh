#!/usr/bin/env bash
# Seed 004 ch. 13's robot teams against one robot (Fig. 13.3; docs/validation.md, "Teams against one
# robot"): scripts/team-benchmark.sh with 2 runs per map, then its table and box plots.
#   results/ste-teams/make.sh [OUT] [all|open-field|test-maps]
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
bash scripts/team-benchmark.sh 2 "$out" "${2:-all}"
/usr/bin/python3 scripts/team_table.py "$out" "$out" >"$out/table.md"
