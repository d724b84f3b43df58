#!/usr/bin/env bash
# The data of the hybrid plume model (issue 46; docs/design/surrogate.md, "Hybrid models"), made
# on the CPU machine: datasets on 0.2 m cells with the physics plume channel (--physics-input), in
# the faithful world, every inlet at a speed drawn from 0.3-2 m/s.
#   scripts/hybrid-data.sh DIR [PLUMEKIT]
# DIR/families, DIR/buildings, DIR/buildings-b: the training data (60 six-family 10 x 4 m maps and
#   65 + 40 random buildings of 6-30 m: 2,320 plumes);
# DIR/test-maps, test-families, test-buildings, each with -floor, -r5, -r6 (the same maps and
#   sources in other filament seeds) and -truth4 (the mean of the four): the test sets.
# About 12 minutes on 2 cores. A dataset already made (its manifest.json there) is kept.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/blas-env.sh
data=$(realpath -m -- "${1:?usage: scripts/hybrid-data.sh DIR [PLUMEKIT]}")
plumekit=${2:-./build/plumekit}
python=${PYTHON:-/usr/bin/python3}
gen() { # OUT FLAGS...: a hybrid dataset, unless made already
  local dir=$1
  shift
  [[ -f $dir/manifest.json ]] || "$plumekit" dataset generate --feature-cell 0.2 --physics-input \
    --threads 2 --out "$dir" "$@" >/dev/null
}
six="rectangle,two-rectangles,l-shape,u-shape,three-rectangles,shape-and-rectangle"
# Training data (scripts/train-model-v2.sh's families and buildings, and 40 more buildings).
gen "$data/families" --maps 60 --sources 16 --seed 21 --inlet-speeds 0.3,2 --families "$six"
gen "$data/buildings" --families building --maps 65 --sources 16 --cell 0.1 --seed 22 --inlet-speeds 0.3,2
gen "$data/buildings-b" --families building --maps 40 --sources 8 --cell 0.1 --seed 24 --inlet-speeds 0.3,2
# Test sets, four realizations each (the same maps and sources, other filament seeds).
gen "$data/test-maps" --map-dir data/test-maps
gen "$data/test-families" --maps 12 --sources 8 --seed 25 --inlet-speeds 0.3,2 --families "$six"
gen "$data/test-buildings" --families building --maps 12 --sources 8 --cell 0.1 --seed 23 --inlet-speeds 0.3,2
declare -A maps=([test-maps]=data/test-maps [test-families]=$data/test-families/maps
  [test-buildings]=$data/test-buildings/maps)
declare -A cell=([test-maps]="" [test-families]="" [test-buildings]="--cell 0.1")
declare -A floor_seed=([test-maps]=2 [test-families]=4 [test-buildings]=3)
for t in test-maps test-families test-buildings; do
  # shellcheck disable=SC2086
  gen "$data/$t-floor" --map-dir "${maps[$t]}" ${cell[$t]} --seed "${floor_seed[$t]}"
  for s in 5 6; do
    # shellcheck disable=SC2086
    gen "$data/$t-r$s" --map-dir "${maps[$t]}" ${cell[$t]} --seed "$s"
  done
  [[ -d $data/$t-truth4 ]] || "$python" surrogate/train/mean_of_realizations.py "$data/$t-truth4" \
    "$data/$t" "$data/$t-floor" "$data/$t-r5" "$data/$t-r6"
done
