# Sourced by the scripts that solve flows: OpenBLAS misdetects some CPUs (on the build machine it
# picks its PRESCOTT kernel, several times slower) and the flow's round-off follows the kernel, so
# name the kernel the CPU has, unless the caller chose one. A result then depends on the CPU's
# kernel, not on OpenBLAS's guess (docs/benchmarks.md).
if [[ -z ${OPENBLAS_CORETYPE:-} ]]; then
  if grep -qw avx512f /proc/cpuinfo 2>/dev/null; then
    export OPENBLAS_CORETYPE=SkylakeX
  elif grep -qw avx2 /proc/cpuinfo 2>/dev/null; then
    export OPENBLAS_CORETYPE=Haswell
  fi
fi
