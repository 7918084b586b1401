//! SWP documents and the spline-annotated OBJ of the CS 4620 revolution tool, both ways:
//! [`SwpDocument::revolution_header`] and [`SwpDocument::save_annotated_obj`] write a `zrev`
//! surface as the tool's file, and [`SplineHeader::to_document`] opens such a file as an
//! editable document.
//!
//! The tool's header can describe exactly one thing: a B-spline or uniform Catmull-Rom
//! profile, open or closed, tessellated by control-polygon angle `epsilon`, scaled and
//! revolved about +z in `ceil(2π / sliceTolerance)` slices — a `zrev` surface whose profile is
//! a `bsp2` or a uniform `cr2`. Other surfaces are refused with the reason, never written
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

use crate::mesh::{MeshIoError, RevolutionHeader, SplineHeader, save_revolution_obj};
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
    /// The header is a sweep tool's, which opens as a mesh only.
    #[error(
        "the sweep tool's header (a cross-section swept along a spline) has no editable form; \
         it opens as a mesh rebuilt from its splines"
    )]
    SweepHeader,
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

    /// Writes surface `index` to `path` as the revolution tool's annotated OBJ: its
    /// [header](Self::revolution_header), then the surface swept with `options`. The file is
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
        let header = self.revolution_header(index)?;
        let mesh = self.surface_mesh(index, options)?;
        save_revolution_obj(&header, &mesh, path)?;
        Ok(mesh)
    }
}

impl SplineHeader {
    /// The editable document of a revolution tool's header: its profile as a `bsp2` or `cr2`
    /// curve named `profile` (drawn with [`OPENED_PROFILE_STEPS`] steps) and a `zrev` surface
    /// named `surface_name` (or `surface` when that is not a usable name) with the header's
    /// `epsilon`, slice tolerance and scale, whose mesh is the header's
    /// [rebuild](SplineHeader::rebuild).
    ///
    /// # Errors
    /// [`AnnotatedError::SweepHeader`] for a sweep tool's header.
    pub fn to_document(&self, surface_name: &str) -> Result<SwpDocument, AnnotatedError> {
        let Self::Revolution(h) = self else { return Err(AnnotatedError::SweepHeader) };
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
        let usable = !surface_name.is_empty()
            && surface_name != "profile"
            && surface_name != "."
            && !surface_name.chars().any(|c| c.is_whitespace() || "[]#".contains(c));
        let surface = SwpSurface {
            name: Some(if usable { surface_name.to_owned() } else { "surface".to_owned() }),
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
