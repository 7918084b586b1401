//! What a subdivision carries from level to level: any [`Attribute`].

use core::ops::{Add, Mul};

/// A value that can be subdivided: an affine combination of values is a value.
pub trait Attribute: Copy + Default + Send + Sync + Add<Output = Self> + Mul<f64, Output = Self> {}
impl<T: Copy + Default + Send + Sync + Add<Output = T> + Mul<f64, Output = T>> Attribute for T {}
