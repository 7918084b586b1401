//! Parametric surfaces, revolution about +z and the lathe (`splinekit::sweep::surface`):
//! topology (closed, oriented, Euler characteristic, poles), volumes against closed forms,
//! normals against faces, counts, and input errors.

use std::collections::HashSet;
use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use splinekit::TriMesh;
use splinekit::sweep::surface::{
    Lathe, LatheOptions, RevolveOptions, SurfaceError, SurfaceOptions, UvMode, mesh_surface, revolve_z,
};

/// Tolerance for values that are exact by construction (up to rounding).
const EXACT: f64 = 1e-12;

fn euler(m: &TriMesh) -> i64 {
    let edges: HashSet<(u32, u32)> = m
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect();
    m.num_vertices() as i64 - edges.len() as i64 + m.num_triangles() as i64
}

/// [`check_structure`], and each vertex normal within 90° of every adjacent face normal.
fn check_mesh(m: &TriMesh, what: &str) {
    check_structure(m, what);
    for i in 0..m.num_triangles() {
        let f = m.face_normal(i);
        for &v in &m.triangles[i] {
            assert!(f.dot(m.normals[v as usize]) > 0.0, "{what}: normal {v} against triangle {i}");
        }
    }
}

/// Valid, unit normals, no duplicate vertices, no zero-area triangles.
fn check_structure(m: &TriMesh, what: &str) {
    m.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(m.normals.len(), m.num_vertices(), "{what}");
    for (k, n) in m.normals.iter().enumerate() {
        assert!((n.length() - 1.0).abs() < EXACT, "{what}: normal {k} = {n}");
    }
    let size = m.positions.iter().fold(0.0f64, |a, p| a.max(p.abs().max_element()));
    let mut sorted = m.positions.clone();
    sorted.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
    for w in sorted.windows(2) {
        assert!(w[0].distance(w[1]) > 1e-9 * size, "{what}: duplicate vertex {}", w[0]);
    }
    for i in 0..m.num_triangles() {
        let f = m.face_normal(i);
        assert!(f.length() > 1e-12 * size * size, "{what}: triangle {i} has zero area");
    }
}

/// Vertices that lie at `p` (within `EXACT`).
fn count_at(m: &TriMesh, p: DVec3) -> usize {
    m.positions.iter().filter(|q| q.distance(p) < EXACT).count()
}

fn torus(big: f64, small: f64) -> impl Fn(f64, f64) -> DVec3 {
    move |u, v| {
        let (a, b) = (TAU * u, TAU * v);
        let r = big + small * b.cos();
        DVec3::new(r * a.cos(), r * a.sin(), small * b.sin())
    }
}

fn sphere(u: f64, v: f64) -> DVec3 {
    let (theta, phi) = (TAU * u, PI * (v - 0.5));
    DVec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin())
}

/// A half circle of radius 1 from the south pole to the north pole, `n` segments.
fn half_circle(n: usize) -> Vec<DVec2> {
    (0..=n)
        .map(|i| {
            let a = PI * (i as f64 / n as f64 - 0.5);
            DVec2::new(a.cos(), a.sin())
        })
        .collect()
}

/// `|error(n)| / |error(2n)|` for successive refinements; ≈ 4 for second-order convergence.
fn ratios(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| w[0] / w[1]).collect()
}

#[test]
fn torus_is_a_closed_oriented_torus_with_converging_volume() {
    let (big, small) = (2.0, 0.6);
    let exact = 2.0 * PI * PI * big * small * small;
    let mut errors = Vec::new();
    for n in [8, 16, 32, 64] {
        let m = mesh_surface(torus(big, small), &SurfaceOptions::new(2 * n, n).with_wrap(true, true)).unwrap();
        check_mesh(&m, &format!("torus {n}"));
        assert!(m.is_closed_oriented(), "torus {n}");
        assert!(m.boundary_edges().is_empty());
        assert_eq!(euler(&m), 0, "torus {n}");
        assert_eq!(m.num_vertices(), 2 * n * n);
        assert_eq!(m.num_triangles(), 4 * n * n);
        assert!(m.uvs.is_empty(), "a wrapped surface has no UVs by default");
        let v = m.signed_volume();
        assert!(v > 0.0 && v < exact, "torus {n}: volume {v}, exact {exact}");
        errors.push(exact - v);
    }
    for r in ratios(&errors) {
        assert!((3.5..4.5).contains(&r), "error ratios {:?} for errors {errors:?}", ratios(&errors));
    }
    // leading order: inscribed polygons around the tube (n sides) and the axis (2n sides)
    for (k, n) in [(1, 16.0), (2, 32.0), (3, 64.0)] {
        let predicted = exact * ((TAU / n).powi(2) + (PI / n).powi(2)) / 6.0;
        assert!((errors[k] / predicted - 1.0).abs() < 0.05, "{errors:?}: {n} predicted {predicted}");
    }
}

#[test]
fn parametric_sphere_has_two_poles_and_converges() {
    let exact = 4.0 / 3.0 * PI;
    let mut errors = Vec::new();
    for n in [8, 16, 32, 64] {
        let m = mesh_surface(sphere, &SurfaceOptions::new(2 * n, n).with_wrap(true, false)).unwrap();
        check_mesh(&m, &format!("sphere {n}"));
        assert!(m.is_closed_oriented(), "sphere {n}");
        assert_eq!(euler(&m), 2, "sphere {n}");
        assert_eq!(m.num_vertices(), 2 + 2 * n * (n - 1));
        assert_eq!(m.num_triangles(), 2 * 2 * n * (n - 1));
        assert_eq!(count_at(&m, -DVec3::Z), 1, "one south pole");
        assert_eq!(count_at(&m, DVec3::Z), 1, "one north pole");
        // pole normals point along the axis, outward
        assert!(m.normals[0].distance(-DVec3::Z) < EXACT);
        assert!(m.normals[m.num_vertices() - 1].distance(DVec3::Z) < EXACT);
        errors.push(exact - m.signed_volume());
    }
    assert!(errors.iter().all(|&e| e > 0.0), "inscribed: {errors:?}");
    for r in ratios(&errors) {
        assert!((3.5..4.5).contains(&r), "error ratios {:?}", ratios(&errors));
    }
}

#[test]
fn flipped_sphere_faces_inward() {
    let o = SurfaceOptions::new(12, 6).with_wrap(true, false);
    let m = mesh_surface(sphere, &o).unwrap();
    let f = mesh_surface(sphere, &o.with_flip(true)).unwrap();
    assert!(f.is_closed_oriented());
    assert!((f.signed_volume() + m.signed_volume()).abs() < EXACT);
    for (a, b) in m.normals.iter().zip(&f.normals) {
        assert!(a.distance(-*b) < EXACT);
    }
}

#[test]
fn flat_open_grid_counts_boundary_and_uvs() {
    let (nu, nv) = (5, 3);
    let m = mesh_surface(|u, v| DVec3::new(3.0 * u, 2.0 * v, 1.0), &SurfaceOptions::new(nu, nv)).unwrap();
    check_mesh(&m, "grid");
    assert_eq!(m.num_vertices(), (nu + 1) * (nv + 1));
    assert_eq!(m.num_triangles(), 2 * nu * nv);
    assert_eq!(m.boundary_edges().len(), 2 * (nu + nv));
    assert_eq!(euler(&m), 1);
    assert!(!m.is_closed_oriented());
    assert!((m.area() - 6.0).abs() < EXACT);
    assert_eq!(m.uvs.len(), m.num_vertices());
    for j in 0..=nv {
        for i in 0..=nu {
            let k = j * (nu + 1) + i;
            let uv = DVec2::new(i as f64 / nu as f64, j as f64 / nv as f64);
            assert_eq!(m.uvs[k], uv);
            assert!(m.positions[k].distance(DVec3::new(3.0 * uv.x, 2.0 * uv.y, 1.0)) < EXACT);
        }
    }
    // counter-clockwise seen from +z = ∂f/∂u × ∂f/∂v
    assert!((0..m.num_triangles()).all(|i| m.face_normal(i).normalize().distance(DVec3::Z) < EXACT));
    let none = mesh_surface(|u, v| DVec3::new(u, v, 0.0), &SurfaceOptions::new(nu, nv).with_uvs(UvMode::Omit)).unwrap();
    assert!(none.uvs.is_empty());
}

#[test]
fn cylinder_wrapped_in_u_only() {
    let tube = |u: f64, v: f64| DVec3::new((TAU * u).cos(), (TAU * u).sin(), v);
    let m = mesh_surface(tube, &SurfaceOptions::new(10, 4).with_wrap(true, false)).unwrap();
    check_mesh(&m, "tube");
    assert_eq!(m.num_vertices(), 10 * 5);
    assert_eq!(m.boundary_edges().len(), 20);
    assert_eq!(euler(&m), 0);
    // outward: the normals point away from the axis
    assert!(m.positions.iter().zip(&m.normals).all(|(p, n)| n.dot(DVec3::new(p.x, p.y, 0.0)) > 0.99));
    let s =
        mesh_surface(tube, &SurfaceOptions::new(10, 4).with_wrap(true, false).with_uvs(UvMode::SplitSeams)).unwrap();
    assert_eq!(s.num_vertices(), 11 * 5);
    assert_eq!(s.uvs[10], DVec2::new(1.0, 0.0));
    assert_eq!(s.positions[10], s.positions[0]);
}

#[test]
fn revolve_half_circle_is_a_sphere() {
    let exact = 4.0 / 3.0 * PI;
    let mut errors = Vec::new();
    for (n, slice_tolerance) in [(8, 0.4), (16, 0.2), (32, 0.1), (64, 0.05)] {
        let options = RevolveOptions::new(1.0, slice_tolerance);
        let slices = (TAU / slice_tolerance).ceil() as usize;
        assert_eq!(options.num_slices().unwrap(), slices);
        let m = revolve_z(&half_circle(n), None, &options).unwrap();
        check_mesh(&m, &format!("revolved sphere {n}"));
        assert!(m.is_closed_oriented());
        assert_eq!(euler(&m), 2);
        assert_eq!(m.num_vertices(), 2 + slices * (n - 1));
        assert_eq!(m.num_triangles(), 2 * slices * (n - 1));
        assert_eq!(count_at(&m, -DVec3::Z), 1);
        assert_eq!(count_at(&m, DVec3::Z), 1);
        // the exact volume of the revolved polygon: slices·sin(2π/slices)/2π times the
        // solid of the profile polyline
        let profile = half_circle(n);
        let solid: f64 = profile
            .windows(2)
            .map(|w| PI * (w[1].y - w[0].y) * (w[0].x * w[0].x + w[0].x * w[1].x + w[1].x * w[1].x) / 3.0)
            .sum();
        let polygon = slices as f64 * (TAU / slices as f64).sin() / TAU;
        assert!((m.signed_volume() - solid * polygon).abs() < 1e-12 * exact);
        errors.push(exact - m.signed_volume());
    }
    for r in ratios(&errors) {
        assert!((3.0..5.0).contains(&r), "error ratios {:?}", ratios(&errors));
    }
}

#[test]
fn revolve_scale_and_given_normals() {
    let profile = half_circle(24);
    let normals = profile.clone(); // a unit circle's outward normals are its points
    let o = RevolveOptions::new(2.5, TAU / 40.0);
    let m = revolve_z(&profile, Some(&normals), &o).unwrap();
    check_mesh(&m, "scaled sphere");
    assert_eq!(o.num_slices().unwrap(), 40);
    for (p, n) in m.positions.iter().zip(&m.normals) {
        assert!((p.length() - 2.5).abs() < EXACT);
        assert!(n.distance(p.normalize()) < EXACT, "{n} at {p}");
    }
    // inward normals and the reversed profile still give an outward sphere
    let inward: Vec<DVec2> = normals.iter().rev().map(|&n| -n).collect();
    let reversed: Vec<DVec2> = profile.iter().rev().copied().collect();
    let r = revolve_z(&reversed, Some(&inward), &o).unwrap();
    check_mesh(&r, "reversed sphere");
    assert!((r.signed_volume() - m.signed_volume()).abs() < EXACT);
    for (p, n) in r.positions.iter().zip(&r.normals) {
        assert!(n.distance(p.normalize()) < EXACT);
    }
}

#[test]
fn revolve_either_direction_is_never_inside_out() {
    let o = RevolveOptions::new(1.0, TAU / 24.0);
    // a closed loop off the axis: a torus (last point repeats the first)
    let circle: Vec<DVec2> =
        (0..=32).map(|i| DVec2::new(2.0, 0.0) + DVec2::from_angle(TAU * i as f64 / 32.0) * 0.5).collect();
    for (what, profile) in [("ccw", circle.clone()), ("cw", circle.iter().rev().copied().collect())] {
        let m = revolve_z(&profile, None, &o).unwrap();
        check_mesh(&m, what);
        assert!(m.is_closed_oriented(), "{what}");
        assert_eq!(euler(&m), 0, "{what}");
        assert_eq!(m.num_vertices(), 24 * 32, "{what}: the repeated point is dropped");
        let exact = 2.0 * PI * PI * 2.0 * 0.25;
        assert!((m.signed_volume() - exact).abs() < 0.02 * exact, "{what}: {}", m.signed_volume());
        // normals point away from the tube's centre circle
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let centre = DVec3::new(p.x, p.y, 0.0).normalize() * 2.0;
            assert!(n.dot((*p - centre).normalize()) > 0.99, "{what}");
        }
    }
    // an open tube (no caps): normals point away from the axis either way
    for profile in [[DVec2::new(1.0, 0.0), DVec2::new(1.0, 3.0)], [DVec2::new(1.0, 3.0), DVec2::new(1.0, 0.0)]] {
        let m = revolve_z(&profile, None, &o).unwrap();
        check_mesh(&m, "tube");
        assert_eq!(m.boundary_edges().len(), 48);
        assert!(m.positions.iter().zip(&m.normals).all(|(p, n)| n.dot(DVec3::new(p.x, p.y, 0.0)) > 0.99));
    }
}

#[test]
fn lathe_with_closed_tips() {
    // radius: two quarter-circle-like segments from 0 up to 1 and back; height: one segment
    let k = 0.552_284_75;
    let lathe = Lathe::new(&[0.0, k, 1.0, 1.0, 1.0, k, 0.0], &[-1.0, -1.0 / 3.0, 1.0 / 3.0, 1.0]).unwrap();
    assert!(lathe.profile(0.5).distance(DVec2::new(1.0, 0.0)) < EXACT);
    assert!(lathe.point(0.25, 0.5).distance(DVec3::Y) < EXACT);
    let mut volumes = Vec::new();
    for n in [16, 32, 64] {
        let m = lathe.to_mesh(&LatheOptions::new(2 * n, n)).unwrap();
        check_mesh(&m, &format!("lathe {n}"));
        assert!(m.is_closed_oriented());
        assert_eq!(euler(&m), 2);
        assert_eq!(m.num_vertices(), 2 + 2 * n * (n - 1));
        assert_eq!(count_at(&m, DVec3::new(0.0, 0.0, -1.0)), 1);
        assert_eq!(count_at(&m, DVec3::new(0.0, 0.0, 1.0)), 1);
        volumes.push(m.signed_volume());
    }
    // π ∫ r(v)² z′(v) dv by Simpson's rule on each Bézier piece
    let m = 2000;
    let reference: f64 = (0..=m)
        .map(|i| {
            let v = i as f64 / m as f64;
            let w = if i == 0 || i == m {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * lathe.profile(v).x.powi(2) * lathe.profile_deriv(v).y
        })
        .sum::<f64>()
        * PI
        / (3.0 * m as f64);
    let errors: Vec<f64> = volumes.iter().map(|v| reference - v).collect();
    assert!(errors.iter().all(|&e| e > 0.0 && e < 0.05 * reference), "{errors:?} of {reference}");
    for r in ratios(&errors) {
        assert!((3.0..5.0).contains(&r), "error ratios {:?}", ratios(&errors));
    }
    // the same lathe with the height running downward is not inside-out
    let down = Lathe::new(&[0.0, k, 1.0, 1.0, 1.0, k, 0.0], &[1.0, 1.0 / 3.0, -1.0 / 3.0, -1.0]).unwrap();
    let d = down.to_mesh(&LatheOptions::new(64, 32)).unwrap();
    check_mesh(&d, "downward lathe");
    assert!((d.signed_volume() - volumes[1]).abs() < 1e-9);
}

#[test]
fn lathe_uvs_split_the_seam_only() {
    let lathe = Lathe::new(&[0.0, 1.0, 1.0, 0.0], &[0.0, 0.0, 1.0, 1.0]).unwrap();
    let m = lathe.to_mesh(&LatheOptions::new(8, 4).with_uvs(UvMode::SplitSeams)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.num_vertices(), 2 + 9 * 3);
    assert_eq!(m.uvs[0], DVec2::new(0.5, 0.0));
    assert_eq!(m.uvs[1], DVec2::new(0.0, 0.25));
    assert_eq!(m.uvs[9], DVec2::new(1.0, 0.25));
    assert_eq!(m.positions[1], m.positions[9]);
}

#[test]
fn bad_inputs_are_errors() {
    use SurfaceError as E;
    let flat = |u: f64, v: f64| DVec3::new(u, v, 0.0);
    assert!(matches!(mesh_surface(flat, &SurfaceOptions::new(3, 0)), Err(E::TooFewQuads { direction: 'v', .. })));
    assert!(matches!(
        mesh_surface(flat, &SurfaceOptions::new(2, 5).with_wrap(true, false)),
        Err(E::TooFewQuads { direction: 'u', needed: 3, given: 2 })
    ));
    assert!(matches!(mesh_surface(|_, _| DVec3::NAN, &SurfaceOptions::new(3, 3)), Err(E::NonFiniteSample { .. })));
    assert!(matches!(
        mesh_surface(flat, &SurfaceOptions::new(3, 3).with_pole_tolerance(-1.0)),
        Err(E::BadPoleTolerance { .. })
    ));
    assert!(matches!(mesh_surface(flat, &SurfaceOptions::new(usize::MAX, usize::MAX)), Err(E::TooLarge { .. })));

    let p = half_circle(4);
    let ok = RevolveOptions::DEFAULT;
    assert_eq!(revolve_z(&p[..1], None, &ok), Err(E::InsufficientPoints { needed: 2, given: 1 }));
    assert_eq!(revolve_z(&[], None, &ok), Err(E::InsufficientPoints { needed: 2, given: 0 }));
    let mut nan = p.clone();
    nan[2].y = f64::NAN;
    assert_eq!(revolve_z(&nan, None, &ok), Err(E::NonFiniteInput { what: "profile point", index: 2 }));
    assert_eq!(revolve_z(&p, Some(&p[..3]), &ok), Err(E::NormalCount { points: 5, normals: 3 }));
    let mut bad_normals = p.clone();
    bad_normals[1] = DVec2::INFINITY;
    assert_eq!(revolve_z(&p, Some(&bad_normals), &ok), Err(E::NonFiniteInput { what: "profile normal", index: 1 }));
    assert_eq!(
        revolve_z(&[DVec2::new(1.0, 0.0), DVec2::new(-0.5, 1.0)], None, &ok),
        Err(E::NegativeRadius { index: 1, value: -0.5 })
    );
    for t in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(revolve_z(&p, None, &RevolveOptions::new(1.0, t)), Err(E::BadSliceTolerance { .. })));
    }
    assert!(matches!(revolve_z(&p, None, &RevolveOptions::new(1.0, 1e-12)), Err(E::TooLarge { .. })));
    for s in [0.0, -2.0, f64::NAN] {
        assert!(matches!(revolve_z(&p, None, &RevolveOptions::new(s, 0.1)), Err(E::BadScale { .. })));
    }
    assert_eq!(revolve_z(&[DVec2::ONE, DVec2::ONE], None, &ok), Err(E::Degenerate));
    assert_eq!(revolve_z(&[DVec2::ZERO, DVec2::Y], None, &ok), Err(E::Degenerate), "all on the axis");

    assert!(matches!(Lathe::new(&[0.0, 1.0, 0.0], &[0.0, 0.0, 1.0, 1.0]), Err(E::Keys { curve: "radius", .. })));
    assert!(matches!(Lathe::new(&[0.0, 1.0, 1.0, 0.0], &[0.0, 1.0]), Err(E::Keys { curve: "height", .. })));
    assert!(matches!(Lathe::new(&[0.0, f64::NAN, 1.0, 0.0], &[0.0, 0.0, 1.0, 1.0]), Err(E::Keys { .. })));
    assert_eq!(
        Lathe::new(&[0.0, -1.0, 1.0, 0.0], &[0.0, 0.0, 1.0, 1.0]),
        Err(E::NegativeRadius { index: 1, value: -1.0 })
    );
    let lathe = Lathe::new(&[0.0, 1.0, 1.0, 0.0], &[0.0, 0.0, 1.0, 1.0]).unwrap();
    assert!(matches!(lathe.to_mesh(&LatheOptions::new(0, 4)), Err(E::TooFewQuads { direction: 'u', .. })));
    assert!(matches!(lathe.to_mesh(&LatheOptions::new(2, 4)), Err(E::TooFewQuads { direction: 'u', .. })));
    assert!(matches!(lathe.to_mesh(&LatheOptions::new(8, 0)), Err(E::TooFewQuads { direction: 'v', .. })));
    let flat_lathe = Lathe::new(&[0.0; 4], &[0.0, 0.0, 1.0, 1.0]).unwrap();
    assert_eq!(flat_lathe.to_mesh(&LatheOptions::DEFAULT), Err(E::Degenerate));
    // messages are lowercase with no trailing period
    let msg = E::NegativeRadius { index: 1, value: -0.5 }.to_string();
    assert!(msg.starts_with("profile point") && !msg.ends_with('.'));
}

/// A profile from the south to the north pole through random radii at increasing angles:
/// star-shaped about the origin, so it bounds a solid of revolution.
fn star_profile() -> impl Strategy<Value = Vec<DVec2>> {
    prop::collection::vec(0.3f64..3.0, 1..12).prop_map(|radii| {
        let n = radii.len() + 1;
        let mut pts = vec![DVec2::new(0.0, -1.0)];
        for (k, r) in radii.iter().enumerate() {
            let a = PI * ((k + 1) as f64 / n as f64 - 0.5);
            pts.push(DVec2::new(a.cos(), a.sin()) * *r);
        }
        pts.push(DVec2::new(0.0, 1.5));
        pts
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn revolved_star_profiles_are_closed_and_outward(
        profile in star_profile(),
        slice_tolerance in 0.05f64..2.0,
        reverse in any::<bool>(),
    ) {
        let profile: Vec<DVec2> = if reverse { profile.into_iter().rev().collect() } else { profile };
        let o = RevolveOptions::new(1.0, slice_tolerance);
        let slices = o.num_slices().unwrap();
        let m = revolve_z(&profile, None, &o).unwrap();
        check_structure(&m, "star");
        prop_assert!(m.is_closed_oriented());
        prop_assert_eq!(euler(&m), 2);
        prop_assert_eq!(m.num_vertices(), 2 + slices * (profile.len() - 2));
        prop_assert!(m.signed_volume() > 0.0);
    }
}

#[test]
fn sweeps_too_large_for_32_bit_indices_are_refused_before_any_allocation() {
    use splinekit::frame::Frame;
    use splinekit::sweep::{MeshLayout, Profile, SweepError, SweepOptions, SweepPath, generalized_cylinder, revolve};
    let options = SweepOptions { layout: MeshLayout::Compat, uvs: false, caps: false, ..SweepOptions::default() };
    // 3 points × (2³¹ + 1) copies (one more with UVs is counted): past u32::MAX
    let profile = Profile {
        points: vec![DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(1.0, 2.0)],
        normals: vec![DVec2::X; 3],
    };
    match revolve(&profile, 1 << 31, options) {
        Err(SweepError::TooLarge { vertices }) => assert_eq!(vertices, 3.0 * ((1u64 << 31) + 1) as f64),
        other => panic!("{other:?}"),
    }
    // a 65536-point profile along 65536 points: (65536 + 2 caps) × 65536 > u32::MAX
    let n = 1 << 16;
    let ring = Profile {
        points: (0..n).map(|i| DVec2::from_angle(TAU * i as f64 / n as f64)).collect(),
        normals: (0..n).map(|i| DVec2::from_angle(TAU * i as f64 / n as f64)).collect(),
    };
    let frame = Frame { t: DVec3::Z, n: DVec3::X, b: DVec3::Y };
    let path = SweepPath {
        positions: (0..n).map(|k| DVec3::new(0.0, 0.0, k as f64)).collect(),
        frames: vec![frame; n],
        scales: Vec::new(),
    };
    match generalized_cylinder(&ring, &path, options) {
        Err(SweepError::TooLarge { vertices }) => assert_eq!(vertices, (65536.0 + 2.0) * 65536.0),
        other => panic!("{other:?}"),
    }
}

/// Checks a triangulation of the simple polygon `ring`: n − 2 triangles, each turning as the
/// polygon does, together covering its area, every corner used.
fn check_triangulation(ring: &[DVec2], tris: &[[usize; 3]]) {
    let n = ring.len();
    assert_eq!(tris.len(), n - 2);
    let area: f64 = (0..n).map(|i| ring[i].perp_dot(ring[(i + 1) % n])).sum::<f64>() / 2.0;
    let mut sum = 0.0;
    let mut used = vec![false; n];
    for t in tris {
        let a = (ring[t[1]] - ring[t[0]]).perp_dot(ring[t[2]] - ring[t[0]]) / 2.0;
        assert!(a * area.signum() > 0.0, "triangle {t:?} turns the other way or is flat: {a}");
        sum += a;
        for &v in t {
            used[v] = true;
        }
    }
    assert!((sum - area).abs() <= 1e-9 * area.abs(), "{sum} vs {area}");
    assert!(used.iter().all(|&u| u));
}

/// #38: caps are triangulated by ear clipping in about n·r tests for n points of which r are
/// reflex (it started over after each ear and tested every point: minutes for a cap of 20 000
/// points); here a star and a comb of 20 000 points each, both orientations.
#[test]
fn large_caps_triangulate_completely() {
    use splinekit::sweep::triangulate_polygon;
    let n = 20_000;
    let star: Vec<DVec2> = (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            DVec2::from_angle(t) * if i % 2 == 0 { 1.0 } else { 0.6 }
        })
        .collect();
    // a comb: teeth along the bottom, a straight back on top
    let teeth = n / 2 - 1;
    let mut comb: Vec<DVec2> =
        (0..2 * teeth).map(|i| DVec2::new(i as f64, if i % 2 == 0 { 0.0 } else { -10.0 })).collect();
    comb.extend([DVec2::new(2.0 * teeth as f64, 5.0), DVec2::new(-1.0, 5.0)]);
    for ring in [star, comb] {
        check_triangulation(&ring, &triangulate_polygon(&ring));
        let reversed: Vec<DVec2> = ring.iter().rev().copied().collect();
        check_triangulation(&reversed, &triangulate_polygon(&reversed));
    }
}
