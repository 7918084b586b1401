//! Mesh files: readers and writers for OBJ, binary glTF, PLY and STL, atomic file writes,
//! and the spline-annotated OBJ header of the CS 4620 revolution and sweep tools.
//!
//! The readers, [`read_obj`], [`read_glb`], [`read_ply`] and [`read_stl`] (or [`load_mesh`],
//! which picks one by the extension of a path, and [`read_mesh`]), give a [`LoadedMesh`]: a
//! [`PolyMesh`] and warnings about what was skipped or dropped.
//!
//! Every writer takes a [`TriMesh`] and comes in two forms:
//!
//! - a stream writer, `write_obj` / `write_glb` / `write_ply` / `write_stl` (or
//!   [`write_mesh`] with a [`MeshFormat`]), for any [`Write`];
//! - a path-level [`save`], which writes through [`atomic::write_file`]: the file appears
//!   complete or not at all, and errors name the path.
//!
//! | format | contents | precision |
//! |---|---|---|
//! | [OBJ](write_obj) | `v`, `vn`, `vt`, `f a/b/c` (by which attributes exist) | `f64`, shortest round-trip text |
//! | [binary glTF](write_glb) | one scene, node and mesh; positions (with min/max), normals, UVs, `u32` indices | `f32` |
//! | [PLY](write_ply) | binary little endian; `x y z [nx ny nz] [u v]`, faces as `uchar int` lists | `f32` |
//! | [STL](write_stl) | binary; face normals computed from the triangles | `f32` |
//!
//! All writers are deterministic: the same mesh gives the same bytes, on every machine and in
//! every locale. They validate the mesh first ([`TriMesh::validate`]) and write nothing if it
//! is invalid.
//!
//! ```
//! use glam::DVec3;
//! use splinekit::TriMesh;
//! use splinekit_io::mesh::{MeshFormat, save};
//!
//! let mesh = TriMesh {
//!     positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
//!     triangles: vec![[0, 1, 2]],
//!     ..TriMesh::default()
//! };
//! # let dir = std::env::temp_dir().join(format!("splinekit-mesh-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir)?;
//! let path = dir.join("triangle.stl");
//! let format = MeshFormat::from_path(&path).unwrap();
//! save(&mesh, &path, format)?;
//! assert_eq!(std::fs::metadata(&path)?.len(), 84 + 50);
//!
//! // Errors name the path, and leave no file behind.
//! let err = save(&mesh, dir.join("missing/triangle.stl"), MeshFormat::Stl).unwrap_err();
//! assert!(err.to_string().contains("missing/triangle.stl: cannot create temporary file"));
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The OBJ files of the CS 4620 spline tools keep the spline that made the mesh in their
//! leading comments ([`revolution_obj`] describes the layout); [`SplineHeader`] reads both
//! kinds, [`SplineHeader::rebuild`] rebuilds the mesh from the header alone (module [`rebuild`]
//! describes the tools' rules, deduced from their files), and
//! [`write_revolution_obj`] writes the revolution kind.

pub mod atomic;
mod error;
mod glb;
mod glb_read;
mod load;
mod obj;
mod obj_read;
mod ply;
mod ply_read;
pub mod rebuild;
pub mod revolution_obj;
mod stl;
mod stl_read;
mod tags;

use std::io::Write;
use std::path::Path;

use splinekit::subdiv::Creases;
use splinekit::{PolyMesh, TriMesh};

pub use error::{MeshIoError, MeshIoErrorKind};
pub use glb::write_glb;
pub use glb_read::read_glb;
pub use load::{LoadedMesh, MAX_WARNINGS, ReadWarning, ReadWarningKind, load_mesh, read_mesh};
pub use obj::{write_obj, write_obj_poly};
pub use obj_read::read_obj;
pub use ply::{write_ply, write_ply_poly};
pub use ply_read::read_ply;
pub use rebuild::{RebuildError, RebuildOptions};
pub use revolution_obj::{
    HeaderSpline, RevolutionHeader, SplineHeader, SweepHeader, save_annotated_obj, save_revolution_obj,
    stage_annotated_obj, write_revolution_obj,
};
pub use stl::write_stl;
pub use stl_read::read_stl;
pub use tags::{BoundaryInterpolation, SubdivTags, read_creases, write_creases};

/// Size of the internal output buffer of the writers.
const BUFFER_SIZE: usize = 1 << 16;

/// A mesh file format, read by [`load_mesh`] and written by [`save`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshFormat {
    /// Wavefront OBJ text ([`write_obj`]).
    Obj,
    /// Binary glTF 2.0 ([`write_glb`]).
    Glb,
    /// Binary little-endian PLY ([`write_ply`]).
    Ply,
    /// Binary STL ([`write_stl`]).
    Stl,
}

impl MeshFormat {
    /// Every format, in the order of the variants.
    pub const ALL: [Self; 4] = [Self::Obj, Self::Glb, Self::Ply, Self::Stl];

    /// The usual file extension, lowercase and without the dot: `obj`, `glb`, `ply` or `stl`.
    #[must_use]
    pub const fn extension(self) -> &'static str {
        match self {
            Self::Obj => "obj",
            Self::Glb => "glb",
            Self::Ply => "ply",
            Self::Stl => "stl",
        }
    }

    /// The format with this extension or name (`obj`, `glb`, `ply`, `stl`, in any case,
    /// with or without a leading dot), or `None`.
    #[must_use]
    pub fn from_extension(extension: &str) -> Option<Self> {
        let extension = extension.strip_prefix('.').unwrap_or(extension);
        Self::ALL.into_iter().find(|f| f.extension().eq_ignore_ascii_case(extension))
    }

    /// The format named by the extension of `path` (`vase.GLB` gives [`Glb`](Self::Glb)), or
    /// `None` if the path has no known extension.
    #[must_use]
    pub fn from_path(path: impl AsRef<Path>) -> Option<Self> {
        path.as_ref().extension().and_then(|e| e.to_str()).and_then(Self::from_extension)
    }

    /// What the format is, in a few words, for lists of formats (`--help`, dialogs).
    #[must_use]
    pub const fn description(self) -> &'static str {
        match self {
            Self::Obj => "Wavefront OBJ (text)",
            Self::Glb => "binary glTF 2.0",
            Self::Ply => "PLY (binary little endian)",
            Self::Stl => "binary STL",
        }
    }

    /// What a file of this format keeps of a mesh, as splinekit writes and reads it.
    #[must_use]
    pub const fn capabilities(self) -> FormatCapabilities {
        let all = FormatCapabilities {
            reads: true,
            writes: true,
            polygons: true,
            normals: Carries::PerCorner,
            uvs: Carries::PerCorner,
            colours: true,
            creases: false,
        };
        match self {
            Self::Obj => FormatCapabilities { creases: true, ..all },
            Self::Ply => FormatCapabilities { normals: Carries::PerVertex, ..all },
            Self::Glb => {
                FormatCapabilities { polygons: false, normals: Carries::PerVertex, uvs: Carries::PerVertex, ..all }
            }
            Self::Stl => {
                FormatCapabilities { polygons: false, normals: Carries::No, uvs: Carries::No, colours: false, ..all }
            }
        }
    }

    /// `obj, glb, ply, stl`: the formats' extensions, for messages.
    #[must_use]
    pub fn list() -> String {
        Self::ALL.map(Self::extension).join(", ")
    }
}

/// What a [`MeshFormat`] holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct FormatCapabilities {
    /// [`load_mesh`] reads it.
    pub reads: bool,
    /// [`save`] and [`save_poly`] write it.
    pub writes: bool,
    /// Faces of any number of corners (else triangles: polygons are fanned).
    pub polygons: bool,
    /// Normals.
    pub normals: Carries,
    /// Texture coordinates.
    pub uvs: Carries,
    /// One colour a vertex.
    pub colours: bool,
    /// OpenSubdiv's crease tags.
    pub creases: bool,
}

/// How a format holds an attribute.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Carries {
    /// Not at all.
    No,
    /// One value a vertex: a vertex whose corners differ is written once per value (a seam).
    PerVertex,
    /// A value per face corner, so a vertex on a seam stays one vertex.
    PerCorner,
}

impl std::fmt::Display for MeshFormat {
    /// The extension, like `glb`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.extension())
    }
}

/// Writes `mesh` to `out` in `format`; see [`write_obj`], [`write_glb`], [`write_ply`] and
/// [`write_stl`] for the layouts.
///
/// # Errors
///
/// As the format's writer: an invalid mesh, a value the format cannot hold, or an I/O error.
pub fn write_mesh<W: Write + ?Sized>(mesh: &TriMesh, out: &mut W, format: MeshFormat) -> Result<(), MeshIoError> {
    match format {
        MeshFormat::Obj => write_obj(mesh, out),
        MeshFormat::Glb => write_glb(mesh, out),
        MeshFormat::Ply => write_ply(mesh, out),
        MeshFormat::Stl => write_stl(mesh, out),
    }
}

/// Writes `mesh` to the file at `path` in `format`, atomically.
///
/// The mesh is validated before any file is created. The bytes go to a temporary file in the
/// same directory, which is renamed to `path` only when everything was written (see
/// [`atomic::write_file`]); on any error no file is left behind, and an existing file at
/// `path` keeps its old contents. The format is given explicitly; use
/// [`MeshFormat::from_path`] to pick it from the extension.
///
/// # Errors
///
/// A [`MeshIoError`] whose origin is `path`: an invalid mesh, a value the format cannot hold,
/// or an I/O error (such as a directory that does not exist).
pub fn save(mesh: &TriMesh, path: impl AsRef<Path>, format: MeshFormat) -> Result<(), MeshIoError> {
    let path = path.as_ref();
    check(mesh).map_err(|e| e.with_origin(path))?;
    atomic::write_file(path, |w| write_mesh(mesh, w, format).map_err(|e| e.with_origin(path)))
}

/// Writes `mesh` like [`save`] to a temporary file next to `path` without renaming it:
/// commit the [`atomic::Staged`] file to put it in place, or drop it to remove it. Staging a
/// set of files before committing any writes all or none.
///
/// # Errors
///
/// As [`save`].
pub fn stage(mesh: &TriMesh, path: impl AsRef<Path>, format: MeshFormat) -> Result<atomic::Staged, MeshIoError> {
    let path = path.as_ref();
    check(mesh).map_err(|e| e.with_origin(path))?;
    atomic::stage_file(path, |w| write_mesh(mesh, w, format).map_err(|e| e.with_origin(path))).map(|(s, ())| s)
}

/// Writes `mesh` like [`save`], stopping as soon as `cancelled()` says so (it is asked before
/// every write to the temporary file, and before the temporary file replaces `path`): a
/// cancelled save fails with an I/O error saying so and leaves `path` as it was. For saves that run on a worker thread while a person waits.
///
/// # Errors
///
/// As [`save`], and when cancelled.
pub fn save_cancellable(
    mesh: &TriMesh,
    path: impl AsRef<Path>,
    format: MeshFormat,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Result<(), MeshIoError> {
    /// Passes writes on until `cancelled()`.
    struct Cancellable<'a, W: ?Sized> {
        inner: &'a mut W,
        cancelled: &'a (dyn Fn() -> bool + Sync),
    }
    impl<W: Write + ?Sized> Write for Cancellable<'_, W> {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if (self.cancelled)() {
                return Err(std::io::Error::other("cancelled"));
            }
            self.inner.write(buf)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            self.inner.flush()
        }
    }
    let path = path.as_ref();
    check(mesh).map_err(|e| e.with_origin(path))?;
    atomic::write_file(path, |w| {
        let mut out = Cancellable { inner: w, cancelled };
        write_mesh(mesh, &mut out, format).map_err(|e| e.with_origin(path))?;
        // once more before the rename: a cancel after the last write still keeps `path`
        if cancelled() {
            return Err(MeshIoError::from(std::io::Error::other("cancelled")).with_origin(path));
        }
        Ok(())
    })
}

/// What [`save_poly`] wrote.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct SavedPoly {
    /// The number of vertices in the file: the mesh's own, or more where seams were split.
    pub vertices: usize,
    /// The mesh's normals differ at some vertex, and the format (PLY) holds one normal a
    /// vertex: they were left out.
    pub normals_left_out: bool,
}

/// Writes the polygon mesh `mesh` to the file at `path` in `format`, atomically (as
/// [`save`]), and says what the file holds.
///
/// OBJ keeps the polygons and the face-varying normals and UVs with their own indices
/// ([`write_obj_poly`]), and PLY the polygons with UVs per corner where they differ at a
/// vertex ([`write_ply_poly`]; normals that differ at a vertex are left out): the file has the
/// mesh's vertices and topology. glb, whose attributes are per vertex, gets the fan
/// triangulation with a vertex for every distinct (vertex, normal, UV) of a corner
/// ([`PolyMesh::to_tri_mesh_with_seams`]), so a vertex on a UV seam or a sharp normal is
/// written once per side; so do OBJ and PLY with `split_seams`. STL gets the fan
/// triangulation's positions.
///
/// # Errors
///
/// As [`save`].
pub fn save_poly(
    mesh: &PolyMesh,
    path: impl AsRef<Path>,
    format: MeshFormat,
    split_seams: bool,
) -> Result<SavedPoly, MeshIoError> {
    save_poly_creased(mesh, &Creases::default(), path, format, split_seams)
}

/// [`save_poly`] with the mesh's creases: an OBJ file gets them as tag lines after the faces
/// ([`write_creases`]); the other formats cannot hold them and do not get them.
///
/// # Errors
///
/// As [`save`].
pub fn save_poly_creased(
    mesh: &PolyMesh,
    creases: &Creases,
    path: impl AsRef<Path>,
    format: MeshFormat,
    split_seams: bool,
) -> Result<SavedPoly, MeshIoError> {
    let (staged, saved) = stage_poly_creased(mesh, creases, path, format, split_seams)?;
    staged.commit()?;
    Ok(saved)
}

/// Writes `mesh` like [`save_poly`] to a temporary file next to `path` without renaming it
/// (as [`stage`]): commit the [`atomic::Staged`] file to put it in place.
///
/// # Errors
///
/// As [`save`].
pub fn stage_poly(
    mesh: &PolyMesh,
    path: impl AsRef<Path>,
    format: MeshFormat,
    split_seams: bool,
) -> Result<(atomic::Staged, SavedPoly), MeshIoError> {
    stage_poly_creased(mesh, &Creases::default(), path, format, split_seams)
}

/// Writes `mesh` like [`save_poly_creased`] to a temporary file next to `path` without
/// renaming it (as [`stage`]): commit the [`atomic::Staged`] file to put it in place.
///
/// # Errors
///
/// As [`save`].
pub fn stage_poly_creased(
    mesh: &PolyMesh,
    creases: &Creases,
    path: impl AsRef<Path>,
    format: MeshFormat,
    split_seams: bool,
) -> Result<(atomic::Staged, SavedPoly), MeshIoError> {
    let path = path.as_ref();
    let split = match format {
        MeshFormat::Glb => Some(mesh.to_tri_mesh_with_seams()),
        MeshFormat::Obj | MeshFormat::Ply if split_seams => Some(mesh.to_tri_mesh_with_seams()),
        MeshFormat::Stl => Some(mesh.to_tri_mesh()),
        MeshFormat::Obj | MeshFormat::Ply => None,
    };
    if let Some(tri) = split {
        let staged = stage(&tri, path, format)?;
        return Ok((staged, SavedPoly { vertices: tri.num_vertices(), normals_left_out: false }));
    }
    // the writers validate before writing a byte; on error the temporary file goes away
    let (staged, normals_left_out) = atomic::stage_file(path, |w| {
        if format == MeshFormat::Ply {
            return write_ply_poly(mesh, w).map_err(|e| e.with_origin(path));
        }
        write_obj_poly(mesh, w).map_err(|e| e.with_origin(path))?;
        write_creases(creases, w).map_err(|e| MeshIoError::from(e).with_origin(path))?;
        Ok(false)
    })?;
    Ok((staged, SavedPoly { vertices: mesh.num_vertices(), normals_left_out }))
}

/// Validates the mesh for writing.
fn check(mesh: &TriMesh) -> Result<(), MeshIoError> {
    mesh.validate().map_err(|e| MeshIoError::new(MeshIoErrorKind::InvalidMesh(e)))
}

/// Rounds to the nearest `f32`.
fn to_f32(x: f64) -> f32 {
    x as f32
}

/// Checks that every position (and, with `attributes`, every normal and UV) is within the
/// `f32` range.
fn check_f32_range(mesh: &TriMesh, format: &'static str, attributes: bool) -> Result<(), MeshIoError> {
    const AXES: [&str; 3] = ["x", "y", "z"];
    let fail = |what: String, x: f64| {
        Err(MeshIoError::new(MeshIoErrorKind::Unrepresentable { format, what: format!("{what} ({x:?})") }))
    };
    for (i, p) in mesh.positions.iter().enumerate() {
        for (axis, x) in AXES.iter().zip(p.to_array()) {
            if !to_f32(x).is_finite() {
                return fail(format!("{axis} coordinate of vertex {i}"), x);
            }
        }
    }
    if !attributes {
        return Ok(());
    }
    for (i, n) in mesh.normals.iter().enumerate() {
        for (axis, x) in AXES.iter().zip(n.to_array()) {
            if !to_f32(x).is_finite() {
                return fail(format!("{axis} component of the normal of vertex {i}"), x);
            }
        }
    }
    for (i, t) in mesh.uvs.iter().enumerate() {
        for (axis, x) in ["u", "v"].iter().zip(t.to_array()) {
            if !to_f32(x).is_finite() || !to_f32(1.0 - x).is_finite() {
                return fail(format!("{axis} of vertex {i}"), x);
            }
        }
    }
    Ok(())
}
