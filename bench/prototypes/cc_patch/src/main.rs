//! How fast could Catmull-Clark be with a different design? A lower-bound experiment, not part
//! of splinekit.
//!
//! On a closed torus of `NU × NV` quads (`bench/meshgen.py quadtorus NU NV`, every vertex of
//! valence 4), three Catmull-Clark levels are the uniform bicubic B-spline refinement of each
//! base face from its 4 × 4 control points: per base face, three separable 1D steps on a grid on
//! the stack (4 → 5 → 7 → 11 points a side), then its 8 × 8 owned level-3 vertices written out,
//! its 64 quads (pointing at the neighbours' vertices for the last row and column) and the face
//! offsets, into fresh memory from splinekit's own huge-page allocator, on one thread.
//!
//! It leaves out everything a real implementation needs beyond that (adjacency of the input,
//! extraordinary vertices, boundaries, creases, splinekit's vertex order), so its time is a
//! lower bound for the design "one patch per base face, nothing stored between levels". It
//! checks its level-3 vertices at the base vertices against splinekit's output (same vertex
//! numbers there) when given one: the tensor-product weights equal Catmull-Clark's only in
//! exact arithmetic, so they agree to rounding, not to the bit.
//!
//! ```text
//! cargo run --release --manifest-path bench/prototypes/cc_patch/Cargo.toml -- \
//!     target/bench-meshes/quadtorus100k.obj 500 200 [splinekit-level-3.obj]
//! ```
#[path = "../../../../crates/splinekit-cli/src/alloc.rs"]
#[allow(dead_code)]
mod alloc;

#[global_allocator]
static ALLOC: alloc::HugePageAlloc = alloc::HugePageAlloc;

use std::time::Instant;

type P = [f64; 3];

/// Edge point of the uniform cubic B-spline refinement.
#[inline(always)]
fn edge(a: P, b: P) -> P {
    [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5, (a[2] + b[2]) * 0.5]
}

/// Vertex point of the uniform cubic B-spline refinement.
#[inline(always)]
fn vertex(a: P, b: P, c: P) -> P {
    [(a[0] + 6.0 * b[0] + c[0]) * 0.125, (a[1] + 6.0 * b[1] + c[1]) * 0.125, (a[2] + 6.0 * b[2] + c[2]) * 0.125]
}

/// One refinement of `N` control points: the `M = 2N − 3` that still have both neighbours.
#[inline(always)]
fn step<const N: usize, const M: usize>(p: &[P; N]) -> [P; M] {
    let mut o = [[0.0; 3]; M];
    for i in 0..N - 1 {
        o[2 * i] = edge(p[i], p[i + 1]);
    }
    for i in 1..N - 1 {
        o[2 * i - 1] = vertex(p[i - 1], p[i], p[i + 1]);
    }
    o
}

/// One refinement of an `N × N` grid: rows, then columns.
#[inline(always)]
fn step2<const N: usize, const M: usize>(g: &[[P; N]; N]) -> [[P; M]; M] {
    let mut rows = [[[0.0; 3]; M]; N];
    for i in 0..N {
        rows[i] = step::<N, M>(&g[i]);
    }
    let mut o = [[[0.0; 3]; M]; M];
    for j in 0..M {
        let col = step::<N, M>(&core::array::from_fn(|i| rows[i][j]));
        for i in 0..M {
            o[i][j] = col[i];
        }
    }
    o
}

fn read_positions(path: &str) -> Vec<P> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|t| t.parse().expect("a number")).collect();
            [x[0], x[1], x[2]]
        })
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "cc_patch QUADTORUS.obj NU NV [SPLINEKIT_LEVEL3.obj]";
    let (path, nu, nv) = match &args[1..] {
        [p, a, b, ..] => (p.as_str(), a.parse::<usize>().expect(usage), b.parse::<usize>().expect(usage)),
        _ => panic!("usage: {usage}"),
    };
    let pos = read_positions(path);
    assert_eq!(pos.len(), nu * nv, "{path}: expected {nu} × {nv} vertices");
    // meshgen's layout: vertex (i, j) is i·NV + j, face (i, j) has corners (i, j) (i+1, j) (i+1, j+1) (i, j+1)
    let idx = |i: usize, j: usize| (i % nu) * nv + (j % nv);
    let nf = nu * nv;
    let mut runs = Vec::new();
    let mut corners_of_base = Vec::new();
    for _ in 0..25 {
        let t = Instant::now();
        let mut values: Vec<[P; 64]> = Vec::with_capacity(nf);
        for f in 0..nf {
            let (i, j) = (f / nv, f % nv);
            let g: [[P; 4]; 4] =
                core::array::from_fn(|a| core::array::from_fn(|b| pos[idx(i + nu - 1 + a, j + nv - 1 + b)]));
            let g3 = step2::<7, 11>(&step2::<5, 7>(&step2::<4, 5>(&g)));
            let mut v = [[0.0; 3]; 64];
            for k in 0..64 {
                v[k] = g3[1 + k / 8][1 + k % 8];
            }
            values.push(v);
        }
        let t_values = t.elapsed();
        // the level-3 vertex (a, b) of the 9 × 9 grid of face f, owned by f or a neighbour
        let at = |f: usize, a: usize, b: usize| -> u32 {
            let (i, j) = (f / nv + a / 8, f % nv + b / 8);
            (64 * idx(i, j) + 8 * (a % 8) + b % 8) as u32
        };
        let mut quads: Vec<[u32; 256]> = Vec::with_capacity(nf);
        for f in 0..nf {
            let mut q = [0u32; 256];
            for a in 0..8 {
                for b in 0..8 {
                    let k = 4 * (8 * a + b);
                    q[k] = at(f, a, b);
                    q[k + 1] = at(f, a + 1, b);
                    q[k + 2] = at(f, a + 1, b + 1);
                    q[k + 3] = at(f, a, b + 1);
                }
            }
            quads.push(q);
        }
        let t_quads = t.elapsed();
        let offsets: Vec<u32> = (0..=64 * nf as u32).map(|k| 4 * k).collect();
        let total = t.elapsed();
        std::hint::black_box((&values, &quads, &offsets));
        corners_of_base = values.iter().map(|v| v[0]).collect();
        runs.push([total, t_values, t_quads - t_values, total - t_quads].map(|d| d.as_secs_f64() * 1e3));
    }
    runs.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let m = runs[runs.len() / 2];
    println!(
        "{{\"faces\": {}, \"ms\": {:.1}, \"values_ms\": {:.1}, \"quads_ms\": {:.1}, \"offsets_ms\": {:.1}}}",
        64 * nf,
        m[0],
        m[1],
        m[2],
        m[3]
    );
    if let Some(reference) = args.get(4) {
        // splinekit keeps a vertex's number at every level: its level-3 vertex v < |V| is base vertex v
        let sk = read_positions(reference);
        let worst = (0..nf)
            .map(|v| (0..3).map(|c| (sk[v][c] - corners_of_base[v][c]).abs()).fold(0.0, f64::max))
            .fold(0.0, f64::max);
        println!("largest difference from splinekit at the base vertices: {worst:e}");
        assert!(worst < 1e-12, "the experiment does not compute Catmull-Clark");
    }
}
