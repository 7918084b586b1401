#!/usr/bin/env bash
# Subdivision speed against the peers, one line per (tool, mesh, levels), then the ratios:
# Loop (issue #4): OpenSubdiv, CGAL, OpenMesh, libigl and splinekit (1 and 2 threads) on three
# triangle meshes; Catmull-Clark (issue #7): OpenSubdiv's catmark and splinekit (1 and 2 threads)
# on a 100k-quad torus.
#
#   bench/compare_loop.sh [--scheme loop|catmull-clark|all] [--levels N] [--repeat R] [--sk-repeat Q|auto]
#                         [--rounds K] [--settle S] [--no-install] [--no-igl] [--no-splinekit]
#
# --scheme picks the comparisons (default all: Loop, then Catmull-Clark).
# Installs the peers if missing (bench/install_peers.sh: Debian libosd-dev libcgal-dev
# libopenmesh-dev, PyPI libigl in bench/.venv), builds the C++ drivers (bench/drivers/) and
# `cargo build --release -p splinekit-cli`, generates the meshes with bench/meshgen.py into
# target/bench-meshes/ (once; target is $CARGO_TARGET_DIR when set, as for cargo), and runs every tool K times (default 3) per mesh with --repeat R,
# each run after S seconds of rest (default 1: a peer's freed memory slows the next process).
#
# seconds  = median over K runs of the median of R repeats (splinekit: Q, default auto, see below) of the subdivision alone (no file I/O; see each driver's header
#            for exactly what is timed), levels N (default 3), peers on one thread;
# memory fill = bench/drivers/fill_scaling: GB/s filling 128 MB of fresh pages and of mapped
#            memory on 1 and 2 threads, before and after the runs (the 2-thread ceiling of
#            memory-bound work on this machine);
# rss_MB   = peak resident memory of the whole process (GNU time %M: input, output, everything);
# out_MB   = size of the output arrays, V*3*8 + F*k*4 bytes (f64 positions, u32 corners: k = 3 for
#            triangles, 4 for quads; splinekit's quads also carry F*4 bytes of face offsets).
#
# Why splinekit repeats more: the first one or two subdivisions of a process run on memory the
# virtual machine's host has not backed yet and take up to 7x longer (grid50k, one thread: 0.23 s
# for the first run, 0.033 s for the next ones). A peer's median of 5 repeats of 0.3-0.6 s is past
# that and spans 1.5-3 s. splinekit's repeats take 6-160 ms, so with --sk-repeat auto (the
# default) each run repeats enough times to span about one second too (at least 25; a probe run of
# 3 repeats sets the count, and as its median can be one of the slow first repeats, runs span
# 0.5-1 s). Fewer would make the two-thread median hostage to the host: on this
# machine a vCPU is now and then taken away for 50-300 ms at a time (two-thread repeats then take
# the one-thread time; see bench/README.md), which can be most of 25 repeats of 6 ms.
#
# Documentation and measurement only: never run by CI, asserts nothing. Takes about five minutes.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
scheme=all
levels=3
repeat=5
sk_repeat=auto
rounds=3
settle=1
install=1
igl=1
splinekit=1
while [ $# -gt 0 ]; do
    case "$1" in
    --scheme) scheme="$2"; shift 2 ;;
    --levels) levels="$2"; shift 2 ;;
    --repeat) repeat="$2"; shift 2 ;;
    --sk-repeat) sk_repeat="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --settle) settle="$2"; shift 2 ;;
    --no-install) install=0; shift ;;
    --no-igl) igl=0; shift ;;
    --no-splinekit) splinekit=0; shift ;;
    *) sed -n '2,/^set -euo/{/^#/p}' "$0" | sed 's/^# \{0,1\}//'; exit 2 ;;
    esac
done
case "$scheme" in
loop | catmull-clark | all) ;;
*) echo "compare_loop.sh: --scheme is loop, catmull-clark or all, not '$scheme'" >&2; exit 2 ;;
esac
if [ "${CI:-}" = true ]; then
    echo "compare_loop.sh: a measurement for people, not for CI" >&2
    exit 0
fi

target="${CARGO_TARGET_DIR:-$root/target}"
peers="$target/bench-peers"
meshdir="$target/bench-meshes"
py="${BENCH_VENV:-$here/.venv}/bin/python"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1

[ "$install" = 1 ] && "$here/install_peers.sh"
"$here/drivers/build.sh" "$peers"
[ -x /usr/bin/time ] || { echo "compare_loop.sh: GNU time missing (apt-get install time)" >&2; exit 1; }

# ---- meshes (bench/meshgen.py; deterministic, generated once)
mkdir -p "$meshdir"
declare -A gen_args=(
    [torus100k]="torus 250 200"        # 100000 triangles, closed, genus 1, valence 6
    [icosphere20k]="icosphere 5"       # 20480 triangles, closed, valences 5 and 6
    [grid50k]="grid 250 100"           # 50000 triangles, open: one boundary loop, 4 corners
    [quadtorus100k]="quadtorus 500 200" # 100000 quads, closed, genus 1, valence 4
)
loop_meshes=(torus100k icosphere20k grid50k)
cc_meshes=(quadtorus100k)
meshes=()
[ "$scheme" = catmull-clark ] || meshes+=("${loop_meshes[@]}")
[ "$scheme" = loop ] || meshes+=("${cc_meshes[@]}")
for m in "${meshes[@]}"; do
    if [ ! -s "$meshdir/$m.obj" ]; then
        # shellcheck disable=SC2086
        python3 "$here/meshgen.py" ${gen_args[$m]} "$meshdir/$m.obj.tmp"
        mv "$meshdir/$m.obj.tmp" "$meshdir/$m.obj"
    fi
done

# ---- splinekit
sk="$target/release/splinekit"
notes=()
if [ "$splinekit" = 1 ]; then
    echo "compare_loop.sh: cargo build --release -p splinekit-cli" >&2
    if ! (cd "$root" && cargo build --release -p splinekit-cli) >"$tmp/cargo.log" 2>&1; then
        notes+=("splinekit skipped: cargo build --release -p splinekit-cli failed (last lines below)")
        notes+=("$(tail -n 5 "$tmp/cargo.log")")
        splinekit=0
    elif ! "$sk" subdivide --help >/dev/null 2>&1; then
        notes+=("splinekit skipped: this build has no 'subdivide' subcommand yet")
        splinekit=0
    fi
fi

# ---- runs
load="$(cut -d' ' -f1 /proc/loadavg)"
echo "# $(getconf _NPROCESSORS_ONLN) cores, load average $load; $levels levels; each line the median over $rounds runs of the median of $repeat repeats (splinekit: $sk_repeat; auto = about 0.5-1 s per run, at least 25); peers on one thread"
if ! python3 -c 'import sys; sys.exit(float(sys.argv[1]) >= 0.5)' "$load"; then
    notes+=("the machine was busy at the start (load average $load): other work inflates every time")
fi
# The machine's own two-thread ceiling for memory-bound work (bench/drivers/fill_scaling.cpp):
# filling fresh pages (faults and clearing, which every new output pays) and memory already
# mapped, on one thread and on two. It varies from run to run on a virtual machine, so it is
# measured before and after the runs.
fill() { # when
    [ -x "$peers/fill_scaling" ] || return 0
    "$peers/fill_scaling" 128 | python3 -c '
import json, sys
j = json.load(sys.stdin)
f, w = j["fresh_gbps"], j["warm_gbps"]
print("# memory fill %s, GB/s on 1 / 2 threads: fresh pages %.1f / %.1f (%.2fx), mapped memory %.1f / %.1f (%.2fx)"
      % (sys.argv[1], f[0], f[1], f[1] / f[0], w[0], w[1], w[1] / w[0]))' "$1"
}
fill before
declare -A secs counts
fmt='%-18s %-13s %6s %10s %10s %10s %9s %9s\n'
printf "$fmt" tool mesh levels seconds vertices faces rss_MB out_MB
run() { # tool mesh command...
    local tool="$1" mesh="$2"
    shift 2
    local r
    : >"$tmp/rounds"
    for ((r = 0; r < rounds; r++)); do
        # Let the kernel finish taking back the previous process's memory first: right after
        # a peer frees 800 MB, fresh pages cost the next process up to 2x more.
        sleep "$settle"
        if ! /usr/bin/time -f '%M' -o "$tmp/rss" "$@" >"$tmp/out" 2>"$tmp/err"; then
            printf '%-18s %-13s %6s   failed: %s\n' "$tool" "$mesh" "$levels" "$(tail -n 1 "$tmp/err")"
            return 0
        fi
        { tail -n 1 "$tmp/out"; tail -n 1 "$tmp/rss"; } >>"$tmp/rounds"
    done
    local line
    local k=3 # corners per output face
    case " ${cc_meshes[*]} " in *" $mesh "*) k=4 ;; esac
    line="$(python3 - "$tmp/rounds" "$k" <<'PY'
import json, statistics, sys
k = int(sys.argv[2])
lines = open(sys.argv[1]).read().strip().splitlines()
runs = [(json.loads(lines[k]), int(lines[k + 1].split()[-1])) for k in range(0, len(lines), 2)]
v, f = int(runs[0][0]["vertices"]), int(runs[0][0]["faces"])
s = statistics.median(float(j["seconds"]) for j, _ in runs)
rss_kb = max(kb for _, kb in runs)
print("%.6f" % s, v, f, "%.1f" % (rss_kb / 1024), "%.1f" % ((24 * v + 4 * k * f) / 1e6))
PY
)"
    read -r s v f rss outmb <<<"$line"
    secs["$tool/$mesh"]="$s"
    if [ -z "${counts[$mesh]:-}" ]; then
        counts["$mesh"]="$v $f"
    elif [ "${counts[$mesh]}" != "$v $f" ]; then
        notes+=("$tool on $mesh: $v vertices $f faces, but the first tool gave ${counts[$mesh]}")
    fi
    printf "$fmt" "$tool" "$mesh" "$levels" "$s" "$v" "$f" "$rss" "$outmb"
}
# Repeats per splinekit run: --sk-repeat, or with auto enough for about one second (at least 25),
# from a probe run of 3 repeats. A probe that fails gives 25, and `run` then reports the failure.
sk_repeats() { # command...
    if [ "$sk_repeat" != auto ]; then
        echo "$sk_repeat"
        return 0
    fi
    { "$@" --repeat 3 2>/dev/null || true; } | python3 -c '
import json, math, sys
try:
    s = float(json.loads(sys.stdin.read().strip().splitlines()[-1])["seconds"])
except Exception:
    s = 0.04
print(min(2000, max(25, math.ceil(1.0 / max(s, 1e-4)))))'
}
if [ "$scheme" != catmull-clark ]; then
    echo "# Loop"
    for m in "${loop_meshes[@]}"; do
        in="$meshdir/$m.obj"
        [ -x "$peers/osd_loop" ] && run opensubdiv "$m" "$peers/osd_loop" "$in" -n "$levels" --repeat "$repeat"
        [ -x "$peers/cgal_loop" ] && run cgal "$m" "$peers/cgal_loop" "$in" -n "$levels" --repeat "$repeat"
        [ -x "$peers/openmesh_loop" ] && run openmesh "$m" "$peers/openmesh_loop" "$in" -n "$levels" --repeat "$repeat"
        if [ "$igl" = 1 ] && [ -x "$py" ]; then
            run libigl "$m" "$py" "$here/drivers/igl_loop.py" "$in" -n "$levels" --repeat "$repeat"
        fi
        if [ "$splinekit" = 1 ]; then
            for t in 1 2; do
                q="$(sk_repeats "$sk" subdivide "$in" -n "$levels" --json --threads "$t")"
                run "splinekit-t$t" "$m" "$sk" subdivide "$in" -n "$levels" --json --repeat "$q" --threads "$t"
            done
        fi
    done
fi
if [ "$scheme" != loop ]; then
    echo "# Catmull-Clark"
    for m in "${cc_meshes[@]}"; do
        in="$meshdir/$m.obj"
        [ -x "$peers/osd_catmark" ] && run opensubdiv "$m" "$peers/osd_catmark" "$in" -n "$levels" --repeat "$repeat"
        if [ "$splinekit" = 1 ]; then
            for t in 1 2; do
                q="$(sk_repeats "$sk" subdivide "$in" -n "$levels" --scheme catmull-clark --json --threads "$t")"
                run "splinekit-t$t" "$m" "$sk" subdivide "$in" -n "$levels" --scheme catmull-clark --json \
                    --repeat "$q" --threads "$t"
            done
        fi
    done
fi

# ---- ratios (issue #4 and #7 targets: OpenSubdiv / splinekit-t1 >= 8, splinekit t1 / t2 >= 1.7)
fill after
echo
if [ "$splinekit" = 1 ]; then
    printf '%-13s %22s %22s %20s\n' mesh "opensubdiv/splinekit-t1" "opensubdiv/splinekit-t2" "splinekit t1/t2"
    for m in "${meshes[@]}"; do
        o="${secs[opensubdiv/$m]:-}" s1="${secs[splinekit-t1/$m]:-}" s2="${secs[splinekit-t2/$m]:-}"
        python3 -c '
import sys
m, o, s1, s2 = sys.argv[1:]
r = lambda a, b: "%.2f" % (float(a) / float(b)) if a and b and float(b) > 0 else "-"
print("%-13s %22s %22s %20s" % (m, r(o, s1), r(o, s2), r(s1, s2)))' "$m" "$o" "$s1" "$s2"
    done
else
    echo "no splinekit lines, so no ratios"
fi
for n in "${notes[@]}"; do echo "note: $n"; done
