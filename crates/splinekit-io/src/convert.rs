//! From the SWP model to the geometry core: [`SwpCurve::to_curve`].
//!
//! Each SWP curve kind maps to its core constructor with the curve's `closed` flag
//! (and, for Catmull-Rom, its `alpha`), then compiles to a [`PiecewiseCubic`](splinekit::PiecewiseCubic);
//! circles, helices and trefoil knots become the exact [`Circle`], [`Helix`] and [`Trefoil`].
//! 2D curves keep `z = 0`, so every curve is an [`AnyCurve<DVec3>`].
//!
//! ```
//! use splinekit::ParamCurve;
//! use splinekit_io::SwpDocument;
//!
//! let doc = SwpDocument::parse("bsp2 . 20 4 [0 0] [1 0] [1 1] [0 1]", "a.swp")?;
//! let curve = doc.curves[0].to_curve()?;
//! assert_eq!(curve.num_segments(), 1);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use glam::DVec3;
use splinekit::{
    AnyCurve, BSpline, BesselOverhauser, BezierCurve, BezierSpline, CatmullRom, Circle, Helix, Hermite,
    KochanekBartels, Nurbs, SplineError, Trefoil,
};

use crate::swp::{SwpCurve, SwpCurveKind, SwpGeometry};

impl SwpCurve {
    /// Builds the core curve this SWP curve describes.
    ///
    /// | SWP kind | core curve |
    /// |---|---|
    /// | `bez2`, `bez3` | [`BezierSpline`] |
    /// | `bsp2`, `bsp3` | [`BSpline`] (uniform cubic) |
    /// | `cr2`, `cr3` | [`CatmullRom`] with the curve's `alpha` |
    /// | `her2`, `her3` | [`Hermite`] |
    /// | `tcb2`, `tcb3` | [`KochanekBartels`] |
    /// | `bo2`, `bo3` | [`BesselOverhauser`] |
    /// | `bezn2`, `bezn3` | [`BezierCurve`] ([`AnyCurve::Bezier`]) |
    /// | `nurbs2`, `nurbs3` | [`Nurbs`] ([`AnyCurve::Nurbs`]; closed: [`Nurbs::periodic`]) |
    /// | `circ` | [`Circle`] ([`AnyCurve::Circle`]) |
    /// | `helix` | [`Helix`] ([`AnyCurve::Helix`]) |
    /// | `trefoil` | [`Trefoil`] ([`AnyCurve::Trefoil`]) |
    ///
    /// The `closed` flag is passed on (circles and trefoils are always closed, helices open).
    ///
    /// # Errors
    ///
    /// The core constructor's [`SplineError`] when the data does not fit the kind (too
    /// few points, a bad Bézier count, a non-finite coordinate, an alpha outside `[0, 1]`, a
    /// tension, continuity or bias outside `[−1, 1]`).
    /// Parsed documents have already passed these checks. A kind whose geometry is of the
    /// wrong shape (say Bézier with Hermite data, possible only in a hand-built model) is
    /// reported as [`SplineError::Empty`], except that Hermite or Kochanek–Bartels data given
    /// to a points kind uses its points.
    pub fn to_curve(&self) -> Result<AnyCurve<DVec3>, SplineError> {
        let points = self.geometry.points();
        let closed = self.closed;
        let curve = match (self.kind, &self.geometry) {
            (SwpCurveKind::Circle, SwpGeometry::Circle { radius }) => {
                return Ok(AnyCurve::Circle(Circle::new(*radius)));
            }
            (SwpCurveKind::Helix, SwpGeometry::Helix { radius, pitch, turns }) => {
                return Ok(AnyCurve::Helix(Helix::new(*radius, *pitch, *turns)));
            }
            (SwpCurveKind::Trefoil, SwpGeometry::Trefoil { size }) => {
                return Ok(AnyCurve::Trefoil(Trefoil::new(*size)));
            }
            (SwpCurveKind::Circle | SwpCurveKind::Helix | SwpCurveKind::Trefoil, _)
            | (_, SwpGeometry::Circle { .. } | SwpGeometry::Helix { .. } | SwpGeometry::Trefoil { .. }) => {
                return Err(SplineError::Empty);
            }
            (SwpCurveKind::Bezier, _) => BezierSpline::new(points, closed)?.to_piecewise(),
            (SwpCurveKind::BSpline, _) => BSpline::new(points, closed)?.to_piecewise(),
            (SwpCurveKind::CatmullRom { alpha }, _) => CatmullRom::new(points, closed, alpha)?.to_piecewise(),
            (SwpCurveKind::Hermite, SwpGeometry::Hermite { points, tangents }) => {
                Hermite::new(points, tangents, closed)?.to_piecewise()
            }
            (SwpCurveKind::KochanekBartels, SwpGeometry::Tcb { points, shape }) => {
                KochanekBartels::new(points, shape, closed)?.to_piecewise()
            }
            (SwpCurveKind::BesselOverhauser, _) => BesselOverhauser::new(points, closed)?.to_piecewise(),
            (SwpCurveKind::BezierN, _) => {
                if closed {
                    return Err(SplineError::NotClosable { what: "a single Bézier curve cannot be closed" });
                }
                return Ok(AnyCurve::Bezier(BezierCurve::new(points.to_vec())?));
            }
            (SwpCurveKind::Nurbs { degree }, SwpGeometry::Nurbs { points, weights, knots }) => {
                let degree = degree as usize;
                let nurbs = match (closed, knots) {
                    (false, knots) => Nurbs::new(degree, points.clone(), weights.clone(), knots.clone())?,
                    (true, None) => Nurbs::periodic(degree, points.clone(), weights.clone())?,
                    (true, Some(_)) => {
                        return Err(SplineError::NotClosable {
                            what: "a closed NURBS is periodic with knots of its own; it takes no knot vector",
                        });
                    }
                };
                return Ok(AnyCurve::Nurbs(nurbs));
            }
            (SwpCurveKind::Hermite, SwpGeometry::Points(_) | SwpGeometry::Tcb { .. } | SwpGeometry::Nurbs { .. })
            | (
                SwpCurveKind::KochanekBartels,
                SwpGeometry::Points(_) | SwpGeometry::Hermite { .. } | SwpGeometry::Nurbs { .. },
            )
            | (SwpCurveKind::Nurbs { .. }, _) => {
                return Err(SplineError::Empty);
            }
        };
        Ok(AnyCurve::Piecewise(curve))
    }
}

#[cfg(test)]
mod tests {
    use core::f64::consts::TAU;

    use splinekit::ParamCurve;

    use super::*;
    use crate::swp::{SourcePos, SwpDocument};

    const EPS: f64 = 1e-12;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() <= EPS
    }

    fn curve(kind: SwpCurveKind, closed: bool, geometry: SwpGeometry) -> SwpCurve {
        SwpCurve { name: None, kind, dim: 3, steps: 10, closed, geometry, pos: SourcePos::default() }
    }

    fn pts() -> Vec<DVec3> {
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.5),
            DVec3::new(3.0, 1.0, -1.0),
            DVec3::new(4.0, -1.0, 2.0),
            DVec3::new(6.0, 0.0, 1.0),
            DVec3::new(7.0, 3.0, 0.0),
            DVec3::new(5.0, 4.0, -2.0),
        ]
    }

    #[test]
    fn bspline_window() {
        let p = pts();
        let c = curve(SwpCurveKind::BSpline, false, SwpGeometry::Points(p[..4].to_vec())).to_curve().unwrap();
        assert_eq!(c.num_segments(), 1);
        assert!(close(c.eval(0.0), (p[0] + 4.0 * p[1] + p[2]) / 6.0));
        assert!(close(c.eval(1.0), (p[1] + 4.0 * p[2] + p[3]) / 6.0));
        assert!(!c.is_closed());

        let closed = curve(SwpCurveKind::BSpline, true, SwpGeometry::Points(p[..4].to_vec())).to_curve().unwrap();
        assert_eq!(closed.num_segments(), 4);
        assert!(closed.is_closed());
        assert!(close(closed.eval(0.0), closed.eval(4.0)));
    }

    #[test]
    fn bezier_counts_and_endpoints() {
        let p = pts();
        let c = curve(SwpCurveKind::Bezier, false, SwpGeometry::Points(p.clone())).to_curve().unwrap();
        assert_eq!(c.num_segments(), 2);
        assert!(close(c.eval(0.0), p[0]));
        assert!(close(c.eval(1.0), p[3]));
        assert!(close(c.eval(2.0), p[6]));

        let closed = curve(SwpCurveKind::Bezier, true, SwpGeometry::Points(p[..6].to_vec())).to_curve().unwrap();
        assert_eq!(closed.num_segments(), 2);
        assert!(close(closed.eval(2.0), p[0]));

        let bad = curve(SwpCurveKind::Bezier, false, SwpGeometry::Points(p[..5].to_vec())).to_curve();
        assert!(matches!(bad, Err(SplineError::BadPointCount { given: 5, .. })));
    }

    #[test]
    fn catmull_rom_interpolates_and_keeps_alpha() {
        let p = pts();
        for alpha in [0.0, 0.5, 1.0] {
            let c =
                curve(SwpCurveKind::CatmullRom { alpha }, false, SwpGeometry::Points(p.clone())).to_curve().unwrap();
            assert_eq!(c.num_segments(), 4);
            for k in 0..=4 {
                assert!(close(c.eval(k as f64), p[k + 1]), "alpha {alpha}, knot {k}");
            }
        }
        // uniform: the exact window conversion P1 + (P2 − P0)/6 is the second Bézier point,
        // so P′(0) = 3·(P2 − P0)/6 = (P2 − P0)/2
        let c =
            curve(SwpCurveKind::CatmullRom { alpha: 0.0 }, false, SwpGeometry::Points(p.clone())).to_curve().unwrap();
        assert!(close(c.deriv(0.0), (p[2] - p[0]) * 0.5));

        let closed = curve(SwpCurveKind::CatmullRom { alpha: 0.5 }, true, SwpGeometry::Points(p[..3].to_vec()));
        assert_eq!(closed.to_curve().unwrap().num_segments(), 3);

        let bad = curve(SwpCurveKind::CatmullRom { alpha: 2.0 }, false, SwpGeometry::Points(p));
        assert!(matches!(bad.to_curve(), Err(SplineError::BadAlpha { .. })));
    }

    #[test]
    fn hermite_tangents() {
        let points = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)];
        let tangents = vec![DVec3::Y, DVec3::Y * 2.0, -DVec3::X];
        let geometry = SwpGeometry::Hermite { points: points.clone(), tangents: tangents.clone() };
        let c = curve(SwpCurveKind::Hermite, false, geometry.clone()).to_curve().unwrap();
        assert_eq!(c.num_segments(), 2);
        for k in 0..3 {
            assert!(close(c.eval(k as f64), points[k]));
            assert!(close(c.deriv(k as f64), tangents[k]));
        }
        assert_eq!(curve(SwpCurveKind::Hermite, true, geometry).to_curve().unwrap().num_segments(), 3);
        assert_eq!(
            curve(SwpCurveKind::Hermite, false, SwpGeometry::Points(points)).to_curve(),
            Err(SplineError::Empty)
        );
    }

    #[test]
    fn circle() {
        let c = curve(SwpCurveKind::Circle, true, SwpGeometry::Circle { radius: 2.0 }).to_curve().unwrap();
        assert!(matches!(c, AnyCurve::Circle(Circle { radius: 2.0 })));
        assert!(close(c.eval(0.25), DVec3::new(0.0, 2.0, 0.0)));
        assert!((c.arclen(1e-9) - 2.0 * TAU).abs() < EPS);
        let wrong = curve(SwpCurveKind::BSpline, false, SwpGeometry::Circle { radius: 1.0 });
        assert_eq!(wrong.to_curve(), Err(SplineError::Empty));
    }

    #[test]
    fn helix_and_trefoil() {
        let h = curve(SwpCurveKind::Helix, false, SwpGeometry::Helix { radius: 2.0, pitch: 0.5, turns: 3.0 });
        let c = h.to_curve().unwrap();
        assert!(matches!(c, AnyCurve::Helix(Helix { radius: 2.0, pitch: 0.5, turns: 3.0 })));
        assert!(close(c.eval(1.0), DVec3::new(2.0, 0.0, 1.5)));
        assert!(!c.is_closed());
        let k = curve(SwpCurveKind::Trefoil, true, SwpGeometry::Trefoil { size: 1.5 }).to_curve().unwrap();
        assert!(close(k.eval(0.0), DVec3::new(0.0, -1.5, 0.0)));
        assert!(k.is_closed());
        let wrong = curve(SwpCurveKind::Helix, false, SwpGeometry::Trefoil { size: 1.0 });
        assert_eq!(wrong.to_curve(), Err(SplineError::Empty));
        let wrong = curve(SwpCurveKind::Bezier, false, SwpGeometry::Helix { radius: 1.0, pitch: 1.0, turns: 1.0 });
        assert_eq!(wrong.to_curve(), Err(SplineError::Empty));
    }

    #[test]
    fn parsed_document() {
        let text = "bez2 . 20 4 [3 0] [3 1] [1 1] [1 0]\n\
                    bsp3 b 20 4 [-2 0 1] [0 2 1] [0 3 -1] [2 0 -1]\n\
                    circ c 30 1\n";
        let doc = SwpDocument::parse(text, "t.swp").unwrap();
        let curves: Vec<_> = doc.curves.iter().map(|c| c.to_curve().unwrap()).collect();
        assert!(close(curves[0].eval(1.0), DVec3::new(1.0, 0.0, 0.0)));
        assert!(close(curves[1].eval(0.0), DVec3::new(-2.0, 11.0, 4.0) / 6.0));
        assert!(matches!(curves[2], AnyCurve::Circle(_)));
    }
}
