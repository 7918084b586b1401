//! `sweep` and `revolve`: an SWP document made in memory and swept by
//! [`SwpDocument::surface_poly`], the entry point `splinekit sweep` uses, so the meshes are
//! the ones it writes.

use glam::DVec3;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use splinekit::TriMesh;
use splinekit::sweep::Join;
use splinekit_io::surface::{ProfileAlign, ScaleMode, SurfaceOptions};
use splinekit_io::{
    SourcePos, SwpCurve, SwpCurveKind, SwpDocument, SwpFrames, SwpGeometry, SwpSurface, SwpSurfaceKind,
    SwpSurfaceSettings, SwpTessellation,
};

use crate::convert::{points_out, value_error};
use crate::curve::{Curve, positive, swp_curve};

/// Surface `index` of `doc` as `(vertices, faces)`: the welded mesh `splinekit sweep` writes
/// (every point of the surface one vertex). With `normals`, `(vertices, faces, normals)` of the
/// mesh for drawing instead, a vertex for each side of a sharp edge, so each has one normal.
pub fn mesh_tuple<'py>(
    py: Python<'py>,
    doc: &SwpDocument,
    index: usize,
    options: &SurfaceOptions,
    normals: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let swept = py.detach(|| doc.surface_poly(index, options)).map_err(value_error)?;
    let mesh: TriMesh = if normals {
        swept.mesh.to_tri_mesh_with_seams()
    } else {
        TriMesh {
            positions: swept.mesh.positions,
            triangles: swept.mesh.face_vertices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
            ..TriMesh::default()
        }
    };
    tri_mesh_tuple(py, &mesh, normals)
}

/// `(vertices (V, 3), faces (F, 3))` of `mesh`, and `normals (V, 3)` when asked.
pub fn tri_mesh_tuple<'py>(py: Python<'py>, mesh: &TriMesh, normals: bool) -> PyResult<Bound<'py, PyTuple>> {
    let vertices = points_out(py, mesh.positions.iter().copied(), 3).into_any();
    let flat: Vec<i64> = mesh.triangles.iter().flat_map(|t| t.map(i64::from)).collect();
    let faces = numpy::ndarray::Array2::from_shape_vec((mesh.triangles.len(), 3), flat).map_err(value_error)?;
    let faces = numpy::IntoPyArray::into_pyarray(faces, py).into_any();
    if normals {
        let n = points_out(py, mesh.normals.iter().copied(), 3).into_any();
        PyTuple::new(py, [vertices, faces, n])
    } else {
        PyTuple::new(py, [vertices, faces])
    }
}

/// `curve`'s SWP description named `role` (unless it has a name of its own).
fn named(curve: &Curve, role: &str) -> SwpCurve {
    let mut swp = curve.swp.clone();
    if swp.name.is_none() {
        swp.name = Some(role.to_owned());
    }
    swp
}

/// A 2D curve for `scale`: a Curve as it is, a number `s` or a pair `(sx, sy)` as a constant.
fn scale_curve(obj: &Bound<'_, PyAny>) -> PyResult<SwpCurve> {
    if let Ok(curve) = obj.cast::<Curve>() {
        return Ok(named(curve.get(), "scale"));
    }
    let (sx, sy) = match obj.extract::<f64>() {
        Ok(s) => (s, s),
        Err(_) => obj
            .extract::<(f64, f64)>()
            .map_err(|_| PyValueError::new_err("scale must be a Curve (2D), a number or a pair (sx, sy)"))?,
    };
    if !(sx.is_finite() && sy.is_finite()) {
        return Err(PyValueError::new_err(format!("scale must be finite, got ({sx}, {sy})")));
    }
    let p = DVec3::new(sx, sy, 0.0);
    let mut swp = swp_curve(SwpCurveKind::Bezier, 2, 1, false, SwpGeometry::Points(vec![p; 4]))?;
    swp.name = Some("scale".into());
    Ok(swp)
}

/// A 2D curve for `twist`: a Curve as it is (its x in degrees), or a number of degrees turned
/// evenly from start to end.
fn twist_curve(obj: &Bound<'_, PyAny>) -> PyResult<SwpCurve> {
    if let Ok(curve) = obj.cast::<Curve>() {
        return Ok(named(curve.get(), "twist"));
    }
    let degrees: f64 = obj
        .extract()
        .map_err(|_| PyValueError::new_err("twist must be a Curve (2D, x in degrees) or a number of degrees"))?;
    if !degrees.is_finite() {
        return Err(PyValueError::new_err(format!("twist must be finite, got {degrees}")));
    }
    // a Bézier with evenly spaced points is linear in u, so the twist grows evenly along the path
    let pts = (0..4).map(|i| DVec3::new(degrees * f64::from(i) / 3.0, 0.0, 0.0)).collect();
    let mut swp = swp_curve(SwpCurveKind::Bezier, 2, 1, false, SwpGeometry::Points(pts))?;
    swp.name = Some("twist".into());
    Ok(swp)
}

fn require_2d(curve: &Curve, what: &str) -> PyResult<()> {
    if curve.swp.dim == 2 {
        Ok(())
    } else {
        Err(PyValueError::new_err(format!("{what} must be a 2D curve (points of shape (n, 2)), got a 3D curve")))
    }
}

fn tessellation(tolerance: Option<f64>) -> PyResult<Option<SwpTessellation>> {
    tolerance.map(|t| positive(t, "tolerance").map(SwpTessellation::Distance)).transpose()
}

/// Sweeps a 2D ``profile`` along ``path`` (a generalized cylinder): ``(vertices, faces)``.
///
/// Each profile point ``(x, y)`` goes to ``V + x·N + y·B`` in the path's frame at ``V``.
/// ``scale``: a 2D Curve whose point ``(sx, sy)`` scales the profile's x and y, a number, or a
/// pair; ``scale_mode``: ``"multiply"`` (the scale multiplies the profile as drawn) or
/// ``"override"`` (the scale is the profile's size: its farthest point from the path lies
/// ``sx`` away along N and ``sy`` along B); ``twist``: a 2D Curve whose x is an angle in degrees, or a number of degrees turned
/// evenly from start to end (both read along the path by normalized arc length).
/// ``frames``: ``"rmf"``, ``"sequential"``, ``"frenet"`` or ``"zup"``. ``caps``: close an open
/// sweep of a closed profile with flat caps. ``tolerance``: an adaptive mesh, triangle
/// interiors included, within this distance of the exact surface, as ``splinekit sweep
/// --tolerance`` (default: each curve's ``steps``). ``align``: which point of the profile
/// rides on the path (``"origin"``, ``"centre"``, ``"start"``). ``join``: how the walls meet at
/// a sharp corner of the path (``"mitre"``, ``"round"``, ``"bevel"``); ``mitre_limit``: the
/// longest mitre, times the profile's offset, before a mitre becomes a bevel. ``normals``:
/// also give the
/// vertex normals ``(V, 3)`` (a vertex is then repeated on each side of a sharp edge, so each
/// has one normal). Triangles are counter-clockwise seen from outside; every point of the
/// surface is one vertex (seams, creases, caps and joints shared), so a closed or capped sweep
/// of a closed profile is watertight. The mesh is what ``splinekit sweep`` writes of the same
/// ``gcyl``.
#[pyfunction]
#[pyo3(signature = (profile, path, scale=None, twist=None, frames="rmf", caps=true, tolerance=None, *, align="origin", join="mitre", mitre_limit=4.0, scale_mode="multiply", normals=false))]
pub fn sweep<'py>(
    py: Python<'py>,
    profile: &Bound<'py, Curve>,
    path: &Bound<'py, Curve>,
    scale: Option<&Bound<'py, PyAny>>,
    twist: Option<&Bound<'py, PyAny>>,
    frames: &str,
    caps: bool,
    tolerance: Option<f64>,
    align: &str,
    join: &str,
    mitre_limit: f64,
    scale_mode: &str,
    normals: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    require_2d(profile.get(), "profile")?;
    let scale_mode = match scale_mode {
        "multiply" => ScaleMode::Multiply,
        "override" => ScaleMode::Override,
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown scale_mode {scale_mode:?}; expected one of multiply, override"
            )));
        }
    };
    let join = match join {
        "mitre" | "miter" => Join::Mitre,
        "round" => Join::Round,
        "bevel" => Join::Bevel,
        _ => {
            return Err(PyValueError::new_err(format!("unknown join {join:?}; expected one of mitre, round, bevel")));
        }
    };
    if !(mitre_limit >= 1.0 && mitre_limit.is_finite()) {
        return Err(PyValueError::new_err(format!("mitre_limit must be a number of at least 1, got {mitre_limit}")));
    }
    let frames = match frames {
        "rmf" => SwpFrames::RotationMinimizing,
        "sequential" => SwpFrames::Sequential,
        "frenet" => SwpFrames::Frenet,
        "zup" => SwpFrames::ZUp,
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown frames {frames:?}; expected one of rmf, sequential, frenet, zup"
            )));
        }
    };
    let align = match align {
        "origin" => ProfileAlign::Origin,
        "centre" | "center" => ProfileAlign::Centre,
        "start" => ProfileAlign::Start,
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown align {align:?}; expected one of origin, centre, start"
            )));
        }
    };
    let mut curves = vec![named(profile.get(), "profile"), named(path.get(), "path")];
    let mut extra = |c: SwpCurve| {
        curves.push(c);
        curves.len() - 1
    };
    let scale = scale.filter(|s| !s.is_none()).map(scale_curve).transpose()?.map(&mut extra);
    let twist = twist.filter(|t| !t.is_none()).map(twist_curve).transpose()?.map(&mut extra);
    let settings = SwpSurfaceSettings {
        tessellation: tessellation(tolerance)?,
        layout: None,
        frames: Some(frames),
        caps: Some(caps),
        align: Some(align),
        join: Some(join),
        mitre_limit: Some(mitre_limit),
        scale_mode: Some(scale_mode),
    };
    let kind = SwpSurfaceKind::GeneralizedCylinder { profile: 0, sweep: 1, scale, twist };
    let surface = SwpSurface { name: Some("sweep".into()), kind, settings, pos: SourcePos::default() };
    let doc = SwpDocument { curves, surfaces: vec![surface] };
    mesh_tuple(py, &doc, 0, &SurfaceOptions::default(), normals)
}

/// Turns a 2D ``profile`` about the y axis (an SWP ``srev``): ``(vertices, faces)``.
///
/// ``slices`` copies of the tessellated profile (each curve's ``steps``), copy ``j`` turned by
/// ``2πj/slices`` about +y; with ``tolerance`` (a distance), the profile is flattened within
/// it and the slices are as many as the tolerance needs. ``normals``: also give the vertex
/// normals ``(V, 3)``. Outward normals and counter-clockwise triangles on either side of the
/// axis; poles are single vertices.
#[pyfunction]
#[pyo3(signature = (profile, slices=32, tolerance=None, *, normals=false))]
pub fn revolve<'py>(
    py: Python<'py>,
    profile: &Bound<'py, Curve>,
    slices: u32,
    tolerance: Option<f64>,
    normals: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    require_2d(profile.get(), "profile")?;
    if !(1..=splinekit_io::MAX_STEPS).contains(&slices) {
        return Err(PyValueError::new_err(format!("slices must be 1 to {}, got {slices}", splinekit_io::MAX_STEPS)));
    }
    let settings = SwpSurfaceSettings { tessellation: tessellation(tolerance)?, ..SwpSurfaceSettings::default() };
    let kind = SwpSurfaceKind::Revolution { steps: slices, profile: 0 };
    let surface = SwpSurface { name: Some("revolve".into()), kind, settings, pos: SourcePos::default() };
    let doc = SwpDocument { curves: vec![named(profile.get(), "profile")], surfaces: vec![surface] };
    mesh_tuple(py, &doc, 0, &SurfaceOptions::default(), normals)
}
