#!/usr/bin/env bash
# Installs the Loop subdivision peers used by compare_loop.sh and make_loop_references.sh:
#   Debian: libosd-dev (OpenSubdiv 3.5), libcgal-dev (CGAL 5.5), libopenmesh-dev (OpenMesh 9.0),
#           g++, and GNU time (/usr/bin/time, for peak memory);
#   PyPI, in the venv bench/.venv (or $BENCH_VENV): libigl and geomdl (pinned), numpy, scipy.
# Only what is missing is installed. Uses sudo when not root. Never run by CI.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="${BENCH_VENV:-$here/.venv}"

pkgs=(libosd-dev libcgal-dev libopenmesh-dev g++ time)
missing=()
for p in "${pkgs[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    sudo=()
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || { echo "install_peers.sh: need root or sudo for apt-get install ${missing[*]}" >&2; exit 1; }
        sudo=(sudo)
    fi
    echo "install_peers.sh: apt-get install ${missing[*]}" >&2
    "${sudo[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
fi

if ! "$venv/bin/python" -c 'import igl, numpy, scipy, geomdl' 2>/dev/null; then
    echo "install_peers.sh: creating $venv with libigl and geomdl" >&2
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q --disable-pip-version-check -r "$here/requirements.txt"
fi
