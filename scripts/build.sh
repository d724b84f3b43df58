#!/usr/bin/env bash
# Installs the Debian packages plumekit needs (if missing), builds it in build/, and installs the
# Python module where Debian's python3 finds it (python/README.md). Extra arguments go to CMake's
# configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build -j "$(nproc)"
if grep -q '^PLUMEKIT_PYTHON_MODULE:BOOL=ON' build/CMakeCache.txt; then
  # /usr/local/lib/python3.X/dist-packages: root's, or a sudo away (as the packages above).
  if [[ $(id -u) -eq 0 ]]; then
    cmake --install build --component python
  elif command -v sudo >/dev/null 2>&1; then
    sudo cmake --install build --component python
  else
    echo "build: cannot install the Python module without root; use PYTHONPATH=$PWD/build/python"
  fi
fi
