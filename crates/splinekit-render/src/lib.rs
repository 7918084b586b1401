//! Headless pictures for splinekit: meshes, swept surfaces and curves drawn on the CPU, with
//! no display and no GPU, the same bytes on every run.
//!
//! - **3D** ([`render_mesh`], [`render_scene`], [`Renderer`]): a rasterizer of our own with a
//!   depth buffer, 2×2 supersampling, per-pixel lighting, front and back faces in different
//!   colours and an optional wireframe with hidden lines removed ([module `raster`](raster)).
//!   Curves, control polygons, frames and markers are [`Mark`]s drawn in the same depth
//!   buffer. Surfaces can be coloured by mean or Gaussian curvature, a UV checker or
//!   subdivision level instead of one colour ([`SurfaceColour`]), with a [`Legend`] drawn
//!   into the picture in a small built-in bitmap font.
//! - **2D** ([`plot_curves`], [`plot_curves_svg`]): curves coloured by segment with control
//!   polygons, frames and arc-length markers, drawn with tiny-skia or written as SVG.
//! - **Files** ([`render_file`]): reads SWP or mesh files and picks the picture (3D when the
//!   SWP file has surfaces, a 2D plot when it has only curves).
//!
//! Pictures are [`Image`]s (RGBA8) with a deterministic PNG encoding; file writes go through a
//! temporary file and a rename.
//!
//! # Render a mesh
//!
//! ```
//! use splinekit_render::{ImageSize, RenderOptions, View, render_mesh};
//! # let mesh = splinekit::TriMesh {
//! #     positions: vec![glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::Y],
//! #     triangles: vec![[0, 1, 2]],
//! #     ..Default::default()
//! # };
//! let options = RenderOptions::DEFAULT
//!     .with_size(ImageSize::new(160, 120).unwrap())
//!     .with_view(View::Front)
//!     .with_wireframe(true);
//! let image = render_mesh(&mesh, &options);
//! assert_eq!((image.width(), image.height()), (160, 120));
//! let png = image.encode_png()?;
//! assert_eq!(png, render_mesh(&mesh, &options).encode_png()?); // the same bytes every time
//! # Ok::<(), splinekit_render::RenderError>(())
//! ```
//!
//! # Plot curves
//!
//! ```
//! use splinekit_io::SwpDocument;
//! use splinekit_render::{CurveOptions, PlotCurve, PlotOptions, plot_curves, plot_curves_svg};
//!
//! let doc = SwpDocument::parse("bez2 arch 20 4 [0 0] [1 1] [2 1] [3 0]", "arch.swp")?;
//! let curves = vec![PlotCurve::from_swp(&doc.curves[0], 0)?];
//! let options = CurveOptions::DEFAULT.with_frames(true).with_marker_spacing(Some(0.25));
//! let image = plot_curves(&curves, &options, &PlotOptions::DEFAULT);
//! assert_eq!(image.width(), 800);
//! let svg = plot_curves_svg(&curves, &options, &PlotOptions::DEFAULT);
//! assert!(svg.contains("<polyline"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Feature flags
//!
//! - `parallel` (default): rasterize bands of rows and shade rows on rayon's thread pool.
//!   The pictures are the same with or without it.

pub mod camera;
pub mod colour;
mod error;
pub mod file;
mod font;
pub mod gallery;
pub mod image;
pub mod legend;
pub mod marks;
pub mod plot;
pub mod raster;

pub use camera::{Camera, DEFAULT_MARGIN, Projection, View, ViewError};
pub use colour::{
    CHECKER_COLOURS, CHECKER_SQUARES, Curvature, SurfaceColour, checker_colour, diverging_colour, level_colour,
    symmetric_scale,
};
pub use error::RenderError;
pub use file::{
    FileOptions, MAX_SCENE_TRIANGLES, Picture, PictureFormat, PictureKind, Rendered, render_file, render_swp_document,
    render_tri_mesh, sweep_surfaces, sweep_surfaces_with,
};
pub use gallery::{Gallery, GalleryOptions, write_gallery};
pub use image::{Image, ImageSize, MAX_SIDE, Rgb, SizeError};
pub use legend::Legend;
pub use marks::{CurveOptions, Mark, PlotCurve, SEGMENT_COLOURS, Theme, curve_marks};
pub use plot::{PlotOptions, draw_marks, marks_svg, plot_curves, plot_curves_svg};
pub use raster::{
    BACK_COLOUR, BACKGROUND, FRONT_COLOUR, RenderOptions, Renderer, Scene, Shading, WIRE_COLOUR, render_mesh,
    render_scene, surface_colours,
};
