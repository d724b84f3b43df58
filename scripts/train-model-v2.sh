#!/usr/bin/env bash
# The v2 surrogate (issue 19; docs/design/surrogate.md, "Physical-grid models (v2)"): one model for any map, on a physical grid
# of 0.2 m cells with the map's wind as input, from nothing:
#   1. training data in the faithful world: the thesis's six random families on the 10 x 4 m arena
#      and random buildings of 6-30 m, every map's inlets at a speed drawn from 0.3-2 m/s;
#   2. ground truth for evaluation: held-out random buildings (another seed) and the nine test maps;
#   3. training (AdamW, cosine learning rate over EPOCHS epochs, batches of about BATCH x 64 x 64
#      cells of one padded shape, loss over the map's cells only);
#   4. the evaluation on the validation maps, the held-out buildings and the test maps.
# Every step resumes where it stopped when run again. WORK (default out/train-v2) holds the
# datasets, checkpoints and the evaluation; the model and its log go to data/models/.
# Settings (environment): FAMILY_MAPS (60), BUILDING_MAPS (65), SOURCES (16 per map), EPOCHS (10),
# BATCH (8), THREADS (nproc), MAX_MINUTES (no limit), PYTHON (/usr/bin/python3; CUDA is used when
# present). The shipped model's settings and timings are in docs/design/surrogate.md.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
work=${1:-out/train-v2}
family_maps=${FAMILY_MAPS:-60}
building_maps=${BUILDING_MAPS:-65}
sources=${SOURCES:-16}
epochs=${EPOCHS:-10}
batch=${BATCH:-8}
threads=${THREADS:-$(nproc)}
python=${PYTHON:-/usr/bin/python3}
model=data/models/plume-unet-v2.pkcnn
mkdir -p "$work" data/models
[ -x build/plumekit ] || bash scripts/build.sh
v2="--feature-cell 0.2 --threads $threads"
./build/plumekit dataset generate $v2 --out "$work/families" --maps "$family_maps" \
  --sources "$sources" --seed 21 --inlet-speeds 0.3,2 \
  --families rectangle,two-rectangles,l-shape,u-shape,three-rectangles,shape-and-rectangle
./build/plumekit dataset generate $v2 --out "$work/buildings" --families building \
  --maps "$building_maps" --sources "$sources" --cell 0.1 --seed 22 --inlet-speeds 0.3,2
./build/plumekit dataset generate $v2 --out "$work/test-buildings" --families building --maps 12 \
  --sources 8 --cell 0.1 --seed 23 --inlet-speeds 0.3,2
./build/plumekit dataset generate $v2 --out "$work/test-maps" --map-dir data/test-maps
"$python" surrogate/train/train.py --data "$work/families" "$work/buildings" \
  --work "$work/checkpoints" --out "$model" --epochs "$epochs" --lr-schedule cosine \
  --batch "$batch" --seed 1 --threads "$threads" ${MAX_MINUTES:+--max-minutes "$MAX_MINUTES"}
cp "$work/checkpoints/log.csv" data/models/plume-unet-v2.log.csv
"$python" surrogate/train/evaluate.py --model "$model" --data "$work/families" "$work/buildings" \
  --test "$work/test-buildings" "$work/test-maps" --out "$work/evaluation" --threads "$threads"
