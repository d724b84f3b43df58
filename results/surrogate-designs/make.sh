#!/usr/bin/env bash
# Issue 46's comparison of plume models (README.md here): the plain, hybrid and residual designs
# trained on the same data with the same budget, the v2 model, the physics plume and the
# two-realization floor, scored on the nine test maps, held-out 10 x 4 m maps and held-out
# buildings, each the mean of four realizations.
#   results/surrogate-designs/make.sh [OUT]
# MODELS=DIR takes the trained models from DIR/e45/ and DIR/e110/ (DESIGN.pkcnn, as
# scripts/train-on-gpu.sh writes them) instead of training; without it the designs are trained
# here with scripts/train-on-gpu.sh, which wants a GPU (about 3 and 7 minutes on an H200; on this
# 2-core CPU, days). Every step keeps what an earlier run of the same OUT finished.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
source scripts/blas-env.sh
python=${PYTHON:-/usr/bin/python3}
data=$out/data
gen() { # OUT FLAGS...: a hybrid dataset (0.2 m cells, the physics channel), unless made already
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
# Training: the three designs side by side, 45 epochs, then 110 (the validation loss picks the
# epoch, patience 20).
models=${MODELS:-$out/models}
if [[ -z ${MODELS:-} ]]; then
  [[ -d $out/pack ]] || "$python" surrogate/train/pack.py pack "$data/families" "$data/buildings" \
    "$data/buildings-b" --out "$out/pack"
  for e in 45 110; do
    [[ -f $models/e$e/residual.pkcnn ]] || PYTHON="$python" EPOCHS=$e \
      bash scripts/train-on-gpu.sh "$out/pack" "$models/e$e"
  done
fi
mkdir -p "$out/eval"
truth=("$data/test-maps-truth4" "$data/test-families-truth4" "$data/test-buildings-truth4")
score() { # NAME MODEL [evaluate.py flags]
  local name=$1 model=$2
  shift 2
  "$python" surrogate/train/evaluate.py --model "$model" --json --threads 2 "$@" \
    2>/dev/null >"$out/eval/$name.json"
}
for e in 45 110; do
  for d in plain hybrid residual; do
    score "$d-e$e" "$models/e$e/$d.pkcnn" --test "${truth[@]}"
    cp "$models/e$e/$d.log.csv" "$out/eval/$d-e$e.log.csv"
  done
done
score v2 data/models/plume-unet-v2.pkcnn --test "${truth[@]}"
score floor "$models/e110/hybrid.pkcnn" --test "$data/test-maps" "$data/test-families" \
  "$data/test-buildings" --floor "$data/test-maps-floor" "$data/test-families-floor" \
  "$data/test-buildings-floor"
"$python" scripts/designs_table.py "$out/eval" "$out"
