//! SWP documents and the spline-annotated OBJ of the CS 4620 revolution and sweep tools,
//! both ways: [`SwpDocument::annotated_header`] and [`SwpDocument::save_annotated_obj`] write a
//! `zrev` or `xsweep` surface as the tool's file, and [`SplineHeader::to_document`] opens such
//! a file as an editable document.
//!
//! The revolution tool's header describes a B-spline or uniform Catmull-Rom profile, open or
//! closed, tessellated by control-polygon angle `epsilon`, scaled and revolved about +z in
//! `ceil(2π / sliceTolerance)` slices — a `zrev` surface whose profile is a `bsp2` or a uniform
//! `cr2`. The sweep tool's describes two B-splines with their epsilons and a scale — an
//! `xsweep` of two `bsp2` curves. Other surfaces are refused with the reason, never written
//! approximately. The mesh written after the header is the surface swept with the given
//! options, so a file written with the defaults rebuilds (`splinekit sweep FILE.obj`) to the
//! very same mesh.
//!
//! ```
//! use splinekit_io::SwpDocument;
//! use splinekit_io::mesh::{RebuildOptions, SplineHeader};
//!
//! let doc = SwpDocument::parse("bsp2 p 10 4 [1 -1] [2 -1] [2 1] [1 1]\nzrev vase p scale 2\n", "v.swp")?;
//! let header = doc.revolution_header(0)?;
//! let mesh = doc.surface_mesh(0, &Default::default())?;
//! assert_eq!(SplineHeader::Revolution(header.clone()).rebuild(&RebuildOptions::DEFAULT)?, mesh);
//! // and back: the same curve and surface
//! let again = SplineHeader::Revolution(header).to_document("vase")?;
//! assert_eq!(again.surfaces[0].kind, doc.surfaces[0].kind);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::Path;

use glam::{DVec2, DVec3};
use splinekit::TriMesh;

use crate::mesh::{HeaderSpline, MeshIoError, RevolutionHeader, SplineHeader, SweepHeader, save_annotated_obj};
use crate::surface::{SurfaceError, SurfaceOptions};
use crate::swp::{
    SourcePos, SwpCurve, SwpCurveKind, SwpDocument, SwpGeometry, SwpSurface, SwpSurfaceKind, SwpSurfaceSettings,
};

/// Steps of the profile curve of a document opened from an annotated OBJ (used to draw it;
/// the surface uses the header's `epsilon`).
pub const OPENED_PROFILE_STEPS: u32 = 16;

/// Why a surface cannot be written as, or a header opened as, an annotated OBJ document.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AnnotatedError {
    /// The revolution tool's header cannot describe the surface.
    #[error("surface {surface} cannot be written as an annotated OBJ: {why}")]
    Unsupported {
        /// Display name of the surface.
        surface: String,
        /// Why, and what would do.
        why: String,
    },
    /// The surface could not be swept.
    #[error(transparent)]
    Surface(#[from] SurfaceError),
    /// Writing failed.
    #[error(transparent)]
    Write(#[from] MeshIoError),
}

impl SwpDocument {
    /// The revolution tool's header of surface `index`: a `zrev` whose profile is a `bsp2` or
    /// a uniform (`alpha 0`) `cr2`, with its `epsilon`, slice tolerance and scale.
    ///
    /// # Errors
    /// [`AnnotatedError::Unsupported`] for another kind of surface or profile, or an index
    /// out of range.
    pub fn revolution_header(&self, index: usize) -> Result<RevolutionHeader, AnnotatedError> {
        let unsupported = |why: String| AnnotatedError::Unsupported {
            surface: self.surfaces.get(index).map_or_else(|| format!("#{index}"), |s| s.display_name(index)),
            why,
        };
        let surface = self.surfaces.get(index).ok_or_else(|| unsupported("there is no such surface".into()))?;
        let SwpSurfaceKind::RevolutionZ { profile, epsilon, slice_tolerance, scale } = surface.kind else {
            return Err(unsupported(format!(
                "the revolution tool's file holds only a revolution about +z (zrev), and this surface is {}",
                surface.kind.keyword()
            )));
        };
        if surface.settings.tessellation.is_some() {
            return Err(unsupported(
                "it has its own tolerance; the revolution tool's file holds an angle tolerance epsilon and a slice \
                 tolerance only"
                    .into(),
            ));
        }
        let curve = self.curves.get(profile).ok_or_else(|| unsupported("its profile does not exist".into()))?;
        let is_bspline = match curve.kind {
            SwpCurveKind::BSpline => true,
            SwpCurveKind::CatmullRom { alpha: 0.0 } => false,
            _ => {
                return Err(unsupported(format!(
                    "its profile {} is a {} curve; the revolution tool's file holds a B-spline (bsp2) or a \
                     uniform Catmull-Rom spline (cr2)",
                    curve.display_name(profile),
                    curve.keyword()
                )));
            }
        };
        let SwpGeometry::Points(points) = &curve.geometry else {
            return Err(unsupported("its profile has no control points".into()));
        };
        if curve.dim != 2 {
            return Err(unsupported("its profile is a 3D curve".into()));
        }
        Ok(RevolutionHeader {
            closed: curve.closed,
            epsilon,
            is_bspline,
            scale,
            slice_tolerance,
            control_points: points.iter().map(|p| p.truncate()).collect(),
        })
    }

    /// The header of either tool for surface `index`: the revolution tool's for a `zrev`
    /// ([`revolution_header`](Self::revolution_header)), the sweep tool's for an `xsweep`
    /// whose two curves are 2D `bsp2` curves (its epsilons and scale).
    ///
    /// # Errors
    /// [`AnnotatedError::Unsupported`] for another surface, another kind of curve, or an index
    /// out of range.
    pub fn annotated_header(&self, index: usize) -> Result<SplineHeader, AnnotatedError> {
        let Some(SwpSurface {
            kind: SwpSurfaceKind::ToolSweep { profile, path, epsilon, path_epsilon, scale }, ..
        }) = self.surfaces.get(index)
        else {
            return self.revolution_header(index).map(SplineHeader::Revolution).map_err(|e| match e {
                AnnotatedError::Unsupported { surface, why } => AnnotatedError::Unsupported {
                    surface,
                    why: why
                        .replace("holds only a revolution about +z (zrev)", "holds a zrev or an xsweep surface only"),
                },
                e => e,
            });
        };
        let spline = |i: usize, epsilon: f64| -> Result<HeaderSpline, AnnotatedError> {
            match self.curves.get(i) {
                Some(c) if c.kind == SwpCurveKind::BSpline && c.dim == 2 => match &c.geometry {
                    SwpGeometry::Points(points) => Ok(HeaderSpline {
                        closed: c.closed,
                        epsilon,
                        control_points: points.iter().map(|p| p.truncate()).collect(),
                    }),
                    _ => Err(self.unsupported(index, "its curves have no control points".into())),
                },
                Some(c) => Err(self.unsupported(
                    index,
                    format!(
                        "its curve {} is a {} curve; the sweep tool's file holds 2D B-splines (bsp2)",
                        c.display_name(i),
                        c.keyword()
                    ),
                )),
                None => Err(self.unsupported(index, "a curve it uses does not exist".into())),
            }
        };
        let settings = &self.surfaces[index].settings;
        if settings.tessellation.is_some() {
            return Err(
                self.unsupported(index, "it has its own tolerance, which the sweep tool's file cannot hold".into())
            );
        }
        Ok(SplineHeader::Sweep(SweepHeader {
            cross_section: spline(*profile, *epsilon)?,
            swept_along: spline(*path, *path_epsilon)?,
            scale: *scale,
        }))
    }

    fn unsupported(&self, index: usize, why: String) -> AnnotatedError {
        let surface = self.surfaces.get(index).map_or_else(|| format!("#{index}"), |s| s.display_name(index));
        AnnotatedError::Unsupported { surface, why }
    }

    /// Writes surface `index` to `path` as an annotated OBJ of either tool: its
    /// [header](Self::annotated_header), then the surface swept with `options`. The file is
    /// written atomically; nothing is written on an error. Returns the mesh written.
    ///
    /// # Errors
    /// A surface the header cannot describe, a surface that cannot be swept, or a write error.
    pub fn save_annotated_obj(
        &self,
        index: usize,
        options: &SurfaceOptions,
        path: &Path,
    ) -> Result<TriMesh, AnnotatedError> {
        let header = self.annotated_header(index)?;
        let mesh = self.surface_mesh(index, options)?;
        save_annotated_obj(&header, &mesh, path)?;
        Ok(mesh)
    }
}

impl SplineHeader {
    /// The editable document of a header, whose surface's mesh is the header's
    /// [rebuild](SplineHeader::rebuild): for the revolution tool, its profile as a `bsp2` or
    /// `cr2` curve named `profile` and a `zrev` surface with the header's `epsilon`, slice
    /// tolerance and scale; for the sweep tool, `bsp2` curves `profile` and `path` and an
    /// `xsweep` surface with its epsilons and scale. The surface is named `surface_name` (or
    /// `surface` when that is not a usable name); curves are drawn with
    /// [`OPENED_PROFILE_STEPS`] steps.
    ///
    /// # Errors
    /// None today (the result keeps room for headers that have no editable form).
    pub fn to_document(&self, surface_name: &str) -> Result<SwpDocument, AnnotatedError> {
        let usable = !surface_name.is_empty()
            && !["profile", "path", "."].contains(&surface_name)
            && !surface_name.chars().any(|c| c.is_whitespace() || "[]#".contains(c));
        let name = if usable { surface_name.to_owned() } else { "surface".to_owned() };
        let h = match self {
            Self::Revolution(h) => h,
            Self::Sweep(h) => return Ok(sweep_document(h, name)),
        };
        let kind = if h.is_bspline { SwpCurveKind::BSpline } else { SwpCurveKind::CatmullRom { alpha: 0.0 } };
        let points = h.control_points.iter().map(|&DVec2 { x, y }| DVec3::new(x, y, 0.0)).collect();
        let profile = SwpCurve {
            name: Some("profile".to_owned()),
            kind,
            dim: 2,
            steps: OPENED_PROFILE_STEPS,
            closed: h.closed,
            geometry: SwpGeometry::Points(points),
            pos: SourcePos::default(),
        };
        let surface = SwpSurface {
            name: Some(name),
            kind: SwpSurfaceKind::RevolutionZ {
                profile: 0,
                epsilon: h.epsilon,
                slice_tolerance: h.slice_tolerance,
                scale: h.scale,
            },
            settings: SwpSurfaceSettings::default(),
            pos: SourcePos::default(),
        };
        Ok(SwpDocument { curves: vec![profile], surfaces: vec![surface] })
    }
}

/// The editable document of a sweep tool's header: its cross-section and swept-along splines
/// as `bsp2` curves `profile` and `path`, and an `xsweep` surface called `name`.
fn sweep_document(h: &SweepHeader, name: String) -> SwpDocument {
    let curve = |name: &str, s: &HeaderSpline| SwpCurve {
        name: Some(name.to_owned()),
        kind: SwpCurveKind::BSpline,
        dim: 2,
        steps: OPENED_PROFILE_STEPS,
        closed: s.closed,
        geometry: SwpGeometry::Points(s.control_points.iter().map(|p| p.extend(0.0)).collect()),
        pos: SourcePos::default(),
    };
    let surface = SwpSurface {
        name: Some(name),
        kind: SwpSurfaceKind::ToolSweep {
            profile: 0,
            path: 1,
            epsilon: h.cross_section.epsilon,
            path_epsilon: h.swept_along.epsilon,
            scale: h.scale,
        },
        settings: SwpSurfaceSettings::default(),
        pos: SourcePos::default(),
    };
    SwpDocument {
        curves: vec![curve("profile", &h.cross_section), curve("path", &h.swept_along)],
        surfaces: vec![surface],
    }
}
