#!/usr/bin/env bash
# scripts/check_layers.py catches what it is for: a world file that includes a method is refused,
# naming the file and line, and a tree whose includes point down passes.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/docs" "$tmp/world" "$tmp/methods"
cp "$src/docs/architecture.md" "$tmp/docs/"
printf '#include "core/geometry.hpp"\n' > "$tmp/methods/ok.cpp"
printf '#include "map/map.hpp"\n' > "$tmp/world/ok.cpp"
/usr/bin/python3 "$src/scripts/check_layers.py" --root "$tmp"
printf '// fine\n#include "methods/method.hpp"\n' > "$tmp/world/bad.cpp"
if out=$(/usr/bin/python3 "$src/scripts/check_layers.py" --root "$tmp"); then
  echo "FAIL: a world file including methods/ passed"; exit 1
fi
grep -q 'world/bad.cpp:2: world/ may not include methods/' <<<"$out" || { echo "FAIL: $out"; exit 1; }
echo "ok: the layering check refuses world -> methods"
