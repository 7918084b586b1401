//! Surfaces coloured by curvature, UV checker and subdivision level: pixels read at points
//! whose curvature or UV is known in closed form, projected with the renderer's camera.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use splinekit::TriMesh;
use splinekit::subdiv::{LEVEL_COLORS, LoopOptions, loop_subdivide};
use splinekit::sweep::SweepOptions;
use splinekit_io::SwpDocument;
use splinekit_io::surface::SurfaceOptions;
use splinekit_render::colour::{CHECKER_COLOURS, DIVERGING_STOPS, to_unit};
use splinekit_render::{
    BACKGROUND, Camera, Curvature, DEFAULT_MARGIN, FileOptions, Image, ImageSize, Legend, PictureFormat, RenderError,
    RenderOptions, Renderer, Shading, SurfaceColour, View, level_colour, render_file, render_mesh, sweep_surfaces,
    sweep_surfaces_with,
};

fn io_data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data").join(rel)
}

fn size(w: u32, h: u32) -> ImageSize {
    ImageSize::new(w, h).unwrap()
}

/// The largest channel difference.
fn diff(a: [u8; 4], b: [u8; 4]) -> u8 {
    (0..3).map(|k| a[k].abs_diff(b[k])).max().unwrap()
}

/// An icosahedron of radius `r` split `levels` times at its edge midpoints, pushed onto the
/// sphere; counter-clockwise outward.
fn icosphere(r: f64, levels: usize) -> TriMesh {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions = Vec::new();
    for (a, b) in [(1.0, phi), (1.0, -phi), (-1.0, phi), (-1.0, -phi)] {
        positions.extend([DVec3::new(0.0, a, b), DVec3::new(a, b, 0.0), DVec3::new(b, 0.0, a)]);
    }
    let mut triangles = Vec::new();
    let near = |p: &[DVec3], i: usize, j: usize| (p[i] - p[j]).length() < 2.0 + 1e-9;
    for i in 0..12 {
        for j in i + 1..12 {
            for k in j + 1..12 {
                if near(&positions, i, j) && near(&positions, j, k) && near(&positions, k, i) {
                    let (a, b, c) = (positions[i], positions[j], positions[k]);
                    let (i, j, k) = (i as u32, j as u32, k as u32);
                    triangles.push(if (b - a).cross(c - a).dot(a + b + c) > 0.0 { [i, j, k] } else { [i, k, j] });
                }
            }
        }
    }
    for _ in 0..levels {
        let mut mid = HashMap::new();
        let mut finer = Vec::new();
        for t in &triangles {
            let m: [u32; 3] = std::array::from_fn(|k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    positions.push(0.5 * (positions[a as usize] + positions[b as usize]));
                    (positions.len() - 1) as u32
                })
            });
            finer.extend([[t[0], m[0], m[2]], [t[1], m[1], m[0]], [t[2], m[2], m[1]], m]);
        }
        triangles = finer;
    }
    TriMesh { positions: positions.into_iter().map(|p| r * p.normalize()).collect(), triangles, ..TriMesh::default() }
}

/// The torus of `gcyl/tor.swp`: a circle of radius 0.5 swept along a circle of radius 2 in
/// the xy-plane, about the z axis.
fn tor(options: &SurfaceOptions) -> TriMesh {
    let path = io_data("swp/gcyl/tor.swp");
    let doc = SwpDocument::read(&path).unwrap();
    let mut meshes = sweep_surfaces_with(&doc, "tor.swp", options).unwrap();
    assert_eq!(meshes.len(), 1);
    meshes.pop().unwrap()
}

/// The pixel under `p` in a picture of `mesh` alone (the renderer's camera frames the mesh).
fn pixel_at(image: &Image, mesh: &TriMesh, options: &RenderOptions, p: DVec3) -> [u8; 4] {
    let camera =
        Camera::fit(options.view, options.projection, mesh.positions.iter().copied(), options.size, DEFAULT_MARGIN);
    let q = camera.project(p);
    image.pixel(q.x as u32, q.y as u32).unwrap()
}

#[test]
fn a_sphere_is_one_colour() {
    // Every vertex has H = 1/r and K = 1/r² (to 0.5 %): the scale is that value, and the whole
    // sphere the positive end colour. Compared pixel by pixel with the sphere painted in that
    // colour (same lighting), silhouettes included.
    let r = 1.7;
    let mut mesh = icosphere(r, 4);
    let options = RenderOptions::DEFAULT.with_size(size(200, 160)).with_view(View::Front).with_shading(Shading::Smooth);
    let mut painted = mesh.clone();
    painted.colors = vec![to_unit(DIVERGING_STOPS[4]); mesh.num_vertices()];
    let reference = render_mesh(&painted, &options);
    for (curvature, exact) in [(Curvature::Mean, 1.0 / r), (Curvature::Gaussian, 1.0 / (r * r))] {
        let opts = options.with_colour(SurfaceColour::Curvature(curvature)).with_legend(false);
        let (image, legend) = Renderer::new().render_with_legend(&[&mesh], &[], &opts);
        let Some(Legend::Curvature { scale, min, max, .. }) = legend else { panic!("{legend:?}") };
        for v in [scale, min, max] {
            assert!((v - exact).abs() < 5e-3 * exact, "{curvature:?}: {v} for {exact}");
        }
        let worst = image.iter_pixels().zip(reference.iter_pixels()).map(|(a, b)| diff(a, b)).max().unwrap();
        assert!(worst <= 3, "{curvature:?}: a pixel differs by {worst}");
        let centre = image.pixel(100, 80).unwrap();
        assert!(centre[0] > centre[2] && centre[2] > centre[1], "{curvature:?}: {centre:?} is not crimson");
    }
    // Turned inside out, the sphere has H = −1/r everywhere (and K unchanged).
    for t in &mut mesh.triangles {
        t.swap(1, 2);
    }
    let (_, legend) = Renderer::new().render_with_legend(
        &[&mesh],
        &[],
        &options.with_colour(SurfaceColour::Curvature(Curvature::Mean)),
    );
    let Some(Legend::Curvature { min, max, .. }) = legend else { panic!() };
    assert!((min + 1.0 / r).abs() < 1e-3 && (max + 1.0 / r).abs() < 1e-3, "{min} {max}");
}

#[test]
fn torus_is_blue_inside_and_red_outside() {
    // Seen from +z. On the top of the tube at distance ρ from the axis, cos φ = (ρ − 2)/0.5,
    // K = cos φ / (r (R + r cos φ)): at ρ = 1.6, K = −1 (inside: a saddle); at ρ = 2.4,
    // K = +0.67 (outside: a cap).
    let mesh = tor(&SurfaceOptions::default());
    let options = RenderOptions::DEFAULT
        .with_size(size(320, 240))
        .with_view(View::Front)
        .with_colour(SurfaceColour::Curvature(Curvature::Gaussian));
    let (image, legend) = Renderer::new().render_with_legend(&[&mesh], &[], &options);
    // The closed forms' extremes: K from −1/(r(R − r)) = −4/3 to 1/(r(R + r)) = 0.8.
    let Some(Legend::Curvature { min, max, .. }) = legend else { panic!("{legend:?}") };
    assert!((min + 4.0 / 3.0).abs() < 0.02 && (max - 0.8).abs() < 0.02, "{min} {max}");
    let top = |rho: f64, angle: f64| {
        let z = (0.25 - (rho - 2.0) * (rho - 2.0)).sqrt();
        DVec3::new(rho * angle.cos(), rho * angle.sin(), z)
    };
    for k in 0..8 {
        let angle = std::f64::consts::TAU * (f64::from(k) + 0.3) / 8.0;
        let inner = pixel_at(&image, &mesh, &options, top(1.6, angle));
        let outer = pixel_at(&image, &mesh, &options, top(2.4, angle));
        assert!(inner[2] > inner[0] + 40, "inside at {angle}: {inner:?} is not blue");
        assert!(outer[0] > outer[2] + 20 && outer[0] > outer[1] + 40, "outside at {angle}: {outer:?} is not red");
        // The top of the tube (ρ = 2) is flat one way: K = 0, light grey.
        let middle = pixel_at(&image, &mesh, &options, top(2.0, angle));
        assert!(diff(middle, [middle[1], middle[1], middle[1], 255]) < 25, "top at {angle}: {middle:?}");
    }
    // The same through render_file, which also draws the file's curves.
    let file = FileOptions::DEFAULT.with_size(size(320, 240)).with_view(Some(View::Front)).with_colour(options.colour);
    let rendered = render_file(&io_data("swp/gcyl/tor.swp"), PictureFormat::Png, &file).unwrap();
    assert_eq!(rendered.legend, legend);
}

#[test]
fn a_plane_is_the_zero_colour() {
    // A 10 × 10 grid in z = 0, seen from the front: every surface pixel is the zero colour,
    // lit as a plane lit in that colour.
    let n = 10;
    let positions = (0..=n).flat_map(|j| (0..=n).map(move |i| DVec3::new(f64::from(i), f64::from(j), 0.0))).collect();
    let at = |i: u32, j: u32| j * (n + 1) + i;
    let triangles = (0..n).flat_map(|j| {
        (0..n)
            .flat_map(move |i| [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]])
    });
    let mesh = TriMesh { positions, triangles: triangles.collect(), ..TriMesh::default() };
    let options = RenderOptions::DEFAULT.with_size(size(160, 160)).with_view(View::Front);
    let mut painted = mesh.clone();
    painted.colors = vec![to_unit(DIVERGING_STOPS[2]); mesh.num_vertices()];
    let reference = render_mesh(&painted, &options);
    for curvature in [Curvature::Mean, Curvature::Gaussian] {
        let opts = options.with_colour(SurfaceColour::Curvature(curvature)).with_legend(false);
        let (image, legend) = Renderer::new().render_with_legend(&[&mesh], &[], &opts);
        assert!(image == reference, "{curvature:?}");
        // The scale is the least one (the plane is flat to rounding).
        let Some(Legend::Curvature { scale, min, max, .. }) = legend else { panic!() };
        assert!(scale > 0.0 && scale < 1e-5 && min.abs() < 1e-12 && max.abs() < 1e-12, "{scale} {min} {max}");
    }
}

#[test]
fn uv_checker_alternates_on_a_swept_surface() {
    // Vertices of the swept torus at the centre of a checker square, facing the camera: the
    // pixel under each shows that square's colour (light grey or steel blue, lit).
    let uvs =
        SurfaceOptions { sweep: SweepOptions { uvs: true, ..SweepOptions::default() }, ..SurfaceOptions::default() };
    let mesh = tor(&uvs);
    assert_eq!(mesh.uvs.len(), mesh.num_vertices());
    let options =
        RenderOptions::DEFAULT.with_size(size(400, 300)).with_view(View::Front).with_colour(SurfaceColour::UvChecker);
    let image = render_mesh(&mesh, &options);
    let normals = mesh.vertex_normal_sums();
    let centred = |x: f64| ((x * 8.0).fract() - 0.5).abs() < 0.2;
    let (mut light, mut dark) = (0, 0);
    for (i, (&p, &uv)) in mesh.positions.iter().zip(&mesh.uvs).enumerate() {
        if !(centred(uv.x) && centred(uv.y) && normals[i].normalize().z > 0.6) {
            continue;
        }
        let parity = ((uv.x * 8.0).floor() + (uv.y * 8.0).floor()) as i64 % 2;
        let pixel = pixel_at(&image, &mesh, &options, p);
        if parity == 0 {
            light += 1;
            assert!(pixel[0].abs_diff(pixel[2]) < 20 && pixel[0] > 120, "vertex {i} {uv}: {pixel:?} is not light");
        } else {
            dark += 1;
            assert!(pixel[2] > pixel[0] + 40, "vertex {i} {uv}: {pixel:?} is not blue");
        }
    }
    assert!(light > 20 && dark > 20, "{light} light and {dark} dark squares checked");
    // Deterministic, and the checker's colours are the stated ones.
    assert!(render_mesh(&mesh, &options) == image);
    assert_eq!(splinekit_render::checker_colour(DVec2::new(0.01, 0.01)), CHECKER_COLOURS[0]);
}

#[test]
fn uv_checker_needs_texture_coordinates() {
    let options = FileOptions::DEFAULT.with_size(size(64, 48)).with_colour(SurfaceColour::UvChecker);
    let err = render_file(&io_data("obj/icosahedron.obj"), PictureFormat::Png, &options).unwrap_err();
    assert!(matches!(err, RenderError::NoTextureCoordinates { .. }), "{err}");
    assert!(err.to_string().ends_with("icosahedron.obj has no texture coordinates"), "{err}");
    // An SWP file's surfaces are swept with UVs.
    let r = render_file(&io_data("swp/srev/wineglass.swp"), PictureFormat::Png, &options).unwrap();
    assert_eq!(r.legend, None);
    // A mesh with face-varying UVs (OBJ vt): kept.
    let doughnut = io_data("obj/cs4620-splines/doughnut.obj");
    assert!(render_file(&doughnut, PictureFormat::Png, &options).is_ok());
}

#[test]
fn levels_show_their_colours() {
    // One Loop level of the icosahedron, coloured by level: at its 12 old vertices the
    // surface is level 0's grey, at its 30 new ones level 1's blue.
    let base = splinekit_io::load_mesh(io_data("obj/icosahedron.obj")).unwrap().mesh;
    let fine = loop_subdivide(&base, 1, &LoopOptions { color_by_level: true, ..LoopOptions::default() }).unwrap();
    let mesh = fine.to_tri_mesh();
    let options = RenderOptions::DEFAULT
        .with_size(size(320, 240))
        .with_view(View::Front)
        .with_colour(SurfaceColour::Level { levels: 1 });
    let (image, legend) = Renderer::new().render_with_legend(&[&mesh], &[], &options);
    assert_eq!(legend, Some(Legend::Levels { levels: 1 }));
    let normals = mesh.vertex_normal_sums();
    let mut checked = [0, 0];
    for (i, &p) in mesh.positions.iter().enumerate() {
        if normals[i].normalize().z < 0.5 {
            continue;
        }
        let pixel = pixel_at(&image, &mesh, &options, p);
        let level = usize::from(i >= 12);
        assert_eq!(mesh.colors[i], LEVEL_COLORS[level]);
        if level == 0 {
            assert!(diff(pixel, [pixel[0], pixel[0], pixel[0], 255]) < 12, "vertex {i}: {pixel:?} is not grey");
        } else {
            assert!(pixel[2] > pixel[0] + 60, "vertex {i}: {pixel:?} is not blue");
        }
        checked[level] += 1;
    }
    assert!(checked[0] >= 2 && checked[1] >= 8, "{checked:?}");
    // The legend: a swatch per level in the bottom left corner, over a dark panel.
    let swatches = (0..2).map(level_colour).collect::<Vec<_>>();
    let found = |c: [u8; 3]| image.iter_pixels().any(|p| p == [c[0], c[1], c[2], 255]);
    assert!(swatches.iter().all(|&c| found(c)), "the legend's swatches are drawn unlit");
    // At level 0 everything is level 0, whatever the mesh's colours.
    let level0 = options.with_colour(SurfaceColour::Level { levels: 0 }).with_legend(false);
    let (image, legend) = Renderer::new().render_with_legend(&[&mesh], &[], &level0);
    assert_eq!(legend.map(|l| l.describe()), Some(String::from("level 0")));
    let mut grey = mesh.clone();
    grey.colors = vec![LEVEL_COLORS[0]; grey.num_vertices()];
    assert!(image == render_mesh(&grey, &options.with_colour(SurfaceColour::Shade)));
}

#[test]
fn colourings_of_a_file_are_deterministic_and_shade_is_unchanged() {
    let glass = io_data("swp/srev/wineglass.swp");
    let doc = SwpDocument::read(&glass).unwrap();
    let meshes = sweep_surfaces(&doc, "wineglass.swp").unwrap();
    for colour in [SurfaceColour::Curvature(Curvature::Mean), SurfaceColour::Curvature(Curvature::Gaussian)] {
        let options = FileOptions::DEFAULT.with_size(size(160, 120)).with_colour(colour);
        let a = render_file(&glass, PictureFormat::Png, &options).unwrap();
        let b = render_file(&glass, PictureFormat::Png, &options).unwrap();
        assert_eq!(a, b, "{colour:?}");
        assert!(a.legend.is_some());
    }
    // Shade draws what it drew before: the same picture as with no colouring chosen.
    let options = RenderOptions::DEFAULT.with_size(size(160, 120));
    let refs: Vec<&TriMesh> = meshes.iter().collect();
    let plain = Renderer::new().render(&refs, &[], &options);
    let (shaded, legend) = Renderer::new().render_with_legend(&refs, &[], &options.with_colour(SurfaceColour::Shade));
    assert!(plain == shaded && legend.is_none());
    assert!(plain.iter_pixels().any(|p| p != [BACKGROUND[0], BACKGROUND[1], BACKGROUND[2], 255]));
}
