#!/usr/bin/env bash
# Test of scripts/compare_results.py on small folders: timings, map_dir and the tables' step
# column are left out; last-digit rounding is reported but passes; a changed result, a changed
# picture and a missing file fail, each named.
set -euo pipefail
compare="$(cd "$(dirname "$0")" && pwd)/compare_results.py"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
make_run() {  # make_run DIR ERROR COMPUTE_S MEAN_ERROR MAP_DIR STEP_MS PICTURE
  mkdir -p "$1/part"
  printf 'map,run,error_m,compute_s\ntest-0,0,%s,%s\n' "$2" "$3" >"$1/runs.csv"
  printf '{"map_dir": "%s", "overall": {"mean_error_m": %s, "wall_s": %s}}\n' "$5" "$4" "$3" \
    >"$1/summary.json"
  printf '| method | error m | step ms |\n|---|---|---|\n| ste | %s | %s |\n' "$2" "$6" >"$1/table.md"
  printf '%s' "$7" >"$1/part/picture.png"
  echo "$3" >"$1/timings.csv"
}
expect() {  # expect EXIT_CODE NEW TEXT
  local code=0 output
  output=$(/usr/bin/python3 "$compare" "$work/old" "$work/$2") || code=$?
  [[ $code == "$1" && $output == *"$3"* ]] ||
    { echo "FAIL: $2: exit $code (want $1), output: $output"; exit 1; }
}
make_run "$work/old" 0.25 1.5 0.1234567890123 out/a/maps 2.1 P1
make_run "$work/timings" 0.25 9.75 0.1234567890123 /tmp/b/maps 3.4 P1
expect 0 timings "4 of 4 files agree"
make_run "$work/rounded" 0.25 1.5 0.12345678901234 out/a/maps 2.1 P1
expect 0 rounded "summary.json: agrees to rounding"
make_run "$work/result" 0.26 1.5 0.1234567890123 out/a/maps 2.1 P1
expect 1 result "runs.csv: 1 of 1 rows differ (rows 1) in error_m"
expect 1 result "table.md: line 3 differs"
make_run "$work/picture" 0.25 1.5 0.1234567890123 out/a/maps 2.1 P2
expect 1 picture "part/picture.png: bytes differ"
make_run "$work/missing" 0.25 1.5 0.1234567890123 out/a/maps 2.1 P1
rm "$work/missing/summary.json"
expect 1 missing "summary.json: missing"
echo "OK"
