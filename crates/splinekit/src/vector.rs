//! The [`Vector`] trait: what a curve needs of its point type.
//!
//! Curves are generic over dimension, not over the scalar: coordinates are
//! always `f64`. The trait is implemented for glam's [`DVec2`] and [`DVec3`].
//!
//! # Axioms
//! An implementor must be a real vector space with a Euclidean inner product
//! (the same list bevy_math's `VectorSpace` documents, property-tested in this
//! module's tests):
//! - `a + b == b + a`, `(a + b) + c == a + (b + c)`, `a + ZERO == a`, `a - a == ZERO`;
//! - `(a + b) * s == a * s + b * s`, `a * (s * t) == (a * s) * t`, `a * 1.0 == a`;
//! - `dot` is symmetric, bilinear, and `a.dot(a) >= 0` with equality only for `ZERO`;
//! - `component(i)` for `i < DIM` reads coordinate `i`, and
//!   `to_dvec3` / `from_dvec3` embed the space in 3D (missing coordinates are 0).

use core::fmt::Debug;
use core::ops::{Add, Mul, Neg, Sub};

use glam::{DVec2, DVec3};

/// A point or vector type that curves can be built from (2D or 3D, `f64`).
pub trait Vector:
    Copy
    + Debug
    + PartialEq
    + Default
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f64, Output = Self>
    + Neg<Output = Self>
{
    /// Number of coordinates.
    const DIM: usize;
    /// The zero vector.
    const ZERO: Self;

    /// Euclidean inner product.
    fn dot(self, other: Self) -> f64;

    /// Coordinate `i` (`0 ≤ i < DIM`); coordinates past `DIM` read as 0.
    fn component(self, i: usize) -> f64;

    /// Embeds the vector in 3D; missing coordinates are 0.
    fn to_dvec3(self) -> DVec3;

    /// Projects a 3D vector onto this space (drops the coordinates past `DIM`).
    fn from_dvec3(v: DVec3) -> Self;

    /// Component-wise minimum.
    #[must_use]
    fn min_components(self, other: Self) -> Self;

    /// Component-wise maximum.
    #[must_use]
    fn max_components(self, other: Self) -> Self;

    /// Squared Euclidean length.
    #[inline]
    fn length_squared(self) -> f64 {
        self.dot(self)
    }

    /// Euclidean length.
    #[inline]
    fn length(self) -> f64 {
        self.dot(self).sqrt()
    }

    /// Euclidean distance to `other`.
    #[inline]
    fn distance(self, other: Self) -> f64 {
        (self - other).length()
    }

    /// Linear interpolation `self·(1−t) + other·t`.
    #[inline]
    #[must_use]
    fn lerp(self, other: Self, t: f64) -> Self {
        self + (other - self) * t
    }

    /// True when every coordinate is finite.
    #[inline]
    fn is_finite_vector(self) -> bool {
        (0..Self::DIM).all(|i| self.component(i).is_finite())
    }

    /// The 3D cross product of the embedded vectors (for 2D, only z is non-zero).
    #[inline]
    fn cross3(self, other: Self) -> DVec3 {
        self.to_dvec3().cross(other.to_dvec3())
    }
}

impl Vector for DVec2 {
    const DIM: usize = 2;
    const ZERO: Self = DVec2::ZERO;

    #[inline]
    fn dot(self, other: Self) -> f64 {
        DVec2::dot(self, other)
    }
    #[inline]
    fn component(self, i: usize) -> f64 {
        match i {
            0 => self.x,
            1 => self.y,
            _ => 0.0,
        }
    }
    #[inline]
    fn to_dvec3(self) -> DVec3 {
        self.extend(0.0)
    }
    #[inline]
    fn from_dvec3(v: DVec3) -> Self {
        v.truncate()
    }
    #[inline]
    fn min_components(self, other: Self) -> Self {
        self.min(other)
    }
    #[inline]
    fn max_components(self, other: Self) -> Self {
        self.max(other)
    }
}

impl Vector for DVec3 {
    const DIM: usize = 3;
    const ZERO: Self = DVec3::ZERO;

    #[inline]
    fn dot(self, other: Self) -> f64 {
        DVec3::dot(self, other)
    }
    #[inline]
    fn component(self, i: usize) -> f64 {
        match i {
            0 => self.x,
            1 => self.y,
            2 => self.z,
            _ => 0.0,
        }
    }
    #[inline]
    fn to_dvec3(self) -> DVec3 {
        self
    }
    #[inline]
    fn from_dvec3(v: DVec3) -> Self {
        v
    }
    #[inline]
    fn min_components(self, other: Self) -> Self {
        self.min(other)
    }
    #[inline]
    fn max_components(self, other: Self) -> Self {
        self.max(other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const EPS: f64 = 1e-9;

    fn v3() -> impl Strategy<Value = DVec3> {
        (-1e3..1e3f64, -1e3..1e3f64, -1e3..1e3f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn close<P: Vector>(a: P, b: P) -> bool {
        (a - b).length() <= EPS * (1.0 + a.length() + b.length())
    }

    #[allow(clippy::eq_op)] // `a - a` is the axiom under test
    fn axioms<P: Vector>(a: P, b: P, c: P, s: f64, t: f64) {
        assert!(close(a + b, b + a));
        assert!(close((a + b) + c, a + (b + c)));
        assert!(close(a + P::ZERO, a));
        assert!(close(a - a, P::ZERO));
        assert!(close((a + b) * s, a * s + b * s));
        assert!(close(a * (s * t), (a * s) * t));
        assert!(close(a * 1.0, a));
        assert!((a.dot(b) - b.dot(a)).abs() <= EPS * (1.0 + a.length() * b.length()));
        assert!(a.dot(a) >= 0.0);
        assert!(close(P::from_dvec3(a.to_dvec3()), a));
        for i in 0..P::DIM {
            assert_eq!(a.component(i), a.to_dvec3()[i]);
        }
        assert_eq!(a.component(P::DIM), 0.0);
    }

    proptest! {
        #[test]
        fn dvec3_axioms(a in v3(), b in v3(), c in v3(), s in -10.0..10.0f64, t in -10.0..10.0f64) {
            axioms(a, b, c, s, t);
        }

        #[test]
        fn dvec2_axioms(a in v3(), b in v3(), c in v3(), s in -10.0..10.0f64, t in -10.0..10.0f64) {
            axioms(a.truncate(), b.truncate(), c.truncate(), s, t);
        }
    }
}
