#!/usr/bin/env bash
# Crease reference data for crates/splinekit/tests/subdivision_reference.rs: copies Catmull-Clark's
# and Loop's reference inputs with sharp and semi-sharp creases added as OBJ tags (`t crease
# N/M v0 .. vN-1 s ..`: the chain v0-v1, v1-v2, ... with one sharpness or one per edge; `t corner
# N/M v .. s ..`; 0-based vertices, see the README), and OpenSubdiv's subdivision of each at
# levels 1-3 (Chaikin creasing; some also Uniform, some with --corners), and its limit positions
# and normals (PrimvarRefinerReal::Limit, `vn` lines) of the finest level at levels 1 and 2, into
# crates/splinekit/tests/data/crease/. Needs the peers (bench/install_peers.sh); CI does not run
# it. Running it twice gives identical bytes.
set -euo pipefail
source "$(dirname "$0")/references_common.sh" crease
data="$tests/crease"
tag() { # name source tags...: the source input with the tag lines appended
    local name="$1" src="$2"
    shift 2
    {
        cat "$tests/$src.in.obj"
        printf '%s\n' "$@"
    } >"$data/$name.in.obj"
}
# cube: a loop of four sharpnesses around the top (Chaikin blends them), a corner with three
# semi-sharp edges (1, 2, 3), a semi-sharp vertex
tag cube6 catmark/cube6 "t crease 5/4 4 5 7 6 4 2 1.5 0.5 3" "t crease 2/1 0 1 1" "t crease 2/1 0 2 2" \
    "t crease 2/1 0 4 3" "t corner 1/1 3 1.25"
# torus: a semi-sharp ring crossing an infinitely sharp one, and a short line whose first edge
# (1.25) loses its sharpness at the far end in one step under Chaikin
tag torus48 catmark/torus48 "t crease 9/1 0 1 2 3 4 5 6 7 0 2.5" "t crease 7/1 0 8 16 24 32 40 0 10" \
    "t crease 3/2 4 12 20 1.25 0.25"
# triangles and pentagons: a crease around the top pentagon, one on the diagonal of the split side,
# an infinitely sharp vertex
tag prism8 catmark/prism8 "t crease 6/1 5 6 7 8 9 5 0.75" "t crease 2/1 1 7 1.5" "t corner 1/1 1 10"
# open grid: a line across with one sharpness per edge, meeting the boundary at both ends
tag grid16 catmark/grid16 "t crease 5/4 10 11 12 13 14 1.25 2.5 0.25 1"
# Loop: the icosahedron with a sharp triangle loop (crease rule at its corners), three
# semi-sharp edges at vertex 0 and a semi-sharp vertex; the open grid with a line across; the
# torus with a semi-sharp ring
tag icosahedron20 loop/icosahedron20 "t crease 4/1 1 2 6 1 1.5" "t crease 2/1 0 4 1" "t crease 2/1 0 7 2" \
    "t crease 2/1 0 8 3" "t corner 1/1 9 0.5"
tag grid32 loop/grid32 "t crease 5/4 10 11 12 13 14 1.25 2.5 0.25 1"
tag torus96 loop/torus96 "t crease 7/1 0 1 2 3 4 5 0 1.75"
# Chaikin at a vertex with several semi-sharp edges of different sharpness: OpenSubdiv sums
# their sharpness in single precision in its order of the vertex's edges (issue #39), which
# differs here from the order of the faces' numbers: the quad torus's vertex 0 has four (1.7,
# 1.7, 0.6, 3.3: 7.3000002 summed by face numbers, 7.2999997 in OpenSubdiv's order), the
# triangle torus's vertex 0 five
tag torus48c4 catmark/torus48 "t crease 2/1 0 1 1.7" "t crease 2/1 0 8 1.7" "t crease 2/1 0 40 0.6" \
    "t crease 2/1 0 7 3.3"
tag torus96c5 loop/torus96 "t crease 2/1 0 6 1.7" "t crease 2/1 0 7 1.7" "t crease 2/1 0 5 0.6" \
    "t crease 2/1 0 1 2.2" "t crease 2/1 0 47 3.3"

run() { # driver name suffix options...
    local driver="$1" name="$2" suffix="$3"
    shift 3
    for l in 1 2 3; do
        "$peers/$driver" "$data/$name.in.obj" -n "$l" "$@" -o "$data/$name.$suffix.l$l.obj" >/dev/null
    done
}
for m in cube6 torus48 prism8 grid16 torus48c4; do
    run osd_catmark "$m" osd
done
run osd_catmark cube6 osd-uniform --creasing uniform
run osd_catmark grid16 osd-corners --corners
for m in icosahedron20 grid32 torus96 torus96c5; do
    run osd_loop "$m" osd
done
run osd_loop icosahedron20 osd-uniform --creasing uniform
run osd_loop grid32 osd-corners --corners
# limit positions and normals of the finest level (PrimvarRefinerReal::Limit)
limit() { # driver name suffix options...
    local driver="$1" name="$2" suffix="$3"
    shift 3
    for l in 1 2; do
        "$peers/$driver" "$data/$name.in.obj" -n "$l" --limit "$@" -o "$data/$name.$suffix.limit.l$l.obj" >/dev/null
    done
}
for m in cube6 torus48 prism8 grid16; do
    limit osd_catmark "$m" osd
done
limit osd_catmark grid16 osd-corners --corners
for m in icosahedron20 grid32 torus96; do
    limit osd_loop "$m" osd
done
limit osd_loop grid32 osd-corners --corners
ls -l "$data"
