//! Exact circles (the SWP `circ` object).

use core::f64::consts::TAU;

use glam::DVec3;

use crate::arclen::ArclenEstimate;
use crate::curve::{Aabb, ParamCurve};
use crate::vector::Vector;

/// A circle of `radius` about the origin in the xy-plane, counter-clockwise from angle 0:
/// `P(u) = r·(cos 2πu, sin 2πu)`, `u ∈ [0, 1]` (one segment). Exact, not a cubic
/// approximation: arc length is `2πr·u`. A radius of 0 is allowed (a point whose
/// tangent is still the circle's direction of travel).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle {
    /// Radius (≥ 0).
    pub radius: f64,
}

impl Circle {
    /// A circle of radius `radius` (negative values are taken as their magnitude).
    #[must_use]
    pub fn new(radius: f64) -> Self {
        Self { radius: radius.abs() }
    }

    fn at(&self, u: f64, order: u32) -> DVec3 {
        let w = TAU;
        let (s, c) = (w * u).sin_cos();
        let r = self.radius * w.powi(order as i32);
        match order % 4 {
            0 => DVec3::new(c, s, 0.0) * r,
            1 => DVec3::new(-s, c, 0.0) * r,
            2 => DVec3::new(-c, -s, 0.0) * r,
            _ => DVec3::new(s, -c, 0.0) * r,
        }
    }
}

impl<P: Vector> ParamCurve<P> for Circle {
    one_segment_from_at!();
    /// Exact: `2πr·(u1 − u0)`, error 0.
    fn arclen_range(&self, u0: f64, u1: f64, _accuracy: f64) -> ArclenEstimate {
        ArclenEstimate { length: TAU * self.radius * (u1 - u0), error: 0.0 }
    }
    fn bounding_box(&self) -> Aabb<P> {
        let r = self.radius;
        Aabb { min: P::from_dvec3(DVec3::new(-r, -r, 0.0)), max: P::from_dvec3(DVec3::new(r, r, 0.0)) }
    }
    /// Exact: `|P″| = r·(2π)²` everywhere.
    fn deriv2_bound(&self, _u0: f64, _u1: f64) -> f64 {
        self.radius * TAU * TAU
    }
    fn unit_tangent(&self, u: f64) -> P {
        let (s, c) = (TAU * u).sin_cos();
        P::from_dvec3(DVec3::new(-s, c, 0.0))
    }
    fn curvature(&self, _u: f64) -> f64 {
        if self.radius > 0.0 { 1.0 / self.radius } else { f64::INFINITY }
    }
    fn torsion(&self, _u: f64) -> f64 {
        0.0
    }
}
