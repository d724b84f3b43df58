# shellcheck shell=bash
# Sourced by results/*/make.sh, from the repository root: the output folder and the binary.
#   source results/make-lib.sh "$@"
# sets $out to the first argument, or to a new temporary folder, and refuses any folder inside
# results/: a re-run never writes over the committed files (compare them with
# scripts/compare_results.py instead). $PLUMEKIT (default ./build/plumekit) must be built.
set -euo pipefail
out=${1:-$(mktemp -d "${TMPDIR:-/tmp}/plumekit-results.XXXXXX")}
case "$(realpath -m "$out")/" in
  "$(realpath results)"/*)
    echo "$0: $out is inside results/; write elsewhere and compare with scripts/compare_results.py" >&2
    exit 2
    ;;
esac
mkdir -p "$out"
PLUMEKIT=${PLUMEKIT:-./build/plumekit}
if [[ ! -x $PLUMEKIT ]]; then
  echo "$0: no $PLUMEKIT; build it first: cmake --build build --target plumekit" >&2
  exit 2
fi
export PLUMEKIT
# shellcheck disable=SC2034  # used by the make.sh that source this file
plumekit=$PLUMEKIT
echo "$0: writing into $out" >&2
