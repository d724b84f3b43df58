#!/usr/bin/env bash
# Issue 48's replays: what --animate and `replay` cost, and frames of each kind of run to look at.
#   results/replay/make.sh [OUT]
# 1. A 50-sample mission (the thesis protocol with no declaration, physics STE) on a 20 x 20 m
#    random building (seed 48, the first of three): `localize` without and with --animate, three
#    times each; `replay` of its run folder to a 720p MP4, three times; medians, the files' sizes.
# 2. A frame (`replay --at`) of: cluttered-1 (surrogate STE), the depot floor (physics STE), a team
#    of three on the thesis arena, the particle filter and surge-cast on cluttered-2, and the 3-D
#    tunnel (STE and surge-spiral).
# Writes OUT/table.md and OUT/frame-*.png (and every run's folder and video).
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"

# Seconds of wall clock `"$@"` takes (its output to OUT/log).
seconds() {
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >>"$out/log" 2>&1
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc
}

"$plumekit" maps random --families building --count 3 --seed 48 --sources 2 \
  --building-min-size 20 --building-max-size 20 --out "$out/buildings" >>"$out/log"
building="$out/buildings/map-00000.json"
mission=(localize "$building" --source 17.2,11.4 --start 2,2 --seed 4 --plume-model physics
  --protocol thesis --entropy-fraction 0 --max-samples 50)
plain=() animated=() replayed=()
for k in 1 2 3; do
  rm -rf "$out/plain-$k" "$out/animated-$k" "$out/animated-$k.mp4" "$out/replayed-$k.mp4"
  plain+=("$(seconds "$plumekit" "${mission[@]}" --out "$out/plain-$k")")
  animated+=("$(seconds "$plumekit" "${mission[@]}" --out "$out/animated-$k" \
    --animate "$out/animated-$k.mp4")")
  replayed+=("$(seconds "$plumekit" replay "$out/animated-1" --out "$out/replayed-$k.mp4")")
done
frames=$("$plumekit" replay "$out/animated-1" --out "$out/replayed.png" --size 640x360 --json |
  /usr/bin/python3 -c 'import json, sys; print(json.load(sys.stdin)["frames"])')
"$plumekit" replay "$out/animated-1" --at 200 --out "$out/frame-building.png" >>"$out/log"

# Frames of other runs.
frame() {  # NAME AT LOCALIZE-ARGS...
  local name=$1 at=$2
  shift 2
  rm -rf "$out/run-$name" "$out/run-$name.mp4"
  "$plumekit" localize "$@" --out "$out/run-$name" --animate "$out/run-$name.mp4" >>"$out/log"
  "$plumekit" replay "$out/run-$name" --at "$at" --out "$out/frame-$name.png" >>"$out/log"
}
frame cluttered-1 25 data/maps/cluttered-1.json --source 8,2 --seed 1
frame depot 80 data/floors/depot.json --source 10,3.5 --seed 2 --plume-model physics
frame team 20 data/test-maps/test-1-block.json --source 7,1.5 --start 1,2.5 --robots 3 \
  --team cooperative --plume-model physics --seed 2
frame pf-sweep 60 data/maps/cluttered-2.json --source 8,2 --start 1,2 --method pf-sweep --seed 3
frame surge-cast 30 data/maps/cluttered-2.json --source 8,2 --start 1,2 --method surge-cast --seed 3
# The 3-D tunnel, seen from above and from the side: 3-D STE and the surge-spiral tracker.
tunnel() {  # NAME AT LOCALIZE-TUNNEL-ARGS...
  local name=$1 at=$2
  shift 2
  rm -rf "$out/run-$name" "$out/run-$name.mp4"
  "$plumekit" localize tunnel "$@" --out "$out/run-$name" --animate "$out/run-$name.mp4" \
    >>"$out/log"
  "$plumekit" replay "$out/run-$name" --at "$at" --out "$out/frame-$name.png" >>"$out/log"
}
tunnel tunnel-ste 40 --source 1,0.99,1.28 --start 4.86,2.58,1.4 --seed 3
tunnel tunnel-spiral 100 --method surge-spiral --source 1,1.5,0.8 --seed 3

/usr/bin/python3 - "$out" "$frames" "${plain[*]}" "${animated[*]}" "${replayed[*]}" <<'PY' \
  >"$out/table.md"
import os, statistics, sys
out, frames = sys.argv[1], int(sys.argv[2])
plain, animated, replayed = (sorted(map(float, a.split())) for a in sys.argv[3:6])
p, a, r = (statistics.median(v) for v in (plain, animated, replayed))
mb = os.path.getsize(os.path.join(out, "animated-1.mp4")) / 1e6
print("| 50-sample mission, 20 x 20 m building | median of 3 | runs |")
print("|---|---|---|")
print(f"| `localize` | {p:.1f} s | {', '.join(f'{v:.1f}' for v in plain)} |")
print(f"| `localize --animate` (720p MP4) | {a:.1f} s (+{100 * (a - p) / p:.0f} %) |"
      f" {', '.join(f'{v:.1f}' for v in animated)} |")
print(f"| `replay` to a 720p MP4, {frames} frames | {r:.1f} s | {', '.join(f'{v:.1f}' for v in replayed)} |")
print(f"| the MP4 | {mb:.1f} MB | |")
PY
cat "$out/table.md"
