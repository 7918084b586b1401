//! Cubic Hermite splines (points and tangents).

use crate::curve::piecewise::{chain, check_finite};
use crate::curve::{CubicBezier, PiecewiseCubic, SplineError};
use crate::vector::Vector;

/// Cubic Hermite spline: points with the tangent (`dP/du`) the curve must have there.
///
/// # Interpolation
/// Passes through every point.
///
/// # Tangency
/// `P′ = tangent[i]` at point i (per unit of `u`).
///
/// # Continuity
/// C1.
///
/// # Parametrization
/// Open: `n ≥ 2` points, `n − 1` segments. Closed: `n ≥ 2` points, `n` segments (the last
/// returns to the first point). Segment k is the Bézier
/// `(Pk, Pk + Mk/3, Pk+1 − Mk+1/3, Pk+1)`.
///
/// # Usage
/// ```
/// use glam::DVec2;
/// use splinekit::{Hermite, ParamCurve};
/// let pts = [DVec2::ZERO, DVec2::new(1.0, 0.0)];
/// let tan = [DVec2::new(0.0, 1.0), DVec2::new(0.0, -1.0)];
/// let curve = Hermite::new(&pts, &tan, false).unwrap().to_piecewise();
/// assert!((curve.deriv(0.0) - tan[0]).length() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Hermite<P> {
    points: Vec<P>,
    tangents: Vec<P>,
    closed: bool,
}

impl<P: Vector> Hermite<P> {
    /// Validates counts (≥ 2 points, one tangent each) and finiteness.
    pub fn new(points: &[P], tangents: &[P], closed: bool) -> Result<Self, SplineError> {
        if points.len() < 2 {
            return Err(SplineError::InsufficientPoints { kind: "hermite", needed: 2, given: points.len() });
        }
        if points.len() != tangents.len() {
            return Err(SplineError::TangentCount { points: points.len(), tangents: tangents.len() });
        }
        check_finite(points)?;
        check_finite(tangents)?;
        Ok(Self { points: points.to_vec(), tangents: tangents.to_vec(), closed })
    }

    /// Compiles to Bézier segments.
    #[must_use]
    pub fn to_piecewise(&self) -> PiecewiseCubic<P> {
        let n = self.points.len();
        let m = if self.closed { n } else { n - 1 };
        let segments = (0..m)
            .map(|k| {
                let (a, b) = (k, (k + 1) % n);
                let (pa, pb) = (self.points[a], self.points[b]);
                CubicBezier::new(pa, pa + self.tangents[a] * (1.0 / 3.0), pb - self.tangents[b] * (1.0 / 3.0), pb)
            })
            .collect();
        chain(segments, self.closed)
    }
}
