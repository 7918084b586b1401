//! NURBS against geomdl (NURBS-Python 5.4.0), an independent implementation of The NURBS
//! Book's algorithms (A3.1/A3.2 with A4.2 for points and derivatives, A5.1 for knot
//! insertion): points, first and second derivatives and knot insertion of 13 seeded random
//! curves — degrees 1–5 and 7, 2D and 3D, clamped uniform and non-uniform knots with interior
//! knots of multiplicity 2 and `degree`, an unclamped knot vector, a domain away from 0, weights
//! in [0.2, 5]. The data is `tests/data/nurbs/geomdl.json`, written by
//! `bench/make_nurbs_references.py` (no Python is needed here).
//!
//! geomdl works in the knot parameter `x`; splinekit's curve parameter `u` runs one unit per
//! span, so the comparison goes through [`Nurbs::param_at_knot`], and derivatives with respect
//! to `u` are geomdl's times `dx/du = h`, the length of the span (`h²` for the second).

use glam::{DVec2, DVec3};
use serde_json::Value;
use splinekit::{Nurbs, ParamCurve, Vector};

/// The tolerance, relative to each quantity's natural scale. With `R = maxᵢ |pᵢ|` and `W` the
/// ratio of the largest weight to the smallest:
/// - points: `C = Σ Nᵢwᵢpᵢ / Σ Nᵢwᵢ`, the numerator a convex combination of the `wᵢpᵢ` and the
///   denominator at least `w_min`: both sides round at `O(p·ε·W·R)` (`p ≤ 7`, `W ≤ 25`: about
///   `4e-14·R`), plus `|dC/du|·|x|/h·ε` from rounding `x` to `u` and back (`|x|/h` up to ~30 for
///   the offset domain) — scale `R`;
/// - `dC/du = (A′ − C·w′)/w` with the homogeneous hodograph's control points `p·ΔQⱼ·h/(x_{j+p} −
///   x_j)`, whose knot gaps all hold the span, so `|A′| ≤ 2p·w_max·R` and `|dC/du| ≤ 4p·W·R` —
///   scale `p·W·R`;
/// - `d²C/du²` by the same steps — scale `p²·W²·R`;
/// - inserted control points `Q/w` (blends of the homogeneous points) — scale `W·R`; weights —
///   scale `w_max`; knots are copied, plus the new one: equal.
///
/// The worst ratio measured (printed by the test) is below 1e-14 of these scales; 1e-12 leaves
/// room for another order of summation and still catches any wrong term, a wrong span or a
/// derivative that misses the `dx/du` factor (those are off by O(1) of the scale).
const TOL: f64 = 1e-12;

struct Case {
    name: String,
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Vec<f64>>,
    weights: Vec<f64>,
    evals: Vec<Eval>,
    insertions: Vec<Insertion>,
}

struct Eval {
    x: f64,
    point: Vec<f64>,
    d1: Vec<f64>,
    d2: Vec<f64>,
}

struct Insertion {
    x: f64,
    times: usize,
    knots: Vec<f64>,
    points: Vec<Vec<f64>>,
    weights: Vec<f64>,
}

/// `f` of each element of the array `v`.
fn each<T>(v: &Value, f: impl Fn(&Value) -> T) -> Vec<T> {
    v.as_array().unwrap_or_else(|| panic!("an array, not {v}")).iter().map(f).collect()
}

fn floats(v: &Value) -> Vec<f64> {
    each(v, |f| f.as_f64().expect("a number"))
}

fn rows(v: &Value) -> Vec<Vec<f64>> {
    each(v, floats)
}

fn load() -> (String, Vec<Case>) {
    let path = format!("{}/tests/data/nurbs/geomdl.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {path}: {e}"));
    let data: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("parsing {path}: {e}"));
    let cases = each(&data["curves"], |c| Case {
        name: c["name"].as_str().expect("name").to_owned(),
        degree: c["degree"].as_u64().expect("degree") as usize,
        knots: floats(&c["knots"]),
        points: rows(&c["points"]),
        weights: floats(&c["weights"]),
        evals: each(&c["evals"], |e| Eval {
            x: e["x"].as_f64().expect("x"),
            point: floats(&e["point"]),
            d1: floats(&e["d1"]),
            d2: floats(&e["d2"]),
        }),
        insertions: each(&c["insertions"], |i| Insertion {
            x: i["x"].as_f64().expect("x"),
            times: i["times"].as_u64().expect("times") as usize,
            knots: floats(&i["knots"]),
            points: rows(&i["points"]),
            weights: floats(&i["weights"]),
        }),
    });
    (data["source"].as_str().unwrap_or("geomdl").to_owned(), cases)
}

fn vec3(v: &[f64]) -> DVec3 {
    DVec3::new(v[0], v[1], v.get(2).copied().unwrap_or(0.0))
}

/// The worst error of each kind as a fraction of its scale, with where it happened.
#[derive(Default)]
struct Worst {
    ratios: [(f64, String); 6],
}

const KINDS: [&str; 6] = ["point", "d/du", "d²/du²", "inserted knot", "inserted point", "inserted weight"];

impl Worst {
    /// Records `|actual − expected| / scale` for `kind` and fails above [`TOL`].
    fn check(&mut self, kind: usize, actual: DVec3, expected: DVec3, scale: f64, what: &str) {
        let ratio = (actual - expected).length() / scale;
        assert!(
            ratio <= TOL,
            "{what}: {} splinekit {actual:?}, geomdl {expected:?}, |diff| = {:e} = {ratio:e} of the scale {scale:e}",
            KINDS[kind],
            (actual - expected).length()
        );
        if ratio >= self.ratios[kind].0 {
            self.ratios[kind] = (ratio, what.to_owned());
        }
    }
}

fn check_case<P: Vector>(case: &Case, worst: &mut Worst) {
    let points: Vec<P> = case.points.iter().map(|p| P::from_dvec3(vec3(p))).collect();
    let curve = Nurbs::new(case.degree, points, case.weights.clone(), Some(case.knots.clone()))
        .unwrap_or_else(|e| panic!("{}: {e}", case.name));
    let p = case.degree as f64;
    let r = case.points.iter().map(|q| vec3(q).length()).fold(0.0, f64::max);
    let w_max = case.weights.iter().copied().fold(0.0, f64::max);
    let w = w_max / case.weights.iter().copied().fold(f64::INFINITY, f64::min);
    let m = ParamCurve::<P>::num_segments(&curve);

    for e in &case.evals {
        let u = curve.param_at_knot(e.x);
        // the segment evaluation uses (the one starting at an interior knot, the last at the
        // end) and its dx/du
        let k = if u > 0.0 { (u.floor() as usize).min(m - 1) } else { 0 };
        let h = curve.knot_at((k + 1) as f64) - curve.knot_at(k as f64);
        let what = format!("{} at x = {} (u = {u})", case.name, e.x);
        worst.check(0, curve.eval(u).to_dvec3(), vec3(&e.point), r, &what);
        worst.check(1, curve.deriv(u).to_dvec3(), vec3(&e.d1) * h, p * w * r, &what);
        worst.check(2, curve.deriv2(u).to_dvec3(), vec3(&e.d2) * (h * h), p * p * w * w * r, &what);
    }

    for ins in &case.insertions {
        let mut inserted = curve.clone();
        for _ in 0..ins.times {
            inserted = inserted.insert_knot(ins.x);
        }
        let what = format!("{} inserting x = {} {} time(s)", case.name, ins.x, ins.times);
        assert_eq!(inserted.knots().len(), ins.knots.len(), "{what}: knot count");
        assert_eq!(inserted.points().len(), ins.points.len(), "{what}: point count");
        for (i, (&a, &b)) in inserted.knots().iter().zip(&ins.knots).enumerate() {
            // copies and the new knot itself: exactly equal (the scale only keeps the ratio finite)
            let scale = b.abs().max(1.0);
            assert!(a == b, "{what}: knot {i} splinekit {a}, geomdl {b}");
            worst.check(3, DVec3::splat(a), DVec3::splat(b), scale, &format!("{what}, knot {i}"));
        }
        for (i, (a, b)) in inserted.points().iter().zip(&ins.points).enumerate() {
            worst.check(4, a.to_dvec3(), vec3(b), w * r, &format!("{what}, point {i}"));
        }
        for (i, (&a, &b)) in inserted.weights().iter().zip(&ins.weights).enumerate() {
            worst.check(5, DVec3::splat(a), DVec3::splat(b), w_max, &format!("{what}, weight {i}"));
        }
    }
}

#[test]
fn nurbs_agree_with_geomdl() {
    let (source, cases) = load();
    assert!(cases.len() >= 13, "the data holds {} curves", cases.len());
    let mut worst = Worst::default();
    let (mut evals, mut insertions) = (0, 0);
    for case in &cases {
        match case.points[0].len() {
            2 => check_case::<DVec2>(case, &mut worst),
            3 => check_case::<DVec3>(case, &mut worst),
            d => panic!("{}: dimension {d}", case.name),
        }
        evals += case.evals.len();
        insertions += case.insertions.len();
    }
    println!("against {source}: {} curves, {evals} parameters, {insertions} insertions", cases.len());
    for (kind, (ratio, what)) in KINDS.iter().zip(&worst.ratios) {
        println!("  worst {kind}: {ratio:.2e} of its scale ({what})");
    }
}
