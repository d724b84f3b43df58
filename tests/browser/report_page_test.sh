#!/usr/bin/env bash
# The browser test of report.html (issue 48; tests/browser/README.md): a small real evaluation of
# two methods on two of the test maps, and one of the 3-D tunnel with its replays, each report.html
# opened in headless Chromium by report_test.mjs (Playwright), which clicks through it and checks
# its screenshot.
# Usage: report_page_test.sh PLUMEKIT_EXE WORK_DIR
set -euo pipefail
exe=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
chromium=${PLUMEKIT_CHROMIUM:-/usr/bin/chromium}
if [[ ! -x $chromium ]]; then
  echo "report_page_test: no Chromium at $chromium; run scripts/install-deps.sh" >&2
  exit 1
fi
if [[ ! -f $here/node_modules/playwright-core/package.json ]]; then
  echo "report_page_test: no tests/browser/node_modules; run scripts/install-deps.sh" >&2
  exit 1
fi
rm -rf "$work"
mkdir -p "$work/maps"
cp "$here/../../data/test-maps/test-0-empty.json" "$here/../../data/test-maps/test-1-block.json" \
  "$work/maps/"
"$exe" evaluate --map-dir "$work/maps" --method ste,zigzag --plume-model gaussian --runs 1 \
  --sources 3 --max-samples 8 --max-steps 30 --threads 2 --out "$work/eval" > "$work/evaluate.log"
node "$here/report_test.mjs" --report "$work/eval/report.html" --screenshot "$work/report.png" \
  --chromium "$chromium"
"$exe" evaluate tunnel --method ste-3d,surge-spiral --runs 2 --time-limit 60 --threads 2 \
  --replays --out "$work/tunnel" > "$work/evaluate-tunnel.log"
node "$here/report_test.mjs" --report "$work/tunnel/report.html" \
  --screenshot "$work/report-tunnel.png" --chromium "$chromium" --tunnel
