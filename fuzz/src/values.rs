//! Numbers for the generators: mostly ordinary, now and then extreme (zero, ±1e-300,
//! ±1e300, the largest `f64`, denormals), and written in the forms a reader must accept.

use crate::rng::Rng;

/// Extreme values every reader and algorithm must survive.
pub const EXTREMES: [f64; 22] = [
    0.0,
    -0.0,
    1e-300,
    -1e-300,
    1e300,
    -1e300,
    1e308,
    -1e308,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
    5e-324,
    -5e-324,
    2.5e-320,
    1e-12,
    1e12,
    1.34e154,
    -1.34e154,
    1e200,
    3.4028235e38,
    -3.4028236e38,
    1e-45,
];

/// How the numbers of one input are drawn: one scale for the whole input, so that shapes
/// stay shapes (a tiny or a huge mesh), with a small share of outliers.
#[derive(Clone, Copy, Debug)]
pub struct Scale {
    /// Typical magnitude.
    pub magnitude: f64,
    /// Probability of an extreme value in place of an ordinary one.
    pub outliers: f64,
}

impl Scale {
    /// A scale drawn for one input: usually 1, sometimes tiny or huge, sometimes with
    /// outliers.
    pub fn draw(rng: &mut Rng) -> Self {
        let magnitude = match rng.below(10) {
            0 => *rng.pick(&[1e-300, 1e-150, 1e-12, 1e-6]),
            1 => *rng.pick(&[1e6, 1e12, 1e150, 1e300, 1e307]),
            _ => *rng.pick(&[0.01, 1.0, 1.0, 1.0, 10.0, 100.0]),
        };
        let outliers = match rng.below(4) {
            0 => 0.05,
            1 => 0.005,
            _ => 0.0,
        };
        Self { magnitude, outliers }
    }

    /// A coordinate.
    pub fn coord(&self, rng: &mut Rng) -> f64 {
        if self.outliers > 0.0 && rng.chance(self.outliers) {
            return *rng.pick(&EXTREMES);
        }
        let x = match rng.below(6) {
            0 => rng.below(5) as f64 - 2.0,
            _ => rng.uniform(-2.0, 2.0),
        };
        x * self.magnitude
    }
}

/// A positive number of about `typical`, now and then extreme (including 0 and negatives,
/// which the readers must refuse or handle).
pub fn positive(rng: &mut Rng, typical: f64) -> f64 {
    match rng.below(12) {
        0 => *rng.pick(&EXTREMES),
        1 => typical * *rng.pick(&[1e-9, 1e-3, 1e3, 1e9]),
        _ => typical * rng.uniform(0.1, 3.0),
    }
}

/// `x` as text in one of the forms `f64::from_str` reads: shortest, exponent, fixed with
/// many digits, with a leading dot or plus sign.
pub fn format(rng: &mut Rng, x: f64) -> String {
    match rng.below(10) {
        0 => format!("{x:e}"),
        1 => format!("{x:E}"),
        2 if x.abs() < 1e6 => format!("{x:.17}"),
        3 if x.abs() < 1.0 && x > 0.0 => format!("{x}").trim_start_matches('0').to_owned(),
        4 if x >= 0.0 => format!("+{x}"),
        5 if x.fract() == 0.0 && x.abs() < 1e15 => format!("{}", x as i64),
        _ => format!("{x}"),
    }
}

/// Whitespace between tokens: mostly one space, sometimes tabs, line ends (LF, CRLF), form
/// feeds or runs of them.
pub fn space(rng: &mut Rng) -> &'static str {
    const SPACES: [&str; 12] = [" ", " ", " ", " ", " ", "  ", "\t", "\n", "\r\n", " \x0b", "\x0c", "\n\n  "];
    let i = rng.below(SPACES.len());
    SPACES[i]
}
