//! `splinekit.Curve`: a spline as an SWP file describes it, compiled once for the geometry core.

use std::ffi::CString;

use glam::DVec3;
use pyo3::exceptions::{PyRuntimeWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use splinekit::flatten::{self, Tessellation};
use splinekit::frame::{self, FrameMethod, FrameOptions, Side, StartNormal};
use splinekit::{AnyCurve, ArclenIndex, ArclenTable, ParamCurve, TableMethod, Tcb, resample_every};
use splinekit_io::{MAX_STEPS, SourcePos, SwpCurve, SwpCurveKind, SwpGeometry};

use crate::convert::{array_out, points, points_out, scalar_or_array, value_error, values};

/// Steps per segment of a curve made in Python (what `flatten()` and `sweep()` use without a
/// tolerance).
pub const DEFAULT_STEPS: u32 = 20;

/// The most points `flatten` makes (as `splinekit curve --max-points`' default).
pub const MAX_FLATTEN_POINTS: u64 = 50_000_000;

/// The most points `resample` makes (as `splinekit arclen --spacing`).
pub const MAX_RESAMPLE_POINTS: usize = 10_000_000;

/// A curve in 2D or 3D: Bézier, B-spline, Catmull-Rom, Hermite, NURBS, a single Bézier of any
/// degree, or an exact circle, helix or trefoil knot.
///
/// The parameter ``u`` runs over ``[0, num_segments]`` (segment ``k`` covers ``[k, k + 1]``);
/// evaluation outside it extrapolates the first or last segment. Methods taking ``u`` accept a
/// number (and give a number or one point) or an array of any shape (and give an array of that
/// shape, with a last axis of ``dim`` coordinates for points).
#[pyclass(module = "splinekit", frozen)]
pub struct Curve {
    /// The curve as an SWP file would describe it.
    pub swp: SwpCurve,
    /// The compiled curve, 2D curves with z = 0.
    pub curve: AnyCurve<DVec3>,
}

impl Curve {
    /// Compiles `swp` (the same conversion `splinekit curve` and `sweep` use).
    pub fn new(swp: SwpCurve) -> PyResult<Self> {
        let curve = swp.to_curve().map_err(value_error)?;
        Ok(Self { swp, curve })
    }

    fn of_points(kind: SwpCurveKind, points_obj: &Bound<'_, PyAny>, closed: bool, steps: u32) -> PyResult<Self> {
        let (pts, dim) = points(points_obj, "points")?;
        Self::new(swp_curve(kind, dim, steps, closed, SwpGeometry::Points(pts))?)
    }

    fn dim(&self) -> usize {
        usize::from(self.swp.dim)
    }

    /// `values` mapped by `f` (one float each) in parallel with the GIL released for arrays.
    fn map_scalar(&self, py: Python<'_>, u: &Bound<'_, PyAny>, f: impl Fn(f64) -> f64 + Sync) -> PyResult<Py<PyAny>> {
        let (us, shape) = values(u, "u")?;
        let out: Vec<f64> = py.detach(|| us.iter().map(|&u| f(u)).collect());
        scalar_or_array(py, out, shape.as_deref())
    }

    /// `values` mapped by `f` to points (`dim` coordinates each).
    fn map_point(&self, py: Python<'_>, u: &Bound<'_, PyAny>, f: impl Fn(f64) -> DVec3 + Sync) -> PyResult<Py<PyAny>> {
        let (us, shape) = values(u, "u")?;
        let dim = self.dim();
        let out: Vec<f64> = py.detach(|| {
            let mut out = Vec::with_capacity(us.len() * dim);
            for &u in &us {
                out.extend_from_slice(&f(u).to_array()[..dim]);
            }
            out
        });
        Ok(array_out(py, out, shape.as_deref(), &[dim])?.into_any().unbind())
    }
}

/// An SWP curve of `kind` made in Python (no name, no place in a file).
pub fn swp_curve(kind: SwpCurveKind, dim: u8, steps: u32, closed: bool, geometry: SwpGeometry) -> PyResult<SwpCurve> {
    check_steps(steps)?;
    Ok(SwpCurve { name: None, kind, dim, steps, closed, geometry, pos: SourcePos::default() })
}

fn check_steps(steps: u32) -> PyResult<()> {
    if (1..=MAX_STEPS).contains(&steps) {
        Ok(())
    } else {
        Err(PyValueError::new_err(format!("steps must be 1 to {MAX_STEPS}, got {steps}")))
    }
}

/// A positive finite number called `what`, or a `ValueError`.
pub fn positive(value: f64, what: &str) -> PyResult<f64> {
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(PyValueError::new_err(format!("{what} must be a positive number, got {value}")))
    }
}

/// The frame method called `kind`.
pub fn frame_method(kind: &str) -> PyResult<FrameMethod> {
    Ok(match kind {
        "rmf" => FrameMethod::RotationMinimizing(StartNormal::Auto(Side::Left)),
        "sequential" => FrameMethod::Sequential(Side::Left),
        "frenet" => FrameMethod::Frenet,
        "zup" => FrameMethod::FixedUp(DVec3::Z),
        _ => {
            return Err(PyValueError::new_err(format!(
                "unknown frames {kind:?}; expected one of rmf, sequential, frenet, zup"
            )));
        }
    })
}

/// Warns (a `RuntimeWarning`) with `message`.
fn warn(py: Python<'_>, message: &str) -> PyResult<()> {
    let text = CString::new(message).unwrap_or_default();
    PyErr::warn(py, &py.get_type::<PyRuntimeWarning>(), &text, 1)
}

#[pymethods]
impl Curve {
    /// A piecewise cubic Bézier curve: ``3m + 1`` points make ``m`` segments, segment ``k``
    /// using points ``3k .. 3k + 3``; closed, ``3m`` points (the first point ends the last segment).
    #[staticmethod]
    #[pyo3(signature = (points, closed=false, *, steps=DEFAULT_STEPS))]
    fn bezier(points: &Bound<'_, PyAny>, closed: bool, steps: u32) -> PyResult<Self> {
        Self::of_points(SwpCurveKind::Bezier, points, closed, steps)
    }

    /// A uniform cubic B-spline: ``n ≥ 4`` points make ``n − 3`` segments (closed: ``n ≥ 3``
    /// points, ``n`` segments).
    #[staticmethod]
    #[pyo3(signature = (points, closed=false, *, steps=DEFAULT_STEPS))]
    fn bspline(points: &Bound<'_, PyAny>, closed: bool, steps: u32) -> PyResult<Self> {
        Self::of_points(SwpCurveKind::BSpline, points, closed, steps)
    }

    /// A Catmull-Rom spline through the points (the first and last only steer the ends when
    /// open: ``n ≥ 4`` points, ``n − 3`` segments; closed: ``n ≥ 3``, ``n`` segments).
    /// ``alpha``: 0 uniform, 0.5 centripetal, 1 chordal.
    #[staticmethod]
    #[pyo3(signature = (points, closed=false, alpha=0.0, *, steps=DEFAULT_STEPS))]
    fn catmull_rom(points: &Bound<'_, PyAny>, closed: bool, alpha: f64, steps: u32) -> PyResult<Self> {
        Self::of_points(SwpCurveKind::CatmullRom { alpha }, points, closed, steps)
    }

    /// A cubic Hermite spline through ``points`` with the given ``tangents`` (``dP/du``, same
    /// shape): one segment per consecutive pair (closed: also from the last back to the first).
    #[staticmethod]
    #[pyo3(signature = (points, tangents, closed=false, *, steps=DEFAULT_STEPS))]
    fn hermite(points: &Bound<'_, PyAny>, tangents: &Bound<'_, PyAny>, closed: bool, steps: u32) -> PyResult<Self> {
        let (pts, dim) = self::points(points, "points")?;
        let (tangents, tdim) = self::points(tangents, "tangents")?;
        if tdim != dim {
            return Err(PyValueError::new_err(format!(
                "tangents must have {dim} coordinates as the points do, got {tdim}"
            )));
        }
        let geometry = SwpGeometry::Hermite { points: pts, tangents };
        Self::new(swp_curve(SwpCurveKind::Hermite, dim, steps, closed, geometry)?)
    }

    /// A Kochanek–Bartels (TCB) spline through the keys, as ``catmull_rom`` (open: ``n ≥ 4``
    /// keys, the first and last only steer the ends, ``n − 3`` segments; closed: ``n ≥ 3``,
    /// ``n`` segments) with each key's tangents shaped by its ``tension``, ``continuity`` and
    /// ``bias`` (each from −1 to 1; a number for every key or an array of ``n``). All zero is
    /// the uniform Catmull-Rom spline.
    #[staticmethod]
    #[pyo3(signature = (points, tension=None, continuity=None, bias=None, closed=false, *, steps=DEFAULT_STEPS))]
    fn kochanek_bartels(
        points: &Bound<'_, PyAny>,
        tension: Option<&Bound<'_, PyAny>>,
        continuity: Option<&Bound<'_, PyAny>>,
        bias: Option<&Bound<'_, PyAny>>,
        closed: bool,
        steps: u32,
    ) -> PyResult<Self> {
        let (pts, dim) = self::points(points, "points")?;
        let n = pts.len();
        let per_key = |obj: Option<&Bound<'_, PyAny>>, what: &str| -> PyResult<Vec<f64>> {
            let Some(obj) = obj.filter(|o| !o.is_none()) else { return Ok(vec![0.0; n]) };
            let (vals, shape) = values(obj, what)?;
            let vals = match shape {
                None => vec![vals[0]; n],
                Some(shape) if shape == [n] => vals,
                Some(shape) => {
                    return Err(PyValueError::new_err(format!(
                        "{what} must be a number or an array of one value per key ({n}), got shape {shape:?}"
                    )));
                }
            };
            if let Some(bad) = vals.iter().find(|v| !(-1.0..=1.0).contains(*v)) {
                return Err(PyValueError::new_err(format!("{what} must be between -1 and 1, got {bad}")));
            }
            Ok(vals)
        };
        let (t, c, b) = (per_key(tension, "tension")?, per_key(continuity, "continuity")?, per_key(bias, "bias")?);
        let shape = (0..n).map(|i| Tcb::new(t[i], c[i], b[i])).collect();
        let geometry = SwpGeometry::Tcb { points: pts, shape };
        Self::new(swp_curve(SwpCurveKind::KochanekBartels, dim, steps, closed, geometry)?)
    }

    /// A Bessel–Overhauser spline through the points (each key's tangent from the parabola
    /// through it and its neighbours, parametrized by chord length): ``n ≥ 4`` points, ``n − 3``
    /// segments, the first and last only steer the ends (closed: ``n ≥ 3``, ``n`` segments).
    #[staticmethod]
    #[pyo3(signature = (points, closed=false, *, steps=DEFAULT_STEPS))]
    fn bessel_overhauser(points: &Bound<'_, PyAny>, closed: bool, steps: u32) -> PyResult<Self> {
        Self::of_points(SwpCurveKind::BesselOverhauser, points, closed, steps)
    }

    /// One Bézier curve of degree ``n − 1`` through its ``n`` control points (2 to 64);
    /// one segment.
    #[staticmethod]
    #[pyo3(signature = (points, *, steps=DEFAULT_STEPS))]
    fn bezier_n(points: &Bound<'_, PyAny>, steps: u32) -> PyResult<Self> {
        Self::of_points(SwpCurveKind::BezierN, points, false, steps)
    }

    /// A NURBS curve of ``degree`` with ``weights`` (default all 1) and ``knots`` (default
    /// clamped uniform; ``len(points) + degree + 1`` of them). Closed: periodic, no knots.
    #[staticmethod]
    #[pyo3(signature = (points, weights=None, degree=3, knots=None, closed=false, *, steps=DEFAULT_STEPS))]
    fn nurbs(
        points: &Bound<'_, PyAny>,
        weights: Option<Vec<f64>>,
        degree: u32,
        knots: Option<Vec<f64>>,
        closed: bool,
        steps: u32,
    ) -> PyResult<Self> {
        let (pts, dim) = self::points(points, "points")?;
        let weights = weights.unwrap_or_else(|| vec![1.0; pts.len()]);
        if weights.len() != pts.len() {
            return Err(PyValueError::new_err(format!(
                "{} points but {} weights; give one weight per point",
                pts.len(),
                weights.len()
            )));
        }
        let kind = SwpCurveKind::Nurbs { degree };
        if !kind.accepts_point_count(closed, pts.len() as u64) {
            return Err(PyValueError::new_err(format!(
                "a{} NURBS of degree {degree} cannot have {} points (degree 1 to {}, more points than the degree{})",
                if closed { " closed" } else { "n open" },
                pts.len(),
                splinekit::MAX_NURBS_DEGREE,
                if closed { ", at least 3" } else { "" }
            )));
        }
        let geometry = SwpGeometry::Nurbs { points: pts, weights, knots };
        Self::new(swp_curve(kind, dim, steps, closed, geometry)?)
    }

    /// The exact circle of ``radius`` about the origin in the xy-plane, counter-clockwise from
    /// ``(radius, 0)``; one segment, 2D.
    #[staticmethod]
    #[pyo3(signature = (radius, *, steps=DEFAULT_STEPS))]
    fn circle(radius: f64, steps: u32) -> PyResult<Self> {
        if !(radius >= 0.0 && radius.is_finite()) {
            return Err(PyValueError::new_err(format!("radius must be a finite number ≥ 0, got {radius}")));
        }
        Self::new(swp_curve(SwpCurveKind::Circle, 2, steps, true, SwpGeometry::Circle { radius })?)
    }

    /// A circular helix about +z from ``(radius, 0, 0)``, rising ``pitch`` per turn; 3D.
    #[staticmethod]
    #[pyo3(signature = (radius, pitch, turns, *, steps=DEFAULT_STEPS))]
    fn helix(radius: f64, pitch: f64, turns: f64, steps: u32) -> PyResult<Self> {
        let ok = radius >= 0.0 && radius.is_finite() && pitch.is_finite() && turns > 0.0 && turns <= 10_000.0;
        if !ok {
            return Err(PyValueError::new_err(format!(
                "a helix needs a finite radius ≥ 0, a finite pitch and 0 < turns ≤ 10000, got {radius}, {pitch}, {turns}"
            )));
        }
        let geometry = SwpGeometry::Helix { radius, pitch, turns };
        Self::new(swp_curve(SwpCurveKind::Helix, 3, steps, false, geometry)?)
    }

    /// The trefoil knot of ``size`` (closed, 3D), as the SWP ``trefoil`` curve.
    #[staticmethod]
    #[pyo3(signature = (size, *, steps=DEFAULT_STEPS))]
    fn trefoil(size: f64, steps: u32) -> PyResult<Self> {
        if !(size >= 0.0 && size.is_finite()) {
            return Err(PyValueError::new_err(format!("size must be a finite number ≥ 0, got {size}")));
        }
        Self::new(swp_curve(SwpCurveKind::Trefoil, 3, steps, true, SwpGeometry::Trefoil { size })?)
    }

    /// This curve with ``steps`` steps per segment (for ``flatten()`` and ``sweep()`` without a
    /// tolerance).
    fn with_steps(&self, steps: u32) -> PyResult<Self> {
        check_steps(steps)?;
        Ok(Self { swp: SwpCurve { steps, ..self.swp.clone() }, curve: self.curve.clone() })
    }

    /// The curve's name in its SWP file (``None`` for curves made in Python and anonymous ones).
    #[getter]
    fn name(&self) -> Option<String> {
        self.swp.name.clone()
    }

    /// The SWP keyword of the curve's kind: ``bez2``, ``bsp3``, ``cr2``, ``her3``, ``nurbs2``, ``circ``, …
    #[getter]
    fn kind(&self) -> &'static str {
        self.swp.keyword()
    }

    /// 2 or 3.
    #[getter(dim)]
    fn dim_py(&self) -> usize {
        self.dim()
    }

    /// Whether the curve is closed.
    #[getter]
    fn closed(&self) -> bool {
        self.curve.is_closed()
    }

    /// Steps per segment of uniform tessellation.
    #[getter]
    fn steps(&self) -> u32 {
        self.swp.steps
    }

    /// The number of segments ``m``; ``u`` runs over ``[0, m]``.
    #[getter]
    fn num_segments(&self) -> usize {
        self.curve.num_segments()
    }

    /// ``(0.0, num_segments)``.
    #[getter]
    fn domain(&self) -> (f64, f64) {
        self.curve.domain()
    }

    /// The control points (or Hermite points), ``(n, dim)``; empty for circles, helices and knots.
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        points_out(py, self.swp.geometry.points().iter().copied(), self.dim())
    }

    /// The position at ``u``: ``(dim,)`` for a number, ``u.shape + (dim,)`` for an array.
    fn evaluate(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.map_point(py, u, |u| self.curve.eval(u))
    }

    /// The ``order``-th derivative ``dᵏP/duᵏ`` at ``u`` (order 0 to 3), shaped as ``evaluate``.
    #[pyo3(signature = (u, order=1))]
    fn derivative(&self, py: Python<'_>, u: &Bound<'_, PyAny>, order: u32) -> PyResult<Py<PyAny>> {
        let c = &self.curve;
        match order {
            0 => self.map_point(py, u, |u| c.eval(u)),
            1 => self.map_point(py, u, |u| c.deriv(u)),
            2 => self.map_point(py, u, |u| c.deriv2(u)),
            3 => self.map_point(py, u, |u| c.deriv3(u)),
            _ => Err(PyValueError::new_err(format!("order must be 0, 1, 2 or 3, got {order}"))),
        }
    }

    /// The curvature ``κ = |P′ × P″| / |P′|³`` at ``u`` (≥ 0; ``inf`` at a cusp).
    fn curvature(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.map_scalar(py, u, |u| self.curve.curvature(u))
    }

    /// The length of the whole curve to within ``accuracy`` (absolute, length units), by
    /// adaptive Gauss–Kronrod quadrature (as ``splinekit arclen --method adaptive``).
    #[pyo3(signature = (accuracy=splinekit::DEFAULT_ACCURACY))]
    fn arclen(&self, py: Python<'_>, accuracy: f64) -> PyResult<f64> {
        let accuracy = positive(accuracy, "accuracy")?;
        let index = py.detach(|| ArclenIndex::new(&self.curve, accuracy));
        check_index(py, &index, accuracy)?;
        Ok(index.length())
    }

    /// The u–s arc-length table ``(u, s)`` with ``samples`` rows per segment (``m·samples + 1``
    /// rows, ``u = k + i/samples``): ``"chord"`` sums straight-line distances between samples
    /// (a lower bound), ``"gauss3"`` integrates the speed with 3-point Gauss–Legendre per
    /// interval (as ``splinekit arclen --method chord|gauss3``).
    #[pyo3(signature = (samples=5, method="chord"))]
    fn arclen_table<'py>(&self, py: Python<'py>, samples: usize, method: &str) -> PyResult<Bound<'py, PyTuple>> {
        let method = match method {
            "chord" => TableMethod::Chord,
            "gauss3" => TableMethod::Gauss3,
            _ => return Err(PyValueError::new_err(format!("unknown method {method:?}; expected chord or gauss3"))),
        };
        let rows = samples.checked_mul(self.curve.num_segments()).and_then(|r| r.checked_add(1));
        if samples == 0 || rows.is_none_or(|r| r > MAX_RESAMPLE_POINTS) {
            return Err(PyValueError::new_err(format!(
                "samples must be 1 or more, and give at most {MAX_RESAMPLE_POINTS} table rows, got {samples}"
            )));
        }
        let table = py.detach(|| ArclenTable::new(&self.curve, method, samples));
        let (u, s): (Vec<f64>, Vec<f64>) = table.iter_rows().unzip();
        let n = u.len();
        PyTuple::new(py, [array_out(py, u, Some(&[n]), &[])?, array_out(py, s, Some(&[n]), &[])?])
    }

    /// The parameter ``u`` where the arc length from the start reaches ``s`` (a number or an
    /// array), with ``|s(u) − s| ≤ accuracy``; ``s`` is clamped to ``[0, length]``.
    #[pyo3(signature = (s, accuracy=splinekit::DEFAULT_ACCURACY))]
    fn inv_arclen(&self, py: Python<'_>, s: &Bound<'_, PyAny>, accuracy: f64) -> PyResult<Py<PyAny>> {
        let accuracy = positive(accuracy, "accuracy")?;
        let (ss, shape) = values(s, "s")?;
        let curve = &self.curve;
        let (index, us) = py.detach(|| {
            let index = ArclenIndex::new(curve, accuracy);
            let us: Vec<f64> = ss.iter().map(|&s| index.u_at(curve, s)).collect();
            (index, us)
        });
        check_index(py, &index, accuracy)?;
        scalar_or_array(py, us, shape.as_deref())
    }

    /// Points every ``spacing`` of arc length from the start, ``(k, dim)`` (the end point only
    /// when the length is a multiple of ``spacing``); each within 1e-9 of its arc length.
    fn resample<'py>(&self, py: Python<'py>, spacing: f64) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        let curve = &self.curve;
        let points = py
            .detach(|| resample_every(curve, spacing, splinekit::DEFAULT_ACCURACY, MAX_RESAMPLE_POINTS))
            .map_err(value_error)?;
        Ok(points_out(py, points.iter().map(|p| p.point), self.dim()))
    }

    /// The curve as a polyline: ``(u, points)``, ``u`` ascending from 0 to ``num_segments``.
    ///
    /// ``tolerance``: the polyline stays within that distance of the curve, both ways.
    /// ``angle_tolerance`` (degrees): segments are halved until their control polygons turn
    /// less. ``steps``: that many equal parameter steps per segment. Give at most one; without
    /// any, the curve's own ``steps``. On a closed curve the last point repeats the first.
    #[pyo3(signature = (tolerance=None, angle_tolerance=None, steps=None))]
    fn flatten<'py>(
        &self,
        py: Python<'py>,
        tolerance: Option<f64>,
        angle_tolerance: Option<f64>,
        steps: Option<u32>,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let given = [tolerance.is_some(), angle_tolerance.is_some(), steps.is_some()];
        if given.iter().filter(|&&g| g).count() > 1 {
            return Err(PyValueError::new_err("give at most one of tolerance, angle_tolerance and steps"));
        }
        let mode = match (tolerance, angle_tolerance, steps) {
            (Some(t), _, _) if t > 0.0 && t.is_finite() => Tessellation::Distance { tolerance: t },
            (Some(t), _, _) => {
                return Err(PyValueError::new_err(format!("tolerance must be a positive number, got {t}")));
            }
            (_, Some(a), _) if a > 0.0 && a.is_finite() => Tessellation::Angle { tolerance: a.to_radians() },
            (_, Some(a), _) => {
                return Err(PyValueError::new_err(format!(
                    "angle_tolerance must be a positive number of degrees, got {a}"
                )));
            }
            (_, _, steps) => {
                let steps = steps.unwrap_or(self.swp.steps);
                check_steps(steps)?;
                Tessellation::Uniform { steps: steps as usize }
            }
        };
        let curve = &self.curve;
        let count = flatten::flatten_count(curve, mode);
        if count > MAX_FLATTEN_POINTS {
            return Err(PyValueError::new_err(format!(
                "this tessellation would give {} points, more than {MAX_FLATTEN_POINTS}; use a coarser tolerance or \
                 fewer steps",
                if count == u64::MAX { "too many".to_owned() } else { format!("up to {count}") },
            )));
        }
        let (params, pts) = py.detach(|| {
            let params = flatten::flatten_any(curve, mode);
            let mut pts: Vec<DVec3> = params.iter().map(|&u| curve.eval(u)).collect();
            // the last point of a closed curve repeats the first exactly
            if curve.is_closed()
                && let Some(&first) = pts.first()
                && let Some(last) = pts.last_mut()
            {
                *last = first;
            }
            (params, pts)
        });
        let n = params.len();
        let u = array_out(py, params, Some(&[n]), &[])?;
        let pts = points_out(py, pts.into_iter(), self.dim());
        PyTuple::new(py, [u.into_any(), pts.into_any()])
    }

    /// Frames ``(T, N, B)`` at the parameters ``u`` (a number or a 1-D array, ascending for
    /// ``rmf``): unit tangent, normal and binormal, each ``(k, 3)`` (``(3,)`` for a number),
    /// right-handed. ``kind``: ``"rmf"`` rotation-minimizing (double reflection),
    /// ``"sequential"`` (the course method, ``B₀ = +z``; N left of travel in 2D), ``"frenet"``,
    /// or ``"zup"`` (B leans toward +z). When the samples close a loop, the closed-curve fix
    /// turns the frames so the last matches the first.
    #[pyo3(signature = (u, kind="rmf"))]
    fn frames<'py>(&self, py: Python<'py>, u: &Bound<'_, PyAny>, kind: &str) -> PyResult<Bound<'py, PyTuple>> {
        let method = frame_method(kind)?;
        let (us, shape) = values(u, "u")?;
        if shape.as_ref().is_some_and(|s| s.len() != 1) {
            return Err(PyValueError::new_err("u must be a number or a 1-dimensional array"));
        }
        let curve = &self.curve;
        let frames = py.detach(|| {
            let samples = frame::sample(curve, &us);
            frame::frames_for_samples(&samples, &FrameOptions::DEFAULT.with_method(method))
        });
        let n = frames.len();
        let column = |pick: fn(&frame::Frame) -> DVec3| -> PyResult<Bound<'py, PyAny>> {
            let data: Vec<f64> = frames.iter().flat_map(|f| pick(f).to_array()).collect();
            let lead = [n];
            Ok(array_out(py, data, shape.as_ref().map(|_| &lead[..]), &[3])?.into_any())
        };
        PyTuple::new(py, [column(|f| f.t)?, column(|f| f.n)?, column(|f| f.b)?])
    }

    fn __repr__(&self) -> String {
        let name = self.swp.name.as_ref().map_or_else(String::new, |n| format!(" {n:?}"));
        let n = self.swp.geometry.points().len();
        let m = self.curve.num_segments();
        format!(
            "<splinekit.Curve {}{name}: {n} points, {m} segment{}{}>",
            self.swp.keyword(),
            if m == 1 { "" } else { "s" },
            if self.curve.is_closed() { ", closed" } else { "" }
        )
    }
}

/// Fails when the length overflowed; warns when the accuracy could not be met.
fn check_index(py: Python<'_>, index: &ArclenIndex, accuracy: f64) -> PyResult<()> {
    if !index.length().is_finite() {
        return Err(PyValueError::new_err(
            "the curve's arc length overflows f64 arithmetic (its coordinates are too close to the largest number, \
             about 1.8e308); scale the curve down",
        ));
    }
    if !index.meets_accuracy() {
        warn(
            py,
            &format!(
                "the length and positions are within about {:.1e}, not the accuracy {accuracy:?}: f64 arithmetic \
                 cannot resolve more on this curve (about 1e-15 of its length, more where its coordinates dwarf its \
                 detail)",
                2.0 * index.error()
            ),
        )?;
    }
    Ok(())
}
