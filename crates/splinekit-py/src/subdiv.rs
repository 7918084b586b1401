//! `subdivide` and `limit_normals`: [`::splinekit::subdiv::subdivide`], the one entry point of
//! every scheme (as `splinekit subdivide` calls it).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use splinekit::PolyMesh;
use splinekit::subdiv::{BoundaryRule, Creases, LoopWeights, Scheme, SubdivisionOptions, subdivide as run};

use crate::convert::{creases as read_creases, mesh, mesh_out, points_out, value_error};

/// Bytes a triangle of the finest level takes while it is made, at most (as `splinekit
/// subdivide`'s memory check).
const BYTES_PER_TRIANGLE: f64 = 160.0;

/// The scheme called `name`.
fn scheme(name: &str) -> PyResult<Scheme> {
    Scheme::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = Scheme::ALL.iter().map(|s| s.name()).collect();
        PyValueError::new_err(format!("unknown scheme {name}; expected one of {}", names.join(", ")))
    })
}

/// The schemes that have `capability`, in words: `Loop and Catmull-Clark`.
fn schemes_with(capability: fn(Scheme) -> bool) -> String {
    let names: Vec<String> = Scheme::ALL.into_iter().filter(|&s| capability(s)).map(|s| s.to_string()).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

/// The options of `scheme` from the keyword arguments, refusing those that mean nothing for it
/// (as `splinekit subdivide` refuses the flags).
fn options(scheme: Scheme, weights: &str, boundary: &str, creases: &Creases) -> PyResult<SubdivisionOptions> {
    let weights = match weights {
        "loop" => LoopWeights::Loop,
        "warren" => LoopWeights::Warren,
        _ => return Err(PyValueError::new_err(format!("unknown weights {weights:?}; expected loop or warren"))),
    };
    if weights != LoopWeights::Loop && !scheme.has_weights() {
        return Err(PyValueError::new_err(format!(
            "weights chooses Loop's even-vertex weights; {scheme} subdivision has none to choose"
        )));
    }
    let boundary = match boundary {
        "smooth" => BoundaryRule::Smooth,
        "corners" => BoundaryRule::Corners,
        _ => {
            return Err(PyValueError::new_err(format!("unknown boundary {boundary:?}; expected smooth or corners")));
        }
    };
    if boundary != BoundaryRule::Smooth && !scheme.has_boundary_rule() {
        return Err(PyValueError::new_err(format!(
            "boundary is for {}; {scheme} subdivision has no boundary rule to choose",
            schemes_with(Scheme::has_boundary_rule)
        )));
    }
    if !creases.is_empty() && !scheme.supports_creases() {
        return Err(PyValueError::new_err(format!(
            "creases are for {}; {scheme} subdivision has no creases",
            schemes_with(Scheme::supports_creases)
        )));
    }
    Ok(SubdivisionOptions::DEFAULT.with_weights(weights).with_boundary(boundary))
}

/// Refuses, before anything is made, a subdivision that would need more memory than the system
/// has available (as `splinekit subdivide` does).
fn check_memory(mesh: &PolyMesh, scheme: Scheme, levels: u32) -> PyResult<()> {
    let faces = scheme.max_triangles(mesh, levels);
    let available = std::fs::read_to_string("/proc/meminfo").ok().and_then(|info| {
        let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?.to_owned();
        line.split_whitespace().nth(1)?.parse::<f64>().ok().map(|kb| kb * 1024.0)
    });
    let need = faces * BYTES_PER_TRIANGLE;
    match available {
        Some(limit) if faces <= f64::from(u32::MAX) && need > limit => Err(PyValueError::new_err(format!(
            "{levels} levels of {scheme} would make up to {faces:.3e} triangles and need about {:.3} GB, more than the \
             {:.3} GB of memory available; ask for fewer levels",
            need / 1e9,
            limit / 1e9
        ))),
        _ => Ok(()),
    }
}

/// Subdivides a mesh ``levels`` times: ``(vertices, faces)``.
///
/// ``scheme``: ``"loop"`` (triangles), ``"catmull-clark"`` (any polygons; gives quads),
/// ``"sqrt3"`` (triangles), ``"doo-sabin"`` (any polygons), ``"butterfly"`` (triangles,
/// interpolating) or ``"bilinear"``. ``weights`` (Loop): ``"loop"`` (β(n) of Loop, as
/// OpenSubdiv) or ``"warren"`` (3/(8n)). ``boundary`` (Loop, Catmull-Clark): ``"smooth"`` or
/// ``"corners"`` (single-face corners fixed). ``creases`` (Loop, Catmull-Clark): ``(edges (k,
/// 2), sharpness (k,))``, sharpness 0 smooth to 10 or more infinitely sharp, semi-sharp in
/// between (OpenSubdiv's rules, Chaikin creasing). ``limit``: move every vertex to its limit
/// position (Loop, Catmull-Clark; butterfly's are there already).
#[pyfunction]
#[pyo3(signature = (vertices, faces, levels, scheme="loop", weights="loop", boundary="smooth", creases=None, limit=false))]
pub fn subdivide(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    levels: u32,
    scheme: &str,
    weights: &str,
    boundary: &str,
    creases: Option<&Bound<'_, PyAny>>,
    limit: bool,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let scheme = self::scheme(scheme)?;
    let base = mesh(vertices, faces)?;
    let creases = read_creases(creases, base.num_vertices())?;
    let options = options(scheme, weights, boundary, &creases)?;
    if limit && scheme.is_linear() {
        return Err(PyValueError::new_err(format!(
            "limit: the {scheme} surface is its polygons, so its vertices are at their limit already"
        )));
    }
    if limit && !scheme.has_limit_positions() && !scheme.is_interpolating() {
        return Err(PyValueError::new_err(format!(
            "limit: limit positions are computed for {} only, not {scheme} subdivision",
            schemes_with(Scheme::has_limit_positions)
        )));
    }
    check_memory(&base, scheme, levels)?;
    let fine = py
        .detach(|| {
            let fine = run(&base, levels as usize, scheme, &options, &creases)?;
            if limit { fine.into_limit(&base, &creases) } else { Ok(fine.mesh) }
        })
        .map_err(value_error)?;
    mesh_out(py, fine)
}

/// The unit normal of the limit surface at each vertex of a mesh, ``(V, 3)`` (unused vertices
/// get 0): Loop's or Catmull-Clark's exact masks (Catmull-Clark needs all quads), with the
/// same options as ``subdivide``.
#[pyfunction]
#[pyo3(signature = (vertices, faces, scheme="loop", weights="loop", boundary="smooth", creases=None))]
pub fn limit_normals<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    scheme: &str,
    weights: &str,
    boundary: &str,
    creases: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let scheme = self::scheme(scheme)?;
    if !scheme.has_limit_positions() {
        return Err(PyValueError::new_err(format!(
            "limit normals are computed for {} only, not {scheme} subdivision",
            schemes_with(Scheme::has_limit_positions)
        )));
    }
    let base = mesh(vertices, faces)?;
    let creases = read_creases(creases, base.num_vertices())?;
    let options = options(scheme, weights, boundary, &creases)?;
    let limit =
        py.detach(|| run(&base, 0, scheme, &options, &creases)?.into_limit(&base, &creases)).map_err(value_error)?;
    let mut normals = vec![glam::DVec3::ZERO; limit.num_vertices()];
    if let Some(fv) = &limit.normals {
        for (&v, &i) in limit.face_vertices.iter().zip(&fv.indices) {
            normals[v as usize] = fv.values[i as usize];
        }
    }
    Ok(points_out(py, normals.into_iter(), 3))
}
