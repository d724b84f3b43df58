#!/usr/bin/env bash
# Issue 46's GPU recipe, the part that runs on the GPU machine (docs/design/surrogate.md,
# "Training on a GPU"): unpack a training pack (surrogate/train/pack.py, made on the CPU machine
# by scripts/train-model-v3.sh pack) and train the designs side by side on the one GPU, the same
# data, seed and schedule for each:
#   plain     region, signed distance, wind, source distance (the v2 model's inputs)
#   hybrid    the same and the physics plume of the source (physics_mean)
#   residual  hybrid inputs, the mean predicted as the physics plume plus a learned correction
#   scripts/train-on-gpu.sh PACK OUT
# OUT gets DESIGN.pkcnn, DESIGN_input.npy, DESIGN_output.npy (the golden pair), DESIGN.log.csv and
# DESIGN.txt (the trainer's output) for each design. Settings (environment): DESIGNS ("plain hybrid
# residual"), EPOCHS (cosine schedule length), BATCH (16), THREADS (4 CPU threads each), MAX_MINUTES (a wall-clock stop per
# design, a safety net: EPOCHS is what sizes the run), MAX_STEPS (a smoke test), PYTHON (python3,
# the GPU machine's PyTorch).
set -euo pipefail
cd "$(dirname "$0")/.."
pack=$(realpath -- "$1")
out=$(realpath -m -- "$2")
designs=${DESIGNS:-plain hybrid residual}
python=${PYTHON:-python3}
mkdir -p "$out"
work=$(mktemp -d)
"$python" surrogate/train/pack.py unpack "$pack" --out "$work/data"
data=()
for d in "$work"/data/*; do data+=("$d"); done
pids=()
for design in $designs; do
  case $design in
    plain) flags=(--inputs plain) ;;
    hybrid) flags=() ;;
    residual) flags=(--residual) ;;
    *) echo "$0: unknown design $design" >&2; exit 2 ;;
  esac
  # From the data folder, so the model records the datasets by name, as the CPU recipe does.
  (cd "$work/data" && PYTHONUNBUFFERED=1 "$python" "$OLDPWD/surrogate/train/train.py" \
    --data "${data[@]##*/}" --work "$work/$design" --out "$out/$design.pkcnn" \
    --epochs "${EPOCHS:-60}" --lr-schedule cosine --batch "${BATCH:-16}" --seed 1 \
    --threads "${THREADS:-4}" \
    ${MAX_MINUTES:+--max-minutes "$MAX_MINUTES"} ${MAX_STEPS:+--max-steps "$MAX_STEPS"} \
    "${flags[@]}" >"$out/$design.txt" 2>&1; cp "$work/$design/log.csv" "$out/$design.log.csv") &
  pids+=($!)
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
exit $status
