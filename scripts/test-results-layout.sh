#!/usr/bin/env bash
# Test of scripts/check_results_layout.py on small git repositories: a good layout passes; a code
# folder's results/ and an experiment folder without README.md each fail, naming the folder.
set -euo pipefail
check="$(cd "$(dirname "$0")" && pwd)/check_results_layout.py"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
repo() {  # a fresh repository in $work/$1 with the files $2...
  local dir="$work/$1"
  shift
  git init -q "$dir"
  for f in "$@"; do
    mkdir -p "$dir/$(dirname "$f")"
    echo x >"$dir/$f"
  done
  git -C "$dir" add -A
}
expect() {  # expect EXIT_CODE REPO TEXT: the check's exit code and a line of its output
  local code=0 output
  output=$(/usr/bin/python3 "$check" --root "$work/$2") || code=$?
  [[ $code == "$1" && $output == *"$3"* ]] ||
    { echo "FAIL: $2: exit $code (want $1), output: $output"; exit 1; }
}
repo good results/README.md results/ste-a/README.md results/ste-a/runs.csv ste/x.cpp
expect 0 good "every experiment documented"
repo nested results/ste-a/README.md ste/results/a/runs.csv
expect 1 nested "ste/results/: committed results belong"
repo deep results/ste-a/README.md methods/x/results/b.png
expect 1 deep "methods/x/results/:"
repo undocumented results/ste-a/README.md results/ste-b/runs.csv results/ste-b/make.sh
expect 1 undocumented "results/ste-b/: no README.md"
# An experiment's README.md in a subfolder does not document it.
repo sub results/ste-c/part/README.md results/ste-c/part/runs.csv
expect 1 sub "results/ste-c/: no README.md"
# This repository.
/usr/bin/python3 "$check"
echo "OK"
