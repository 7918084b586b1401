//! One entry point for every scheme: [`subdivide`] refines a mesh by a [`Scheme`] with
//! [`SubdivisionOptions`] and creases, and [`Subdivided::into_limit`] moves the result to its
//! limit surface.

use glam::DVec3;

use super::bilinear::{BilinearOptions, bilinear_subdivide};
use super::butterfly::{ButterflyOptions, butterfly_subdivide};
use super::catmull_clark::catmull_clark_subdivide;
use super::counts::{self, Counts};
use super::crease::Creases;
use super::creased::{catmull_clark_subdivide_creased, loop_subdivide_creased};
use super::doo_sabin::{DooSabinOptions, doo_sabin_subdivide};
use super::error::SubdivError;
use super::holes::{HoleSplit, boundary_holes, remove_holes};
use super::limit::{
    LimitMesh, catmull_clark_limit_creased, catmull_clark_limit_normals, catmull_clark_limit_positions,
    catmull_clark_subdivide_limit, loop_limit_creased, loop_limit_normals, loop_limit_positions, loop_subdivide_limit,
};
use super::loop_scheme::LoopPyramid;
use super::nonmanifold::{self, Split, is_nonmanifold};
use super::options::{CreasingMethod, SubdivisionOptions};
use super::scheme::Scheme;
use super::sqrt3::{Sqrt3Options, sqrt3_subdivide};
use crate::mesh::{FaceVarying, PolyMesh};

/// A subdivided mesh: what [`subdivide`] gives.
#[derive(Clone, Debug)]
pub struct Subdivided {
    /// The refined mesh.
    pub mesh: PolyMesh,
    /// Its creases: the input's carried to the finest level (Loop and Catmull-Clark; none for
    /// the other schemes), so that subdividing `mesh` again goes on where this stopped.
    pub creases: Creases,
    /// Where each level's vertices start: the vertices made by level `k` are
    /// `level_starts[k] .. level_starts[k + 1]` (the last up to the mesh's vertex count),
    /// level 0 being the input's. `levels + 1` entries. The schemes keep the vertices of the
    /// level above and add theirs after them, except Doo-Sabin, which makes every vertex anew:
    /// all its vertices are the last level's (every other entry is 0).
    pub level_starts: Vec<usize>,
    scheme: Scheme,
    levels: usize,
    options: SubdivisionOptions,
    /// Whether it was made level by level through the crease rules (creases, a non-manifold
    /// mesh or holes), rather than by the scheme's fast path.
    creased: bool,
}

/// `levels` levels of `scheme` on `mesh` with `options` and `creases` (on `mesh`'s vertices;
/// ignored by the schemes without creases, see [`Scheme::supports_creases`]): the one entry
/// point to every scheme's function ([`loop_subdivide`](super::loop_subdivide),
/// [`catmull_clark_subdivide`](super::catmull_clark_subdivide), …, and their creased forms),
/// which it calls with the options that apply to the scheme and ignores the others.
///
/// Loop and Catmull-Clark go through their creased forms when there are creases, when `mesh`
/// is non-manifold or degenerate ([`is_nonmanifold`](super::is_nonmanifold)), or with
/// [`SubdivisionOptions::holes`] (the faces that descend from a hole of `mesh` are then left
/// out, their vertices kept); else through their fast paths.
///
/// ```
/// use glam::DVec3;
/// use splinekit::PolyMesh;
/// use splinekit::subdiv::{Creases, Scheme, SubdivisionOptions, subdivide};
/// // A tetrahedron: V = 4, E = 6, F = 4.
/// let mesh = PolyMesh::from_triangles(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// );
/// let options = SubdivisionOptions::DEFAULT.with_color_by_level(true);
/// for scheme in Scheme::ALL {
///     let fine = subdivide(&mesh, 2, scheme, &options, &Creases::default())?;
///     assert_eq!(fine.level_starts.len(), 3, "{scheme}");
/// }
/// let fine = subdivide(&mesh, 2, Scheme::Loop, &options, &Creases::default())?;
/// // level 1 adds a vertex per edge (6), level 2 one per edge of level 1 (2·6 + 3·4 = 24)
/// assert_eq!(fine.level_starts, [0, 4, 10]);
/// assert_eq!(fine.mesh.num_vertices(), 10 + 24);
/// # Ok::<(), splinekit::subdiv::SubdivError>(())
/// ```
///
/// # Errors
///
/// The scheme's function's: a face the scheme does not take (see [`Scheme::triangles_only`]),
/// topology it refuses, a crease on an edge or vertex `mesh` does not have, a result that
/// would not fit `u32` indices.
pub fn subdivide(
    mesh: &PolyMesh,
    levels: usize,
    scheme: Scheme,
    options: &SubdivisionOptions,
    creases: &Creases,
) -> Result<Subdivided, SubdivError> {
    subdivide_with_progress(mesh, levels, scheme, options, creases, |_| {})
}

/// [`subdivide`], calling `progress(k)` once level `k` is made (for the schemes that make the
/// levels one after another; the others call it for every level at the end).
///
/// # Errors
///
/// As [`subdivide`].
pub fn subdivide_with_progress(
    mesh: &PolyMesh,
    levels: usize,
    scheme: Scheme,
    options: &SubdivisionOptions,
    creases: &Creases,
    mut progress: impl FnMut(usize) + Send,
) -> Result<Subdivided, SubdivError> {
    let creased = takes_creased_path(mesh, scheme, options, creases);
    let loop_levels = u32::try_from(levels).unwrap_or(u32::MAX);
    let color_by_level = options.color_by_level;
    let (mut fine, child) = match scheme {
        Scheme::Loop if creased => {
            loop_subdivide_creased(mesh, loop_levels, &options.loop_options(), creases, options.creasing)?
        }
        Scheme::Loop => {
            let pyramid = LoopPyramid::new(mesh, options.loop_options())?;
            (pyramid.into_refined(levels, &mut progress)?.to_mesh(), Creases::default())
        }
        Scheme::CatmullClark if creased => {
            let cc = options.catmull_clark_options();
            catmull_clark_subdivide_creased(mesh, levels, &cc, creases, options.creasing)?
        }
        Scheme::CatmullClark => {
            (catmull_clark_subdivide(mesh, levels, &options.catmull_clark_options())?, Creases::default())
        }
        Scheme::Sqrt3 => (sqrt3_subdivide(mesh, levels, &Sqrt3Options { color_by_level })?, Creases::default()),
        Scheme::DooSabin => (doo_sabin_subdivide(mesh, levels, &DooSabinOptions::default())?, Creases::default()),
        Scheme::Butterfly => {
            (butterfly_subdivide(mesh, levels, &ButterflyOptions { color_by_level })?, Creases::default())
        }
        Scheme::Bilinear => {
            (bilinear_subdivide(mesh, levels, &BilinearOptions { color_by_level })?, Creases::default())
        }
    };
    if !matches!(scheme, Scheme::Loop) || creased {
        (1..=levels).for_each(&mut progress);
    }
    if creased && options.holes {
        let split = if scheme.triangles_only() { HoleSplit::Triangles } else { HoleSplit::Quads };
        remove_holes(&mut fine, mesh, levels, split, &boundary_holes(mesh, creases));
    }
    let level_starts = level_starts(mesh, levels, scheme, creased)?;
    Ok(Subdivided { mesh: fine, creases: child, level_starts, scheme, levels, options: *options, creased })
}

/// Whether `scheme` makes `mesh` through its crease rules: Loop and Catmull-Clark with
/// `creases`, holes or a non-manifold mesh.
fn takes_creased_path(mesh: &PolyMesh, scheme: Scheme, options: &SubdivisionOptions, creases: &Creases) -> bool {
    scheme.supports_creases() && (!creases.is_empty() || options.holes || is_nonmanifold(mesh))
}

/// The first vertex of each level of `levels` levels of `scheme` on `mesh` (see
/// [`Subdivided::level_starts`]): from the counts of `mesh`, or on the path of non-manifold
/// meshes (`creased`, and `mesh` non-manifold) from its levels' tables.
fn level_starts(mesh: &PolyMesh, levels: usize, scheme: Scheme, creased: bool) -> Result<Vec<usize>, SubdivError> {
    if matches!(scheme, Scheme::DooSabin) || levels == 0 {
        return Ok(vec![0; levels + 1]);
    }
    let mut starts = vec![0];
    if creased && is_nonmanifold(mesh) {
        let split = if scheme.triangles_only() { Split::Triangles } else { Split::Quads };
        nonmanifold::level_vertices(mesh, split, levels, |v| starts.push(v))?;
    } else {
        counts::level_vertices(scheme, Counts::of_mesh(mesh), levels, |v| starts.push(v as usize));
    }
    Ok(starts)
}

impl Subdivided {
    /// The subdivided mesh with every vertex moved to its limit position and given the limit
    /// surface's unit normal there (one per vertex; UVs and colours stay): Loop's and
    /// Catmull-Clark's exact masks for the weights, boundary rule and creases (OpenSubdiv's
    /// limit rules, a vertex on a sharp crease on the crease's limit curve); `base` and
    /// `creases` are what was given to [`subdivide`]. Where a level of a non-manifold `base`
    /// joins what the subdivision keeps apart, the limit is that of the subdivision's own
    /// vertex rules ([`loop_subdivide_limit`](super::loop_subdivide_limit)). An interpolating
    /// scheme's vertices are on their limit surface already: its mesh is given back as it is.
    ///
    /// # Errors
    ///
    /// [`SubdivError::NoLimit`] for √3 and Doo-Sabin (see [`Scheme::has_limit_positions`]);
    /// the limit functions' errors, such as [`SubdivError::NotQuads`] for Catmull-Clark
    /// without levels on a mesh that is not all quads.
    pub fn into_limit(self, base: &PolyMesh, creases: &Creases) -> Result<PolyMesh, SubdivError> {
        let Self { mesh: fine, creases: child, scheme, levels, options, creased, .. } = self;
        let loop_levels = u32::try_from(levels).unwrap_or(u32::MAX);
        let method = options.creasing;
        let no = Creases::default();
        let nonmanifold = creased && is_nonmanifold(base);
        let (mesh, positions, normals) = match scheme {
            Scheme::Loop => {
                let lo = options.loop_options();
                let subdivided = |with: bool| {
                    let (creases, method) = if with { (creases, method) } else { (&no, CreasingMethod::Chaikin) };
                    loop_subdivide_limit(base, loop_levels, &lo, creases, method)
                };
                let plain = |m: &PolyMesh| {
                    let normals = loop_limit_normals(m, &lo)?;
                    Ok((loop_limit_positions(m, &lo)?, normals))
                };
                limit_of(fine, nonmanifold, subdivided, |m| loop_limit_creased(m, &lo, &child), plain, creased)?
            }
            Scheme::CatmullClark => {
                let cc = options.catmull_clark_options();
                let subdivided = |with: bool| {
                    catmull_clark_subdivide_limit(base, levels, &cc, if with { creases } else { &no }, method)
                };
                let plain = |m: &PolyMesh| {
                    let normals = catmull_clark_limit_normals(m, &cc)?;
                    Ok((catmull_clark_limit_positions(m, &cc)?, normals))
                };
                limit_of(
                    fine,
                    nonmanifold,
                    subdivided,
                    |m| catmull_clark_limit_creased(m, &cc, &child),
                    plain,
                    creased,
                )?
            }
            _ if scheme.is_interpolating() => return Ok(fine),
            _ => return Err(SubdivError::NoLimit { scheme }),
        };
        Ok(with_limit(mesh, positions, normals))
    }
}

/// Positions and normals, one per vertex.
type Limits = (Vec<DVec3>, Vec<DVec3>);

/// The limit of `fine` as [`Subdivided::into_limit`] gives it: when it was made `creased`, by
/// `subdivided(true)` (the subdivision's own levels, with the creases) if its base was
/// non-manifold (`nonmanifold`) or it is, else by `creased_limit` (from its creases); else,
/// from its faces without the face-varying channels, by `subdivided(false)` (no creases) where
/// two edges of a level join the same two vertices (back-to-back faces: the limit needs the
/// subdivision's own edges), else by `plain`.
fn limit_of(
    fine: PolyMesh,
    nonmanifold: bool,
    subdivided: impl FnOnce(bool) -> Result<LimitMesh, SubdivError>,
    creased_limit: impl FnOnce(&PolyMesh) -> Result<Limits, SubdivError>,
    plain: impl FnOnce(&PolyMesh) -> Result<Limits, SubdivError>,
    creased: bool,
) -> Result<LimitMesh, SubdivError> {
    if creased {
        if nonmanifold || is_nonmanifold(&fine) {
            return subdivided(true);
        }
        let (positions, normals) = creased_limit(&fine)?;
        return Ok((fine, positions, normals));
    }
    let bare = PolyMesh { normals: None, uvs: None, colors: Vec::new(), ..fine.clone() };
    if is_nonmanifold(&bare) {
        return subdivided(false);
    }
    let (positions, normals) = plain(&bare)?;
    Ok((fine, positions, normals))
}

/// `mesh` at its limit `positions`, with its limit `normals` (one per vertex).
fn with_limit(mesh: PolyMesh, positions: Vec<DVec3>, normals: Vec<DVec3>) -> PolyMesh {
    let indices = mesh.face_vertices.clone();
    PolyMesh { positions, normals: Some(FaceVarying { values: normals, indices }), ..mesh }
}
