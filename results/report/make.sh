#!/usr/bin/env bash
# Issue 48's report.html: its size and opening time for 540 runs x 10 methods (the target names 8)
# with every replay linked, and pages to look at on the thesis's maps and on real floors.
#   results/report/make.sh [OUT]
# 1. All ten methods (`--method all`) on the nine 10 x 4 m test maps, 3 runs per source (540 runs
#    each), physics STE, --replays: report.html's size, the replays' total, and the median of 7 fresh opens in
#    headless Chromium (tests/browser/measure_open.mjs).
# 2. STE, surge-cast and the particle filter on the three real floors (data/floors), 1 run of
#    2 sources each, --replays.
# 3. The 3-D tunnel: `evaluate tunnel` of 3-D STE and surge-spiral, 10 runs each, --replays.
# Each page is put through the browser test (tests/browser/report_test.mjs), whose screenshot of
# an opened run is kept: OUT/shot-test-maps.png, OUT/shot-floors.png, OUT/shot-tunnel.png.
# Writes OUT/table.md.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
source scripts/blas-env.sh

t0=$(date +%s)
"$plumekit" evaluate --map-dir data/test-maps --runs 3 --method all --plume-model physics \
  --replays --threads 2 --out "$out/test-maps" >"$out/test-maps.log"
evaluate_s=$(($(date +%s) - t0))
"$plumekit" evaluate --map-dir data/floors --runs 1 --sources 2 --method ste,surge-cast,pf-sweep \
  --plume-model physics --replays --threads 2 --out "$out/floors" >"$out/floors.log"
"$plumekit" evaluate tunnel --method ste-3d,surge-spiral --runs 10 --replays --threads 2 \
  --out "$out/tunnel" >"$out/tunnel.log"

for name in test-maps floors tunnel; do
  node tests/browser/report_test.mjs --report "$out/$name/report.html" \
    --screenshot "$out/shot-$name.png" $([[ $name == tunnel ]] && echo --tunnel) \
    >"$out/browser-$name.log"
done
node tests/browser/measure_open.mjs "$out/test-maps/report.html" --runs 7 >"$out/open.json"

/usr/bin/python3 - "$out" "$evaluate_s" <<'PY' >"$out/table.md"
import json, os, sys
out, evaluate_s = sys.argv[1], int(sys.argv[2])
def size(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(path) for f in fs)
opened = json.load(open(os.path.join(out, "open.json")))
page = os.path.getsize(os.path.join(out, "test-maps", "report.html"))
replays = sum(size(os.path.join(out, "test-maps", m, "replays"))
              for m in os.listdir(os.path.join(out, "test-maps"))
              if os.path.isdir(os.path.join(out, "test-maps", m, "replays")))
print("| report.html, 540 runs x 10 methods (`--method all`), replays linked | measured | target |")
print("|---|---|---|")
print(f"| size | {page / 1e6:.1f} MB | <= 30 MB |")
print(f"| opens in headless Chromium (median of 7) | {opened['median_open_s']:.2f} s | <= 2 s |")
print(f"| its replays beside it (not in the page) | {replays / 1e6:.0f} MB | - |")
print(f"| the evaluation with --replays, 2 threads | {evaluate_s} s | - |")
PY
cat "$out/table.md"
