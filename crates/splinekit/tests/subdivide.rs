//! The one entry point, `subdiv::subdivide`: for every scheme of `Scheme::ALL` it gives the
//! same mesh, to the bit, as the scheme's own function, and the capability methods of `Scheme`
//! say what it does (issue #40).

mod common;

use common::{cube, icosahedron, poly, prism, read_obj};
use glam::{DVec2, DVec3};
use splinekit::PolyMesh;
use splinekit::mesh::FaceVarying;
use splinekit::subdiv::{
    BilinearOptions, BoundaryRule, ButterflyOptions, Creases, CreasingMethod, DooSabinOptions, EdgeCrease,
    LEVEL_COLORS, LoopWeights, Scheme, Sqrt3Options, SubdivError, SubdivisionOptions, TriangleSubdivision,
    VertexCrease, bilinear_subdivide, butterfly_subdivide, catmull_clark_limit_positions, catmull_clark_subdivide,
    catmull_clark_subdivide_creased, doo_sabin_subdivide, loop_limit_positions, loop_subdivide, loop_subdivide_creased,
    sqrt3_subdivide, subdivide,
};

/// An open 3 × 3 grid of quads, each split into two triangles (`triangles`) or not.
fn grid(triangles: bool) -> PolyMesh {
    let g = |i: u32, j: u32| j * 4 + i;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            let (a, b, c, d) = (g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1));
            if triangles {
                faces.extend([vec![a, b, c], vec![a, c, d]]);
            } else {
                faces.push(vec![a, b, c, d]);
            }
        }
    }
    let positions = (0..16).map(|k| DVec3::new(f64::from(k % 4), f64::from(k / 4), f64::from(k * k % 5) * 0.1));
    let faces: Vec<&[u32]> = faces.iter().map(Vec::as_slice).collect();
    poly(positions.collect(), &faces)
}

/// `mesh` with a colour per vertex, a UV per vertex (seamless) and a normal per corner.
fn with_attributes(mut mesh: PolyMesh) -> PolyMesh {
    mesh.colors = mesh.positions.iter().map(|p| p.abs().min(DVec3::ONE)).collect();
    let uvs = mesh.positions.iter().map(|p| DVec2::new(p.x, p.y)).collect();
    mesh.uvs = Some(FaceVarying { values: uvs, indices: mesh.face_vertices.clone() });
    let normals = mesh.positions.iter().map(|p| p.normalize_or(DVec3::Z)).collect();
    mesh.normals = Some(FaceVarying { values: normals, indices: mesh.face_vertices.clone() });
    mesh
}

/// The test meshes: closed and open, triangles, quads and mixed, with and without attributes.
fn meshes() -> Vec<(&'static str, PolyMesh)> {
    vec![
        ("icosahedron", icosahedron()),
        ("icosahedron with attributes", with_attributes(icosahedron())),
        ("cube", cube()),
        ("cube with attributes", with_attributes(cube())),
        ("prism", prism()),
        ("triangle grid", with_attributes(grid(true))),
        ("quad grid", grid(false)),
    ]
}

/// The option sets tried: the defaults, and every option away from its default.
fn option_sets() -> Vec<SubdivisionOptions> {
    let d = SubdivisionOptions::DEFAULT;
    vec![
        d,
        d.with_color_by_level(true),
        d.with_weights(LoopWeights::Warren),
        d.with_boundary(BoundaryRule::Corners),
        d.with_triangles(TriangleSubdivision::Smooth),
        d.with_creasing(CreasingMethod::Uniform),
    ]
}

/// `levels` levels of `scheme` by its own function, with the options of `options` that it has.
fn own(mesh: &PolyMesh, levels: usize, scheme: Scheme, options: &SubdivisionOptions) -> Result<PolyMesh, SubdivError> {
    let color_by_level = options.color_by_level;
    match scheme {
        Scheme::Loop => loop_subdivide(mesh, levels as u32, &options.loop_options()),
        Scheme::CatmullClark => catmull_clark_subdivide(mesh, levels, &options.catmull_clark_options()),
        Scheme::Sqrt3 => sqrt3_subdivide(mesh, levels, &Sqrt3Options { color_by_level }),
        Scheme::DooSabin => doo_sabin_subdivide(mesh, levels, &DooSabinOptions::default()),
        Scheme::Butterfly => butterfly_subdivide(mesh, levels, &ButterflyOptions { color_by_level }),
        Scheme::Bilinear => bilinear_subdivide(mesh, levels, &BilinearOptions { color_by_level }),
        _ => unreachable!("a scheme this test does not know"),
    }
}

#[test]
fn every_scheme_as_its_own_function() {
    let no = Creases::default();
    for (name, mesh) in meshes() {
        for scheme in Scheme::ALL {
            for options in option_sets() {
                // three levels: Loop's and Catmull-Clark's fast paths two and three levels down
                for levels in 0..=3 {
                    let what = format!("{name}, {levels} levels of {scheme}, {options:?}");
                    let expected = own(&mesh, levels, scheme, &options);
                    match subdivide(&mesh, levels, scheme, &options, &no) {
                        Ok(fine) => {
                            assert_eq!(Ok(&fine.mesh), expected.as_ref(), "{what}");
                            assert!(fine.creases.is_empty(), "{what}");
                        }
                        Err(e) => assert_eq!(Err(e), expected, "{what}"),
                    }
                }
            }
        }
    }
}

/// A sharp edge, a semi-sharp edge and a corner on the cube or the icosahedron.
fn creases() -> Creases {
    Creases {
        edges: vec![EdgeCrease { a: 0, b: 2, sharpness: 10.0 }, EdgeCrease { a: 0, b: 1, sharpness: 1.5 }],
        vertices: vec![VertexCrease { vertex: 3, sharpness: 2.0 }],
    }
}

#[test]
fn creases_as_the_creased_functions_or_ignored() {
    let creases = creases();
    for (name, mesh) in [("cube", cube()), ("icosahedron", icosahedron())] {
        for scheme in Scheme::ALL {
            for options in option_sets() {
                let what = format!("{name}, 2 levels of {scheme}, {options:?}");
                let with = subdivide(&mesh, 2, scheme, &options, &creases);
                let without = subdivide(&mesh, 2, scheme, &options, &Creases::default());
                let (method, n) = (options.creasing, 2);
                let expected = match scheme {
                    Scheme::Loop => loop_subdivide_creased(&mesh, 2, &options.loop_options(), &creases, method),
                    Scheme::CatmullClark => {
                        catmull_clark_subdivide_creased(&mesh, n, &options.catmull_clark_options(), &creases, method)
                    }
                    _ => {
                        assert!(!scheme.supports_creases(), "{what}");
                        // ignored: the same as without creases
                        match (&with, &without) {
                            (Ok(a), Ok(b)) => assert_eq!(a.mesh, b.mesh, "{what}"),
                            (a, b) => assert_eq!(a.as_ref().err(), b.as_ref().err(), "{what}"),
                        }
                        continue;
                    }
                };
                assert!(scheme.supports_creases(), "{what}");
                match (with, expected) {
                    (Ok(fine), Ok((mesh, child))) => {
                        assert_eq!(fine.mesh, mesh, "{what}");
                        assert_eq!(fine.creases, child, "{what}");
                        // and the creases change the surface
                        assert_ne!(fine.mesh.positions, without.unwrap().mesh.positions, "{what}");
                    }
                    (Err(e), Err(f)) => assert_eq!(e, f, "{what}"),
                    (a, b) => panic!("{what}: {:?} against {:?}", a.err(), b.err()),
                }
            }
        }
    }
}

#[test]
fn triangle_schemes_refuse_other_faces() {
    let options = SubdivisionOptions::DEFAULT;
    for scheme in Scheme::ALL {
        for (name, mesh) in [("cube", cube()), ("prism", prism())] {
            let result = subdivide(&mesh, 1, scheme, &options, &Creases::default());
            if scheme.triangles_only() {
                let Err(SubdivError::NotTriangles { scheme: named, .. }) = result else {
                    panic!("{scheme} took the {name}: {result:?}");
                };
                assert_eq!(named, scheme.to_string(), "{name}");
            } else {
                assert!(result.is_ok(), "{scheme} refused the {name}: {:?}", result.err());
            }
        }
    }
}

#[test]
fn level_starts_are_the_vertex_counts_of_the_levels_above() {
    let mut meshes = meshes();
    for file in ["backtoback", "cones", "cubes", "degenerate", "fins3", "valence2"] {
        meshes.push((file, read_obj(&format!("nonmanifold/{file}.in.obj"))));
    }
    let options = SubdivisionOptions::DEFAULT;
    let no = Creases::default();
    for (name, mesh) in &meshes {
        for scheme in Scheme::ALL {
            let Ok(fine) = subdivide(mesh, 4, scheme, &options, &no) else { continue };
            assert_eq!(fine.level_starts.len(), 5, "{name}, {scheme}");
            if scheme == Scheme::DooSabin {
                assert_eq!(fine.level_starts, [0; 5], "{name}: every vertex is the last level's");
                continue;
            }
            for k in 1..=4 {
                let above = subdivide(mesh, k - 1, scheme, &options, &no).unwrap();
                assert_eq!(fine.level_starts[k], above.mesh.num_vertices(), "{name}, {scheme}, level {k}");
            }
        }
    }
}

#[test]
fn colours_by_level_follow_the_level_starts() {
    let options = SubdivisionOptions::DEFAULT.with_color_by_level(true);
    for (name, mesh) in meshes() {
        for scheme in Scheme::ALL.into_iter().filter(|s| s.colors_by_level()) {
            let Ok(fine) = subdivide(&mesh, 3, scheme, &options, &Creases::default()) else { continue };
            let n = fine.mesh.num_vertices();
            for (k, &start) in fine.level_starts.iter().enumerate() {
                let end = fine.level_starts.get(k + 1).copied().unwrap_or(n);
                for v in start..end {
                    assert_eq!(fine.mesh.colors[v], LEVEL_COLORS[k], "{name}, {scheme}, vertex {v} of level {k}");
                }
            }
        }
    }
}

#[test]
fn carried_attributes_as_the_scheme_says() {
    for (name, mesh) in [("icosahedron", with_attributes(icosahedron())), ("cube", with_attributes(cube()))] {
        for scheme in Scheme::ALL {
            let Ok(fine) = subdivide(&mesh, 1, scheme, &SubdivisionOptions::DEFAULT, &Creases::default()) else {
                assert!(scheme.triangles_only(), "{scheme} refused the {name}");
                continue;
            };
            let carries = scheme.carries();
            assert_eq!(fine.mesh.uvs.is_some(), carries.uvs, "{name}, {scheme}: UVs");
            assert_eq!(fine.mesh.normals.is_some(), carries.normals, "{name}, {scheme}: normals");
            assert_eq!(!fine.mesh.colors.is_empty(), carries.colors, "{name}, {scheme}: colours");
        }
    }
}

#[test]
fn interpolating_schemes_keep_the_vertices() {
    for (name, mesh) in meshes() {
        for scheme in Scheme::ALL {
            let Ok(fine) = subdivide(&mesh, 2, scheme, &SubdivisionOptions::DEFAULT, &Creases::default()) else {
                continue;
            };
            let kept = fine.mesh.positions[..mesh.num_vertices()] == mesh.positions[..];
            assert_eq!(kept, scheme.is_interpolating(), "{name}, {scheme}");
        }
    }
}

#[test]
fn nonmanifold_meshes_taken_as_the_scheme_says() {
    let mesh = read_obj("nonmanifold/fins3.in.obj");
    for scheme in Scheme::ALL {
        let result = subdivide(&mesh, 1, scheme, &SubdivisionOptions::DEFAULT, &Creases::default());
        match result {
            Err(SubdivError::Topology(e)) => {
                assert!(e.is_nonmanifold() && !scheme.takes_nonmanifold(), "{scheme}: {e}");
            }
            other => assert!(other.is_ok() && scheme.takes_nonmanifold(), "{scheme}: {:?}", other.err()),
        }
    }
}

#[test]
fn limit_positions_as_the_scheme_says() {
    let (mesh, no) = (icosahedron(), Creases::default());
    let options = SubdivisionOptions::DEFAULT;
    for scheme in Scheme::ALL {
        let fine = subdivide(&mesh, 2, scheme, &options, &no).unwrap();
        let before = fine.mesh.clone();
        let limit = fine.into_limit(&mesh, &no);
        let what = format!("{scheme}");
        match scheme {
            Scheme::Loop => {
                let expected = loop_limit_positions(&before, &options.loop_options()).unwrap();
                assert_eq!(limit.unwrap().positions, expected, "{what}");
            }
            Scheme::CatmullClark => {
                let expected = catmull_clark_limit_positions(&before, &options.catmull_clark_options()).unwrap();
                assert_eq!(limit.unwrap().positions, expected, "{what}");
            }
            _ if scheme.is_interpolating() => assert_eq!(limit.unwrap(), before, "{what}"),
            _ => {
                assert_eq!(limit, Err(SubdivError::NoLimit { scheme }), "{what}");
                assert!(!scheme.has_limit_positions(), "{what}");
                continue;
            }
        }
        assert!(scheme.has_limit_positions() || scheme.is_interpolating(), "{what}");
    }
}

#[test]
fn names_and_bounds() {
    for scheme in Scheme::ALL {
        assert_eq!(Scheme::from_name(scheme.name()), Some(scheme));
        assert_eq!(Scheme::ALL.iter().filter(|s| s.title() == scheme.title()).count(), 1, "{scheme}");
        for (name, mesh) in meshes() {
            for levels in 0..=3 {
                let Ok(fine) = subdivide(&mesh, levels, scheme, &SubdivisionOptions::DEFAULT, &Creases::default())
                else {
                    continue;
                };
                let triangles = fine.mesh.faces().map(|f| f.len() - 2).sum::<usize>() as f64;
                let bound = scheme.max_triangles(&mesh, levels as u32);
                assert!(triangles <= bound, "{name}, {levels} levels of {scheme}: {triangles} > {bound}");
            }
        }
    }
    assert_eq!(Scheme::from_name("catmull_clark"), None);
    assert_eq!(Scheme::default(), Scheme::Loop);
}
