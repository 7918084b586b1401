//! The arc-length reference scene of SPEC §1.4: 8 control points, open uniform
//! Catmull-Rom (5 segments), 5 samples per segment.

use std::f64::consts::TAU;

use glam::DVec3;
use splinekit::{ArclenIndex, ArclenTable, CatmullRom, ParamCurve, PiecewiseCubic};

/// The `s` column of SPEC §1.4, u = 0.0, 0.2, …, 5.0 (independent published table).
const CHORD_S: [f64; 26] = [
    0.00000, 0.13984, 0.35788, 0.59640, 0.77689, 0.82383, 0.99348, 1.31196, 1.68453, 2.01578, 2.21177, 2.28435,
    2.43888, 2.63035, 2.78487, 2.85746, 3.05345, 3.38470, 3.75727, 4.07574, 4.24539, 4.29233, 4.47283, 4.71135,
    4.92939, 5.06923,
];

fn scene() -> PiecewiseCubic<DVec3> {
    let pts: Vec<DVec3> = (0..8)
        .map(|i| {
            let a = i as f64 / 7.0;
            let th = TAU * a;
            let r = (2.0 * th).cos();
            DVec3::new(r * th.cos(), r * th.sin(), -0.5 + a)
        })
        .collect();
    CatmullRom::new(&pts, false, 0.0).unwrap().to_piecewise()
}

#[test]
fn chord_table_matches_all_26_rows_to_5_decimals() {
    let table = ArclenTable::chord(&scene(), 5);
    assert_eq!(table.len(), 26);
    for (i, ((u, s), want)) in table.iter_rows().zip(CHORD_S).enumerate() {
        assert!((u - i as f64 * 0.2).abs() < 1e-12, "row {i}: u = {u}");
        assert!((s - want).abs() <= 0.5e-5, "row {i}: s = {s:.7}, table says {want:.5}");
    }
}

#[test]
fn gauss3_total_matches() {
    let table = ArclenTable::gauss3(&scene(), 5);
    assert_eq!(table.len(), 26);
    let total = table.length();
    assert!((total - 5.14943).abs() <= 0.5e-5, "gauss3 total {total:.7}");
}

#[test]
fn adaptive_total_matches_true_length() {
    let c = scene();
    for acc in [1e-3, 1e-6, 1e-9, 1e-11] {
        let e = c.arclen_range(0.0, 5.0, acc);
        assert!((e.length - 5.147598456).abs() <= acc.max(1e-9), "acc {acc}: {:.12}", e.length);
        assert!(e.error <= acc, "acc {acc}: error estimate {}", e.error);
    }
    // the true length to 5 decimals, as SPEC §1.4 prints it
    assert!((c.arclen(1e-9) - 5.14760).abs() <= 0.5e-5);
}

#[test]
fn inverse_from_chord_table() {
    let table = ArclenTable::chord(&scene(), 5);
    let u = table.u_at(0.417);
    assert!((u - 0.4496).abs() <= 0.5e-4, "u(0.417) = {u:.6}");
    // round trip through the table's own rows
    for (u, s) in table.iter_rows() {
        assert!((table.u_at(s) - u).abs() < 1e-12);
    }
    assert_eq!(table.u_at(-1.0), 0.0);
    assert_eq!(table.u_at(100.0), 5.0);
}

#[test]
fn exact_inverse_on_scene_meets_accuracy_in_length_units() {
    let c = scene();
    let truth = |u: f64| c.arclen_range(0.0, u, 1e-13).length;
    for acc in [1e-3, 1e-6, 1e-9] {
        let index = ArclenIndex::new(&c, acc);
        for i in 0..=50 {
            let s = 5.1475 * i as f64 / 50.0;
            let u = index.u_at(&c, s);
            assert!((0.0..=5.0).contains(&u));
            let err = (truth(u) - s).abs();
            assert!(err <= acc, "acc {acc}, s {s}: |s(u) − s| = {err:e}");
        }
    }
}

#[test]
fn resampling_by_arc_length_on_scene() {
    use splinekit::{ResampleError, resample_equal, resample_every};
    let c = scene();
    let acc = 1e-9;
    let truth = |u: f64| c.arclen_range(0.0, u, 1e-13).length;
    // k equal pieces: k + 1 points, first at the start, last at the end, s(uᵢ) = i·L/k
    let pts = resample_equal(&c, 7, acc);
    assert_eq!(pts.len(), 8);
    assert_eq!(pts[0].u, 0.0);
    assert_eq!(pts[7].u, 5.0);
    for (i, p) in pts.iter().enumerate() {
        assert!((truth(p.u) - 5.147598456 * i as f64 / 7.0).abs() <= 1e-8, "piece {i}");
        assert!((p.point - c.eval(p.u)).length() == 0.0);
    }
    // every ds: floor(L/ds) + 1 points at s = i·ds
    let every = resample_every(&c, 0.5, acc, 1000).unwrap();
    assert_eq!(every.len(), (5.147598456f64 / 0.5).floor() as usize + 1);
    for (i, p) in every.iter().enumerate() {
        assert_eq!(p.s, 0.5 * i as f64);
        assert!((truth(p.u) - p.s).abs() <= acc);
    }
    assert!(matches!(resample_every(&c, 0.0, acc, 10), Err(ResampleError::BadSpacing(_))));
    assert!(matches!(resample_every(&c, f64::NAN, acc, 10), Err(ResampleError::BadSpacing(_))));
    assert!(matches!(resample_every(&c, 1e-6, acc, 1000), Err(ResampleError::TooManyPoints { .. })));
}
