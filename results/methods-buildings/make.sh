#!/usr/bin/env bash
# Issue 20's comparison of every localization method on 20 random buildings (seed 1001), each
# map's first source, one run (docs/validation.md, "In cluttered maps: every method side by
# side"): the buildings part of scripts/compare-methods.sh, then its table and box plot. Writes
# OUT/buildings/ in this folder's layout (the maps in OUT/buildings-maps):
#   scripts/compare_results.py results/methods-buildings OUT/buildings
#   results/methods-buildings/make.sh [OUT]
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
bash scripts/compare-methods.sh 3 "$out" buildings
dirs=()
for m in ste sweeping surge-cast zigzag pseudo-gradient pf-gradient pf-sweep apf; do
  dirs+=("$out/buildings/$m")
done
/usr/bin/python3 scripts/methods_table.py "${dirs[@]}" >"$out/buildings/table.md"
/usr/bin/python3 scripts/methods_boxplot.py "$out/buildings/buildings-boxplot.png" \
  "20 random buildings" "${dirs[@]}"
