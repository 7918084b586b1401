//! Files: SWP documents (`read_swp`) and meshes (`read_mesh`, `write_mesh`).

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::exceptions::{PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use splinekit::FaceVarying;
use splinekit_io::mesh::{MeshFormat, save_poly_creased};
use splinekit_io::surface::{SurfaceOptions, SurfaceTessellation};
use splinekit_io::{MeshIoError, MeshIoErrorKind, SwpDocument, SwpError, SwpErrorKind, load_mesh};

use crate::convert::{creases, faces_out, mesh, os_error, points, points_out, value_error};
use crate::curve::{Curve, positive};
use crate::surface::mesh_tuple;

/// An SWP error as `OSError` (the file could not be read) or `ValueError` (its text).
fn swp_error(error: SwpError) -> PyErr {
    match error.kind() {
        SwpErrorKind::Io { path, error: io } => os_error(io, error.to_string(), path),
        _ => value_error(error),
    }
}

/// A mesh file error as `OSError` (reading or writing failed) or `ValueError`.
fn mesh_error(error: MeshIoError, path: &std::path::Path) -> PyErr {
    match error.kind() {
        MeshIoErrorKind::Io { error: io, .. } => os_error(io, error.to_string(), path),
        _ => value_error(error),
    }
}

/// The contents of an SWP file: ``curves`` and ``surfaces``, each a dict from name to object in
/// file order (anonymous ones named ``#0``, ``#1``, … by their index).
#[pyclass(module = "splinekit", frozen)]
pub struct Document {
    doc: Arc<SwpDocument>,
}

#[pymethods]
impl Document {
    /// ``{name: Curve}`` in file order.
    #[getter]
    fn curves<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (i, swp) in self.doc.curves.iter().enumerate() {
            dict.set_item(swp.display_name(i), Curve::new(swp.clone())?)?;
        }
        Ok(dict)
    }

    /// ``{name: Surface}`` in file order.
    #[getter]
    fn surfaces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (i, s) in self.doc.surfaces.iter().enumerate() {
            dict.set_item(s.display_name(i), Surface { doc: Arc::clone(&self.doc), index: i })?;
        }
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        format!("<splinekit.Document: {} curves, {} surfaces>", self.doc.curves.len(), self.doc.surfaces.len())
    }
}

/// A surface of an SWP file (``srev``, ``gcyl``, ``zrev``, ``xsweep`` or ``lathe``).
#[pyclass(module = "splinekit", frozen)]
pub struct Surface {
    doc: Arc<SwpDocument>,
    index: usize,
}

#[pymethods]
impl Surface {
    /// The surface's SWP keyword: ``srev``, ``gcyl``, ``zrev``, ``xsweep`` or ``lathe``.
    #[getter]
    fn kind(&self) -> &'static str {
        self.doc.surfaces[self.index].kind.keyword()
    }

    /// The names of the curves it uses, in file order.
    #[getter]
    fn curves(&self) -> Vec<String> {
        let surface = &self.doc.surfaces[self.index];
        surface.kind.references().into_iter().map(|(_, c)| self.doc.curves[c].display_name(c)).collect()
    }

    /// Its mesh ``(vertices, faces)`` (and ``normals`` when asked), as ``splinekit sweep``
    /// makes it: the file's steps and settings, or ``tolerance`` (a distance) in place of the
    /// steps.
    #[pyo3(signature = (tolerance=None, *, normals=false))]
    fn mesh<'py>(&self, py: Python<'py>, tolerance: Option<f64>, normals: bool) -> PyResult<Bound<'py, PyTuple>> {
        let mut options = SurfaceOptions::default();
        if let Some(t) = tolerance {
            options.tessellation = SurfaceTessellation::Distance(positive(t, "tolerance")?);
        }
        mesh_tuple(py, &self.doc, self.index, &options, normals)
    }

    fn __repr__(&self) -> String {
        let s = &self.doc.surfaces[self.index];
        format!("<splinekit.Surface {} {:?}>", s.kind.keyword(), s.display_name(self.index))
    }
}

/// Reads an SWP file: a ``Document`` with ``.curves`` and ``.surfaces``.
///
/// Raises ``OSError`` when the file cannot be read and ``ValueError`` (``FILE:LINE:COL: …``)
/// when its text is not valid SWP.
#[pyfunction]
pub fn read_swp(py: Python<'_>, path: PathBuf) -> PyResult<Document> {
    let doc = py.detach(|| SwpDocument::read(&path)).map_err(swp_error)?;
    Ok(Document { doc: Arc::new(doc) })
}

/// Reads a mesh file (OBJ, PLY, STL or glb, by extension): ``(vertices, faces)``.
///
/// ``faces`` is ``(F, k)`` int64 when every face has ``k`` corners, else a pair ``(indices,
/// offsets)``. With ``creases=True``, a third item: the OBJ file's crease tags as ``(edges (k,
/// 2), sharpness (k,))``. What the reader skipped (unknown OBJ statements, …) is reported as
/// ``UserWarning``.
#[pyfunction]
#[pyo3(signature = (path, *, creases=false))]
pub fn read_mesh<'py>(py: Python<'py>, path: PathBuf, creases: bool) -> PyResult<Bound<'py, PyTuple>> {
    let loaded = py.detach(|| load_mesh(&path)).map_err(|e| mesh_error(e, &path))?;
    for w in &loaded.warnings {
        let text = std::ffi::CString::new(format!("{}: {w}", path.display())).unwrap_or_default();
        PyErr::warn(py, &py.get_type::<PyUserWarning>(), &text, 1)?;
    }
    let mesh = loaded.mesh;
    let vertices = points_out(py, mesh.positions.iter().copied(), 3).into_any();
    let faces = faces_out(py, &mesh.face_vertices, &mesh.face_offsets)?.into_bound(py);
    if !creases {
        return PyTuple::new(py, [vertices, faces]);
    }
    let edges: Vec<i64> = loaded.creases.edges.iter().flat_map(|e| [i64::from(e.a), i64::from(e.b)]).collect();
    let k = loaded.creases.edges.len();
    let edges = numpy::ndarray::Array2::from_shape_vec((k, 2), edges).map_err(value_error)?;
    let sharp: Vec<f64> = loaded.creases.edges.iter().map(|e| f64::from(e.sharpness)).collect();
    let pair = PyTuple::new(
        py,
        [
            numpy::IntoPyArray::into_pyarray(edges, py).into_any(),
            numpy::IntoPyArray::into_pyarray(sharp, py).into_any(),
        ],
    )?;
    PyTuple::new(py, [vertices, faces, pair.into_any()])
}

/// Writes a mesh to ``path`` (OBJ, PLY, STL or glb, by extension), atomically: through a
/// temporary file, so an error leaves no partial file.
///
/// ``faces`` as ``read_mesh`` gives them; ``normals`` one per vertex ``(V, 3)``; ``creases``
/// ``(edges (k, 2), sharpness (k,))`` are written as OBJ crease tags (the other formats cannot
/// hold them). Raises ``OSError`` when the file cannot be written, ``ValueError`` for a bad
/// mesh or an unknown extension.
#[pyfunction]
#[pyo3(signature = (path, vertices, faces, normals=None, creases=None))]
pub fn write_mesh(
    py: Python<'_>,
    path: PathBuf,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    normals: Option<&Bound<'_, PyAny>>,
    creases: Option<&Bound<'_, PyAny>>,
) -> PyResult<()> {
    let format = MeshFormat::from_path(&path).ok_or_else(|| {
        PyValueError::new_err(format!(
            "{}: unknown output format (expected one of {})",
            path.display(),
            MeshFormat::list()
        ))
    })?;
    let mut mesh = mesh(vertices, faces)?;
    if let Some(normals) = normals.filter(|n| !n.is_none()) {
        let (values, dim) = points(normals, "normals")?;
        if dim != 3 || values.len() != mesh.num_vertices() {
            return Err(PyValueError::new_err(format!(
                "normals must be an array of shape ({}, 3), one per vertex",
                mesh.num_vertices()
            )));
        }
        mesh.normals = Some(FaceVarying { values, indices: mesh.face_vertices.clone() });
    }
    let creases = self::creases(creases, mesh.num_vertices())?;
    py.detach(|| save_poly_creased(&mesh, &creases, &path, format, false)).map_err(|e| mesh_error(e, &path))?;
    Ok(())
}
