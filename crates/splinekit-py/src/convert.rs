//! numpy in and out: points, parameters, meshes and creases, and errors as Python exceptions.

use glam::DVec3;
use numpy::ndarray::{Array2, ArrayD, IxDyn};
use numpy::{AllowTypeChange, IntoPyArray, PyArrayDyn, PyArrayLikeDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use splinekit::PolyMesh;
use splinekit::subdiv::{Creases, EdgeCrease};

/// A `ValueError` with `error`'s message.
pub fn value_error(error: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(error.to_string())
}

/// An `OSError` for `error` on `path` with `message`: `FileNotFoundError`, `PermissionError`, …
/// as Python picks from the error number.
pub fn os_error(error: &std::io::Error, message: String, path: &std::path::Path) -> PyErr {
    let path = path.display().to_string();
    match error.raw_os_error() {
        Some(errno) => PyOSError::new_err((errno, message, path)),
        None => PyOSError::new_err(message),
    }
}

/// A float64 array of any shape from anything numpy can convert (lists, ints, arrays).
pub fn float_array<'py>(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<PyArrayLikeDyn<'py, f64, AllowTypeChange>> {
    obj.extract::<PyArrayLikeDyn<'py, f64, AllowTypeChange>>()
        .map_err(|_| PyValueError::new_err(format!("{what} must be a number or an array of numbers")))
}

/// Values of `obj` (a number or an array of any shape) in C order, with its shape, or `None`
/// for the shape of a scalar (a Python number or a 0-dimensional array).
pub fn values(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<f64>, Option<Vec<usize>>)> {
    if let Ok(x) = obj.extract::<f64>()
        && !obj.hasattr("shape")?
    {
        return Ok((vec![x], None));
    }
    let array = float_array(obj, what)?;
    let shape = array.shape().to_vec();
    let data: Vec<f64> = array.as_array().iter().copied().collect();
    Ok((data, if shape.is_empty() { None } else { Some(shape) }))
}

/// Points of shape `(n, 2)` or `(n, 3)` as 3D points (z = 0 for 2D) and their dimension.
pub fn points(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<DVec3>, u8)> {
    let array = float_array(obj, what)?;
    let shape = array.shape().to_vec();
    if shape.len() != 2 || !(shape[1] == 2 || shape[1] == 3) {
        return Err(PyValueError::new_err(format!(
            "{what} must be an array of shape (n, 2) or (n, 3), got shape {}",
            shape_text(&shape)
        )));
    }
    let view = array.as_array();
    let dim = shape[1];
    let pts = (0..shape[0])
        .map(|i| DVec3::new(view[[i, 0]], view[[i, 1]], if dim == 3 { view[[i, 2]] } else { 0.0 }))
        .collect();
    Ok((pts, dim as u8))
}

/// `(3,)` or `(2, 4)`, as Python writes shapes.
pub fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!("({})", shape.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")),
    }
}

/// A float64 array of `shape` (`None`: a scalar's, `[]`) followed by `tail`, from `data`.
pub fn array_out<'py>(
    py: Python<'py>,
    data: Vec<f64>,
    shape: Option<&[usize]>,
    tail: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let mut full: Vec<usize> = shape.unwrap_or(&[]).to_vec();
    full.extend_from_slice(tail);
    let array = ArrayD::from_shape_vec(IxDyn(&full), data).map_err(value_error)?;
    Ok(array.into_pyarray(py))
}

/// The result for a scalar parameter (a float) or an array of them.
pub fn scalar_or_array(py: Python<'_>, data: Vec<f64>, shape: Option<&[usize]>) -> PyResult<Py<PyAny>> {
    match shape {
        None => Ok(data[0].into_pyobject(py)?.into_any().unbind()),
        Some(shape) => Ok(array_out(py, data, Some(shape), &[])?.into_any().unbind()),
    }
}

/// Points as an `(n, dim)` float64 array (`dim` 2 drops z).
pub fn points_out<'py>(
    py: Python<'py>,
    pts: impl ExactSizeIterator<Item = DVec3>,
    dim: usize,
) -> Bound<'py, numpy::PyArray2<f64>> {
    let n = pts.len();
    let mut flat = Vec::with_capacity(n * dim);
    for p in pts {
        flat.extend_from_slice(&p.to_array()[..dim]);
    }
    Array2::from_shape_vec((n, dim), flat).expect("n·dim values").into_pyarray(py)
}

/// Flat vertex indices and offsets (`F + 1` of them, from 0) of the faces `obj`: an `(F, k)`
/// integer array, or a pair `(indices, offsets)` for polygons of mixed sizes.
pub fn faces(obj: &Bound<'_, PyAny>, num_vertices: usize) -> PyResult<(Vec<u32>, Vec<u32>)> {
    let (indices, offsets) = if let Ok((indices, offsets)) = obj.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>()
        && !obj.hasattr("shape")?
    {
        let indices = int_vector(&indices, "faces' indices")?;
        let offsets = int_vector(&offsets, "faces' offsets")?;
        let ok = offsets.first() == Some(&0)
            && offsets.windows(2).all(|w| w[0] < w[1])
            && offsets.last().is_some_and(|&last| last == indices.len() as i64);
        if !ok {
            return Err(PyValueError::new_err(
                "faces' offsets must start at 0, rise at every face and end at the number of indices",
            ));
        }
        (indices, offsets)
    } else {
        let array = obj
            .extract::<PyArrayLikeDyn<'_, i64, AllowTypeChange>>()
            .map_err(|_| PyValueError::new_err("faces must be an (F, k) integer array or a pair (indices, offsets)"))?;
        let shape = array.shape().to_vec();
        if shape.len() != 2 || shape[1] < 3 {
            return Err(PyValueError::new_err(format!(
                "faces must be an array of shape (F, k) with k ≥ 3, got shape {}",
                shape_text(&shape)
            )));
        }
        let indices: Vec<i64> = array.as_array().iter().copied().collect();
        let offsets = (0..=shape[0]).map(|f| (f * shape[1]) as i64).collect();
        (indices, offsets)
    };
    let mut out = Vec::with_capacity(indices.len());
    for (corner, &v) in indices.iter().enumerate() {
        if v < 0 || v as usize >= num_vertices {
            return Err(PyValueError::new_err(format!(
                "face corner {corner} refers to vertex {v}, but there are {num_vertices} vertices"
            )));
        }
        out.push(v as u32);
    }
    let offsets = offsets
        .into_iter()
        .map(|o| u32::try_from(o).map_err(|_| PyValueError::new_err("too many face corners for 32-bit indices")))
        .collect::<PyResult<Vec<u32>>>()?;
    Ok((out, offsets))
}

/// A 1-dimensional integer array.
fn int_vector(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<i64>> {
    let array = obj
        .extract::<PyArrayLikeDyn<'_, i64, AllowTypeChange>>()
        .map_err(|_| PyValueError::new_err(format!("{what} must be an array of integers")))?;
    if array.ndim() != 1 {
        return Err(PyValueError::new_err(format!(
            "{what} must be 1-dimensional, got shape {}",
            shape_text(array.shape())
        )));
    }
    Ok(array.as_array().iter().copied().collect())
}

/// A mesh from `(V, 3)` vertices and faces (see [`faces`]), checked for finite coordinates.
pub fn mesh(vertices: &Bound<'_, PyAny>, faces_obj: &Bound<'_, PyAny>) -> PyResult<PolyMesh> {
    let (positions, dim) = points(vertices, "vertices")?;
    if dim != 3 {
        return Err(PyValueError::new_err("vertices must be an array of shape (V, 3), got shape (V, 2)"));
    }
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(PyValueError::new_err(format!("vertex {i} is not finite")));
    }
    let (face_vertices, face_offsets) = faces(faces_obj, positions.len())?;
    Ok(PolyMesh { positions, face_offsets, face_vertices, ..PolyMesh::default() })
}

/// `(vertices (V, 3) float64, faces)`: faces `(F, k)` int64 when every face has `k` corners,
/// else a pair `(indices, offsets)`.
pub fn mesh_out(py: Python<'_>, mesh: PolyMesh) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let vertices = points_out(py, mesh.positions.iter().copied(), 3).into_any().unbind();
    Ok((vertices, faces_out(py, &mesh.face_vertices, &mesh.face_offsets)?))
}

/// Faces `(F, k)` int64 when every face has `k` corners, else `(indices, offsets)`.
pub fn faces_out(py: Python<'_>, face_vertices: &[u32], face_offsets: &[u32]) -> PyResult<Py<PyAny>> {
    let sizes = face_offsets.windows(2).map(|w| w[1] - w[0]);
    let first = face_offsets.get(1).copied().unwrap_or(3);
    let indices: Vec<i64> = face_vertices.iter().map(|&v| i64::from(v)).collect();
    let f = face_offsets.len().saturating_sub(1);
    if sizes.clone().all(|k| k == first) {
        let k = first as usize;
        let array = Array2::from_shape_vec((f, k), indices).map_err(value_error)?;
        return Ok(array.into_pyarray(py).into_any().unbind());
    }
    let offsets: Vec<i64> = face_offsets.iter().map(|&o| i64::from(o)).collect();
    let pair = (indices.into_pyarray(py), offsets.into_pyarray(py));
    Ok(pair.into_pyobject(py)?.into_any().unbind())
}

/// Creases `(edges (k, 2), sharpness (k,))` on a mesh of `num_vertices` vertices.
pub fn creases(obj: Option<&Bound<'_, PyAny>>, num_vertices: usize) -> PyResult<Creases> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(Creases::default());
    };
    let (edges, sharpness) = obj
        .extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>()
        .map_err(|_| PyValueError::new_err("creases must be a pair (edges (k, 2), sharpness (k,))"))?;
    let edges = edges
        .extract::<PyArrayLikeDyn<'_, i64, AllowTypeChange>>()
        .map_err(|_| PyValueError::new_err("crease edges must be a (k, 2) integer array"))?;
    let shape = edges.shape().to_vec();
    if shape.len() != 2 || shape[1] != 2 {
        return Err(PyValueError::new_err(format!(
            "crease edges must be an array of shape (k, 2), got shape {}",
            shape_text(&shape)
        )));
    }
    let sharp = float_array(&sharpness, "crease sharpness")?;
    let sharp: Vec<f64> = sharp.as_array().iter().copied().collect();
    if sharp.len() != shape[0] {
        return Err(PyValueError::new_err(format!("{} crease edges but {} sharpness values", shape[0], sharp.len())));
    }
    let view = edges.as_array();
    let mut out = Creases::default();
    for (i, &s) in sharp.iter().enumerate() {
        let (a, b) = (view[[i, 0]], view[[i, 1]]);
        for v in [a, b] {
            if v < 0 || v as usize >= num_vertices {
                return Err(PyValueError::new_err(format!(
                    "crease {i} refers to vertex {v}, but there are {num_vertices} vertices"
                )));
            }
        }
        if !(s >= 0.0) {
            return Err(PyValueError::new_err(format!("crease {i} has sharpness {s}; it must be 0 or more")));
        }
        out.edges.push(EdgeCrease { a: a as u32, b: b as u32, sharpness: s as f32 });
    }
    Ok(out)
}
