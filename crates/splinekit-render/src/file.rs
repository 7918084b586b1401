//! Pictures of files: [`render_file`] reads an SWP or mesh file and chooses the picture.
//!
//! - **SWP with surfaces**: a 3D picture ([`render_scene`](crate::render_scene)): every surface swept with the
//!   default [`SurfaceOptions`] and shaded, and every curve of the file drawn in 3D with its
//!   control polygon (hidden where a surface is in front of it).
//! - **SWP with only curves**: a 2D plot ([`plot_curves`]), orthographic; the default view is
//!   `front` (the xy-plane) when every curve is 2D and `iso` otherwise.
//! - **Mesh** (`.obj`, `.ply`, `.stl`): a 3D picture of the mesh ([`render_mesh`](crate::render_mesh)).
//!
//! The output is PNG, or SVG for a 2D plot.
//!
//! [`FileOptions::colour`] colours 3D pictures by curvature, UV checker or subdivision level
//! ([`SurfaceColour`]). For the UV checker, SWP surfaces are swept with arc-length UVs (their
//! seams split) and a mesh keeps its face-varying UVs (a vertex on a seam split in two,
//! [`PolyMesh::to_tri_mesh_with_seams`](splinekit::PolyMesh::to_tri_mesh_with_seams)); a
//! picture with no UVs at all is an error, [`RenderError::NoTextureCoordinates`].

use std::path::Path;

use splinekit::TriMesh;
use splinekit::sweep::SweepOptions;
use splinekit_io::surface::SurfaceOptions;
use splinekit_io::{MeshFormat, SwpDocument};

use crate::RenderError;
use crate::camera::{View, bounding_radius};
use crate::colour::SurfaceColour;
use crate::image::{Image, ImageSize};
use crate::legend::Legend;
use crate::marks::{CurveOptions, Mark, PlotCurve, Theme, curve_marks};
use crate::plot::{PlotOptions, plot_curves, plot_curves_svg};
use crate::raster::{RenderOptions, Renderer};

/// A picture format, chosen by the output's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PictureFormat {
    /// `.png`
    Png,
    /// `.svg` (2D plots only)
    Svg,
}

impl PictureFormat {
    /// The format named by `path`'s extension (case-insensitive).
    ///
    /// # Errors
    /// [`RenderError::UnknownOutput`] for any other extension.
    pub fn from_path(path: &Path) -> Result<Self, RenderError> {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("png") => Ok(Self::Png),
            Some("svg") => Ok(Self::Svg),
            _ => Err(RenderError::UnknownOutput { path: path.display().to_string(), extension: extension_of(path) }),
        }
    }
}

/// A finished picture.
#[derive(Clone, Debug, PartialEq)]
pub enum Picture {
    /// Pixels (PNG output).
    Image(Image),
    /// An SVG document.
    Svg(String),
}

impl Picture {
    /// Writes the picture (PNG or SVG text) to `path` through a temporary file and a rename.
    ///
    /// # Errors
    /// Encoding or writing errors, naming `path`.
    pub fn write(&self, path: &Path) -> Result<(), RenderError> {
        match self {
            Self::Image(image) => image.write_png(path),
            Self::Svg(text) => crate::image::write_bytes(path, text.as_bytes()),
        }
    }
}

/// What a file held, and which picture was made of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PictureKind {
    /// A 3D picture of an SWP file's surfaces (and curves).
    Surfaces,
    /// A 2D plot of an SWP file's curves.
    CurvePlot,
    /// A 3D picture of a mesh file.
    Mesh,
}

/// What [`render_file`] drew.
#[derive(Clone, Debug, PartialEq)]
pub struct Rendered {
    /// The picture.
    pub picture: Picture,
    /// Which kind of picture.
    pub kind: PictureKind,
    /// The view used.
    pub view: View,
    /// Surfaces or meshes drawn.
    pub num_surfaces: usize,
    /// Curves drawn.
    pub num_curves: usize,
    /// Triangles drawn.
    pub num_triangles: usize,
    /// What the colours stand for (curvature and level colourings), as drawn in the picture.
    pub legend: Option<Legend>,
}

/// Options of [`render_file`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct FileOptions {
    /// Picture size.
    pub size: ImageSize,
    /// View; `None` chooses (iso, or front for a plot of 2D curves).
    pub view: Option<View>,
    /// Wireframe over surfaces and meshes.
    pub wireframe: bool,
    /// What to draw with curves.
    pub curves: CurveOptions,
    /// What colours surfaces and meshes (3D pictures).
    pub colour: SurfaceColour,
}

impl FileOptions {
    /// 800×600, the chosen view, no wireframe, control polygons, shaded surfaces.
    pub const DEFAULT: Self = Self {
        size: ImageSize::DEFAULT,
        view: None,
        wireframe: false,
        curves: CurveOptions::DEFAULT,
        colour: SurfaceColour::Shade,
    };

    /// With this size.
    #[must_use]
    pub fn with_size(mut self, size: ImageSize) -> Self {
        self.size = size;
        self
    }

    /// With this view (`None`: chosen by content).
    #[must_use]
    pub fn with_view(mut self, view: Option<View>) -> Self {
        self.view = view;
        self
    }

    /// With or without the wireframe.
    #[must_use]
    pub fn with_wireframe(mut self, wireframe: bool) -> Self {
        self.wireframe = wireframe;
        self
    }

    /// With these curve options.
    #[must_use]
    pub fn with_curves(mut self, curves: CurveOptions) -> Self {
        self.curves = curves;
        self
    }

    /// With this colouring of surfaces and meshes.
    #[must_use]
    pub fn with_colour(mut self, colour: SurfaceColour) -> Self {
        self.colour = colour;
        self
    }
}

impl Default for FileOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Reads `input` and draws it in `format`. See the [module docs](self).
///
/// # Errors
/// An unknown input extension, a file that cannot be read or parsed, a curve or surface that
/// cannot be built, a file with nothing to draw, a bad marker spacing, SVG asked for a 3D
/// picture, or the UV checker asked for a file without texture coordinates.
pub fn render_file(input: &Path, format: PictureFormat, options: &FileOptions) -> Result<Rendered, RenderError> {
    if let Some(spacing) = options.curves.marker_spacing
        && !(spacing > 0.0 && spacing.is_finite())
    {
        return Err(RenderError::BadMarkerSpacing(spacing));
    }
    let path = input.display().to_string();
    let is_swp = input.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("swp"));
    if is_swp {
        return render_swp(input, &path, format, options);
    }
    if MeshFormat::from_path(input).is_none() {
        return Err(RenderError::UnknownInput { path, extension: extension_of(input) });
    }
    if format == PictureFormat::Svg {
        return Err(RenderError::SvgOf3d { path, what: "a mesh" });
    }
    let loaded = splinekit_io::load_mesh(input)?;
    let mesh = if options.colour == SurfaceColour::UvChecker {
        loaded.mesh.to_tri_mesh_with_seams()
    } else {
        loaded.mesh.to_tri_mesh()
    };
    render_tri_mesh(&mesh, &path, options)
}

/// Draws a mesh already in memory as [`render_file`] draws a mesh file (a PNG picture);
/// `path` names it in errors. For the UV checker, give it per-vertex UVs (a mesh read from a
/// file: [`PolyMesh::to_tri_mesh_with_seams`](splinekit::PolyMesh::to_tri_mesh_with_seams)).
///
/// # Errors
/// [`RenderError::Empty`] for a mesh without triangles, [`RenderError::NoTextureCoordinates`]
/// for the UV checker on a mesh without UVs.
pub fn render_tri_mesh(mesh: &TriMesh, path: &str, options: &FileOptions) -> Result<Rendered, RenderError> {
    if mesh.triangles.is_empty() {
        return Err(RenderError::Empty { path: path.to_string(), what: "the mesh has no faces" });
    }
    if options.colour == SurfaceColour::UvChecker && mesh.uvs.len() != mesh.positions.len() {
        return Err(RenderError::NoTextureCoordinates { path: path.to_string() });
    }
    let view = options.view.unwrap_or_default();
    let (image, legend) = Renderer::new().render_with_legend(&[mesh], &[], &render_options(options, view));
    Ok(Rendered {
        picture: Picture::Image(image),
        kind: PictureKind::Mesh,
        view,
        num_surfaces: 1,
        num_curves: 0,
        num_triangles: mesh.triangles.len(),
        legend,
    })
}

fn render_options(options: &FileOptions, view: View) -> RenderOptions {
    RenderOptions::DEFAULT
        .with_size(options.size)
        .with_view(view)
        .with_wireframe(options.wireframe)
        .with_colour(options.colour)
}

/// The most triangles a picture of an SWP file's surfaces draws, all surfaces together (about
/// 2.5 GB of meshes and renderer buffers at the peak): a file whose surfaces would have more is
/// refused, from their sample counts, before any is built.
pub const MAX_SCENE_TRIANGLES: usize = 20_000_000;

fn render_swp(input: &Path, path: &str, format: PictureFormat, options: &FileOptions) -> Result<Rendered, RenderError> {
    let doc = SwpDocument::read(input)?;
    let base = SurfaceOptions {
        sweep: SweepOptions { uvs: options.colour == SurfaceColour::UvChecker, ..SweepOptions::default() },
        ..SurfaceOptions::default()
    };
    // one budget for the whole scene: each surface gets what the ones before it left
    let mut meshes = Vec::with_capacity(doc.surfaces.len());
    let mut left = MAX_SCENE_TRIANGLES;
    for i in 0..doc.surfaces.len() {
        let surface_options = SurfaceOptions { max_triangles: Some(left), ..base };
        let mesh = doc
            .surface_mesh(i, &surface_options)
            .map_err(|error| RenderError::Surface { path: path.to_string(), error })?;
        left = left.saturating_sub(mesh.num_triangles());
        meshes.push(mesh);
    }
    render_swp_document(&doc, &meshes, path, format, options)
}

/// Every surface of `doc` swept with the default [`SurfaceOptions`] (as `splinekit sweep`
/// does), in file order; `path` names the file in errors.
///
/// # Errors
/// [`RenderError::Surface`] for the first surface that cannot be swept.
pub fn sweep_surfaces(doc: &SwpDocument, path: &str) -> Result<Vec<TriMesh>, RenderError> {
    sweep_surfaces_with(doc, path, &SurfaceOptions::default())
}

/// Every surface of `doc` swept with `options` (for example with UVs, for the UV checker),
/// in file order; `path` names the file in errors.
///
/// # Errors
/// [`RenderError::Surface`] for the first surface that cannot be swept.
pub fn sweep_surfaces_with(
    doc: &SwpDocument,
    path: &str,
    options: &SurfaceOptions,
) -> Result<Vec<TriMesh>, RenderError> {
    (0..doc.surfaces.len())
        .map(|i| doc.surface_mesh(i, options).map_err(|error| RenderError::Surface { path: path.to_string(), error }))
        .collect()
}

/// Draws a parsed SWP document whose surfaces are already swept (`meshes`, one per surface
/// of `doc`, e.g. from [`sweep_surfaces`]), as [`render_file`] draws an SWP file; `path` names
/// the document in errors.
///
/// # Errors
/// As [`render_file`] for an SWP file, after parsing.
pub fn render_swp_document(
    doc: &SwpDocument,
    meshes: &[TriMesh],
    path: &str,
    format: PictureFormat,
    options: &FileOptions,
) -> Result<Rendered, RenderError> {
    if let Some(spacing) = options.curves.marker_spacing
        && !(spacing > 0.0 && spacing.is_finite())
    {
        return Err(RenderError::BadMarkerSpacing(spacing));
    }
    if doc.curves.is_empty() && doc.surfaces.is_empty() {
        return Err(RenderError::Empty { path: path.to_string(), what: "no curves or surfaces" });
    }
    let curves = doc
        .curves
        .iter()
        .enumerate()
        .map(|(i, c)| {
            PlotCurve::from_swp(c, i).map_err(|error| RenderError::Curve {
                path: path.to_string(),
                curve: c.display_name(i),
                error,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if doc.surfaces.is_empty() {
        let all_2d = doc.curves.iter().all(|c| c.dim != 3);
        let view = options.view.unwrap_or(if all_2d { View::Front } else { View::Iso });
        let plot = PlotOptions::DEFAULT.with_size(options.size).with_view(view);
        let picture = match format {
            PictureFormat::Png => Picture::Image(plot_curves(&curves, &options.curves, &plot)),
            PictureFormat::Svg => Picture::Svg(plot_curves_svg(&curves, &options.curves, &plot)),
        };
        return Ok(Rendered {
            picture,
            kind: PictureKind::CurvePlot,
            view,
            num_surfaces: 0,
            num_curves: curves.len(),
            num_triangles: 0,
            legend: None,
        });
    }
    if format == PictureFormat::Svg {
        return Err(RenderError::SvgOf3d { path: path.to_string(), what: "surfaces" });
    }
    if options.colour == SurfaceColour::UvChecker && meshes.iter().all(|m| m.uvs.len() != m.positions.len()) {
        return Err(RenderError::NoTextureCoordinates { path: path.to_string() });
    }
    let view = options.view.unwrap_or_default();
    let radius = bounding_radius(
        meshes.iter().flat_map(|m| m.positions.iter().copied()).chain(curves.iter().flat_map(PlotCurve::bound_points)),
    );
    let marks: Vec<Mark> = curve_marks(&curves, &options.curves, Theme::Dark, radius, None);
    let refs: Vec<&TriMesh> = meshes.iter().collect();
    let (image, legend) = Renderer::new().render_with_legend(&refs, &marks, &render_options(options, view));
    Ok(Rendered {
        picture: Picture::Image(image),
        kind: PictureKind::Surfaces,
        view,
        num_surfaces: meshes.len(),
        num_curves: curves.len(),
        num_triangles: meshes.iter().map(|m| m.triangles.len()).sum(),
        legend,
    })
}

/// `.ext` of `path`, or `no extension`.
fn extension_of(path: &Path) -> String {
    path.extension().map_or_else(|| String::from("no extension"), |e| format!(".{}", e.to_string_lossy()))
}
