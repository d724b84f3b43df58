#!/usr/bin/env bash
# Installs what the OpenFOAM benchmark needs from Debian 12's own archive:
#   openfoam       OpenFOAM v1912 (blockMesh, topoSet, subsetMesh, simpleFoam, foamDictionary)
#   python3-numpy  for bench/openfoam/foam_case.py and bench/flow_vs_openfoam.py (run them with /usr/bin/python3)
# Idempotent: does nothing when both packages are already installed. Needs root or sudo.
set -euo pipefail

pkgs=(openfoam python3-numpy)
missing=()
for p in "${pkgs[@]}"; do
    # dpkg-query prints "install ok installed" only for a fully installed package
    if [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)" != "install ok installed" ]; then
        missing+=("$p")
    fi
done

if [ ${#missing[@]} -eq 0 ]; then
    echo "install.sh: ${pkgs[*]} already installed"
    exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
    SUDO=()
elif command -v sudo >/dev/null 2>&1; then
    SUDO=(sudo)
else
    echo "install.sh: need root or sudo to install: ${missing[*]}" >&2
    exit 1
fi

echo "install.sh: installing ${missing[*]} (openfoam is large; this takes several minutes)"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -q
"${SUDO[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
