#!/usr/bin/env bash
# STE with each plume model on the nine test maps in the thesis-style world (docs/validation.md,
# "Figures", "The thesis-style world"): 540 runs each, seed 1, 2 threads.
#   results/ste-thesis/make.sh [OUT] [MODEL...]   # MODEL: surrogate physics gaussian (default all)
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
models=("${@:2}")
[[ ${#models[@]} -gt 0 ]] || models=(surrogate physics gaussian)
for model in "${models[@]}"; do
  case $model in
    # The physics model as it was then: the thesis's sigma_M 30, no decay, no relative error.
    physics) extra=(--sigma-m 30 --decay-rate 0 --sigma-rel 0) ;;
    # The thesis's 64 x 64 model, which was the default then (the hybrid is now).
    surrogate) extra=(--cnn thesis) ;;
    gaussian) extra=() ;;
    *) echo "$0: unknown model $model" >&2; exit 2 ;;
  esac
  "$plumekit" evaluate --map-dir data/test-maps --runs 3 --plume-model "$model" "${extra[@]}" \
    --threads 2 --world thesis --protocol thesis --out "$out/$model"
done
