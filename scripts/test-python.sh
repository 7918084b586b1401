#!/usr/bin/env bash
# The Python package's tests: a fresh virtual environment under target/, `pip install` of
# crates/splinekit-py (maturin builds the extension from PyPI and crates.io alone), then pytest
# against the installed package. Needs Rust, a C compiler, Python 3 (3.9 or later, with venv)
# and git; nothing else. trimesh is installed when PyPI has it and its tests are skipped
# otherwise.
#
#   bash scripts/test-python.sh             # debug build of the extension (fast to build)
#   PROFILE=release bash scripts/test-python.sh
#   PYTHON=python3.12 bash scripts/test-python.sh -k arclen   # pytest arguments after the options
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python3}"
PROFILE="${PROFILE:-dev}"
VENV="${VENV:-target/python-venv}"
case "$VENV" in /*) ;; *) VENV="$PWD/$VENV" ;; esac

start=$(date +%s)
if [ ! -x "$VENV/bin/python" ]; then
    "$PYTHON" -m venv "$VENV"
fi
"$VENV/bin/python" -m pip install --quiet --upgrade pip
"$VENV/bin/python" -m pip install --quiet numpy pytest
"$VENV/bin/python" -m pip install --quiet trimesh || echo "note: trimesh not installed; its tests are skipped"
# maturin's PEP 517 backend reads its build options from this variable
MATURIN_PEP517_ARGS="--profile $PROFILE" \
    "$VENV/bin/python" -m pip install --quiet --force-reinstall --no-deps ./crates/splinekit-py
built=$(date +%s)
echo "== built and installed in $((built - start)) s ($PROFILE profile)"

# the command line, when built, for the same-bits tests (skipped without it)
for p in release debug; do
    if [ -z "${SPLINEKIT_CLI:-}" ] && [ -x "target/$p/splinekit" ]; then export SPLINEKIT_CLI="$PWD/target/$p/splinekit"; fi
done
# run from the tests' folder so that `import splinekit` finds the installed package
cd crates/splinekit-py/tests
"$VENV/bin/python" -m pytest -q -p no:cacheprovider "$@" .
echo "== python tests in $(($(date +%s) - built)) s"
