//! # splinekit for Python
//!
//! The `splinekit` Python module: curves, arc length and its inverse, flattening, frames,
//! sweeps, subdivision and mesh files, with numpy arrays in and out. Built by maturin (`pip
//! install ./crates/splinekit-py`); see `docs/python.md` for the Python API.
//!
//! This crate only converts: every algorithm is the core's (`splinekit`) or the file crate's
//! (`splinekit-io`), called the way the command line calls them, so Python gets the same
//! numbers bit for bit. Curves are kept as the SWP model describes them
//! ([`splinekit_io::SwpCurve`]) and compiled by its `to_curve`; sweeps and revolutions are
//! made by [`::splinekit_io::SwpDocument::surface_poly`] on a document built in memory;
//! subdivision goes through [`::splinekit::subdiv::subdivide`].
//!
//! Long calls release the GIL. Errors are `ValueError` with the library's messages, and
//! `OSError` (with the error number, so `FileNotFoundError` and the like) for files.
//!
//! The crate is a `cdylib` (lib `splinekit_py`, so that its docs do not collide with the core
//! crate's) with no Rust tests: its tests are the pytest suite in `tests/`,
//! run by `scripts/test-python.sh` against the installed package.

// pyo3's macros expand to unsafe FFI glue (the module's init function, method trampolines):
// allowed here, where no hand-written unsafe code is.
#![allow(unsafe_code)]

mod convert;
mod curve;
mod files;
mod subdiv;
mod surface;

use pyo3::prelude::*;

/// Spline curves, arc length, frames, sweeps and subdivision surfaces, with numpy arrays.
#[pymodule]
fn splinekit(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULT_ACCURACY", ::splinekit::DEFAULT_ACCURACY)?;
    m.add("DEFAULT_STEPS", curve::DEFAULT_STEPS)?;
    m.add_class::<curve::Curve>()?;
    m.add_class::<files::Document>()?;
    m.add_class::<files::Surface>()?;
    m.add_function(wrap_pyfunction!(files::read_swp, m)?)?;
    m.add_function(wrap_pyfunction!(files::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(files::write_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(surface::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(surface::revolve, m)?)?;
    m.add_function(wrap_pyfunction!(subdiv::subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(subdiv::limit_normals, m)?)?;
    Ok(())
}
