#!/usr/bin/env bash
# Installs every Debian package plumekit needs to build, test and run, then the browser test's
# npm package (tests/browser: `npm ci`, as the invoking user, never through sudo); or, given
# package names as arguments, just those Debian packages (the benchmarks' extras).
# Idempotent: when all packages are present it changes nothing and exits 0.
# Works as root, or as a user with sudo (for apt).
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config git
  # a compiler cache: rebuilds of unchanged files, in any clone, come from it (docs/ci.md)
  ccache
  # fuzzing (scripts/fuzz.sh): clang and its sanitizer runtimes. -fsanitize=fuzzer links
  # libclang_rt.fuzzer from libclang-rt-14-dev, which clang-14 only recommends; libfuzzer-14-dev
  # (a standalone libFuzzer.a) is not needed. GCC's ThreadSanitizer runtime, libtsan2, comes
  # with build-essential.
  clang-14 libclang-rt-14-dev
  # numerics and geometry
  libeigen3-dev libsuitesparse-dev libcgal-dev libgmp-dev libmpfr-dev
  # MUMPS's sequential library: the single-precision LU of large flow systems (docs/design/flow-solver.md,
  # "Building scale"); without it the build uses UMFPACK for them
  libmumps-seq-dev
  # an optimised BLAS: UMFPACK's dense kernels run ~2.4x faster than with netlib BLAS. The pthread
  # build, which plumekit pins to one thread: the serial build is not reentrant (docs/design/flow-solver.md).
  libopenblas0-pthread
  # planning: OMPL links only with these boost components present
  libompl-dev libboost-filesystem-dev libboost-serialization-dev libboost-system-dev
  # images, PNG, ROS map_server files (YAML + PGM/PNG)
  libopencv-dev libyaml-cpp-dev libpng-dev
  # replays as H.264 video (core/video_plugin.cpp): FFmpeg's libraries and x264
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev pkg-config
  # file formats and the command line
  nlohmann-json3-dev libcli11-dev
  # SHA-256 of shards, model and wind files: OpenSSL's EVP (docs/own-code.md)
  libssl-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # the libraries our own core/ code was measured against (docs/own-code.md): oneTBB for
  # bench/thread_pool_bench, xtensor for bench/npy_vs_xtensor; the build never needs them
  libtbb-dev libxtensor-dev
  # surrogate training and its golden files, and the dataset tests' numpy round trip: run with
  # /usr/bin/python3. Debian's torch uses one thread unless told otherwise (torch.set_num_threads),
  # which the training script does.
  python3-torch python3-numpy
  # `plumekit flow --engine openfoam` and its test (openfoam_tests, 2 MPI ranks): OpenFOAM v1912
  # (simpleFoam, decomposePar, reconstructPar) and the Open MPI launcher, mpirun.
  openfoam openmpi-bin
  # the Python module (python/README.md): pybind11, its tests, and the examples' pictures
  pybind11-dev python3-dev python3-pytest python3-matplotlib
  # scale-out (scripts/scaleout/README.md): a single-node Slurm with munge, started by its test,
  # and GNU parallel
  slurm-wlm munge parallel
  # report.html's browser test (tests/browser/README.md): headless Chromium, driven by the npm package
  # playwright-core (tests/browser/package-lock.json): 1.61.1, the last release that runs on Debian 12's
  # Node.js 18 (later ones need Node.js 20) and drives its chromium. NodeSource's
  # nodejs brings its own npm and conflicts with Debian's npm package: an npm on the PATH counts as it.
  chromium nodejs npm
)
# Optional, never needed by the build: libtorch-dev for bench/surrogate_vs_libtorch
# (bench/libtorch/run.sh passes it as an argument).

npm_step=true
if [[ $# -gt 0 ]]; then
  packages=("$@")
  npm_step=false
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] && continue
  # NodeSource's nodejs includes npm and conflicts with Debian's npm package.
  [[ "$p" == npm ]] && command -v npm >/dev/null 2>&1 && continue
  missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  if [[ $(id -u) -eq 0 ]]; then
    sudo=()
  elif command -v sudo >/dev/null 2>&1; then
    sudo=(sudo)
  else
    echo "install-deps: need root or sudo to install: ${missing[*]}" >&2
    exit 1
  fi

  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -q
  "${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

[[ "$npm_step" == true ]] || exit 0

# The browser test's npm package, at the version its lock file holds; skipped when it is there.
browser_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tests/browser"
locked=$(node -p 'require(process.argv[1]).packages["node_modules/playwright-core"].version' \
  "$browser_dir/package-lock.json")
installed=$(node -p 'try { require(process.argv[1]).version } catch (e) { "" }' \
  "$browser_dir/node_modules/playwright-core/package.json")
if [[ "$installed" == "$locked" ]]; then
  echo "install-deps: playwright-core $locked present (tests/browser)"
else
  echo "install-deps: installing playwright-core $locked into tests/browser/node_modules"
  npm ci --prefix "$browser_dir" --no-audit --no-fund
fi
