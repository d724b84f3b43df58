#!/usr/bin/env bash
# Quick start 1: install, build, and run the main job on the shipped default map.
# Writes its pictures and summaries to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
map=data/maps/cluttered-1.json
./build/plumekit map validate "$map"
./build/plumekit map render "$map" --out out/cluttered-1.png
echo "demo: done; open out/cluttered-1.png"
