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
# The training data and the test sets, four realizations each (scripts/hybrid-data.sh).
bash scripts/hybrid-data.sh "$data" "$plumekit"
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
# The thesis's 64 x 64 models (v1), on their own grid: the same maps and sources of the two
# 10 x 4 m test sets, four realizations each, in v1/ under the same set names so that their
# figures fall in the same columns (they cannot take the buildings).
declare -A v1_maps=([test-maps]=data/test-maps [test-families]=$data/test-families/maps)
declare -A v1_seeds=([test-maps]="1 2 5 6" [test-families]="1 4 5 6")
v1_truth=()
for t in test-maps test-families; do
  runs=()
  for s in ${v1_seeds[$t]}; do
    [[ -f $data/v1/$t-s$s/manifest.json ]] || "$plumekit" dataset generate --threads 2 \
      --map-dir "${v1_maps[$t]}" --seed "$s" --out "$data/v1/$t-s$s" >/dev/null
    runs+=("$data/v1/$t-s$s")
  done
  [[ -d $data/v1/$t-truth4 ]] || "$python" surrogate/train/mean_of_realizations.py \
    "$data/v1/$t-truth4" "${runs[@]}"
  v1_truth+=("$data/v1/$t-truth4")
done
score v1 data/models/plume-unet.pkcnn --test "${v1_truth[@]}"
score v1-faithful data/models/plume-unet-faithful.pkcnn --test "${v1_truth[@]}"
score floor "$models/e110/hybrid.pkcnn" --test "$data/test-maps" "$data/test-families" \
  "$data/test-buildings" --floor "$data/test-maps-floor" "$data/test-families-floor" \
  "$data/test-buildings-floor"
"$python" scripts/designs_table.py "$out/eval" "$out"
