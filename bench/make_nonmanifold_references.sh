#!/usr/bin/env bash
# Non-manifold and degenerate reference data for crates/splinekit/tests/nonmanifold.rs: the input
# meshes of bench/meshgen.py's nonmanifold_meshes() (edges of 3, 4 and 100 faces, vertices with
# several fans, back-to-back faces (alone: manifold, but its levels have two edges between the
# same two vertices), interior vertices of valence 2, a fold-over, faces that repeat
# a vertex, quad poles, triangles and quads mixed) and OpenSubdiv 3.5's refinement of each
# (bench/drivers/osd_loop.cpp for the all-triangle ones, osd_catmark.cpp for all): levels 1 to 3,
# and with --limit --no-normals the limit positions of levels 1 and 2, and three meshes with
# --corners (VTX_BOUNDARY_EDGE_AND_CORNER) at levels 1 and 2, into tests/data/nonmanifold/. OpenSubdiv's
# Far::TopologyRefinerFactory takes such topology as it is (no validation asked for): it makes
# non-manifold edges infinitely sharp and non-manifold vertices corners. Needs the peers
# (bench/install_peers.sh); CI does not run it. Deterministic.
set -euo pipefail
source "$(dirname "$0")/references_common.sh" nonmanifold
data="$tests/nonmanifold"
rm -f "$data"/*.obj
python3 "$here/meshgen.py" nonmanifold "$data"
loop=(fins3 fins4 edge100 cones backtoback pillow foldgrid degenerate)
catmark=("${loop[@]}" poles valence2 cubes)
run() { # driver mesh tag levels...
    local driver="$1" m="$2" tag="$3"
    shift 3
    for l in "$@"; do
        "$peers/$driver" "$data/$m.in.obj" -n "$l" -o "$data/$m.$tag.l$l.obj" >/dev/null
        "$peers/$driver" "$data/$m.in.obj" -n "$l" --limit --no-normals -o "$data/$m.$tag.limit.l$l.obj" >/dev/null
    done
}
for m in "${loop[@]}"; do
    run osd_loop "$m" osd-loop 1 2
    # level 3 of the 100-face edge is 6400 triangles: levels 1 and 2 are enough there
    [ "$m" = edge100 ] || "$peers/osd_loop" "$data/$m.in.obj" -n 3 -o "$data/$m.osd-loop.l3.obj" >/dev/null
done
for m in "${catmark[@]}"; do
    run osd_catmark "$m" osd-catmark 1 2
    [ "$m" = edge100 ] || "$peers/osd_catmark" "$data/$m.in.obj" -n 3 -o "$data/$m.osd-catmark.l3.obj" >/dev/null
done
# VTX_BOUNDARY_EDGE_AND_CORNER (--corners) on meshes with one-face corners next to non-manifold
# features: levels 1 and 2
for m in cones foldgrid degenerate; do
    for l in 1 2; do
        "$peers/osd_loop" "$data/$m.in.obj" -n "$l" --corners -o "$data/$m.osd-loop-corners.l$l.obj" >/dev/null
        "$peers/osd_catmark" "$data/$m.in.obj" -n "$l" --corners -o "$data/$m.osd-catmark-corners.l$l.obj" >/dev/null
    done
done
ls -l "$data" | awk '{ s += $5 } END { printf "%d files, %d bytes\n", NR - 1, s }'
