//! The counting functions of the sweeps (`revolve_counts`, `generalized_cylinder_counts`,
//! `revolve_z_counts`, `Lathe::counts`) give the counts of the mesh the builder makes (the
//! file's polygon mesh for the first two), on
//! random profiles and paths with the cases that change them: points on the axis, repeated
//! points (creases), closed loops, one step, UVs, caps and both layouts.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use splinekit::TriMesh;
use splinekit::frame::Frame;
use splinekit::mesh::PolyMesh;
use splinekit::sweep::surface::{Lathe, LatheOptions, RevolveOptions, UvMode, revolve_z, revolve_z_counts};
use splinekit::sweep::{
    MeshCounts, MeshLayout, Profile, SweepOptions, SweepPath, generalized_cylinder_counts, generalized_cylinder_poly,
    revolve_counts, revolve_poly,
};

/// The counts of a file's mesh: its vertices and faces.
fn poly_counts(mesh: &PolyMesh) -> MeshCounts {
    MeshCounts { vertices: mesh.num_vertices() as u64, triangles: mesh.num_faces() as u64 }
}

fn counts_of(mesh: &TriMesh) -> MeshCounts {
    MeshCounts { vertices: mesh.num_vertices() as u64, triangles: mesh.num_triangles() as u64 }
}

/// A profile point: on the axis, or off it at a random place.
fn point() -> impl Strategy<Value = DVec2> {
    prop_oneof![
        1 => (-2.0f64..2.0).prop_map(|y| DVec2::new(0.0, y)),
        4 => (0.1f64..3.0, -2.0f64..2.0).prop_map(|(x, y)| DVec2::new(x, y)),
    ]
}

/// Profile points, some repeated (a crease sampled twice), maybe closed (last = first).
fn profile_points() -> impl Strategy<Value = Vec<DVec2>> {
    (prop::collection::vec((point(), prop::bool::weighted(0.2)), 2..9), any::<bool>()).prop_map(|(points, closed)| {
        let mut out = Vec::new();
        for (p, twice) in points {
            out.push(p);
            if twice {
                out.push(p);
            }
        }
        if closed {
            out.push(out[0]);
        }
        out
    })
}

/// A profile with unit normals: the right normal of each point's next segment, or a fixed
/// one (a closed profile's first and last normals then agree, and it wraps).
fn profile() -> impl Strategy<Value = Profile> {
    (profile_points(), any::<bool>()).prop_map(|(points, fixed)| {
        let normals = (0..points.len())
            .map(|i| {
                let d = points[(i + 1) % points.len()] - points[i];
                if fixed { DVec2::X } else { DVec2::new(d.y, -d.x).try_normalize().unwrap_or(DVec2::Y) }
            })
            .collect();
        Profile { points, normals }
    })
}

/// A path: a helix turn (open), or a circle whose last sample repeats the first (closed).
fn path() -> impl Strategy<Value = SweepPath> {
    (3usize..9, any::<bool>(), any::<bool>()).prop_map(|(n, closed, scaled)| {
        let at = |k: usize| {
            let a = TAU * k as f64 / (n - 1) as f64;
            let rise = if closed { 0.0 } else { k as f64 };
            (DVec3::new(2.0 * a.cos(), rise, 2.0 * a.sin()), DVec3::new(-a.sin(), 0.0, a.cos()))
        };
        let mut positions = Vec::new();
        let mut frames = Vec::new();
        for k in 0..n {
            let (p, t) = at(k);
            positions.push(p);
            frames.push(Frame { t, n: DVec3::Y, b: t.cross(DVec3::Y) });
        }
        if closed {
            positions[n - 1] = positions[0];
            frames[n - 1] = frames[0];
        }
        let scales = if scaled { (0..n).map(|k| DVec2::splat(1.0 + 0.1 * k as f64)).collect() } else { Vec::new() };
        SweepPath { positions, frames, scales }
    })
}

fn sweep_options() -> impl Strategy<Value = SweepOptions> {
    (any::<bool>(), any::<bool>(), any::<bool>()).prop_map(|(welded, uvs, caps)| SweepOptions {
        layout: if welded { MeshLayout::Welded } else { MeshLayout::Compat },
        uvs,
        caps,
        ..SweepOptions::default()
    })
}

fn uv_mode() -> impl Strategy<Value = UvMode> {
    prop_oneof![Just(UvMode::Omit), Just(UvMode::Auto), Just(UvMode::SplitSeams)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn revolve_counts_are_the_meshes(profile in profile(), steps in 1usize..7, options in sweep_options()) {
        let built = revolve_poly(&profile, steps, options).map(|m| poly_counts(&m));
        prop_assert_eq!(revolve_counts(&profile, steps, options), built);
    }

    #[test]
    fn cylinder_counts_are_the_meshes(profile in profile(), path in path(), options in sweep_options()) {
        let built = generalized_cylinder_poly(&profile, &path, options).map(|m| poly_counts(&m.mesh));
        prop_assert_eq!(generalized_cylinder_counts(&profile, &path, options), built);
    }

    #[test]
    fn revolve_z_counts_are_the_meshes(
        points in profile_points(),
        slice_tolerance in 0.3f64..2.5,
        uvs in uv_mode(),
        with_normals in any::<bool>(),
    ) {
        let normals: Vec<DVec2> = vec![DVec2::X; points.len()];
        let normals = with_normals.then_some(normals.as_slice());
        let options = RevolveOptions::new(1.5, slice_tolerance).with_uvs(uvs);
        let built = revolve_z(&points, normals, &options).map(|m| counts_of(&m));
        prop_assert_eq!(revolve_z_counts(&points, normals, &options), built);
    }

    #[test]
    fn lathe_counts_are_the_meshes(
        radius in prop::collection::vec(prop_oneof![Just(0.0), 0.0f64..2.0], 4..5),
        pieces in 1usize..3,
        slices in 3usize..9,
        stacks in 1usize..9,
        uvs in uv_mode(),
    ) {
        // `pieces` cubic pieces: 3·pieces + 1 keys each
        let keys = |f: &dyn Fn(usize) -> f64| (0..=3 * pieces).map(f).collect::<Vec<f64>>();
        let r = keys(&|i| radius[i % radius.len()]);
        let z = keys(&|i| i as f64 * 0.5);
        let lathe = Lathe::new(&r, &z).unwrap();
        let options = LatheOptions::new(slices, stacks).with_uvs(uvs);
        let built = lathe.to_mesh(&options).map(|m| counts_of(&m));
        prop_assert_eq!(lathe.counts(&options), built);
    }
}

/// The counts of a revolution in a billion slices are known at once: nothing is allocated
/// for the slices.
#[test]
fn counting_a_huge_revolution_builds_nothing() {
    let profile = Profile {
        points: vec![DVec2::new(0.0, -1.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0)],
        normals: vec![DVec2::NEG_Y, DVec2::X, DVec2::Y],
    };
    let steps = 1_000_000_000;
    let counts = revolve_counts(&profile, steps, SweepOptions::default()).unwrap();
    // two poles, one ring of `steps` vertices, one triangle per slice on each side
    assert_eq!(counts, MeshCounts { vertices: steps as u64 + 2, triangles: 2 * steps as u64 });
}
