#!/usr/bin/env bash
# Reproduces the shipped surrogate data/models/plume-unet.pkcnn and its evaluation, from nothing:
#   1. the thesis-scale training dataset (180 random maps x 100 sources, filament model, seed 1);
#   2. the ground-truth plumes of the nine test maps;
#   3. training (AdamW, batch 32, cosine learning rate over 5 epochs; see surrogate/README.md);
#   4. the evaluation on the held-out maps and the test maps.
# Every step resumes where it stopped when run again. WORK (default out/train) holds the datasets
# (about 1.5 GB) and the checkpoints; the model and its evaluation go to data/models/.
# On this 2-core machine: about 20 min for the data and 7 to 8 min per epoch on the CPU.
set -euo pipefail
cd "$(dirname "$0")/.."
work=${1:-out/train}
epochs=${EPOCHS:-5}
mkdir -p "$work" data/models
[ -x build/plumekit ] || bash scripts/build.sh
./build/plumekit dataset generate --maps 180 --sources 100 --seed 1 --threads 2 --out "$work/dataset"
./build/plumekit dataset generate --from-maps data/test-maps --threads 2 --out "$work/test-truth"
/usr/bin/python3 surrogate/train/train.py --data "$work/dataset" --work "$work/checkpoints" \
  --out data/models/plume-unet.pkcnn --epochs "$epochs" --lr-schedule cosine --batch 32 --seed 1 \
  ${MAX_MINUTES:+--max-minutes "$MAX_MINUTES"}
cp "$work/checkpoints/log.csv" data/models/plume-unet.log.csv
/usr/bin/python3 surrogate/train/evaluate.py --model data/models/plume-unet.pkcnn \
  --data "$work/dataset" --test "$work/test-truth" --out data/models/plume-unet-eval
