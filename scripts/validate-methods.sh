#!/usr/bin/env bash
# Issue 20's validation of the seeds' methods in the seeds' own setting (docs/validation.md,
# "Validation against the seeds"): the 32 x 8 m tunnel at 0.5 m/s, seed 000's filaments
# (--world neumann, from a 0.2 m source disc), its infrared sensor under the rotor's 0.5 m disc,
# 20 s stops at 1 Hz, 1 m steps at 1 m/s, the wind direction's 14.02 degrees, the synthetic
# circular variance (23.08 degrees) and the GPS.
#
#   scripts/validate-methods.sh [RUNS] [OUT]      # RUNS per configuration (the seeds: 100)
#   TRACKING_RUNS=10 scripts/validate-methods.sh 20   # fewer runs for the trackers' eight
#   scripts/validate-methods.sh 10                    # as results/methods-validation/
#   scripts/validation_table.py OUT                   # the tables of docs/validation.md
#
# Writes one `evaluate` folder per configuration under OUT (default out/validate). About 1 to
# 2.5 min of CPU per particle-filter run and 15 to 60 s per tracking run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
runs=${1:-100}
out=${2:-out/validate}
tracking_runs=${TRACKING_RUNS:-$runs}
plumekit=${PLUMEKIT:-./build/plumekit}
# th_c: 5 % of the mean plume's peak (2534 units on the plume grid), as the seeds' 0.05 of a
# normalised field.
seeds=(--world neumann --stop-s 20 --stop-rate 1 --speed 1 --track-step 1 --wind-noise 14.02
  --wind-variance-noise 23.08 --position-noise gps --gas-sensor infrared --rotor-disc 0.5
  --detection-threshold 125 --threads 0)
run() {
  local name=$1 n=$2
  shift 2
  "$plumekit" evaluate --protocol thesis --runs "$n" --out "$out/$name" "${seeds[@]}" "$@"
}
# The particle filter, source (8, 4); the seeds' best (alpha, beta) are the defaults.
run pf-sweep "$runs" --map-dir data/seeds/pf-sweep --method pf-sweep
run pf-gradient "$runs" --map-dir data/seeds/pf-gradient --method pf-gradient --max-steps 150
# Plume tracking from (31, 4) to the source at (2, 4): the distance overhead of each.
run surge-cast "$tracking_runs" --map-dir data/seeds/tracking --method surge-cast
for a in 15 30 60 75; do
  run "zigzag-$a" "$tracking_runs" --map-dir data/seeds/tracking --method zigzag \
    --zigzag-angle "$a"
done
for b in 30 60 90; do
  run "gradient-$b" "$tracking_runs" --map-dir data/seeds/tracking --method pseudo-gradient \
    --gradient-angle "$b"
done
