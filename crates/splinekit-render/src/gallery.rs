//! The gallery: every bundled example turned into meshes, pictures and one web page.
//!
//! [`write_gallery`] writes into a directory:
//!
//! - `images/*.png`: one picture per entry (3D pictures of swept surfaces and meshes, 2D plots
//!   of curves), plus `images/*.svg` for the plots of files that hold only curves;
//! - `meshes/*.obj` and `meshes/*.glb`: every swept surface and every subdivided mesh;
//! - `index.html`: one self-contained page (styles inline, pictures embedded as `data:` URLs)
//!   showing every entry with its counts and timings and linking its files.
//!
//! The entries, in order ([`Section`]):
//!
//! 1. every SWP file of the course set (12 files: surfaces of revolution, generalized
//!    cylinders, curves), swept as `splinekit sweep` sweeps them;
//! 2. the arc-length reference scene (an open uniform Catmull-Rom curve of 8 control points,
//!    5 segments) with its chord table, and a plot with a
//!    marker every 0.1 of arc length;
//! 3. Loop subdivision of the course's icosahedron and bunny at levels 0 to 3;
//! 4. a flat ribbon swept along a trefoil knot with rotation-minimizing frames.
//!
//! The inputs are compiled into the library, so the gallery needs no files. Meshes and
//! pictures are the same bytes on every run; `index.html` differs only in its timings. Every
//! file goes through a temporary file and a rename.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use splinekit::subdiv::{LoopOptions, loop_subdivide};
use splinekit::{ArclenIndex, ArclenTable, PolyMesh, TriMesh};
use splinekit_io::SwpDocument;
use splinekit_io::mesh::{MeshFormat, read_mesh, save};
use splinekit_io::surface::{SurfaceFrames, SurfaceOptions};

use crate::file::{FileOptions, PictureFormat, render_swp_document, sweep_surfaces};
use crate::image::ImageSize;
use crate::marks::CurveOptions;
use crate::raster::{RenderOptions, Shading, render_mesh};
use crate::{RenderError, View};

/// `(name, text)` of a file of the course set, compiled in.
macro_rules! course_file {
    ($name:literal) => {
        ($name, include_str!(concat!("../../splinekit-io/tests/data/swp/", $name)))
    };
}

/// The course set of SWP files (`../shared/data/swp`): path in the set, text.
const COURSE_FILES: [(&str, &str); 12] = [
    course_file!("srev/wineglass.swp"),
    course_file!("srev/norm.swp"),
    course_file!("gcyl/tor.swp"),
    course_file!("gcyl/gentorus.swp"),
    course_file!("gcyl/florus.swp"),
    course_file!("gcyl/flircle.swp"),
    course_file!("gcyl/weird.swp"),
    course_file!("gcyl/weirder.swp"),
    course_file!("extra/tube-table.swp"),
    course_file!("extra/dragonfly.swp"),
    course_file!("core.swp"),
    course_file!("circles.swp"),
];

/// The project's examples of its curve kinds: one 2D curve of each kind through the same
/// points, and Kochanek–Bartels and Bessel–Overhauser curves as profiles and sweeps.
const EXAMPLE_FILES: [(&str, &str); 2] = [
    ("curve-kinds.swp", include_str!("../../../examples/curve-kinds.swp")),
    ("tcb-bessel.swp", include_str!("../../../examples/tcb-bessel.swp")),
];

/// The arc-length reference scene: 8 control points on the rose `r = cos 2θ` rising in z, an
/// open uniform Catmull-Rom curve of 5 segments.
const REFERENCE_SCENE: &str = include_str!("../../../examples/reference-scene.swp");

/// The course's meshes (`../shared/data/obj`), as distributed (the HTML lines around them
/// are skipped with warnings).
const COURSE_MESHES: [(&str, &[u8]); 2] = [
    ("icosahedron.obj", include_bytes!("../../splinekit-io/tests/data/obj/icosahedron.obj")),
    ("bunny.obj", include_bytes!("../../splinekit-io/tests/data/obj/bunny.obj")),
];

/// Arc length between the markers of the marker plot.
pub const MARKER_SPACING: f64 = 0.1;

/// A trefoil knot and a flat ribbon to sweep along it (splinekit's SWP extensions).
const RIBBON_ON_TREFOIL: &str = "\
trefoil knot 400 1
bsp2 ribbon 6 8 closed
[0.5 0] [0.4 0.03] [0 0.04] [-0.4 0.03] [-0.5 0] [-0.4 -0.03] [0 -0.04] [0.4 -0.03]
gcyl ribbon-on-knot ribbon knot
";

/// Options for [`write_gallery`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct GalleryOptions {
    /// Size of every picture.
    pub size: ImageSize,
    /// The finest Loop level of the subdivided meshes (levels 0 to this).
    pub max_level: u32,
}

impl GalleryOptions {
    /// 800×600 pictures, levels 0–3.
    pub const DEFAULT: Self = Self { size: ImageSize::DEFAULT, max_level: 3 };

    /// With pictures of this size.
    #[must_use]
    pub fn with_size(mut self, size: ImageSize) -> Self {
        self.size = size;
        self
    }

    /// With Loop levels 0 to `max_level`.
    #[must_use]
    pub fn with_max_level(mut self, max_level: u32) -> Self {
        self.max_level = max_level;
        self
    }
}

impl Default for GalleryOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The part of the page an entry belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Section {
    /// The course set of SWP files.
    CourseFiles,
    /// The curve kinds, with the project's examples.
    CurveKinds,
    /// Arc length.
    ArcLength,
    /// Loop subdivision.
    Subdivision,
    /// Frames along a space curve.
    Frames,
}

impl Section {
    /// Every section, in page order.
    pub const ALL: [Self; 5] = [Self::CourseFiles, Self::CurveKinds, Self::ArcLength, Self::Subdivision, Self::Frames];

    /// The heading on the page.
    #[must_use]
    pub fn title(self) -> &'static str {
        match self {
            Self::CourseFiles => "Course SWP files, swept",
            Self::CurveKinds => "Curve kinds",
            Self::ArcLength => "Arc length",
            Self::Subdivision => "Loop subdivision",
            Self::Frames => "Frames along a space curve",
        }
    }
}

/// One entry of the gallery: a picture, the files made with it, counts and timings.
#[derive(Clone, Debug)]
pub struct Entry {
    /// Where it goes on the page.
    pub section: Section,
    /// A short title.
    pub title: String,
    /// A sentence on what is shown.
    pub caption: String,
    /// The picture, relative to the gallery directory (`images/….png`).
    pub picture: String,
    /// Other files written for this entry (meshes, SVG), relative to the gallery directory.
    pub files: Vec<String>,
    /// Counts and other facts: (name, value).
    pub facts: Vec<(String, String)>,
    /// How long each step took: (step, time).
    pub timings: Vec<(String, Duration)>,
    /// An optional table: header and rows of cells.
    pub table: Option<(Vec<String>, Vec<Vec<String>>)>,
}

/// What [`write_gallery`] made.
#[derive(Clone, Debug)]
pub struct Gallery {
    /// The entries, in page order.
    pub entries: Vec<Entry>,
    /// Every file written, relative to the gallery directory, `index.html` last.
    pub files: Vec<String>,
    /// Wall-clock time of the whole run.
    pub elapsed: Duration,
}

/// The number of steps [`write_gallery`] reports through its `progress` callback.
#[must_use]
pub fn num_steps(options: &GalleryOptions) -> usize {
    COURSE_FILES.len() + EXAMPLE_FILES.len() + 2 + COURSE_MESHES.len() * (options.max_level as usize + 1) + 1 + 1
}

/// Writes the gallery into `dir` (created if missing; files of the same names are replaced,
/// nothing else is touched). `progress` is called after every step with the number of steps
/// done (out of [`num_steps`]) and what was done.
///
/// # Errors
/// A directory or file that cannot be written (naming it), or a bundled example that fails
/// to build (a bug: the tests build them all).
pub fn write_gallery(
    dir: &Path,
    options: &GalleryOptions,
    progress: &mut dyn FnMut(usize, &str),
) -> Result<Gallery, RenderError> {
    let start = Instant::now();
    for sub in ["images", "meshes"] {
        let path = dir.join(sub);
        std::fs::create_dir_all(&path)
            .map_err(|error| RenderError::Write { path: path.display().to_string(), error })?;
    }
    let mut writer = Writer {
        dir: dir.to_path_buf(),
        size: options.size,
        files: Vec::new(),
        pictures: BTreeMap::new(),
        steps: 0,
        progress,
    };
    let mut entries = Vec::new();
    for (name, text) in COURSE_FILES {
        entries.push(writer.course_file(name, text)?);
        writer.step(name);
    }
    for (name, text) in EXAMPLE_FILES {
        entries.push(Entry { section: Section::CurveKinds, ..writer.course_file(name, text)? });
        writer.step(name);
    }
    entries.extend(writer.reference_scene()?);
    for (name, bytes) in COURSE_MESHES {
        let stem = name.trim_end_matches(".obj");
        let loaded = read_mesh(bytes, MeshFormat::Obj, name)?;
        for level in 0..=options.max_level {
            entries.push(writer.subdivided(stem, &loaded.mesh, loaded.warnings.len(), level)?);
            writer.step(&format!("{stem}, Loop level {level}"));
        }
    }
    entries.push(writer.ribbon()?);
    writer.step("ribbon along a trefoil knot");
    let elapsed = start.elapsed();
    let html = page(&entries, &writer.pictures, options, elapsed);
    writer.write_bytes("index.html", html.as_bytes())?;
    writer.step("index.html");
    Ok(Gallery { entries, files: writer.files, elapsed })
}

/// Writes the files of the gallery and counts its steps.
struct Writer<'a> {
    dir: PathBuf,
    size: ImageSize,
    files: Vec<String>,
    /// The PNG bytes of every picture written, for the page.
    pictures: BTreeMap<String, Vec<u8>>,
    steps: usize,
    progress: &'a mut dyn FnMut(usize, &str),
}

impl Writer<'_> {
    fn step(&mut self, what: &str) {
        self.steps += 1;
        (self.progress)(self.steps, what);
    }

    fn write_bytes(&mut self, rel: &str, bytes: &[u8]) -> Result<(), RenderError> {
        crate::image::write_bytes(&self.dir.join(rel), bytes)?;
        self.files.push(rel.to_string());
        Ok(())
    }

    /// Writes a PNG picture and keeps its bytes for the page.
    fn write_picture(&mut self, rel: &str, png: Vec<u8>) -> Result<(), RenderError> {
        self.write_bytes(rel, &png)?;
        self.pictures.insert(rel.to_string(), png);
        Ok(())
    }

    /// Writes `mesh` as OBJ and glb under `meshes/`; returns the relative paths.
    fn save_mesh(&mut self, stem: &str, mesh: &TriMesh) -> Result<Vec<String>, RenderError> {
        let mut out = Vec::new();
        for format in [MeshFormat::Obj, MeshFormat::Glb] {
            let rel = format!("meshes/{stem}.{}", format.extension());
            save(mesh, self.dir.join(&rel), format)?;
            self.files.push(rel.clone());
            out.push(rel);
        }
        Ok(out)
    }

    fn file_options(&self) -> FileOptions {
        FileOptions::DEFAULT.with_size(self.size)
    }

    /// One file of the course set: its surfaces swept, saved and drawn (or its curves plotted).
    fn course_file(&mut self, name: &str, text: &str) -> Result<Entry, RenderError> {
        let stem = file_stem(name);
        let doc = SwpDocument::parse(text, name)?;
        let t = Instant::now();
        let meshes = sweep_surfaces(&doc, name)?;
        let sweep_time = t.elapsed();
        let mut files = Vec::new();
        let t = Instant::now();
        for (k, mesh) in meshes.iter().enumerate() {
            let surface = safe_name(&doc.surfaces[k].display_name(k));
            files.extend(self.save_mesh(&format!("{stem}-{surface}"), mesh)?);
        }
        let write_time = t.elapsed();
        let t = Instant::now();
        let rendered = render_swp_document(&doc, &meshes, name, PictureFormat::Png, &self.file_options())?;
        let render_time = t.elapsed();
        let picture = format!("images/{stem}.png");
        let png = picture_png(&rendered.picture)?;
        self.write_picture(&picture, png)?;
        if meshes.is_empty() {
            let svg = render_swp_document(&doc, &meshes, name, PictureFormat::Svg, &self.file_options())?;
            if let crate::Picture::Svg(text) = svg.picture {
                let rel = format!("images/{stem}.svg");
                self.write_bytes(&rel, text.as_bytes())?;
                files.push(rel);
            }
        }
        let vertices: usize = meshes.iter().map(TriMesh::num_vertices).sum();
        let triangles: usize = meshes.iter().map(|m| m.triangles.len()).sum();
        let mut facts = vec![
            (String::from("curves"), doc.curves.len().to_string()),
            (String::from("surfaces"), doc.surfaces.len().to_string()),
        ];
        let mut timings = Vec::new();
        let caption = if meshes.is_empty() {
            format!("{name}: its curves, coloured by segment, with their control polygons.")
        } else {
            facts.push((String::from("vertices"), group_digits(vertices)));
            facts.push((String::from("triangles"), group_digits(triangles)));
            timings.push((String::from("sweep"), sweep_time));
            timings.push((String::from("write OBJ + glb"), write_time));
            format!(
                "{name}: every surface swept as `splinekit sweep` sweeps it (welded layout; front faces \
                 grey-blue, back faces orange-red), with the file's curves and control polygons."
            )
        };
        timings.push((String::from("render"), render_time));
        Ok(Entry {
            section: Section::CourseFiles,
            title: name.to_string(),
            caption,
            picture,
            files,
            facts,
            timings,
            table: None,
        })
    }

    /// The reference scene (3D, with its chord table) and the arc-length marker plot.
    fn reference_scene(&mut self) -> Result<[Entry; 2], RenderError> {
        let name = "reference-scene.swp";
        let doc = SwpDocument::parse(REFERENCE_SCENE, name)?;
        let curve = doc.curves[0].to_curve().map_err(|error| RenderError::Curve {
            path: name.into(),
            curve: doc.curves[0].display_name(0),
            error,
        })?;
        let t = Instant::now();
        let chord = ArclenTable::chord(&curve, 5);
        let gauss = ArclenTable::gauss3(&curve, 5);
        let exact = ArclenIndex::new(&curve, 1e-12).length();
        let table_time = t.elapsed();

        let t = Instant::now();
        let scene =
            render_swp_document(&doc, &[], name, PictureFormat::Png, &self.file_options().with_view(Some(View::Iso)))?;
        let scene_time = t.elapsed();
        self.write_picture("images/reference-scene.png", picture_png(&scene.picture)?)?;
        let rows: Vec<Vec<String>> =
            chord.iter_rows().map(|(u, s)| vec![format!("{u:.1}"), format!("{s:.5}")]).collect();
        let first = Entry {
            section: Section::ArcLength,
            title: String::from("The arc-length reference scene"),
            caption: String::from(
                "8 control points on a rose r = cos 2θ rising in z, an open uniform Catmull-Rom curve (5 \
                 segments), seen from +x+y+z. The table is the chord method with 5 samples per segment.",
            ),
            picture: String::from("images/reference-scene.png"),
            files: Vec::new(),
            facts: vec![
                (String::from("segments"), curve_segments(&doc).to_string()),
                (String::from("length, chord table"), format!("{:.5}", chord.length())),
                (String::from("length, 3-point Gauss"), format!("{:.5}", gauss.length())),
                (String::from("true length (±1e-12)"), format!("{exact:.5}")),
            ],
            timings: vec![(String::from("tables + true length"), table_time), (String::from("render"), scene_time)],
            table: Some((vec![String::from("u"), String::from("s (chord)")], rows)),
        };

        let options = self
            .file_options()
            .with_view(Some(View::Front))
            .with_curves(CurveOptions::DEFAULT.with_marker_spacing(Some(MARKER_SPACING)));
        let t = Instant::now();
        let plot = render_swp_document(&doc, &[], name, PictureFormat::Png, &options)?;
        let png = picture_png(&plot.picture)?;
        let svg = render_swp_document(&doc, &[], name, PictureFormat::Svg, &options)?;
        let plot_time = t.elapsed();
        self.write_picture("images/arc-length-markers.png", png)?;
        let mut files = Vec::new();
        if let crate::Picture::Svg(text) = svg.picture {
            self.write_bytes("images/arc-length-markers.svg", text.as_bytes())?;
            files.push(String::from("images/arc-length-markers.svg"));
        }
        self.step(name);
        let markers = (exact / MARKER_SPACING).floor() as usize + 1;
        let second = Entry {
            section: Section::ArcLength,
            title: String::from("Markers every 0.1 of arc length"),
            caption: String::from(
                "The reference scene seen from +z (its xy-plane): a dot every 0.1 of 3D arc length from \
                 the start. Where the curve climbs steeply in z the dots crowd together in this view; \
                 equal steps in u would crowd where the curve is slow instead.",
            ),
            picture: String::from("images/arc-length-markers.png"),
            files,
            facts: vec![(String::from("markers"), markers.to_string())],
            timings: vec![(String::from("render PNG + SVG"), plot_time)],
            table: None,
        };
        self.step("arc-length markers");
        Ok([first, second])
    }

    /// `mesh` Loop-subdivided `level` times, saved and drawn.
    fn subdivided(&mut self, stem: &str, mesh: &PolyMesh, warnings: usize, level: u32) -> Result<Entry, RenderError> {
        let t = Instant::now();
        let refined = if level == 0 {
            mesh.clone()
        } else {
            loop_subdivide(mesh, level, &LoopOptions::default())
                .map_err(|e| RenderError::Example { name: format!("{stem}.obj"), message: e.to_string() })?
        };
        let subdivide_time = t.elapsed();
        let tri = refined.to_tri_mesh();
        let name = format!("{stem}-loop{level}");
        let t = Instant::now();
        let files = self.save_mesh(&name, &tri)?;
        let write_time = t.elapsed();
        // The coarse levels with their edges; the fine ones would be all lines.
        let wireframe = tri.triangles.len() <= 6_000;
        let options = RenderOptions::DEFAULT
            .with_size(self.size)
            .with_view(View::Front)
            .with_wireframe(wireframe)
            .with_shading(if level == 0 { Shading::Flat } else { Shading::Smooth });
        let t = Instant::now();
        let image = render_mesh(&tri, &options);
        let render_time = t.elapsed();
        let picture = format!("images/{name}.png");
        self.write_picture(&picture, image.encode_png()?)?;
        let mut facts = vec![
            (String::from("vertices"), group_digits(tri.num_vertices())),
            (String::from("triangles"), group_digits(tri.triangles.len())),
        ];
        if level == 0 && warnings > 0 {
            facts.push((String::from("lines skipped on reading"), warnings.to_string()));
        }
        let mut timings = Vec::new();
        if level > 0 {
            timings.push((format!("subdivide (levels 1–{level})"), subdivide_time));
        }
        timings.push((String::from("write OBJ + glb"), write_time));
        timings.push((String::from("render"), render_time));
        let caption = if level == 0 {
            format!("The course's {stem}.obj as read (flat-shaded, with its edges).")
        } else {
            format!(
                "{stem}.obj after {level} level{} of Loop subdivision (Loop's β, smooth boundary), \
                 smooth-shaded.",
                if level == 1 { "" } else { "s" }
            )
        };
        Ok(Entry {
            section: Section::Subdivision,
            title: format!("{stem}, level {level}"),
            caption,
            picture,
            files,
            facts,
            timings,
            table: None,
        })
    }

    /// A flat ribbon swept along a trefoil knot with rotation-minimizing frames.
    fn ribbon(&mut self) -> Result<Entry, RenderError> {
        let name = "ribbon-on-trefoil.swp";
        let doc = SwpDocument::parse(RIBBON_ON_TREFOIL, name)?;
        let surface_options = SurfaceOptions { frames: SurfaceFrames::RotationMinimizing, ..SurfaceOptions::default() };
        let t = Instant::now();
        let mesh =
            doc.surface_mesh(0, &surface_options).map_err(|error| RenderError::Surface { path: name.into(), error })?;
        let sweep_time = t.elapsed();
        let stem = "trefoil-rmf";
        let t = Instant::now();
        let files = self.save_mesh(stem, &mesh)?;
        let write_time = t.elapsed();
        let t = Instant::now();
        let image = render_mesh(&mesh, &RenderOptions::DEFAULT.with_size(self.size).with_view(View::Iso));
        let render_time = t.elapsed();
        let picture = format!("images/{stem}.png");
        self.write_picture(&picture, image.encode_png()?)?;
        Ok(Entry {
            section: Section::Frames,
            title: String::from("A ribbon along a trefoil knot"),
            caption: String::from(
                "A tube with a flat cross-section (a ribbon: a closed B-spline about 12 times wider than \
                 thick) swept along a trefoil knot with \
                 rotation-minimizing frames: double reflection from the exact derivatives, the \
                 closed-curve correction spread by arc length, so the ribbon closes without a seam.",
            ),
            picture,
            files,
            facts: vec![
                (String::from("vertices"), group_digits(mesh.num_vertices())),
                (String::from("triangles"), group_digits(mesh.triangles.len())),
            ],
            timings: vec![
                (String::from("sweep"), sweep_time),
                (String::from("write OBJ + glb"), write_time),
                (String::from("render"), render_time),
            ],
            table: None,
        })
    }
}

/// The PNG bytes of a picture made as PNG.
fn picture_png(picture: &crate::Picture) -> Result<Vec<u8>, RenderError> {
    match picture {
        crate::Picture::Image(image) => image.encode_png(),
        crate::Picture::Svg(_) => Err(RenderError::Png(String::from("expected a PNG picture, got SVG"))),
    }
}

/// The number of curve segments of the first curve of `doc`.
fn curve_segments(doc: &SwpDocument) -> usize {
    doc.curves[0].to_curve().map_or(0, |c| splinekit::ParamCurve::num_segments(&c))
}

/// `gcyl/weird.swp` → `weird`.
fn file_stem(name: &str) -> String {
    let base = name.rsplit('/').next().unwrap_or(name);
    safe_name(base.strip_suffix(".swp").unwrap_or(base))
}

/// `name` with every character other than ASCII letters, digits, `-` and `_` replaced by `_`.
fn safe_name(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect()
}

/// `1234567` → `1 234 567` (thin spaces).
fn group_digits(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push('\u{2009}');
        }
        out.push(c);
    }
    out
}

/// A duration for people: `0.42 ms`, `12.3 ms`, `1.25 s`.
fn format_duration(d: Duration) -> String {
    let ms = d.as_secs_f64() * 1e3;
    if ms < 10.0 {
        format!("{ms:.2} ms")
    } else if ms < 1000.0 {
        format!("{ms:.1} ms")
    } else {
        format!("{:.2} s", ms / 1e3)
    }
}

/// `text` with `&`, `<`, `>` and `"` escaped for HTML.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}

/// Standard base64 (RFC 4648, with padding).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], chunk.get(1).copied().unwrap_or(0), chunk.get(2).copied().unwrap_or(0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// The page: every entry by section, pictures embedded.
fn page(
    entries: &[Entry],
    pictures: &BTreeMap<String, Vec<u8>>,
    options: &GalleryOptions,
    elapsed: Duration,
) -> String {
    let mut html = String::new();
    let total_files: usize = entries.iter().map(|e| 1 + e.files.len()).sum();
    let _ = write!(
        html,
        r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>splinekit gallery</title>
<style>
body {{ font-family: system-ui, sans-serif; margin: 0 auto; max-width: 1320px; padding: 1em 2em; color: #222; background: #f4f4f2; }}
h1 {{ margin-bottom: 0.2em; }}
h2 {{ margin-top: 1.6em; border-bottom: 1px solid #ccc; }}
.grid {{ display: grid; grid-template-columns: repeat(auto-fill, minmax(400px, 1fr)); gap: 1.2em; }}
.card {{ background: #fff; border-radius: 6px; box-shadow: 0 1px 3px #0002; padding: 0.8em; }}
.card img {{ width: 100%; height: auto; border-radius: 4px; }}
.card h3 {{ margin: 0.4em 0 0.2em; font-size: 1.05em; }}
.card p {{ margin: 0.3em 0; font-size: 0.9em; color: #444; }}
table {{ border-collapse: collapse; font-size: 0.85em; margin: 0.3em 0; }}
td, th {{ padding: 0.1em 0.8em 0.1em 0; text-align: left; vertical-align: top; }}
td.n {{ text-align: right; font-variant-numeric: tabular-nums; }}
.files a {{ margin-right: 0.8em; font-size: 0.85em; }}
.scroll {{ max-height: 12em; overflow-y: auto; display: inline-block; }}
footer {{ margin: 2em 0; font-size: 0.85em; color: #666; }}
</style>
</head>
<body>
<h1>splinekit gallery</h1>
<p>Made by <code>splinekit gallery</code> (splinekit {version}) from the examples bundled with it: {n} entries, {files} files, pictures {w}×{h}, in {time} in all. Every mesh is linked as OBJ and glb; the pictures are drawn on the CPU.</p>
"#,
        version = env!("CARGO_PKG_VERSION"),
        n = entries.len(),
        files = total_files,
        w = options.size.width,
        h = options.size.height,
        time = format_duration(elapsed),
    );
    for section in Section::ALL {
        let in_section: Vec<&Entry> = entries.iter().filter(|e| e.section == section).collect();
        if in_section.is_empty() {
            continue;
        }
        let _ = writeln!(html, "<h2>{}</h2>\n<div class=\"grid\">", escape(section.title()));
        for entry in in_section {
            card(&mut html, entry, &pictures[&entry.picture]);
        }
        html.push_str("</div>\n");
    }
    html.push_str("<footer>Timings are wall-clock times of this run on this machine.</footer>\n</body>\n</html>\n");
    html
}

/// One entry's card.
fn card(html: &mut String, entry: &Entry, png: &[u8]) {
    let _ = writeln!(
        html,
        "<div class=\"card\">\n<a href=\"{src}\"><img src=\"data:image/png;base64,{data}\" alt=\"{alt}\"></a>\n<h3>{title}</h3>\n<p>{caption}</p>",
        src = escape(&entry.picture),
        data = base64(png),
        alt = escape(&entry.title),
        title = escape(&entry.title),
        caption = escape(&entry.caption),
    );
    html.push_str("<table>\n");
    for (name, value) in &entry.facts {
        let _ = writeln!(html, "<tr><td>{}</td><td class=\"n\">{}</td></tr>", escape(name), escape(value));
    }
    for (step, time) in &entry.timings {
        let _ = writeln!(html, "<tr><td>{}</td><td class=\"n\">{}</td></tr>", escape(step), format_duration(*time));
    }
    html.push_str("</table>\n");
    if let Some((header, rows)) = &entry.table {
        html.push_str("<div class=\"scroll\"><table>\n<tr>");
        for h in header {
            let _ = write!(html, "<th>{}</th>", escape(h));
        }
        html.push_str("</tr>\n");
        for row in rows {
            html.push_str("<tr>");
            for cell in row {
                let _ = write!(html, "<td class=\"n\">{}</td>", escape(cell));
            }
            html.push_str("</tr>\n");
        }
        html.push_str("</table></div>\n");
    }
    html.push_str("<div class=\"files\">");
    for file in std::iter::once(&entry.picture).chain(&entry.files) {
        let label = file.rsplit('/').next().unwrap_or(file);
        let _ = write!(html, "<a href=\"{}\">{}</a>", escape(file), escape(label));
    }
    html.push_str("</div>\n</div>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64(plain.as_bytes()), encoded, "{plain:?}");
        }
        assert_eq!(base64(&[0xff, 0xfe, 0xfd]), "//79");
    }

    #[test]
    fn names_and_numbers() {
        assert_eq!(file_stem("gcyl/weird.swp"), "weird");
        assert_eq!(safe_name("a b/c.d"), "a_b_c_d");
        assert_eq!(group_digits(1_234_567), "1\u{2009}234\u{2009}567");
        assert_eq!(group_digits(999), "999");
        assert_eq!(escape("<a & \"b\">"), "&lt;a &amp; &quot;b&quot;&gt;");
        assert_eq!(format_duration(Duration::from_micros(420)), "0.42 ms");
        assert_eq!(format_duration(Duration::from_millis(1250)), "1.25 s");
    }
}
