#!/usr/bin/env bash
# Issue 20's comparison of every localization method on the nine test maps, 3 runs per source
# (docs/validation.md, "In cluttered maps: every method side by side"): the test-map part of
# scripts/compare-methods.sh, then its table and box plot. Writes OUT/test-maps/ in this folder's
# layout: scripts/compare_results.py results/methods-test-maps OUT/test-maps
#   results/methods-test-maps/make.sh [OUT]
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
bash scripts/compare-methods.sh 3 "$out" test-maps
dirs=()
for m in ste sweeping surge-cast zigzag pseudo-gradient pf-gradient pf-sweep apf; do
  dirs+=("$out/test-maps/$m")
done
/usr/bin/python3 scripts/methods_table.py "${dirs[@]}" >"$out/test-maps/table.md"
/usr/bin/python3 scripts/methods_boxplot.py "$out/test-maps/test-maps-boxplot.png" \
  "Nine test maps, 540 runs per method (faithful world, mox-fast)" "${dirs[@]}"
