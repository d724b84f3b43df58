#!/usr/bin/env bash
# scripts/check_doc_links.py catches a quoted-section pointer to a heading its page lacks, in a
# comment wrapped over two lines, in a help string split into literals and as a further title
# chained after a good one, and passes the pointers that name a heading, a heading's start or a
# bold paragraph title.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/docs" "$tmp/cfd"
printf '# Page\n\n## Building scale: how the solver got there\n\n**Memory estimate.** Text.\n' \
  > "$tmp/docs/page.md"
printf '// See (docs/page.md, "Building\n// scale") and docs/page.md, "Memory".\n' > "$tmp/cfd/ok.hpp"
printf '// gone: moved/README.md, "Numerics" (no such file: not checked)\n' >> "$tmp/cfd/ok.hpp"
/usr/bin/python3 "$src/scripts/check_doc_links.py" --root "$tmp"
printf '// The solver (docs/page.md,\n// "Numerics").\n' > "$tmp/cfd/bad.hpp"
printf '# docs/page.md, "Building scale", "Memory estimate", "Seen sources"\n' > "$tmp/cfd/bad.sh"
printf 'auto h = "a help (docs/page.md, "\n         "\\"Building height\\")";\n' > "$tmp/cfd/bad.cpp"
if out=$(/usr/bin/python3 "$src/scripts/check_doc_links.py" --root "$tmp"); then
  echo "FAIL: pointers to missing headings passed"; exit 1
fi
grep -q 'cfd/bad.hpp: docs/page.md, "Numerics" (no such heading)' <<<"$out" || { echo "FAIL: $out"; exit 1; }
grep -q 'cfd/bad.cpp: docs/page.md, "Building height" (no such heading)' <<<"$out" ||
  { echo "FAIL: $out"; exit 1; }
grep -q 'cfd/bad.sh: docs/page.md, "Seen sources" (no such heading)' <<<"$out" ||
  { echo "FAIL: $out"; exit 1; }
grep -q '3 broken' <<<"$out" || { echo "FAIL: $out"; exit 1; }
echo "ok: the link check refuses pointers to headings a page lacks"
