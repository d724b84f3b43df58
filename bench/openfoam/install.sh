#!/usr/bin/env bash
# Installs what the OpenFOAM benchmark needs from Debian 12's own archive:
#   openfoam       OpenFOAM v1912 (blockMesh, topoSet, subsetMesh, simpleFoam, foamDictionary)
#   openmpi-bin    mpirun, for --ranks N (simpleFoam over MPI ranks)
#   python3-numpy  for bench/openfoam/foam_case.py and bench/flow_vs_openfoam.py (run them with /usr/bin/python3)
# Idempotent, root or sudo: the project's installer does the work.
set -euo pipefail
exec bash "$(dirname "$0")/../../scripts/install-deps.sh" openfoam openmpi-bin python3-numpy
