#!/usr/bin/env bash
# The engine against libtorch (bench/surrogate_vs_libtorch.cpp): installs Debian 12's libtorch-dev
# through the project's installer (idempotent, root or sudo), configures the build so CMake finds
# Torch, builds the benchmark and runs it. Arguments go to the program: [MODEL.pkcnn [REPEATS
# [ROWS COLS]]] (ROWS COLS: the input size of a physical-grid model, by default 112 x 112).
# Run it under `nice -n 19` on a shared machine.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
bash "$root/scripts/install-deps.sh" libtorch-dev
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j2 --target surrogate_vs_libtorch
exec "$root/build/bench/surrogate_vs_libtorch" "$@"
