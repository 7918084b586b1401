//! Sweeping the surfaces of an SWP document into meshes ([`SwpDocument::surface_mesh`]).
//!
//! Each curve is tessellated ([`Tessellation`]), given frames (the sequential method of the
//! course software by default, with the closed-curve fix when its ends meet in position and
//! tangent), and handed to [`splinekit::sweep`].
//!
//! In the welded layout, sharp corners of a piecewise curve (a join whose two tangents differ
//! by more than [`CREASE_ANGLE`]) are sampled twice, once with each tangent, so the surface
//! gets a crease with sharp normals there; the compat layout keeps the course program's one
//! sample per point.

use glam::{DVec2, DVec3};
use splinekit::flatten::{self, Tessellation};
use splinekit::frame::{self, CurveSample, Frame, FrameMethod, FrameOptions, Side, StartNormal};
use splinekit::sweep::{self, MeshLayout, Profile, SweepOptions, SweepPath};
use splinekit::{AnyCurve, TriMesh};

use crate::swp::{SwpDocument, SwpSurfaceKind};

/// Joins whose tangents turn by more than this (radians, 1°) are creases.
pub const CREASE_ANGLE: f64 = std::f64::consts::PI / 180.0;

/// How curves are tessellated for a sweep.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum SurfaceTessellation {
    /// The `steps` of each curve in the file (and of each `srev`): the course program's counts.
    #[default]
    FileSteps,
    /// Adaptive: every polyline within this distance of its curve, and revolutions cut into
    /// enough slices that no chord strays further from the circle it approximates.
    Distance(f64),
    /// Adaptive by control-polygon angle (radians); revolutions use slices of at most this angle.
    Angle(f64),
}

/// Which frames carry the profile along a sweep curve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SurfaceFrames {
    /// The course program's sequential method (SPEC §1.5), with the closed-curve fix.
    #[default]
    Sequential,
    /// Rotation-minimizing frames (double reflection), closed-curve correction by arc length.
    RotationMinimizing,
}

/// Options for [`SwpDocument::surface_mesh`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceOptions {
    /// Vertex layout and UVs.
    pub sweep: SweepOptions,
    /// Tessellation of the curves.
    pub tessellation: SurfaceTessellation,
    /// Frames along sweep curves.
    pub frames: SurfaceFrames,
}

/// Why a surface could not be swept.
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    /// No surface with that index.
    #[error("no surface {0}")]
    NoSuchSurface(usize),
    /// A curve the surface uses does not compile.
    #[error("curve {curve}: {source}")]
    Curve {
        /// Display name of the curve.
        curve: String,
        /// What is wrong with it.
        source: splinekit::SplineError,
    },
    /// The profile of a surface is a 3D curve.
    #[error("profile {curve} of surface {surface} is 3D; a profile must be a 2D curve")]
    ProfileNot2d {
        /// Display name of the curve.
        curve: String,
        /// Display name of the surface.
        surface: String,
    },
    /// The sweep itself failed.
    #[error("surface {surface}: {source}")]
    Sweep {
        /// Display name of the surface.
        surface: String,
        /// What went wrong.
        source: sweep::SweepError,
    },
}

impl SwpDocument {
    /// The mesh of surface `index`.
    ///
    /// # Errors
    /// An unknown index, a curve that does not compile, a 3D profile, or a degenerate sweep.
    pub fn surface_mesh(&self, index: usize, options: &SurfaceOptions) -> Result<TriMesh, SurfaceError> {
        let surface = self.surfaces.get(index).ok_or(SurfaceError::NoSuchSurface(index))?;
        let surface_name = surface.display_name(index);
        let curve = |i: usize| {
            self.curves[i]
                .to_curve()
                .map_err(|source| SurfaceError::Curve { curve: self.curves[i].display_name(i), source })
        };
        let profile_of = |i: usize| -> Result<Profile, SurfaceError> {
            if self.curves[i].dim == 3 {
                return Err(SurfaceError::ProfileNot2d {
                    curve: self.curves[i].display_name(i),
                    surface: surface_name.clone(),
                });
            }
            let c = curve(i)?;
            let samples = sample_curve(&c, self.curves[i].steps, options);
            let frames = frames_for(&samples, SurfaceFrames::Sequential);
            Ok(Profile {
                points: samples.iter().map(|s| s.position.truncate()).collect(),
                normals: frames.iter().map(|f| f.n.truncate().try_normalize().unwrap_or(DVec2::Y)).collect(),
            })
        };
        let sweep_err = |source| SurfaceError::Sweep { surface: surface_name.clone(), source };
        match surface.kind {
            SwpSurfaceKind::Revolution { steps, profile } => {
                let prof = profile_of(profile)?;
                let steps = revolution_steps(&prof, steps, options.tessellation);
                sweep::revolve(&prof, steps, options.sweep).map_err(sweep_err)
            }
            SwpSurfaceKind::GeneralizedCylinder { profile, sweep: path } => {
                let prof = profile_of(profile)?;
                let c = curve(path)?;
                let samples = sample_curve(&c, self.curves[path].steps, options);
                let frames = frames_for(&samples, options.frames);
                let path =
                    SweepPath { positions: samples.iter().map(|s| s.position).collect(), frames, scales: Vec::new() };
                sweep::generalized_cylinder(&prof, &path, options.sweep).map_err(sweep_err)
            }
        }
    }
}

/// Slices around the axis: the file's steps, or enough for the tolerance at the largest radius.
fn revolution_steps(profile: &Profile, file_steps: u32, mode: SurfaceTessellation) -> usize {
    let radius = profile.points.iter().map(|p| p.x.abs()).fold(0.0, f64::max);
    let from_angle = |a: f64| (std::f64::consts::TAU / a).ceil();
    let n = match mode {
        SurfaceTessellation::FileSteps => return file_steps.max(1) as usize,
        // a chord of angle θ strays r·(1 − cos(θ/2)) from its circle
        SurfaceTessellation::Distance(tol) if radius > tol && tol > 0.0 => {
            from_angle(2.0 * (1.0 - tol / radius).clamp(-1.0, 1.0).acos())
        }
        SurfaceTessellation::Distance(_) => 3.0,
        SurfaceTessellation::Angle(a) if a > 0.0 => from_angle(a),
        SurfaceTessellation::Angle(_) => 3.0,
    };
    n.clamp(3.0, f64::from(crate::MAX_STEPS)) as usize
}

/// Tessellates a curve and samples positions and unit tangents; in the welded layout, sharp
/// joins are sampled twice (incoming and outgoing tangent).
fn sample_curve(curve: &AnyCurve<DVec3>, steps: u32, options: &SurfaceOptions) -> Vec<CurveSample> {
    let mode = match options.tessellation {
        SurfaceTessellation::FileSteps => Tessellation::Uniform { steps: steps.max(1) as usize },
        SurfaceTessellation::Distance(tolerance) => Tessellation::Distance { tolerance },
        SurfaceTessellation::Angle(tolerance) => Tessellation::Angle { tolerance },
    };
    let params = flatten::flatten_any(curve, mode);
    match curve {
        AnyCurve::Piecewise(pc) if options.sweep.layout == MeshLayout::Welded => {
            frame::sample_with_corners(pc, &params, CREASE_ANGLE)
        }
        _ => frame::sample(curve, &params),
    }
}

fn frames_for(samples: &[CurveSample], method: SurfaceFrames) -> Vec<Frame> {
    let method = match method {
        SurfaceFrames::Sequential => FrameMethod::Sequential(Side::Left),
        SurfaceFrames::RotationMinimizing => FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left)),
    };
    frame::frames_for_samples(samples, &FrameOptions::DEFAULT.with_method(method))
}
