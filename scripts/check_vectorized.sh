#!/usr/bin/env bash
# Does GCC vectorize the fast world's inner loops (issue 45)? Compiles scripts/vectorize_probe.cpp
# with -fopt-info-vec-optimized and exits 1 unless both of its loops (a counter_normals loop and
# an exp_neg loop, each marked "probe-loop: NAME") are reported vectorized; for a loop that is
# not, it prints GCC's -fopt-info-vec-missed reasons. GCC only (-fopt-info); not run by CI.
#
# Flags: -O3 -march=native -fno-math-errno by default, or PLUMEKIT_VEC_FLAGS. Without
# -fno-math-errno (CMakeLists.txt's release flags are -O3 -march=native) the counter_normals loop
# is not vectorized: std::sqrt may set errno, so GCC keeps a branch to the libm call around it.
# Without AVX-512 (e.g. -march=x86-64-v3, AVX2) neither loop is: GCC 12 will not if-convert the
# multiplies it left under a condition (log_positive's 0.5 * m, exp_neg's clamped * log2 e) since
# they could trap, and has no AVX2 conversion between int64 and double (AVX-512DQ has).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
probe="$root/scripts/vectorize_probe.cpp"
cxx="${CXX:-g++}"
read -r -a flags <<<"${PLUMEKIT_VEC_FLAGS:--O3 -march=native -fno-math-errno}"
compile() {  # compile OPT_INFO: the probe's compiler diagnostics for that -fopt-info kind
  "$cxx" -std=c++17 "${flags[@]}" -I"$root" -c "$probe" -o /dev/null "-fopt-info-$1" 2>&1
}
optimized=$(compile vec-optimized)
failed=0
for loop in counter_normals exp_neg; do
  line=$(grep -n "probe-loop: $loop\$" "$probe" | cut -d: -f1)
  if grep -q "vectorize_probe.cpp:$line:[0-9]*: optimized: loop vectorized" <<<"$optimized"; then
    echo "vectorized: the $loop loop (line $line; flags: ${flags[*]})"
  else
    echo "NOT vectorized: the $loop loop (line $line; flags: ${flags[*]}). GCC says:"
    # The loop's own lines, and the statements in the inlined headers that stopped it.
    compile vec-missed | grep -E "vectorize_probe.cpp:$line:|^[^ ]*core/[a-z_]+\.hpp:" | sort -u
    failed=1
  fi
done
exit "$failed"
