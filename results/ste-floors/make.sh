#!/usr/bin/env bash
# STE on the three real floors (data/floors) and on 20 random buildings (seed 1001), every
# default (the faithful world, the ideal sensor), seed 1 (docs/validation.md, "Real floors and
# buildings"; the v2 surrogate: "Against physics-STE, the same runs").
#   results/ste-floors/make.sh [OUT] [PART...]
#   PART: real buildings real-gaussian buildings-gaussian real-surrogate-v2
#         buildings-surrogate-v2 (default all)
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
parts=("${@:2}")
[[ ${#parts[@]} -gt 0 ]] ||
  parts=(real buildings real-gaussian buildings-gaussian real-surrogate-v2 buildings-surrogate-v2)
buildings="$out/buildings-1001"
v2=(--plume-model surrogate --cnn data/models/plume-unet-v2.pkcnn --threads 2)
for part in "${parts[@]}"; do
  if [[ $part == buildings* && ! -d $buildings ]]; then
    "$plumekit" maps random --families building --count 20 --seed 1001 --sources 3 \
      --out "$buildings"
  fi
  case $part in
    real) flags=(--map-dir data/floors --runs 2 --plume-model physics --cell 0.1 --threads 2) ;;
    buildings) flags=(--map-dir "$buildings" --runs 1 --plume-model physics --threads 2) ;;
    # The Gaussian baseline ran on one thread beside another job.
    real-gaussian) flags=(--map-dir data/floors --runs 2 --plume-model gaussian --cell 0.1 --threads 1) ;;
    buildings-gaussian) flags=(--map-dir "$buildings" --runs 1 --plume-model gaussian --threads 1) ;;
    real-surrogate-v2) flags=(--map-dir data/floors --runs 2 --cell 0.1 "${v2[@]}") ;;
    buildings-surrogate-v2) flags=(--map-dir "$buildings" --runs 1 "${v2[@]}") ;;
    *) echo "$0: unknown part $part" >&2; exit 2 ;;
  esac
  "$plumekit" evaluate --protocol thesis "${flags[@]}" --out "$out/$part"
  # The committed picture of the depot's median run.
  if [[ $part == real ]]; then cp "$out/real/trajectories/depot.png" "$out/real/trajectory-depot.png"; fi
done
