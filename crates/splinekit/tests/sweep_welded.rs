//! The welded layout of generalized cylinders: walls, creases, joints and caps share their
//! vertices, so a closed profile swept along a closed path, or capped, is one closed,
//! consistently oriented 2-manifold — checked on the polygon mesh as files get it, by
//! topology (no vertices merged by position). Joints at path corners: L, U and zig-zag paths,
//! open and closed, with square and circle profiles, for every join; the mitred sweep of a
//! profile centred on the path has the volume `area × centre-line length` (a prism cut by
//! planes through its axis keeps that volume), and the bevel and round ones lie between the
//! mitre's and the walls' volumes.

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};
use splinekit::frame::{self, CurveSample, FrameMethod, FrameOptions, Side};
use splinekit::mesh::{PolyMesh, TopologyReport};
use splinekit::sweep::{
    Join, Profile, SweepOptions, SweepPath, generalized_cylinder, generalized_cylinder_counts,
    generalized_cylinder_poly,
};

/// A closed polygon profile with its corners sampled twice (a crease: one normal per side),
/// counter-clockwise, centred on the origin.
fn polygon(corners: &[DVec2]) -> Profile {
    let n = corners.len();
    let mut profile = Profile::default();
    for i in 0..n {
        let (a, b) = (corners[i], corners[(i + 1) % n]);
        let d = (b - a).normalize();
        let normal = DVec2::new(d.y, -d.x);
        profile.points.extend([a, b]);
        profile.normals.extend([normal, normal]);
    }
    // closed: the last point is the first
    profile
}

fn square(half: f64) -> Profile {
    polygon(&[DVec2::new(-half, -half), DVec2::new(half, -half), DVec2::new(half, half), DVec2::new(-half, half)])
}

/// A smooth closed circle profile of `n` segments (last point = first).
fn circle(radius: f64, n: usize) -> Profile {
    let mut profile = Profile::default();
    for i in 0..=n {
        let a = TAU * (i % n) as f64 / n as f64;
        let d = DVec2::new(a.cos(), a.sin());
        profile.points.push(d * radius);
        profile.normals.push(d);
    }
    profile
}

/// A polyline path through `corners`, `per_edge` samples an edge, every inner corner sampled
/// twice (incoming, then outgoing tangent) as the SWP sampler does; closed: back to the first
/// corner, whose two samples are the path's first (outgoing) and last (incoming).
fn polyline(corners: &[DVec3], per_edge: usize, closed: bool) -> Vec<CurveSample> {
    let mut pts = corners.to_vec();
    if closed {
        pts.push(corners[0]);
    }
    let edges = pts.len() - 1;
    let mut samples = Vec::new();
    for e in 0..edges {
        let (a, b) = (pts[e], pts[e + 1]);
        let t = (b - a).normalize();
        for j in 0..per_edge {
            let s = j as f64 / per_edge as f64;
            // the corner at `a` from this edge's side (outgoing)
            samples.push(CurveSample::new(e as f64 + s, a.lerp(b, s), t));
        }
        // the corner at `b` from this edge's side (incoming)
        samples.push(CurveSample::new(e as f64 + 1.0, b, t));
    }
    samples
}

fn path_of(samples: &[CurveSample]) -> SweepPath {
    let options = FrameOptions::DEFAULT.with_method(FrameMethod::Sequential(Side::Left));
    SweepPath {
        positions: samples.iter().map(|s| s.position).collect(),
        frames: frame::frames_for_samples(samples, &options),
        scales: Vec::new(),
    }
}

fn length(corners: &[DVec3], closed: bool) -> f64 {
    let mut l: f64 = corners.windows(2).map(|w| w[0].distance(w[1])).sum();
    if closed {
        l += corners[corners.len() - 1].distance(corners[0]);
    }
    l
}

fn signed_volume(mesh: &PolyMesh) -> f64 {
    mesh.to_tri_mesh().signed_volume()
}

/// One closed, consistently oriented 2-manifold without degenerate faces, whose
/// face-varying normals agree with its faces, and no two faces across an edge turned by
/// more than `max_turn` (radians: the sharpest corner of the path or the profile) and a
/// little (0.2 rad: the twist a 3D corner leaves to the next step); a fold turns by nearly π.
fn assert_solid(mesh: &PolyMesh, max_turn: f64, what: &str) {
    let report = TopologyReport::new(mesh, 0.0);
    assert!(report.is_clean(), "{what}: {report}");
    assert!(report.is_closed(), "{what}: {} boundary edges", report.num_boundary_edges);
    assert_eq!(report.components.len(), 1, "{what}: components");
    assert!(report.is_manifold() && report.is_consistently_oriented(), "{what}: {report}");
    assert_eq!(report.genus(), Some(report.genus().unwrap_or(0)), "{what}");
    assert!(signed_volume(mesh) > 0.0, "{what}: volume {}", signed_volume(mesh));
    let tri = mesh.to_tri_mesh();
    let normals = mesh.normals.as_ref().expect("normals");
    for (f, t) in tri.triangles.iter().enumerate() {
        let face = tri.face_normal(f).normalize();
        for c in 0..3 {
            let n = normals.values[normals.indices[3 * f + c] as usize];
            assert!(face.dot(n) > 0.0, "{what}: face {f} {t:?} against its corner {c}'s normal {n} (face {face})");
        }
    }
    // a fold-over: two faces across an edge facing (nearly) opposite ways
    let mut by_edge = std::collections::HashMap::new();
    for (f, t) in tri.triangles.iter().enumerate() {
        for c in 0..3 {
            let (a, b) = (t[c], t[(c + 1) % 3]);
            by_edge.entry((a.min(b), a.max(b))).or_insert_with(Vec::new).push(f);
        }
    }
    for (edge, faces) in by_edge {
        if let [f, g] = faces[..] {
            let (nf, ng) = (tri.face_normal(f).normalize(), tri.face_normal(g).normalize());
            assert!(nf.dot(ng) > (max_turn + 0.2).cos(), "{what}: faces {f} and {g} fold over edge {edge:?}");
        }
    }
}

fn joins() -> [(Join, &'static str); 3] {
    [(Join::Mitre, "mitre"), (Join::Round, "round"), (Join::Bevel, "bevel")]
}

fn options(join: Join) -> SweepOptions {
    SweepOptions { join, ..SweepOptions::default() }
}

#[test]
fn straight_capped_tubes_are_one_closed_solid() {
    let samples = polyline(&[DVec3::ZERO, DVec3::new(0.0, 0.0, 3.0)], 4, false);
    let path = path_of(&samples);
    for (profile, name, area) in
        [(square(0.5), "square", 1.0), (circle(1.0, 24), "circle", 0.5 * 24.0 * (TAU / 24.0).sin())]
    {
        let swept = generalized_cylinder_poly(&profile, &path, SweepOptions::default()).unwrap();
        assert_solid(&swept.mesh, PI / 2.0, name);
        assert!(swept.unfit_corners.is_empty());
        let v = signed_volume(&swept.mesh);
        assert!((v - 3.0 * area).abs() < 1e-12, "{name}: volume {v} against {}", 3.0 * area);
        // the counts say what the file has
        let counts = generalized_cylinder_counts(&profile, &path, SweepOptions::default()).unwrap();
        assert_eq!(
            (counts.vertices, counts.triangles),
            (swept.mesh.num_vertices() as u64, swept.mesh.num_faces() as u64),
            "{name}"
        );
    }
    // a square tube: 4 corners × 5 rings, and no vertex for the caps of their own
    let swept = generalized_cylinder_poly(&square(0.5), &path, SweepOptions::default()).unwrap();
    assert_eq!(swept.mesh.num_vertices(), 20);
    // the split mesh for drawing keeps a vertex per side of each sharp edge
    let split = generalized_cylinder(&square(0.5), &path, SweepOptions::default()).unwrap();
    assert!(split.num_vertices() > 20);
    assert_eq!(split.num_triangles(), swept.mesh.num_faces());
}

#[test]
fn joints_on_l_u_and_zigzag_paths_are_solid() {
    let l = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(4.0, 3.0, 0.0)];
    let u = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(4.0, 3.0, 0.0), DVec3::new(0.0, 3.0, 0.0)];
    let zigzag = [
        DVec3::ZERO,
        DVec3::new(3.0, 2.0, 0.0),
        DVec3::new(6.0, 0.0, 0.0),
        DVec3::new(9.0, 2.0, 0.0),
        DVec3::new(12.0, 0.0, 0.5),
    ];
    // a square loop and a 3D zig-zag loop (corners out of one plane)
    let square_loop = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(4.0, 4.0, 0.0), DVec3::new(0.0, 4.0, 0.0)];
    let bent_loop = [DVec3::ZERO, DVec3::new(4.0, 0.0, 1.0), DVec3::new(5.0, 4.0, 0.0), DVec3::new(1.0, 5.0, 1.0)];
    let paths: [(&[DVec3], bool, &str); 5] = [
        (&l, false, "L"),
        (&u, false, "U"),
        (&zigzag, false, "zig-zag"),
        (&square_loop, true, "square loop"),
        (&bent_loop, true, "bent loop"),
    ];
    for (corners, closed, path_name) in paths {
        // the square profile's own creases turn by π/2
        let max_turn = sharpest_turn(corners, closed).max(PI / 2.0);
        let path = path_of(&polyline(corners, 3, closed));
        let centre_line = length(corners, closed);
        for (profile, profile_name) in [(square(0.4), "square"), (circle(0.5, 16), "circle")] {
            let area = signed_area(&profile);
            let mut volumes = Vec::new();
            for (join, join_name) in joins() {
                let what = format!("{profile_name} along {path_name}, {join_name}");
                let swept = generalized_cylinder_poly(&profile, &path, options(join)).unwrap();
                assert!(swept.unfit_corners.is_empty(), "{what}: {:?}", swept.unfit_corners);
                assert_solid(&swept.mesh, max_turn, &what);
                let counts = generalized_cylinder_counts(&profile, &path, options(join)).unwrap();
                assert_eq!(counts.vertices, swept.mesh.num_vertices() as u64, "{what}");
                volumes.push(signed_volume(&swept.mesh));
            }
            let (mitre, round, bevel) = (volumes[0], volumes[1], volumes[2]);
            let what = format!("{profile_name} along {path_name}");
            // a prism cut by planes through its axis: the profile's area times the axis length
            // (in the plane; a corner out of the plane is not cut symmetrically)
            if corners.iter().all(|c| c.z == 0.0) {
                let exact = area * centre_line;
                assert!((mitre - exact).abs() < 1e-9 * exact, "{what}: mitre {mitre} against {exact}");
            }
            assert!(bevel < round && round < mitre, "{what}: bevel {bevel} < round {round} < mitre {mitre}");
        }
    }
}

/// The largest angle between consecutive edges of a polyline.
fn sharpest_turn(corners: &[DVec3], closed: bool) -> f64 {
    let n = corners.len();
    let edges: Vec<DVec3> =
        (0..if closed { n } else { n - 1 }).map(|i| (corners[(i + 1) % n] - corners[i]).normalize()).collect();
    let pairs = if closed { edges.len() } else { edges.len() - 1 };
    (0..pairs).map(|i| edges[i].angle_between(edges[(i + 1) % edges.len()])).fold(0.0, f64::max)
}

fn signed_area(profile: &Profile) -> f64 {
    let p = &profile.points;
    0.5 * (0..p.len()).map(|i| p[i].perp_dot(p[(i + 1) % p.len()])).sum::<f64>()
}

#[test]
fn a_sharp_corner_past_the_mitre_limit_is_bevelled() {
    // a turn of 160°: mitre ratio 1/cos(80°) ≈ 5.8 > 4
    let a = 160f64.to_radians();
    let corners = [DVec3::ZERO, DVec3::new(5.0, 0.0, 0.0), DVec3::new(5.0 + 5.0 * a.cos(), 5.0 * a.sin(), 0.0)];
    let path = path_of(&polyline(&corners, 3, false));
    let profile = square(0.3);
    let mitre = generalized_cylinder_poly(&profile, &path, options(Join::Mitre)).unwrap();
    let bevel = generalized_cylinder_poly(&profile, &path, options(Join::Bevel)).unwrap();
    assert_eq!(mitre, bevel);
    let long = SweepOptions { mitre_limit: 10.0, ..options(Join::Mitre) };
    let mitred = generalized_cylinder_poly(&profile, &path, long).unwrap();
    assert_solid(&mitred.mesh, a, "mitre limit 10");
    assert!(signed_volume(&mitred.mesh) > signed_volume(&bevel.mesh));
}

#[test]
fn a_profile_wider_than_the_turn_is_reported() {
    // a U of width 0.5 swept with a square of side 2: the inner cut runs past the U's bottom
    let corners = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(4.0, 0.5, 0.0), DVec3::new(0.0, 0.5, 0.0)];
    let path = path_of(&polyline(&corners, 3, false));
    let swept = generalized_cylinder_poly(&square(1.0), &path, SweepOptions::default()).unwrap();
    assert!(!swept.unfit_corners.is_empty());
    assert!(swept.unfit_corners.iter().all(|c| (c.angle - PI / 2.0).abs() < 1e-9));
}

#[test]
fn smooth_closed_sweeps_and_uvs_share_their_seams() {
    // a circle swept round a circle: a torus, one closed manifold of genus 1, with and
    // without UVs (the UV seam is face-varying, not a second vertex)
    let n = 48;
    let samples: Vec<CurveSample> = (0..=n)
        .map(|i| {
            let a = TAU * i as f64 / n as f64;
            CurveSample::new(a, DVec3::new(3.0 * a.cos(), 3.0 * a.sin(), 0.0), DVec3::new(-a.sin(), a.cos(), 0.0))
        })
        .collect();
    let path = path_of(&samples);
    for uvs in [false, true] {
        for profile in [circle(0.5, 12), square(0.5)] {
            let swept =
                generalized_cylinder_poly(&profile, &path, SweepOptions { uvs, ..SweepOptions::default() }).unwrap();
            let report = TopologyReport::new(&swept.mesh, 0.0);
            assert!(report.is_clean() && report.is_closed(), "{report}");
            assert_eq!((report.components.len(), report.genus()), (1, Some(1)));
            assert!(signed_volume(&swept.mesh) > 0.0);
            assert_eq!(swept.mesh.uvs.is_some(), uvs);
        }
    }
}

mod random {
    //! Random polygon profiles (with creases) along random 3D polylines, open and closed, with
    //! each join: one closed, consistently oriented 2-manifold whenever no corner is reported
    //! as too tight for the profile.
    use super::*;
    use proptest::prelude::*;

    fn profile() -> impl Strategy<Value = Profile> {
        (3usize..7, 0.05f64..0.3, any::<bool>()).prop_map(|(n, r, creased)| {
            if creased {
                let corners: Vec<DVec2> = (0..n)
                    .map(|i| {
                        let a = TAU * i as f64 / n as f64;
                        DVec2::new(a.cos(), a.sin()) * r
                    })
                    .collect();
                polygon(&corners)
            } else {
                circle(r, 4 * n)
            }
        })
    }

    fn corners() -> impl Strategy<Value = Vec<DVec3>> {
        prop::collection::vec((-3.0f64..3.0, -3.0f64..3.0, -1.0f64..1.0), 3..6)
            .prop_map(|v| v.into_iter().map(|(x, y, z)| DVec3::new(x, y, z)).collect())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn welded_sweeps_are_closed_manifolds(
            profile in profile(),
            corners in corners(),
            closed in any::<bool>(),
            join in 0usize..3,
            per_edge in 1usize..4,
        ) {
            let samples = polyline(&corners, per_edge, closed);
            // edges of some length, corners that turn (not back on themselves)
            let n = corners.len();
            let edges: Vec<DVec3> = (0..if closed { n } else { n - 1 }).map(|i| corners[(i + 1) % n] - corners[i]).collect();
            prop_assume!(edges.iter().all(|e| e.length() > 0.5));
            let pairs = if closed { edges.len() } else { edges.len() - 1 };
            prop_assume!((0..pairs).all(|i| {
                let a = edges[i].angle_between(edges[(i + 1) % edges.len()]);
                a > 0.05 && a < 2.5
            }));
            let path = path_of(&samples);
            let options = SweepOptions { join: joins()[join].0, ..SweepOptions::default() };
            let swept = generalized_cylinder_poly(&profile, &path, options).unwrap();
            prop_assume!(swept.unfit_corners.is_empty());
            let report = TopologyReport::new(&swept.mesh, 0.0);
            prop_assert!(report.is_closed() && report.is_manifold() && report.is_consistently_oriented(), "{}", report);
            prop_assert_eq!(report.components.len(), 1);
            prop_assert!(report.nonmanifold.is_empty() && report.degenerate_faces.is_empty(), "{}", report);
            let counts = generalized_cylinder_counts(&profile, &path, options).unwrap();
            prop_assert_eq!(counts.vertices, swept.mesh.num_vertices() as u64);
            prop_assert_eq!(counts.triangles, swept.mesh.num_faces() as u64);
        }
    }
}
