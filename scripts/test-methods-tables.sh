#!/usr/bin/env bash
# Test of issue 20's table and plot scripts on small real evaluations: methods_table.py's row
# (its within-1.5 m share counted again here from runs.csv), validation_table.py's rows for a
# particle filter and a tracker, and methods_boxplot.py's picture (and its refusal to overwrite
# a file it did not draw).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
plumekit=${PLUMEKIT:-$root/build/plumekit}
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/maps"
cp "$root/data/test-maps/test-1-block.json" "$work/maps/"
evaluate() {
  "$plumekit" evaluate --map-dir "$work/maps" --sources 4 --runs 1 --max-steps "$3" --threads 0 --protocol thesis \
    --out "$work/$1" --method "$2" > /dev/null
}
# On this map, surge-cast reaches two of the four sources' boxes in 40 stops.
evaluate surge-cast surge-cast 40
evaluate pf-sweep pf-sweep 15

row=$("$python" "$root/scripts/methods_table.py" "$work/surge-cast" | tail -1)
echo "$row"
runs_csv="$work/surge-cast/runs.csv"
# Counted with python's csv module, not split at commas: runs.csv quotes a field as RFC 4180 says.
column() {  # the values of column $2 of CSV file $1, one a line
  "$python" -c 'import csv, sys; [print(r[sys.argv[2]]) for r in csv.DictReader(open(sys.argv[1], newline=""))]' "$1" "$2"
}
share=$(column "$runs_csv" error_m | awk '{ n++; if ($1 <= 1.5) k++ } END { printf "%.0f %%", 100 * k / n }')
[[ $row == "| surge-cast | 4 | "* ]] || { echo "FAIL: methods_table row: $row"; exit 1; }
[[ $row == *"| $share |"* ]] || { echo "FAIL: within 1.5 m should read $share: $row"; exit 1; }
overhead=$(column "$runs_csv" distance_overhead |
  awk '$1 != "" { n++; s += $1 } END { printf "%.2f", s / n }')

table=$("$python" "$root/scripts/validation_table.py" "$work")
echo "$table"
grep -q '^| PF + sweeping (0.4, 0.9) | 4 | ' <<< "$table" || { echo "FAIL: no PF row"; exit 1; }
grep -q "^| surge-cast | 4 | [0-9]* % | $overhead ± " <<< "$table" ||
  { echo "FAIL: the tracker row should have the mean d_o $overhead"; exit 1; }
grep -q '^Same as published: ' <<< "$table" || { echo "FAIL: no ordering line"; exit 1; }

"$python" "$root/scripts/methods_boxplot.py" "$work/box.png" "test" "$work/surge-cast" \
  "$work/pf-sweep"
[[ $(head -c 8 "$work/box.png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] ||
  { echo "FAIL: methods_boxplot.py wrote no PNG"; exit 1; }
# Its own picture is redrawn; a file it did not write is refused (exit 2) and left as it was.
"$python" "$root/scripts/methods_boxplot.py" "$work/box.png" "again" "$work/surge-cast"
echo "a user's notes" > "$work/notes.png"
code=0
"$python" "$root/scripts/methods_boxplot.py" "$work/notes.png" "x" "$work/surge-cast" 2> /dev/null ||
  code=$?
[[ $code == 2 && $(cat "$work/notes.png") == "a user's notes" ]] ||
  { echo "FAIL: methods_boxplot.py overwrote a file it did not write (exit $code)"; exit 1; }
echo "OK"
