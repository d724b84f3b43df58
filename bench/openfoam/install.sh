#!/usr/bin/env bash
# Installs what the OpenFOAM benchmark needs from Debian 12's own archive:
#   openfoam       OpenFOAM v1912 (blockMesh, topoSet, subsetMesh, simpleFoam, foamDictionary)
#   python3-numpy  for bench/openfoam/foam_case.py and bench/flow_vs_openfoam.py (run them with /usr/bin/python3)
# Idempotent, root or sudo: the project's installer does the work.
set -euo pipefail
exec bash "$(dirname "$0")/../../scripts/install-deps.sh" openfoam python3-numpy
