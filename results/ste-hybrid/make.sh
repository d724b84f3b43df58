#!/usr/bin/env bash
# STE with the hybrid plume model (data/models/plume-unet-v3.pkcnn, issue 46) against STE with the
# physics model, the same runs: the nine test maps, three held-out 10 x 4 m maps (seed 4601), the
# three real floors and 20 random buildings (seed 1001); the faithful world, the mox-fast sensor,
# seed 1 (README.md here).
#   results/ste-hybrid/make.sh [OUT] [PART...]
#   PART: test-hybrid test-physics heldout-hybrid heldout-physics real-hybrid real-physics
#         buildings-hybrid buildings-physics (default all); also tuning, the likelihood sweep on
#         maps of its own (results/ste-hybrid/README.md, "The likelihood"; OUT/tuning/SET-mS-kK
#         and OUT/tuning/table.md), and predict-depot, the hybrid's plume of one source on Nav2's
#         depot (predict-depot.png here)
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
source scripts/blas-env.sh
parts=("${@:2}")
[[ ${#parts[@]} -gt 0 ]] || parts=(test-hybrid test-physics heldout-hybrid heldout-physics
  real-hybrid real-physics buildings-hybrid buildings-physics)
six=rectangle,two-rectangles,l-shape,u-shape,three-rectangles,shape-and-rectangle
[[ -d $out/heldout-4601 ]] || "$plumekit" maps random --families "$six" --count 3 --seed 4601 \
  --sources 10 --out "$out/heldout-4601" >/dev/null
[[ -d $out/buildings-1001 ]] || "$plumekit" maps random --families building --count 20 \
  --seed 1001 --sources 3 --out "$out/buildings-1001" >/dev/null
tuning() { # held-out maps of the likelihood's own: six-family 10 x 4 m maps and buildings
  local t=$out/tuning
  [[ -d $t/maps-4700 ]] || "$plumekit" maps random --families "$six" --count 6 --seed 4700 \
    --sources 10 --out "$t/maps-4700" >/dev/null
  [[ -d $t/buildings-2002 ]] || "$plumekit" maps random --families building --count 12 \
    --seed 2002 --sources 2 --out "$t/buildings-2002" >/dev/null
  local sm k
  for sm in 200 100; do
    for k in 0 1 2 4; do
      [[ -f $t/families-m$sm-k$k/summary.json ]] || "$plumekit" evaluate --map-dir "$t/maps-4700" \
        --runs 3 --cnn hybrid --gas-sensor mox-fast --threads 2 --sigma-m "$sm" --sigma-std "$k" \
        --protocol thesis --table-cache "$t/tables" --out "$t/families-m$sm-k$k" >/dev/null
      [[ -f $t/buildings-m$sm-k$k/summary.json ]] || "$plumekit" evaluate --map-dir \
        "$t/buildings-2002" --runs 1 --cnn hybrid --gas-sensor mox-fast --threads 2 \
        --sigma-m "$sm" --sigma-std "$k" --protocol thesis --table-cache "$t/tables" \
        --out "$t/buildings-m$sm-k$k" >/dev/null
    done
  done
  /usr/bin/python3 scripts/likelihood_table.py "$t" >"$t/table.md"
}
for part in "${parts[@]}"; do
  [[ $part == tuning ]] && { tuning; continue; }
  if [[ $part == predict-depot ]]; then
    "$plumekit" predict data/floors/depot.json --source 2,0 --out "$out/predict-depot" >/dev/null
    continue
  fi
  case ${part#*-} in
    hybrid) model=(--plume-model surrogate --cnn hybrid) ;;
    physics) model=(--plume-model physics) ;;
    *) echo "$0: unknown part $part" >&2; exit 2 ;;
  esac
  case ${part%%-*} in
    test) maps=(--map-dir data/test-maps --runs 1) ;;
    heldout) maps=(--map-dir "$out/heldout-4601" --runs 9) ;;
    real) maps=(--map-dir data/floors --runs 2 --cell 0.1) ;;
    buildings) maps=(--map-dir "$out/buildings-1001" --runs 1) ;;
    *) echo "$0: unknown part $part" >&2; exit 2 ;;
  esac
  "$plumekit" evaluate "${maps[@]}" "${model[@]}" --gas-sensor mox-fast --threads 2 \
    --protocol thesis --out "$out/$part"
done
