#!/usr/bin/env bash
# Regenerates the Loop subdivision reference data of crates/splinekit/tests/data/loop/
# (read by crates/splinekit/tests/subdivision_reference.rs) with independent implementations:
#   OpenSubdiv 3.5 (Debian libosd-dev): Loop's beta, crease rules on the boundary;
#   libigl 2.6.3 (PyPI libigl): Warren's beta, the same boundary rules;
# and cross-checks them against CGAL 5.5 and OpenMesh 9.0 (not committed).
#
#   bench/make_loop_references.sh [OUTDIR]
#
# Installs the peers if needed (bench/install_peers.sh), builds the drivers into
# target/bench-peers, writes inputs and outputs into OUTDIR (default: the test data folder)
# and prints the cross-checks. Deterministic: a second run rewrites the same bytes (with the
# same package versions). Never run by CI; the outputs are committed.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
out="${1:-$root/crates/splinekit/tests/data/loop}"
shared="${SHARED_DATA:-$root/../shared/data/obj/clean}"
peers="$root/target/bench-peers"
venv="${BENCH_VENV:-$here/.venv}"
py="$venv/bin/python"

if [ "${CI:-}" = true ]; then
    echo "make_loop_references.sh: not for CI" >&2
    exit 0
fi
"$here/install_peers.sh"
"$here/drivers/build.sh" "$peers"
mkdir -p "$out"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

# ---- inputs (written with %.17g by bench/meshgen.py)
gen() { python3 "$here/meshgen.py" "$@"; }
gen copy "$shared/icosahedron.obj" "$out/icosahedron20.in.obj"
gen icosphere 1 "$out/icosphere80.in.obj"
gen torus 8 6 "$out/torus96.in.obj"
gen grid 4 4 "$out/grid32.in.obj"
# The whole bunny at level 1 is ~960 KB per file: keep its base instead, which holds the four
# holes (and gets a fifth, outer boundary loop and four one-face corners from the cut).
gen crop "$shared/bunny.obj" y 0.05 "$out/bunnybase883.in.obj"

meshes=(icosahedron20 icosphere80 torus96 grid32 bunnybase883)
quiet() { "$@" >/dev/null; }

# ---- outputs: every mesh at levels 1 and 2 into the scratch folder; the committed subset
# (the bunny base at level 1 only, to keep the data small) is copied to OUTDIR below.
for m in "${meshes[@]}"; do
    for l in 1 2; do
        quiet "$peers/osd_loop" "$out/$m.in.obj" -n "$l" -o "$scratch/$m.osd.l$l.obj"
        quiet "$py" "$here/drivers/igl_loop.py" "$out/$m.in.obj" -n "$l" -o "$scratch/$m.igl.l$l.obj"
    done
done
for l in 1 2; do
    quiet "$peers/osd_loop" "$out/grid32.in.obj" -n "$l" --corners -o "$scratch/grid32.osd-corners.l$l.obj"
done
rm -f "$out"/*.osd.l?.obj "$out"/*.igl.l?.obj "$out"/*.osd-corners.l?.obj
for m in icosahedron20 icosphere80 torus96 grid32; do
    cp "$scratch/$m".{osd,igl}.l[12].obj "$out/"
done
cp "$scratch/grid32".osd-corners.l[12].obj "$scratch/bunnybase883".{osd,igl}.l1.obj "$out/"

# ---- cross-checks (relative tolerance 1e-12 of the bounding-box diagonal)
fail=0
check() { # label args...
    local label="$1"
    shift
    printf '%-52s ' "$label"
    "$py" "$here/compare_meshes.py" "$@" || fail=1
}
for m in "${meshes[@]}"; do
    for l in 1 2; do
        for tool in cgal openmesh; do
            if [ -x "$peers/${tool}_loop" ]; then
                quiet "$peers/${tool}_loop" "$out/$m.in.obj" -n "$l" -o "$scratch/$m.$tool.l$l.obj"
                check "$m l$l: $tool = osd" "$scratch/$m.$tool.l$l.obj" "$scratch/$m.osd.l$l.obj"
            fi
        done
    done
done
# Loop's and Warren's beta coincide for valences 3 and 6: on the torus and the grid (interior
# valence 6 only) libigl must equal OpenSubdiv everywhere.
for m in torus96 grid32; do
    for l in 1 2; do check "$m l$l: igl = osd (valence 6 only)" "$scratch/$m.igl.l$l.obj" "$scratch/$m.osd.l$l.obj"; done
done
# Elsewhere they differ inside, but boundary vertices follow the crease rules alone.
for m in grid32 bunnybase883; do
    for l in 1 2; do
        check "$m l$l: igl = osd on the boundary" --boundary-only "$scratch/$m.igl.l$l.obj" "$scratch/$m.osd.l$l.obj"
    done
done
# Show how far Warren is from Loop's beta where they differ (expected to DIFFER).
for m in icosahedron20 icosphere80 bunnybase883; do
    printf '%-52s ' "$m l2: igl vs osd (expected to differ)"
    "$py" "$here/compare_meshes.py" "$scratch/$m.igl.l2.obj" "$scratch/$m.osd.l2.obj" || true
done

echo
(cd "$out" && ls -l -- *.obj | awk '{ s += $5; printf "%8d %s\n", $5, $9 } END { printf "%8d total\n", s }')
if [ "$fail" -ne 0 ]; then
    echo "make_loop_references.sh: a cross-check failed" >&2
    exit 1
fi
