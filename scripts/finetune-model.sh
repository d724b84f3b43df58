#!/usr/bin/env bash
# Second stage of the shipped surrogate: fine-tunes the base model (data/models/plume-unet-base.pkcnn,
# made by scripts/train-model.sh on the thesis's four map families) on more cluttered layouts, which
# gives data/models/plume-unet.pkcnn and its evaluation (docs/design/surrogate.md):
#   1. MAPS random maps x 50 sources, filament model, seed 2, drawn from all six families (the
#      thesis's four, three-rectangles, shape-and-rectangle; docs/design/dataset.md);
#   2. the ground-truth plumes of the nine test maps;
#   3. train.py --init BASE: EPOCHS epochs, lr 3e-4 with a cosine decay, batch 32;
#   4. the evaluation on this dataset's validation maps and on the test maps.
# Every step resumes where it stopped when run again. WORK (default out/finetune) holds the datasets
# and the checkpoints. Settings (environment): MAPS (200), EPOCHS (4), THREADS (nproc), BASE,
# MAX_MINUTES, PYTHON (/usr/bin/python3), as in train-model.sh; SEED (2) of the maps and plumes;
# OUT (data/models/plume-unet.pkcnn), whose log is OUT's name with .log.csv and whose evaluation
# goes to OUT's name with -eval; WORLD: thesis (default, the shipped model's: --world thesis, steady
# wind, gas through walls) or faithful (--world faithful, the plumekit default: occlusion and the
# unsteady wind), for both the data and the test maps' truth.
# On the 2-core build machine the data take about 10 min and an epoch about 13 min.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
work=${1:-out/finetune}
maps=${MAPS:-200}
epochs=${EPOCHS:-4}
threads=${THREADS:-$(nproc)}
python=${PYTHON:-/usr/bin/python3}
base=${BASE:-data/models/plume-unet-base.pkcnn}
seed=${SEED:-2}
out=${OUT:-data/models/plume-unet.pkcnn}
WORLD=${WORLD:-thesis}
case $WORLD in
  thesis | faithful) world=(--world "$WORLD") ;;
  *) echo "finetune-model.sh: WORLD must be thesis or faithful, not '$WORLD'" >&2; exit 2 ;;
esac
# OUT is replaced, so it must be a model file or not exist: never another file of the user's.
if [ -e "$out" ] && [ "$(head -c 8 "$out")" != PLUMECNN ]; then
  echo "finetune-model.sh: OUT=$out exists and is not a plumekit-cnn model; not replacing it" >&2
  exit 2
fi
mkdir -p "$work" "$(dirname "$out")"
[ -x build/plumekit ] || bash scripts/build.sh
./build/plumekit dataset generate --maps "$maps" --sources 50 --seed "$seed" --threads "$threads" \
  --families rectangle,two-rectangles,l-shape,u-shape,three-rectangles,shape-and-rectangle \
  "${world[@]}" --out "$work/dataset"
./build/plumekit dataset generate --map-dir data/test-maps --seed 0 --threads "$threads" "${world[@]}" \
  --out "$work/test-truth"
"$python" surrogate/train/train.py --data "$work/dataset" --work "$work/checkpoints" --init "$base" \
  --out "$out" --epochs "$epochs" --lr 3e-4 --lr-schedule cosine --batch 32 \
  --seed 1 --threads "$threads" ${MAX_MINUTES:+--max-minutes "$MAX_MINUTES"}
cp "$work/checkpoints/log.csv" "${out%.pkcnn}.log.csv"
"$python" surrogate/train/evaluate.py --model "$out" \
  --data "$work/dataset" --test "$work/test-truth" --out "${out%.pkcnn}-eval" --threads "$threads"
