#!/usr/bin/env bash
# Issue 20's validation of the seeds' methods in the seeds' own setting (docs/validation.md,
# "Validation against the seeds"): scripts/validate-methods.sh with 10 runs per configuration.
# point-sensor/ holds earlier runs of a world without the rotor's disc (see README.md); this
# script does not make them.
#   results/methods-validation/make.sh [OUT]
#   scripts/validation_table.py OUT       # the table of docs/validation.md
# OUT as given from where this was called; then work from the repository root.
set -- "${1:+$(realpath -m -- "$1")}" "${@:2}"
cd "$(dirname "$0")/../.."
source results/make-lib.sh "$1"
TRACKING_RUNS=10 bash scripts/validate-methods.sh 10 "$out"
