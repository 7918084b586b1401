//! Pictures: deterministic bytes, sizes, pixel statistics, golden images, SVG output and
//! errors of `render_file`.
//!
//! Golden images live in `tests/golden/`; `UPDATE_GOLDEN=1 cargo test -p splinekit-render`
//! rewrites them (look at them before committing).

use std::path::{Path, PathBuf};

use glam::DVec3;
use splinekit::TriMesh;
use splinekit_render::{
    BACKGROUND, CurveOptions, FileOptions, Image, ImageSize, Picture, PictureFormat, PictureKind, PlotOptions,
    RenderError, RenderOptions, Rendered, View, plot_curves, render_file, render_mesh,
};

// ---------------------------------------------------------------------------------------
// Harness

fn io_data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../splinekit-io/tests/data").join(rel)
}

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden").join(name)
}

fn icosahedron() -> TriMesh {
    splinekit_io::load_mesh(io_data("obj/icosahedron.obj")).unwrap().mesh.to_tri_mesh()
}

fn size(w: u32, h: u32) -> ImageSize {
    ImageSize::new(w, h).unwrap()
}

fn image_of(r: &Rendered) -> &Image {
    match &r.picture {
        Picture::Image(i) => i,
        Picture::Svg(_) => panic!("expected an image"),
    }
}

fn render(path: &Path, options: &FileOptions) -> Rendered {
    render_file(path, PictureFormat::Png, options).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Colour distance: the largest channel difference.
fn diff(a: [u8; 4], b: [u8; 4]) -> u8 {
    (0..4).map(|k| a[k].abs_diff(b[k])).max().unwrap()
}

fn is_bg(p: [u8; 4], bg: [u8; 3]) -> bool {
    diff(p, [bg[0], bg[1], bg[2], 255]) == 0
}

/// Per-pixel tolerance of golden comparisons: anti-aliased edges and rounding may move a
/// channel by this much…
const GOLDEN_CHANNEL_TOLERANCE: u8 = 40;
/// …on at most this fraction of the pixels; every other pixel is within 2.
const GOLDEN_MAX_CHANGED: f64 = 0.01;

/// Compares `image` with the golden PNG `name` (or writes it with `UPDATE_GOLDEN=1`).
#[track_caller]
fn check_golden(name: &str, image: &Image) {
    let path = golden_path(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        image.write_png(&path).unwrap();
        return;
    }
    let bytes = std::fs::read(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with UPDATE_GOLDEN=1 to create it)", path.display()));
    let golden = Image::decode_png(&bytes).unwrap();
    assert_eq!(golden.size(), image.size(), "{name}: size");
    let mut changed = 0usize;
    let mut worst = (0u8, 0u32, 0u32);
    for y in 0..image.height() {
        for x in 0..image.width() {
            let d = diff(image.pixel(x, y).unwrap(), golden.pixel(x, y).unwrap());
            if d > 2 {
                changed += 1;
            }
            if d > worst.0 {
                worst = (d, x, y);
            }
        }
    }
    let n = image.size().num_pixels();
    let actual = std::env::temp_dir().join(format!("actual-{name}"));
    let _ = image.write_png(&actual);
    assert!(
        worst.0 <= GOLDEN_CHANNEL_TOLERANCE && (changed as f64) <= GOLDEN_MAX_CHANGED * n as f64,
        "{name}: {changed} of {n} pixels differ by more than 2; the worst by {} at ({}, {}); actual picture written to {}",
        worst.0,
        worst.1,
        worst.2,
        actual.display()
    );
}

// ---------------------------------------------------------------------------------------
// Meshes

#[test]
fn mesh_render_is_deterministic_whatever_the_thread_count() {
    let mesh = icosahedron();
    let options = RenderOptions::DEFAULT.with_size(size(160, 120)).with_wireframe(true);
    let a = render_mesh(&mesh, &options).encode_png().unwrap();
    let b = render_mesh(&mesh, &options).encode_png().unwrap();
    assert!(a == b, "two renders differ");
    let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let c = one_thread.install(|| render_mesh(&mesh, &options).encode_png().unwrap());
    assert!(a == c, "one thread and many differ");
    let three = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
    let d = three.install(|| render_mesh(&mesh, &options).encode_png().unwrap());
    assert!(a == d, "three threads and many differ");
}

#[test]
fn mesh_render_has_the_size_and_front_colour() {
    let mesh = icosahedron();
    for (w, h) in [(160, 120), (37, 91), (1, 1)] {
        let image = render_mesh(&mesh, &RenderOptions::DEFAULT.with_size(size(w, h)));
        assert_eq!((image.width(), image.height()), (w, h));
        let png = Image::decode_png(&image.encode_png().unwrap()).unwrap();
        assert_eq!(png, image);
    }
    let image = render_mesh(&mesh, &RenderOptions::DEFAULT.with_size(size(160, 120)));
    // The icosahedron fills the middle: lit grey-blue (blue above red), not background.
    let centre = image.pixel(80, 60).unwrap();
    assert!(!is_bg(centre, BACKGROUND));
    assert!(centre[2] > centre[0] + 20, "centre {centre:?} is not the front colour");
    let covered = image.iter_pixels().filter(|&p| !is_bg(p, BACKGROUND)).count();
    let fraction = covered as f64 / (160.0 * 120.0);
    assert!((0.25..0.8).contains(&fraction), "the mesh covers {fraction} of the picture");
    // Corners are background.
    for (x, y) in [(0, 0), (159, 0), (0, 119), (159, 119)] {
        assert!(is_bg(image.pixel(x, y).unwrap(), BACKGROUND), "({x}, {y})");
    }
}

#[test]
fn inside_out_mesh_shows_the_back_colour() {
    let mut mesh = icosahedron();
    for t in &mut mesh.triangles {
        t.swap(1, 2);
    }
    let image = render_mesh(&mesh, &RenderOptions::DEFAULT.with_size(size(160, 120)));
    let centre = image.pixel(80, 60).unwrap();
    assert!(centre[0] > centre[2] + 40, "centre {centre:?} is not the back colour");
}

#[test]
fn every_view_frames_the_mesh() {
    let mesh = icosahedron();
    for view in View::ALL {
        let image = render_mesh(&mesh, &RenderOptions::DEFAULT.with_size(size(64, 48)).with_view(view));
        let centre = image.pixel(32, 24).unwrap();
        assert!(!is_bg(centre, BACKGROUND), "{view}");
        assert!(is_bg(image.pixel(0, 0).unwrap(), BACKGROUND), "{view}");
    }
}

#[test]
fn wireframe_draws_dark_edges() {
    let mesh = icosahedron();
    let opts = RenderOptions::DEFAULT.with_size(size(160, 120));
    let plain = render_mesh(&mesh, &opts);
    let wire = render_mesh(&mesh, &opts.with_wireframe(true));
    let luma = |p: [u8; 4]| u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2]);
    let darker = plain.iter_pixels().zip(wire.iter_pixels()).filter(|&(a, b)| luma(b) + 90 < luma(a)).count();
    let lighter = plain.iter_pixels().zip(wire.iter_pixels()).filter(|&(a, b)| luma(b) > luma(a)).count();
    assert!(darker > 300, "{darker} pixels darker with the wireframe");
    assert_eq!(lighter, 0, "the wireframe lightens pixels");
}

#[test]
fn degenerate_meshes_do_not_panic() {
    let opts = RenderOptions::DEFAULT.with_size(size(32, 24));
    let empty = TriMesh::default();
    let image = render_mesh(&empty, &opts);
    assert!(image.iter_pixels().all(|p| is_bg(p, BACKGROUND)));
    let point = TriMesh { positions: vec![DVec3::ONE; 3], triangles: vec![[0, 1, 2], [0, 1, 7]], ..TriMesh::default() };
    let _ = render_mesh(&point, &opts);
    let nan = TriMesh {
        positions: vec![DVec3::ZERO, DVec3::X, DVec3::NAN, DVec3::Y],
        triangles: vec![[0, 1, 2], [0, 1, 3]],
        ..TriMesh::default()
    };
    let image = render_mesh(&nan, &opts);
    assert!(image.iter_pixels().any(|p| !is_bg(p, BACKGROUND)));
}

#[test]
fn golden_icosahedron() {
    let image = render_mesh(&icosahedron(), &RenderOptions::DEFAULT.with_size(size(160, 120)).with_wireframe(true));
    check_golden("icosahedron-160x120.png", &image);
}

// ---------------------------------------------------------------------------------------
// SWP files

#[test]
fn curves_only_file_is_a_2d_plot() {
    let path = io_data("swp/core.swp");
    let options = FileOptions::DEFAULT
        .with_size(size(240, 180))
        .with_curves(CurveOptions::DEFAULT.with_frames(true).with_marker_spacing(Some(0.5)));
    let r = render(&path, &options);
    assert_eq!(r.kind, PictureKind::CurvePlot);
    assert_eq!(r.view, View::Iso, "core.swp has 3D curves");
    assert_eq!(r.num_curves, 4);
    let image = image_of(&r);
    assert_eq!((image.width(), image.height()), (240, 180));
    // Every segment colour is drawn (4 curves of 1 segment each: only the first colour),
    // over the plot's background.
    let near =
        |image: &Image, c: [u8; 3]| image.iter_pixels().filter(|p| diff(*p, [c[0], c[1], c[2], 255]) <= 8).count();
    assert!(near(image, splinekit_render::plot::PLOT_BACKGROUND) > 240 * 180 / 2);
    for (c, what) in splinekit_render::marks::FRAME_COLOURS.into_iter().zip(["T", "N", "B"]) {
        assert!(near(image, c) > 20, "{what} arrows");
    }
    let again = render(&path, &options);
    assert!(image.encode_png().unwrap() == image_of(&again).encode_png().unwrap(), "not deterministic");
    // Without frames and markers: the curves (one segment each, in the first colour).
    let plain = render(&path, &options.with_curves(CurveOptions::DEFAULT));
    let curve = near(image_of(&plain), splinekit_render::SEGMENT_COLOURS[0]);
    assert!(curve > 60, "{curve} curve pixels");
}

#[test]
fn golden_plot_of_2d_curves() {
    let r = render(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/extensions.swp"),
        &FileOptions::DEFAULT.with_size(size(200, 150)),
    );
    // extensions.swp has a surface: it is a 3D picture.
    assert_eq!(r.kind, PictureKind::Surfaces);

    let doc = splinekit_io::SwpDocument::parse(
        "bsp2 wave 20 6 [0 0] [1 1] [2 0] [3 1] [4 0] [5 1]\ncirc ring 40 0.8\n",
        "golden.swp",
    )
    .unwrap();
    let curves: Vec<_> =
        doc.curves.iter().enumerate().map(|(i, c)| splinekit_render::PlotCurve::from_swp(c, i).unwrap()).collect();
    let options = CurveOptions::DEFAULT.with_frames(true).with_marker_spacing(Some(0.4));
    let image = plot_curves(&curves, &options, &PlotOptions::DEFAULT.with_size(size(200, 150)));
    check_golden("plot-wave-ring-200x150.png", &image);
}

#[test]
fn surfaces_are_shaded_and_curves_drawn_in_3d() {
    let path = io_data("swp/srev/wineglass.swp");
    let r = render(&path, &FileOptions::DEFAULT.with_size(size(200, 240)));
    assert_eq!(r.kind, PictureKind::Surfaces);
    assert_eq!((r.num_surfaces, r.num_curves), (1, 1));
    assert!(r.num_triangles > 10_000);
    let image = image_of(&r);
    let centre = image.pixel(100, 120).unwrap();
    assert!(!is_bg(centre, BACKGROUND), "{centre:?}");
    // The profile lies on the surface and shows in its segment colours.
    let coloured = image
        .iter_pixels()
        .filter(|p| splinekit_render::SEGMENT_COLOURS.iter().any(|c| diff(*p, [c[0], c[1], c[2], 255]) <= 3))
        .count();
    assert!(coloured > 50, "{coloured} curve pixels");
}

#[test]
fn svg_of_a_curve_file_is_well_formed() {
    let path = io_data("swp/circles.swp");
    let r = render_file(&path, PictureFormat::Svg, &FileOptions::DEFAULT.with_size(size(300, 200))).unwrap();
    assert_eq!(r.view, View::Front);
    let Picture::Svg(svg) = &r.picture else { panic!("expected SVG") };
    // Parse with an independent XML reader.
    let mut depth = 0i32;
    let mut elements = Vec::new();
    let mut root_attrs = Vec::new();
    for event in xml::reader::EventReader::from_str(svg) {
        match event.unwrap_or_else(|e| panic!("bad XML: {e}\n{svg}")) {
            xml::reader::XmlEvent::StartElement { name, attributes, .. } => {
                if depth == 0 {
                    root_attrs = attributes.iter().map(|a| (a.name.local_name.clone(), a.value.clone())).collect();
                }
                depth += 1;
                elements.push(name.local_name);
            }
            xml::reader::XmlEvent::EndElement { .. } => depth -= 1,
            _ => {}
        }
    }
    assert_eq!(depth, 0);
    assert_eq!(elements[0], "svg");
    assert!(root_attrs.contains(&("width".into(), "300".into())), "{root_attrs:?}");
    assert!(root_attrs.contains(&("height".into(), "200".into())), "{root_attrs:?}");
    // Background, 3 axes, two circles.
    assert_eq!(elements.iter().filter(|e| *e == "rect").count(), 1);
    assert_eq!(elements.iter().filter(|e| *e == "polyline").count(), 3 + 2);
    let again = render_file(&path, PictureFormat::Svg, &FileOptions::DEFAULT.with_size(size(300, 200))).unwrap();
    assert_eq!(again.picture, r.picture);
}

#[test]
fn errors_name_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = io_data("obj/icosahedron.obj");
    let err = render_file(&mesh, PictureFormat::Svg, &FileOptions::DEFAULT).unwrap_err();
    assert!(matches!(err, RenderError::SvgOf3d { .. }), "{err}");
    assert!(err.to_string().contains("SVG output draws curves only"), "{err}");

    let wineglass = io_data("swp/srev/wineglass.swp");
    let err = render_file(&wineglass, PictureFormat::Svg, &FileOptions::DEFAULT).unwrap_err();
    assert!(err.to_string().contains("has surfaces"), "{err}");

    let txt = dir.path().join("notes.txt");
    std::fs::write(&txt, "hello").unwrap();
    let err = render_file(&txt, PictureFormat::Png, &FileOptions::DEFAULT).unwrap_err();
    assert!(
        err.to_string()
            .ends_with("notes.txt: cannot draw a file of this kind (.txt); expected .swp, .obj, .glb, .ply or .stl"),
        "{err}"
    );

    let missing = dir.path().join("missing.swp");
    let err = render_file(&missing, PictureFormat::Png, &FileOptions::DEFAULT).unwrap_err();
    assert!(err.to_string().contains("missing.swp"), "{err}");

    let bad = dir.path().join("bad.swp");
    std::fs::write(&bad, "bez2 . 20 4\n[0 0]\n[1 1.2.3]").unwrap();
    let err = render_file(&bad, PictureFormat::Png, &FileOptions::DEFAULT).unwrap_err();
    assert!(err.to_string().contains("bad.swp:3:4"), "{err}");

    let empty = dir.path().join("empty.swp");
    std::fs::write(&empty, "# nothing\n").unwrap();
    let err = render_file(&empty, PictureFormat::Png, &FileOptions::DEFAULT).unwrap_err();
    assert!(err.to_string().contains("nothing to draw"), "{err}");

    let options = FileOptions::DEFAULT.with_curves(CurveOptions::DEFAULT.with_marker_spacing(Some(0.0)));
    let err = render_file(&io_data("swp/core.swp"), PictureFormat::Png, &options).unwrap_err();
    assert_eq!(err.to_string(), "marker spacing must be a positive number, found 0");

    let err = PictureFormat::from_path(Path::new("out.jpg")).unwrap_err();
    assert_eq!(err.to_string(), "out.jpg: cannot write a picture of this kind (.jpg); expected .png or .svg");
}

#[test]
fn writing_replaces_the_file_atomically() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ico.png");
    let r = render(&io_data("obj/icosahedron.obj"), &FileOptions::DEFAULT.with_size(size(40, 30)));
    r.picture.write(&out).unwrap();
    let image = Image::decode_png(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!((image.width(), image.height()), (40, 30));
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, ["ico.png"]);
    // A directory that does not exist: an error naming the path, nothing written.
    let err = r.picture.write(&dir.path().join("no/such/dir/x.png")).unwrap_err();
    assert!(err.to_string().contains("x.png"), "{err}");
}

#[test]
fn glb_meshes_render_like_their_obj() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("icosahedron.glb");
    splinekit_io::mesh::save(&icosahedron(), &glb, splinekit_io::MeshFormat::Glb).unwrap();
    let options = FileOptions::DEFAULT.with_size(size(160, 120));
    let from_glb = render(&glb, &options);
    let from_obj = render(&io_data("obj/icosahedron.obj"), &options);
    assert_eq!(from_glb.kind, PictureKind::Mesh);
    assert_eq!(from_glb.num_triangles, 20);
    // The same picture up to the f32 rounding of the glb's coordinates.
    let (a, b) = (image_of(&from_glb), image_of(&from_obj));
    let changed = a.iter_pixels().zip(b.iter_pixels()).filter(|(p, q)| diff(*p, *q) > 2).count();
    assert!(changed <= 16, "{changed} pixels differ");
    let trimesh = io_data("glb/trimesh_scene.glb");
    assert!(render(&trimesh, &options).num_triangles > 0);
}

/// The curve points of `marks` (solid lines only: the curves, not their polygons).
fn curve_points(marks: &[splinekit_render::Mark]) -> usize {
    marks
        .iter()
        .map(|m| match m {
            splinekit_render::Mark::Line { points, dash: None, .. } => points.len(),
            _ => 0,
        })
        .sum()
}

/// #38: a circle traced 10 000 times (`helix c 20 1 0 10000`, 20 bytes) is framed by its box
/// (17 samples of it are 17 times its start, which framed a point) and drawn as a ring with
/// all of the point budget, not 6.6 chords a turn; a small picture draws it with fewer points.
#[test]
fn a_helix_of_ten_thousand_turns_is_drawn_as_its_ring() {
    use splinekit_render::{Theme, curve_marks, marks::MAX_DRAWN_POINTS};
    let doc = splinekit_io::SwpDocument::parse("helix c 20 1 0 10000\n", "ring.swp").unwrap();
    let curves = [splinekit_render::PlotCurve::from_swp(&doc.curves[0], 0).unwrap()];
    let plot = PlotOptions::DEFAULT.with_size(size(200, 150)).with_view(View::Front);
    let image = plot_curves(&curves, &CurveOptions::DEFAULT, &plot);
    // the coloured pixels: a ring about the centre, as wide as the framed picture allows
    let colour = splinekit_render::SEGMENT_COLOURS[0];
    let (mut lo, mut hi, mut at_centre) = ([u32::MAX; 2], [0u32; 2], 0);
    for y in 0..150 {
        for x in 0..200 {
            let p = image.pixel(x, y).unwrap();
            if diff(p, [colour[0], colour[1], colour[2], 255]) <= 40 {
                (lo, hi) = ([lo[0].min(x), lo[1].min(y)], [hi[0].max(x), hi[1].max(y)]);
                at_centre += u32::from((x as i32 - 100).pow(2) + (y as i32 - 75).pow(2) < 20 * 20);
            }
        }
    }
    let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
    assert!(w > 100 && h > 100 && w.abs_diff(h) <= 3, "ring box {lo:?}..{hi:?}");
    assert_eq!(at_centre, 0, "chords across the ring");
    // the budget in full at 800×600; far fewer points at 64×48 (a tenth of a pixel)
    let count = |s: ImageSize| curve_points(&curve_marks(&curves, &CurveOptions::DEFAULT, Theme::Light, 1.0, Some(s)));
    assert_eq!(count(ImageSize::DEFAULT), MAX_DRAWN_POINTS);
    assert!(count(size(64, 48)) < MAX_DRAWN_POINTS / 2);
}

/// #38: curves of size 1e304 are tessellated to their own scale (the scene's radius
/// overflowed to infinity and was taken as 1, so each was drawn with the whole budget), and
/// curves that need more than the budget share it.
#[test]
fn huge_scenes_and_many_fine_curves_stay_within_the_point_budget() {
    use splinekit_render::camera::bounding_radius;
    use splinekit_render::{Theme, curve_marks, marks::MAX_DRAWN_POINTS_3D};
    let doc = splinekit_io::SwpDocument::parse("trefoil k 84 2.6e304\ncirc r 30 3e304\n", "huge.swp").unwrap();
    let curves: Vec<_> =
        doc.curves.iter().enumerate().map(|(i, c)| splinekit_render::PlotCurve::from_swp(c, i).unwrap()).collect();
    let corners = [DVec3::splat(-9e304), DVec3::splat(9e304)];
    let radius = bounding_radius(corners.into_iter());
    assert!((radius / (9e304 * 3f64.sqrt()) - 1.0).abs() < 1e-12, "{radius}");
    let marks = curve_marks(&curves, &CurveOptions::DEFAULT, Theme::Dark, radius, None);
    assert!(curve_points(&marks) < 5000, "{} points", curve_points(&marks));
    // ten helices of 10 000 turns in a 3D picture, drawn to 1e-4 (2.2 million points each):
    // the 3D budget, shared
    let text: String = (0..10).map(|k| format!("helix h{k} 20 1 0.{k} 10000\n")).collect();
    let doc = splinekit_io::SwpDocument::parse(&text, "helices.swp").unwrap();
    let curves: Vec<_> =
        doc.curves.iter().enumerate().map(|(i, c)| splinekit_render::PlotCurve::from_swp(c, i).unwrap()).collect();
    let marks = curve_marks(&curves, &CurveOptions::DEFAULT, Theme::Dark, 1.0, None);
    let n = curve_points(&marks);
    assert!(n <= MAX_DRAWN_POINTS_3D + 10 && n > MAX_DRAWN_POINTS_3D / 2, "{n} points");
}

/// #38: the SVG of a circle of radius 1e300 is clipped to the picture, as the PNG is: its axes
/// reached 1e300 pixels, written as numbers of 300 digits (the fuzzer's 20-second hang).
#[test]
fn svg_lines_are_clipped_to_the_picture() {
    let doc = splinekit_io::SwpDocument::parse("circ c 9 1e300\n", "huge.swp").unwrap();
    let curves = [splinekit_render::PlotCurve::from_swp(&doc.curves[0], 0).unwrap()];
    let plot = PlotOptions::DEFAULT.with_size(size(200, 150));
    let svg = splinekit_render::plot_curves_svg(&curves, &CurveOptions::DEFAULT, &plot);
    assert!(svg.len() < 10_000, "{} bytes", svg.len());
    for line in svg.lines().filter(|l| l.starts_with("<polyline")) {
        let points = line.split("points=\"").nth(1).unwrap().split('"').next().unwrap();
        for xy in points.split(' ') {
            for v in xy.split(',') {
                let v: f64 = v.parse().unwrap();
                assert!((-10.0..=210.0).contains(&v), "{v} in {line}");
            }
        }
    }
    // the ring is there: a polyline in the first segment colour
    let c = splinekit_render::SEGMENT_COLOURS[0];
    assert!(svg.contains(&format!("stroke=\"#{:02x}{:02x}{:02x}\"", c[0], c[1], c[2])));
}
