#!/usr/bin/env bash
# STE with each plume model on the nine test maps in the faithful world (the default) with the
# fast MOX sensor, seeds 1 and 2: 1,080 runs each, 2 threads (docs/validation.md, "Figures", "The
# faithful world"; surrogate-v2: "The nine test maps, against v1").
#   results/ste-faithful/make.sh [OUT] [MODEL...]   # surrogate physics gaussian surrogate-v2
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
models=("${@:2}")
[[ ${#models[@]} -gt 0 ]] || models=(surrogate physics gaussian surrogate-v2)
for model in "${models[@]}"; do
  case $model in
    surrogate-v2) flags=(--plume-model surrogate --cnn v2) ;;
    # The thesis's 64 x 64 model, which was the default then (the hybrid is now).
    surrogate) flags=(--plume-model surrogate --cnn thesis) ;;
    physics | gaussian) flags=(--plume-model "$model") ;;
    *) echo "$0: unknown model $model" >&2; exit 2 ;;
  esac
  "$plumekit" evaluate --map-dir data/test-maps --runs 3 --seeds 2 --gas-sensor mox-fast \
    --protocol thesis "${flags[@]}" --threads 2 --out "$out/$model"
done
