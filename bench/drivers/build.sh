#!/usr/bin/env bash
# Builds the C++ subdivision drivers into OUTDIR (default: target/bench-peers of the workspace),
# skipping a driver whose headers are missing and rebuilding only when a source changed.
# Needs the Debian packages libosd-dev, libcgal-dev (+ libgmp-dev libmpfr-dev, pulled in),
# libopenmesh-dev and g++; bench/install_peers.sh installs them.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:-$here/../../target/bench-peers}"
mkdir -p "$out"
CXX="${CXX:-g++}"
# Same optimisation for every driver; no -march=native (the Debian libraries are generic x86-64,
# and so is splinekit's release build).
CXXFLAGS="${CXXFLAGS:--std=c++17 -O3 -DNDEBUG}"

build() { # name header libs...
    local name="$1" header="$2"
    shift 2
    if [ ! -e "$header" ]; then
        echo "build.sh: $header missing, not building $name" >&2
        return 0
    fi
    if [ "$out/$name" -nt "$here/$name.cpp" ] && [ "$out/$name" -nt "$here/common.hpp" ] \
        && [ "$out/$name" -nt "$here/osd_common.hpp" ] && [ "$out/$name" -nt "$here/cgal_common.hpp" ]; then
        return 0
    fi
    echo "build.sh: building $name" >&2
    # shellcheck disable=SC2086
    $CXX $CXXFLAGS -o "$out/$name" "$here/$name.cpp" "$@"
}

build osd_loop /usr/include/opensubdiv/far/primvarRefiner.h -losdCPU
build osd_catmark /usr/include/opensubdiv/far/primvarRefiner.h -losdCPU
build cgal_loop /usr/include/CGAL/subdivision_method_3.h -lgmp -lmpfr
build cgal_sqrt3_doosabin /usr/include/CGAL/subdivision_method_3.h -lgmp -lmpfr
build openmesh_loop /usr/include/OpenMesh/Tools/Subdivider/Uniform/LoopT.hh -lOpenMeshCore
build fill_scaling /usr/include/stdlib.h -pthread
