#!/usr/bin/env bash
# Quick start 1: install, build, and run the pipeline so far on the shipped
# default map. Writes its pictures and data to out/.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/blas-env.sh"
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
map=data/maps/cluttered-1.json
./build/plumekit map validate "$map"
./build/plumekit map render "$map" --out out/cluttered-1.png
./build/plumekit flow "$map" --out out/wind
./build/plumekit plan "$map" --from 1.0,1.0 --to 9.0,3.5 --out out/plan.png
echo "demo: pipeline so far done; see out/cluttered-1.png, out/wind/wind.png and out/plan.png"
# The main job: a simulated robot localizes a gas source (ste/).
./build/plumekit demo --out out/demo
