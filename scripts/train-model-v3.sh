#!/usr/bin/env bash
# The hybrid surrogate's CPU recipe (issue 46; docs/design/surrogate.md, "Hybrid models"): from
# nothing to a model and its evaluation within 2 hours on 2 cores.
#   1. the data (scripts/hybrid-data.sh: 2,320 training plumes and the test sets, about 12 min);
#   2. the hybrid design alone (the map, its wind and the physics plume of the source as inputs),
#      AdamW with a cosine learning rate over EPOCHS epochs, stopped after MAX_MINUTES of
#      training at the latest;
#   3. its evaluation against the mean of four realizations on the nine test maps, held-out
#      10 x 4 m maps and held-out buildings, the physics plume's figures beside it.
#   scripts/train-model-v3.sh [WORK] [MODEL]
# WORK (default out/train-v3) holds the data, the checkpoints and the evaluation; MODEL (default
# WORK/plume-unet-v3-cpu.pkcnn) gets the model, its golden pair and MODEL.log.csv. Every step
# resumes where it stopped when run again. Settings (environment): EPOCHS (16), MAX_MINUTES (95),
# BATCH (8), THREADS (nproc), PYTHON (/usr/bin/python3). The shipped model was trained on a GPU
# instead (results/surrogate-designs/make.sh; scripts/train-on-gpu.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
work=$(realpath -m -- "${1:-out/train-v3}")
model=$(realpath -m -- "${2:-$work/plume-unet-v3-cpu.pkcnn}")
threads=${THREADS:-$(nproc)}
python=${PYTHON:-/usr/bin/python3}
[ -x build/plumekit ] || bash scripts/build.sh
start=$(date +%s)
bash scripts/hybrid-data.sh "$work/data"
echo "train-model-v3: data ready after $(($(date +%s) - start)) s"
mkdir -p "$(dirname "$model")"
# From the data folder, so the model records the datasets by name (as scripts/train-on-gpu.sh).
(cd "$work/data" && "$python" "$OLDPWD/surrogate/train/train.py" \
  --data families buildings buildings-b --work "$work/checkpoints" --out "$model" \
  --epochs "${EPOCHS:-16}" --lr-schedule cosine --batch "${BATCH:-8}" --seed 1 \
  --threads "$threads" --max-minutes "${MAX_MINUTES:-95}")
cp "$work/checkpoints/log.csv" "${model%.pkcnn}.log.csv"
echo "train-model-v3: trained after $(($(date +%s) - start)) s"
d=$work/data
"$python" surrogate/train/evaluate.py --model "$model" --json --threads "$threads" \
  --test "$d/test-maps-truth4" "$d/test-families-truth4" "$d/test-buildings-truth4" \
  --out "$work/evaluation" >"$work/evaluation.json"
echo "train-model-v3: evaluated after $(($(date +%s) - start)) s: $work/evaluation.json"
