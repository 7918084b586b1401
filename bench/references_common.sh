# The shared start of bench/make_{catmark,cgal,butterfly,limit}_references.sh (sourced, after
# `set -euo pipefail`): stops under CI (the data is committed; the peers are not installed
# there), sets `here` (bench/), `root` (the workspace), `tests` (crates/splinekit/tests/data) and
# `peers` (the drivers, in target/bench-peers of CARGO_TARGET_DIR or the workspace), makes the
# folder `tests/$1`, builds the drivers (bench/drivers/build.sh), and lets the scripts' Python
# `from meshgen import write_input` (bench/meshgen.py).
#
#   source "$(dirname "$0")/references_common.sh" SUBFOLDER
if [ "${CI:-}" = true ]; then
    echo "$(basename "$0"): not for CI" >&2
    exit 0
fi
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
tests="$root/crates/splinekit/tests/data"
peers="${CARGO_TARGET_DIR:-$root/target}/bench-peers"
mkdir -p "$tests/$1"
bash "$here/drivers/build.sh" "$peers"
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}"
