#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/README.md) with clang in build-fuzz/ and runs each for
# SECONDS_PER_TARGET (default 60) on its committed seed corpus, fuzz/corpus/TARGET/.
#
#   bash scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default: every target)
#
# The committed corpus is only read: new inputs go to build-fuzz/fuzz-runs/TARGET/corpus/, which
# starts empty each run (FUZZ_KEEP_CORPUS=1 resumes from the last run's). Prints per target the
# executions, coverage (libFuzzer's cov: edges and ft: features) and crashes; a crash, leak,
# timeout or out-of-memory input is kept in build-fuzz/fuzz-runs/TARGET/crashes/ and the script
# exits 1 after running the remaining targets. Targets run FUZZ_JOBS at a time (default: nproc).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
[[ $# -gt 0 ]] && shift
all_targets=(fuzz_map_json fuzz_ros_import fuzz_model_file fuzz_manifest fuzz_table_cache
  fuzz_gdm_samples fuzz_gdm_run fuzz_evaluate_part
  fuzz_wind_file)
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=("${all_targets[@]}")
build="build-fuzz"
jobs=${FUZZ_JOBS:-$(nproc)}

# Largest input each target tries: above its biggest seed (the office map, the 49 kB model).
declare -A max_len=(
  [fuzz_map_json]=16384 [fuzz_ros_import]=65536 [fuzz_model_file]=65536
  [fuzz_manifest]=16384 [fuzz_table_cache]=65536 [fuzz_gdm_samples]=16384
  [fuzz_gdm_run]=16384 [fuzz_evaluate_part]=16384
  [fuzz_wind_file]=16384)

cxx=${FUZZ_CXX:-}
if [[ -z "$cxx" ]]; then
  for c in clang++-14 clang++; do
    if command -v "$c" >/dev/null; then cxx=$c; break; fi
  done
fi
[[ -n "$cxx" ]] || { echo "fuzz.sh: needs clang++ with libFuzzer (scripts/install-deps.sh)" >&2; exit 2; }

if [[ ! -f $build/CMakeCache.txt ]]; then
  # -O1, no NDEBUG (asserts stay on), line tables only: stacks with line numbers, faster builds.
  # The compiler cache, when installed, comes from CMakeLists.txt.
  CXX=$cxx cmake -S . -B $build -DPLUMEKIT_FUZZ=ON -DBUILD_TESTING=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DPLUMEKIT_NATIVE=OFF
fi
cmake --build $build -j "$(nproc)" --target "${targets[@]}"

run_one() {
  local t=$1 work=$build/fuzz-runs/$1
  [[ "${FUZZ_KEEP_CORPUS:-0}" == 1 ]] || rm -rf "$work/corpus"
  mkdir -p "$work/corpus" "$work/crashes"
  touch "$work/started"  # crash inputs of earlier runs stay, but are not counted
  # The first folder receives new inputs; the committed seeds are read from the second.
  # -timeout: seconds for one input (a hang is a finding); -rss_limit_mb: also the malloc limit.
  # stdin is /dev/null: a fuzzed ROS YAML may name /dev/stdin as its image.
  set +e
  "$build/fuzz/$t" "$work/corpus" "fuzz/corpus/$t" -max_total_time="$seconds" \
    -max_len="${max_len[$t]:-65536}" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/crashes/" </dev/null >"$work/log.txt" 2>&1
  echo $? >"$work/exit_code"
  set -e
}

summary() {
  local t=$1 work=$build/fuzz-runs/$1 code
  code=$(cat "$work/exit_code")
  local execs cov ft crashes
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log.txt" | tail -1)
  [[ -n "$execs" ]] || execs=$(grep -o '^#[0-9]*' "$work/log.txt" | tail -1 | tr -d '#')
  cov=$(grep -o 'cov: [0-9]*' "$work/log.txt" | tail -1 | cut -d' ' -f2)
  ft=$(grep -o 'ft: [0-9]*' "$work/log.txt" | tail -1 | cut -d' ' -f2)
  crashes=$(find "$work/crashes" -type f -newer "$work/started" | wc -l)
  printf '%-18s %4s s  executions %10s  cov %6s  ft %6s  crash inputs %s  exit %s\n' \
    "$t" "$seconds" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$crashes" "$code"
  if [[ $code != 0 ]]; then
    grep -m3 -E 'ERROR: |SUMMARY: |uncaught exception|terminate called' "$work/log.txt" | sed 's/^/    /'
    find "$work/crashes" -type f -newer "$work/started" | sed 's/^/    kept: /'
    echo "    log: $work/log.txt"
    return 1
  fi
}

for t in "${targets[@]}"; do
  [[ -x $build/fuzz/$t ]] || { echo "fuzz.sh: no target $t" >&2; exit 2; }
  rm -f "$build/fuzz-runs/$t/exit_code"
done
running=0
for t in "${targets[@]}"; do
  run_one "$t" &
  running=$((running + 1))
  if ((running >= jobs)); then wait -n || true; running=$((running - 1)); fi
done
wait

status=0
for t in "${targets[@]}"; do
  summary "$t" || status=1
done
exit $status
