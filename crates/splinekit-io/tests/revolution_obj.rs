//! Rebuilding the surfaces of spline-annotated OBJ files from their headers
//! ([`SplineHeader::rebuild`]).
//!
//! - Every annotated OBJ of the test data is rebuilt and compared with the mesh stored after
//!   its header, read by a small independent OBJ reader: the compat layout must give the same
//!   counts, the same triangles index for index, and the same positions and normals up to the
//!   files' six decimals of `f32` arithmetic.
//! - No file of the revolution tool survives, so revolution rebuilds are checked against an
//!   independent re-implementation of the tool's tessellation (the spline windows of SPEC §1.1
//!   and the recursive control-polygon-angle split of SPEC §1.3), and written, read back and
//!   rebuilt again byte for byte.

use std::collections::HashSet;
use std::f64::consts::TAU;
use std::fs;
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use splinekit::TriMesh;
use splinekit::sweep::MeshLayout;
use splinekit_io::mesh::{
    RebuildError, RebuildOptions, RevolutionHeader, SplineHeader, save_revolution_obj, write_revolution_obj,
};

/// Largest position difference allowed against a stored mesh: the files keep six decimals
/// (±5e-7) of `f32` arithmetic (a few ulps of 1 on top).
const STORED_POSITION: f64 = 5e-6;
/// Largest normal difference allowed against a stored mesh: `f32` normals of short
/// control-polygon edges, rounded to six decimals.
const STORED_NORMAL: f64 = 5e-4;
/// Values computed the same way twice, or exact by construction, up to rounding.
const EXACT: f64 = 1e-12;

fn compat() -> RebuildOptions {
    RebuildOptions::DEFAULT.with_layout(MeshLayout::Compat)
}

/// The bundled spline-annotated OBJ files (copies of the shared data, see their SOURCES.md).
fn annotated_objs() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/obj/cs4620-splines");
    let mut files: Vec<PathBuf> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj")))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "expected the four bundled files in {}", dir.display());
    files
}

/// The mesh of an OBJ file as stored: `v`, `vn`, and `f a/a/a` triangles (the tools' files
/// number positions, UVs and normals alike), 0-based. A reader independent of the crate's.
struct Stored {
    positions: Vec<DVec3>,
    normals: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

fn read_stored(path: &Path) -> Stored {
    let text = fs::read_to_string(path).unwrap();
    let mut m = Stored { positions: Vec::new(), normals: Vec::new(), triangles: Vec::new() };
    let vec3 = |w: &[&str]| DVec3::new(w[1].parse().unwrap(), w[2].parse().unwrap(), w[3].parse().unwrap());
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first() {
            Some(&"v") => m.positions.push(vec3(&w)),
            Some(&"vn") => m.normals.push(vec3(&w)),
            Some(&"f") => {
                assert_eq!(w.len(), 4, "{}: not a triangle: {line}", path.display());
                let corner = |c: &str| {
                    let ids: Vec<u32> = c.split('/').map(|i| i.parse().unwrap()).collect();
                    assert!(ids.iter().all(|&i| i == ids[0]), "{}: {line}", path.display());
                    ids[0] - 1
                };
                m.triangles.push([corner(w[1]), corner(w[2]), corner(w[3])]);
            }
            _ => {}
        }
    }
    m
}

fn rebuild_file(path: &Path, options: &RebuildOptions) -> TriMesh {
    let header = SplineHeader::read(path).unwrap().unwrap_or_else(|| panic!("{}: no header", path.display()));
    header.rebuild(options).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn rebuilt_sweeps_reproduce_the_stored_meshes() {
    for path in annotated_objs() {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let stored = read_stored(&path);
        let mesh = rebuild_file(&path, &compat());
        mesh.validate().unwrap();
        assert_eq!(
            (mesh.num_vertices(), mesh.num_triangles()),
            (stored.positions.len(), stored.triangles.len()),
            "{name}: (vertices, triangles)"
        );
        assert!(mesh.triangles == stored.triangles, "{name}: triangles differ");
        let position_error = mesh
            .positions
            .iter()
            .zip(&stored.positions)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0, f64::max);
        assert!(position_error <= STORED_POSITION, "{name}: positions differ by up to {position_error:e}");
        // normals agree with the stored ones up to one global sign (the tool's normals of an open
        // cross-section point inward, against its own triangles; the rebuild's follow the faces)
        let sign = if mesh.normals.iter().zip(&stored.normals).map(|(a, b)| a.dot(*b)).sum::<f64>() < 0.0 {
            -1.0
        } else {
            1.0
        };
        let normal_error = mesh
            .normals
            .iter()
            .zip(&stored.normals)
            .map(|(a, b)| (*a - *b * sign).abs().max_element())
            .fold(0.0, f64::max);
        assert!(normal_error <= STORED_NORMAL, "{name}: normals differ by up to {normal_error:e}");
        let faces_agree: f64 = (0..mesh.num_triangles())
            .map(|i| mesh.triangles[i].iter().map(|&v| mesh.face_normal(i).dot(mesh.normals[v as usize])).sum::<f64>())
            .sum();
        assert!(faces_agree > 0.0, "{name}: normals against the triangles");
        eprintln!(
            "{name}: {} vertices, {} triangles, position error {position_error:.2e}, normal error {normal_error:.2e}, normal sign {sign}",
            mesh.num_vertices(),
            mesh.num_triangles()
        );
    }
}

#[test]
fn welded_sweeps_keep_the_samples_and_share_the_seams() {
    for path in annotated_objs() {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let Some(SplineHeader::Sweep(h)) = SplineHeader::read(&path).unwrap() else { panic!("{name}") };
        let c = rebuild_file(&path, &compat());
        let w = rebuild_file(&path, &RebuildOptions::DEFAULT);
        w.validate().unwrap();
        // every compat vertex is a welded vertex, bit for bit (same samples, same arithmetic)
        let welded: HashSet<[u64; 3]> = w.positions.iter().map(|p| p.to_array().map(f64::to_bits)).collect();
        assert!(c.positions.iter().all(|p| welded.contains(&p.to_array().map(f64::to_bits))), "{name}");
        // compat: rings of P samples, the first triangle is (0, P, 1); welded drops the seam
        // copy of a closed curve and reaches the end point of an open one
        let p = c.triangles[0][1] as usize;
        let s = c.num_vertices() / p;
        assert_eq!(c.triangles[0], [0, p as u32, 1], "{name}");
        let welded_len = |closed: bool, compat_len: usize| if closed { compat_len - 1 } else { compat_len + 1 };
        let quads = |closed: bool, len: usize| if closed { len } else { len - 1 };
        let (pw, sw) = (welded_len(h.cross_section.closed, p), welded_len(h.swept_along.closed, s));
        assert_eq!(w.num_vertices(), pw * sw, "{name}: vertices");
        let quads = quads(h.cross_section.closed, pw) * quads(h.swept_along.closed, sw);
        assert_eq!(w.num_triangles(), 2 * quads, "{name}: triangles");
        // both curves closed: a closed, consistently oriented surface (a torus by its indices)
        let closed_both = h.cross_section.closed && h.swept_along.closed;
        assert_eq!(w.is_closed_oriented(), closed_both, "{name}");
        if !closed_both {
            // open cross-section: two boundary loops, one per end of the cross-section
            assert_eq!(w.boundary_edges().len(), 2 * quads / (pw - 1), "{name}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// Revolution headers

/// The revolution tool's tessellation, re-implemented from SPEC §1.1 and §1.3 (not with the
/// crate's curves): spline windows to Bézier segments, each halved at `t = ½` while an angle
/// of its control polygon exceeds `epsilon / 2`; the start of every piece, then the end of
/// the curve if it is open.
fn reference_profile(h: &RevolutionHeader) -> Vec<DVec2> {
    let p = &h.control_points;
    let n = p.len();
    let windows = if h.closed { n } else { n - 3 };
    let mut out = Vec::new();
    let mut last = DVec2::ZERO;
    for k in 0..windows {
        let [p0, p1, p2, p3] = [0, 1, 2, 3].map(|i| p[(k + i) % n]);
        let bezier = if h.is_bspline {
            [
                (p0 + 4.0 * p1 + p2) / 6.0,
                (4.0 * p1 + 2.0 * p2) / 6.0,
                (2.0 * p1 + 4.0 * p2) / 6.0,
                (p1 + 4.0 * p2 + p3) / 6.0,
            ]
        } else {
            [p1, p1 + (p2 - p0) / 6.0, p2 - (p3 - p1) / 6.0, p2]
        };
        split(bezier, h.epsilon / 2.0, 0, &mut out);
        last = bezier[3];
    }
    if !h.closed {
        out.push(last);
    }
    out
}

fn split(b: [DVec2; 4], limit: f64, depth: u32, out: &mut Vec<DVec2>) {
    let angle = |u: DVec2, v: DVec2| (u.dot(v) / (u.length() * v.length())).clamp(-1.0, 1.0).acos();
    let (d0, d1, d2) = (b[1] - b[0], b[2] - b[1], b[3] - b[2]);
    if depth < 10 && angle(d0, d1).max(angle(d1, d2)) > limit {
        let mid = |u: DVec2, v: DVec2| (u + v) / 2.0;
        let (p01, p12, p23) = (mid(b[0], b[1]), mid(b[1], b[2]), mid(b[2], b[3]));
        let (p012, p123) = (mid(p01, p12), mid(p12, p23));
        let p0123 = mid(p012, p123);
        split([b[0], p01, p012, p0123], limit, depth + 1, out);
        split([p0123, p123, p23, b[3]], limit, depth + 1, out);
    } else {
        out.push(b[0]);
    }
}

/// A vase: an open B-spline from near the axis at the bottom up to a rim, as the Java tool
/// writes it (see `mesh_io.rs`), and a closed Catmull-Rom ring off the axis.
fn revolution_headers() -> Vec<RevolutionHeader> {
    let pts = |p: &[[f64; 2]]| p.iter().map(|&q| DVec2::from(q)).collect::<Vec<_>>();
    vec![
        RevolutionHeader {
            closed: false,
            epsilon: 0.11220185,
            is_bspline: true,
            scale: 0.7943282,
            slice_tolerance: 0.25118864,
            control_points: pts(&[[0.1, -1.0], [0.6, -0.5], [0.4, 0.25], [0.7, 1.0], [1.0e-4, 1.0]]),
        },
        RevolutionHeader {
            closed: true,
            epsilon: 0.3,
            is_bspline: false,
            scale: 1.5,
            slice_tolerance: 0.1,
            control_points: pts(&[[1.0, 0.0], [1.5, -0.4], [2.0, 0.0], [1.8, 0.5], [1.2, 0.4]]),
        },
    ]
}

#[test]
fn revolutions_follow_the_reference_tessellation_and_slice_count() {
    for h in revolution_headers() {
        let what = format!("closed {} bspline {}", h.closed, h.is_bspline);
        let mesh = SplineHeader::Revolution(h.clone()).rebuild(&RebuildOptions::DEFAULT).unwrap();
        mesh.validate().unwrap();
        let profile = reference_profile(&h);
        let slices = (TAU / h.slice_tolerance).ceil() as usize;
        // rows of `slices` vertices, one per profile sample (no sample is on the axis here)
        assert_eq!(mesh.num_vertices(), profile.len() * slices, "{what}");
        for (j, p) in profile.iter().enumerate() {
            let v = mesh.positions[j * slices];
            let expected = DVec3::new(h.scale * p.x, 0.0, h.scale * p.y);
            assert!(v.distance(expected) < EXACT, "{what}: row {j}: {v} vs {expected}");
            // the row is the sample turned about +z in equal steps
            for i in 0..slices {
                let (sin, cos) = (TAU * i as f64 / slices as f64).sin_cos();
                let q = DVec3::new(expected.x * cos, expected.x * sin, expected.z);
                assert!(mesh.positions[j * slices + i].distance(q) < EXACT, "{what}: vertex ({j}, {i})");
            }
        }
        // quads between rows (an open profile has one row of quads fewer)
        let quad_rows = if h.closed { profile.len() } else { profile.len() - 1 };
        assert_eq!(mesh.num_triangles(), 2 * slices * quad_rows, "{what}");
        assert_eq!(mesh.is_closed_oriented(), h.closed, "{what}");
        if h.closed {
            assert!(mesh.signed_volume() > 0.0, "{what}: faces point out");
        }
    }
}

#[test]
fn revolution_write_read_rebuild_is_byte_identical() {
    for h in revolution_headers() {
        let mesh = h.rebuild(&RebuildOptions::DEFAULT).unwrap();
        let mut first = Vec::new();
        write_revolution_obj(&h, &mesh, &mut first).unwrap();
        let text = String::from_utf8(first.clone()).unwrap();
        let Some(SplineHeader::Revolution(back)) = SplineHeader::parse(&text, "vase.obj").unwrap() else {
            panic!("{text}")
        };
        assert_eq!(back, h);
        let again = SplineHeader::Revolution(back.clone()).rebuild(&RebuildOptions::DEFAULT).unwrap();
        let mut second = Vec::new();
        write_revolution_obj(&back, &again, &mut second).unwrap();
        assert!(first == second, "second write differs from the first");
        // and through a file
        let path = std::env::temp_dir().join(format!("splinekit-rebuild-{}-{}.obj", std::process::id(), h.closed));
        save_revolution_obj(&h, &mesh, &path).unwrap();
        let read = SplineHeader::read(&path).unwrap().unwrap();
        let _ = fs::remove_file(&path);
        assert_eq!(read.rebuild(&RebuildOptions::DEFAULT).unwrap(), mesh);
        // with UVs as well (split seam)
        let uv = h.rebuild(&RebuildOptions::DEFAULT.with_uvs(true)).unwrap();
        assert_eq!(uv.uvs.len(), uv.num_vertices());
        assert!(uv.num_vertices() > mesh.num_vertices());
    }
}

#[test]
fn sweep_rebuild_with_uvs() {
    for path in annotated_objs() {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let plain = rebuild_file(&path, &compat());
        for layout in [MeshLayout::Compat, MeshLayout::Welded] {
            let mesh = rebuild_file(&path, &RebuildOptions::DEFAULT.with_layout(layout).with_uvs(true));
            mesh.validate().unwrap();
            assert_eq!(mesh.uvs.len(), mesh.num_vertices(), "{name}");
            assert!(mesh.uvs.iter().all(|t| (0.0..=1.0).contains(&t.x) && (0.0..=1.0).contains(&t.y)), "{name}");
            if layout == MeshLayout::Compat {
                // the compat layout already has its seams twice: UVs add no vertex
                assert_eq!(mesh.positions, plain.positions, "{name}");
                assert_eq!(mesh.triangles, plain.triangles, "{name}");
            }
        }
    }
}

#[test]
fn rebuild_errors_name_the_spline() {
    let mut h = revolution_headers().remove(0);
    h.control_points.truncate(3);
    let e = h.rebuild(&RebuildOptions::DEFAULT).unwrap_err();
    assert_eq!(e.to_string(), "cross-section spline: b-spline needs at least 4 control points, got 3");
    assert!(matches!(e, RebuildError::Spline { spline: "cross-section", .. }));
    h.closed = true;
    assert!(h.rebuild(&RebuildOptions::DEFAULT).is_ok(), "3 points make a closed spline");
    h.control_points[1].x = -0.5;
    let e = h.rebuild(&RebuildOptions::DEFAULT).unwrap_err();
    assert!(e.to_string().starts_with("the cross-section crosses the axis of revolution"), "{e}");

    let text = fs::read_to_string(&annotated_objs()[0]).unwrap();
    let cut = text.replacen("# -0.0875 -0.0078125\n", "", 1).replacen("# 0.00625 -0.0859375\n", "", 1);
    let Some(header) = SplineHeader::parse(&cut, "cut.obj").unwrap() else { panic!() };
    let e = header.rebuild(&compat()).unwrap_err();
    assert_eq!(e.to_string(), "swept-along spline: b-spline needs at least 3 control points, got 2");
}

#[test]
fn the_triangle_limit_is_checked_before_the_rebuild() {
    // the closed revolution: 2 triangles per profile sample and slice, exactly
    let h = revolution_headers().remove(1);
    let slices = (TAU / h.slice_tolerance).ceil() as usize;
    let t = 2 * slices * reference_profile(&h).len();
    let header = SplineHeader::Revolution(h.clone());
    assert_eq!(header.rebuild(&RebuildOptions::DEFAULT.with_max_triangles(Some(t))).unwrap().num_triangles(), t);
    // (the check counts the closed profile's repeated end point: one row of quads more)
    let e = header.rebuild(&RebuildOptions::DEFAULT.with_max_triangles(Some(t - 1))).unwrap_err();
    let RebuildError::TooLarge { triangles, limit, .. } = e else { panic!("{e}") };
    assert!((triangles as usize) >= t && triangles as usize <= t + 2 * slices && limit == t - 1, "{triangles}");
    // a slice tolerance of 1e-7 rad: 62 831 854 slices, refused at once instead of filling memory
    let fine = SplineHeader::Revolution(RevolutionHeader { slice_tolerance: 1e-7, ..h });
    let e = fine.rebuild(&RebuildOptions::DEFAULT.with_max_triangles(Some(50_000_000))).unwrap_err();
    assert!(e.to_string().contains("62831854 slices of a"), "{e}");

    // a sweep-tool file: the compat mesh's own count is the one checked
    let doughnut = annotated_objs().into_iter().find(|p| p.ends_with("doughnut.obj")).unwrap();
    let stored = read_stored(&doughnut).triangles.len();
    assert!(rebuild_file(&doughnut, &compat().with_max_triangles(Some(stored))).num_triangles() == stored);
    let text = fs::read_to_string(&doughnut).unwrap();
    let Some(header) = SplineHeader::parse(&text, "doughnut.obj").unwrap() else { panic!() };
    let e = header.rebuild(&compat().with_max_triangles(Some(stored - 1))).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "the surface would have about {stored} triangles (a 81-point cross-section swept along 81 points), more than the limit of {}",
            stored - 1
        )
    );
}
