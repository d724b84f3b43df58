#!/usr/bin/env bash
# First stage of the shipped surrogate: the base model data/models/plume-unet-base.pkcnn, from nothing
# (scripts/finetune-model.sh then makes data/models/plume-unet.pkcnn from it):
#   1. the training dataset (MAPS random maps x 100 sources, filament model, seed 1, in the
#      thesis-style world: --world thesis);
#   2. the ground-truth plumes of the nine test maps;
#   3. training (AdamW, batch 32, cosine learning rate over EPOCHS epochs; docs/design/surrogate.md);
#   4. the evaluation on the held-out maps and the test maps.
# Every step resumes where it stopped when run again. WORK (default out/train) holds the datasets,
# the checkpoints and the evaluation (WORK/evaluation); the model and its log go to data/models/.
# Settings (environment): MAPS (default 180, the thesis's scale), EPOCHS (5), THREADS (nproc),
# MAX_MINUTES (no limit: stop training after this many minutes; rerun to go on), PYTHON
# (/usr/bin/python3, Debian's torch; any python3 with torch and numpy works, CUDA is used when
# present). The shipped base model came from two runs on a GPU machine (docs/design/surrogate.md):
#   MAPS=360 EPOCHS=8 bash scripts/train-model.sh; MAPS=360 EPOCHS=22 bash scripts/train-model.sh
# (the second resumes the first and carries the cosine on as planned for 22 epochs).
# On the 2-core build machine the 180-map dataset takes about 20 min and an epoch 7 to 8 min.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
work=${1:-out/train}
maps=${MAPS:-180}
epochs=${EPOCHS:-5}
threads=${THREADS:-$(nproc)}
python=${PYTHON:-/usr/bin/python3}
mkdir -p "$work" data/models
[ -x build/plumekit ] || bash scripts/build.sh
./build/plumekit dataset generate --maps "$maps" --sources 100 --seed 1 --threads "$threads" --world thesis \
  --out "$work/dataset"
./build/plumekit dataset generate --map-dir data/test-maps --seed 0 --threads "$threads" --world thesis \
  --out "$work/test-truth"
"$python" surrogate/train/train.py --data "$work/dataset" --work "$work/checkpoints" \
  --out data/models/plume-unet-base.pkcnn --epochs "$epochs" --lr-schedule cosine --batch 32 --seed 1 \
  --threads "$threads" ${MAX_MINUTES:+--max-minutes "$MAX_MINUTES"}
cp "$work/checkpoints/log.csv" data/models/plume-unet-base.log.csv
"$python" surrogate/train/evaluate.py --model data/models/plume-unet-base.pkcnn \
  --data "$work/dataset" --test "$work/test-truth" --out "$work/evaluation" --threads "$threads"
