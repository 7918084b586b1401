//! [`AnyCurve`]: one type for every curve a file can hold.

use crate::arclen::ArclenEstimate;
use crate::curve::{Aabb, BezierCurve, Circle, Helix, Nurbs, ParamCurve, PiecewiseCubic, Trefoil};
use crate::vector::Vector;

/// Any curve splinekit can evaluate: a chain of cubics (the cubic spline kinds), an exact
/// parametric curve (circle, helix, trefoil knot), a Bézier curve of any degree or a NURBS.
#[derive(Clone, Debug, PartialEq)]
pub enum AnyCurve<P> {
    /// A compiled spline.
    Piecewise(PiecewiseCubic<P>),
    /// An exact circle.
    Circle(Circle),
    /// An exact circular helix (open).
    Helix(Helix),
    /// The exact trefoil knot (closed).
    Trefoil(Trefoil),
    /// A Bézier curve of any degree (one segment).
    Bezier(BezierCurve<P>),
    /// A NURBS curve (one segment per knot span).
    Nurbs(Nurbs<P>),
}

impl<P: Vector> AnyCurve<P> {
    /// Whether the curve is a closed loop: as defined for splines, always for circles and
    /// trefoils, never for helices.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        match self {
            Self::Piecewise(c) => c.is_closed(),
            Self::Circle(_) | Self::Trefoil(_) => true,
            Self::Helix(_) | Self::Bezier(_) => false,
            Self::Nurbs(c) => c.is_closed(),
        }
    }
}

macro_rules! dispatch {
    ($self:ident, $c:ident => $e:expr) => {
        match $self {
            AnyCurve::Piecewise($c) => $e,
            AnyCurve::Circle($c) => $e,
            AnyCurve::Helix($c) => $e,
            AnyCurve::Trefoil($c) => $e,
            AnyCurve::Bezier($c) => $e,
            AnyCurve::Nurbs($c) => $e,
        }
    };
}

impl<P: Vector> ParamCurve<P> for AnyCurve<P> {
    fn num_segments(&self) -> usize {
        dispatch!(self, c => ParamCurve::<P>::num_segments(c))
    }
    fn eval(&self, u: f64) -> P {
        dispatch!(self, c => c.eval(u))
    }
    fn deriv(&self, u: f64) -> P {
        dispatch!(self, c => c.deriv(u))
    }
    fn deriv2(&self, u: f64) -> P {
        dispatch!(self, c => c.deriv2(u))
    }
    fn deriv3(&self, u: f64) -> P {
        dispatch!(self, c => c.deriv3(u))
    }
    fn arclen_range(&self, u0: f64, u1: f64, accuracy: f64) -> ArclenEstimate {
        dispatch!(self, c => ParamCurve::<P>::arclen_range(c, u0, u1, accuracy))
    }
    fn bounding_box(&self) -> Aabb<P> {
        dispatch!(self, c => c.bounding_box())
    }
    fn segment_end(&self, k: usize) -> P {
        dispatch!(self, c => ParamCurve::<P>::segment_end(c, k))
    }
    fn deriv2_bound(&self, u0: f64, u1: f64) -> f64 {
        dispatch!(self, c => ParamCurve::<P>::deriv2_bound(c, u0, u1))
    }
    fn unit_tangent(&self, u: f64) -> P {
        dispatch!(self, c => c.unit_tangent(u))
    }
    fn curvature(&self, u: f64) -> f64 {
        dispatch!(self, c => ParamCurve::<P>::curvature(c, u))
    }
    fn torsion(&self, u: f64) -> f64 {
        dispatch!(self, c => ParamCurve::<P>::torsion(c, u))
    }
}
