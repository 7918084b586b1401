//! Gauss–Legendre rules with 1 to 20 nodes, then every 4th to 64 and every 8th to 128
//! ([`RULES`]),
//! and the error bound for analytic integrands.
//!
//! The nodes and weights are in `gauss_tables.rs`, written by `make_gauss_tables.py` beside
//! this file (40-digit arithmetic with Python's mpmath: Legendre roots refined by Newton's
//! method, weights `2 / ((1 − x²)·P′ₘ(x)²)`, rounded to 20 significant digits); to regenerate
//! them, run `python3 make_gauss_tables.py > gauss_tables.rs` in this directory. The tests
//! check them against the moments of `x^k`.
//!
//! # Error bound
//! Theorem 19.3 of Trefethen, *Approximation Theory and Approximation Practice* (SIAM
//! 2013): if `f` is analytic in the open Bernstein ellipse `E_ρ` (foci ±1, semi-axes
//! summing to `ρ > 1`) and `|f| ≤ M` there, the `(n+1)`-point Gauss–Legendre rule on
//! `[−1, 1]` has error at most `(64/15)·M·ρ^(−2n)/(ρ² − 1)`. So `m` nodes give
//! `(64/15)·M·ρ^(−2(m−1))/(ρ² − 1)`. Proof sketch: the Chebyshev coefficients obey
//! `|aₖ| ≤ 2Mρ^(−k)`, the rule integrates `Tₖ` exactly for `k < 2m` and for odd `k`, and
//! misses an even `Tₖ` by at most `2 + 2/(k² − 1)`.

use glam::DVec2;

use super::gauss_tables::{NODES, WEIGHTS};

/// The bound of the [module docs](self) for `m` nodes, with `rho2_minus_1 = ρ² − 1`.
/// (The arc-length code uses it in logarithmic form, see `arclen::planar`.)
#[cfg(test)]
fn ellipse_error_bound(m: usize, rho2_minus_1: f64, bound: f64) -> f64 {
    (64.0 / 15.0) * bound * (1.0 + rho2_minus_1).powi(1 - m as i32) / rho2_minus_1
}

/// The rule with `RULES[rule]` nodes applied to `f` on `[c − h, c + h]`.
#[cfg(test)]
fn integrate<F: Fn(f64) -> f64>(f: &F, c: f64, h: f64, rule: usize) -> f64 {
    let m = RULES[rule];
    let (lo, hi) = (OFFSETS[rule], OFFSETS[rule + 1]);
    let (x, w) = (&NODES[lo..hi], &WEIGHTS[lo..hi]);
    let pairs = m / 2;
    let mut sum = 0.0;
    for i in 0..pairs {
        let dx = h * x[i];
        sum += w[i] * (f(c - dx) + f(c + dx));
    }
    if m % 2 == 1 {
        sum += w[pairs] * f(c);
    }
    sum * h
}

/// `Σ wᵢ·|q(xᵢ)|` over the nodes of rule `RULES[rule]` on `[−1, 1]`, for the complex
/// quadratic `q(z) = qa + qb·z + qc·z²` (complex numbers as `DVec2`, `x` the real part).
///
/// Nodes come in pairs `±x`, and `q(±x) = (qa + qc·x²) ± qb·x`: the even part is shared,
/// so a pair costs about as much as one general evaluation. Multiply by the half-width of
/// the interval to get the integral.
#[inline]
pub(crate) fn sum_quadratic_modulus(qa: DVec2, qb: DVec2, qc: DVec2, rule: usize) -> f64 {
    let m = RULES[rule];
    let (lo, hi) = (OFFSETS[rule], OFFSETS[rule + 1]);
    let (x, w) = (&NODES[lo..hi], &WEIGHTS[lo..hi]);
    let pairs = m / 2;
    // |q(x)| + |q(−x)| from q(±x) = (qa + qc·x²) ± qb·x
    let pair = |xi: f64| {
        let u = xi * xi;
        let (er, ei) = (qa.x + qc.x * u, qa.y + qc.y * u);
        let (or, oi) = (qb.x * xi, qb.y * xi);
        let (pr, pi, mr, mi) = (er + or, ei + oi, er - or, ei - oi);
        (pr * pr + pi * pi).sqrt() + (mr * mr + mi * mi).sqrt()
    };
    // LANES pairs of nodes at a time: the same arithmetic in each lane compiles to packed
    // operations, and the lanes' sums are independent
    const LANES: usize = 4;
    let (xs, ws) = (x[..pairs].chunks_exact(LANES), w[..pairs].chunks_exact(LANES));
    let (x_rest, w_rest) = (xs.remainder(), ws.remainder());
    let mut acc = [0.0f64; LANES];
    for (xc, wc) in xs.zip(ws) {
        for j in 0..LANES {
            acc[j] += wc[j] * pair(xc[j]);
        }
    }
    let mut sum = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for (&xi, &wi) in x_rest.iter().zip(w_rest) {
        sum += wi * pair(xi);
    }
    if m % 2 == 1 {
        sum += w[pairs] * qa.length();
    }
    sum
}

/// The most nodes of any rule.
pub(crate) const MAX_NODES: usize = RULES[RULES.len() - 1];

/// `FIRST_RULE[m]`: the index of the smallest rule with at least `m` nodes (`m ≤ MAX_NODES`).
pub(crate) const FIRST_RULE: [u8; MAX_NODES + 1] = {
    let mut t = [0u8; MAX_NODES + 1];
    let mut m = 0;
    while m <= MAX_NODES {
        let mut i = 0;
        while RULES[i] < m {
            i += 1;
        }
        t[m] = i as u8;
        m += 1;
    }
    t
};

/// The node counts available, ascending; rule `RULES[i]` uses entries `OFFSETS[i]..OFFSETS[i + 1]`.
pub(crate) const RULES: [usize; 39] = [
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 24, 28, 32, 36, 40, 44, 48, 52, 56, 60, 64,
    72, 80, 88, 96, 104, 112, 120, 128,
];
/// Offsets into `NODES` / `WEIGHTS` per rule.
const OFFSETS: [usize; RULES.len() + 1] = {
    let mut t = [0; RULES.len() + 1];
    let mut i = 0;
    while i < RULES.len() {
        t[i + 1] = t[i] + RULES[i].div_ceil(2);
        i += 1;
    }
    t
};
#[cfg(test)]
mod tests {
    use super::*;

    /// Exact for polynomials of degree `2m − 1`: the moments `∫x^k = 2/(k+1)` (even k), 0 (odd k).
    #[test]
    fn rules_integrate_monomials_exactly() {
        for (rule, &m) in RULES.iter().enumerate() {
            for k in 0..2 * m {
                let exact = if k % 2 == 0 { 2.0 / (k as f64 + 1.0) } else { 0.0 };
                let got = integrate(&|x: f64| x.powi(k as i32), 0.0, 1.0, rule);
                // x^k with large k is tiny except near ±1, where the nodes are dense: the rounding
                // of the sum is that of its few largest terms
                assert!((got - exact).abs() <= 1e-15 * (m as f64), "m = {m}, k = {k}: {got} vs {exact}");
            }
            // and not for degree 2m (so the table is the m-point rule, not a higher one)
            if m > 8 {
                continue; // the miss falls below rounding
            }
            let k = 2 * m;
            let got = integrate(&|x: f64| x.powi(k as i32), 0.0, 1.0, rule);
            assert!((got - 2.0 / (k as f64 + 1.0)).abs() > 1e-6, "m = {m}");
        }
    }

    /// The paired, four-lane sum equals the plain rule applied to `|q|`, for every rule.
    #[test]
    fn quadratic_modulus_matches_the_plain_rule() {
        let (qa, qb, qc) = (DVec2::new(0.3, -1.2), DVec2::new(-2.0, 0.7), DVec2::new(1.5, 0.25));
        let q = |z: f64| (qa + (qb + qc * z) * z).length();
        for (rule, &m) in RULES.iter().enumerate() {
            let plain = integrate(&q, 0.0, 1.0, rule);
            let paired = sum_quadratic_modulus(qa, qb, qc, rule);
            assert!((plain - paired).abs() <= 1e-15 * m as f64 * plain, "m = {m}: {plain} vs {paired}");
        }
    }

    #[test]
    fn rule_tables_are_consistent() {
        assert_eq!(OFFSETS[RULES.len()], NODES.len());
        for (i, &m) in RULES.iter().enumerate() {
            assert_eq!(OFFSETS[i + 1] - OFFSETS[i], m.div_ceil(2));
            // nodes descending in (0, 1), and 0 last for odd m
            let x = &NODES[OFFSETS[i]..OFFSETS[i + 1]];
            assert!(x.windows(2).all(|p| p[0] > p[1]) && x[0] < 1.0, "m = {m}");
            assert_eq!(m % 2 == 1, x[x.len() - 1] == 0.0, "m = {m}");
        }
        for (m, &rule) in FIRST_RULE.iter().enumerate() {
            let rule = rule as usize;
            assert!(RULES[rule] >= m && (rule == 0 || RULES[rule - 1] < m), "m = {m}");
        }
    }

    /// The bound holds for `1/(x − r)`-type integrands with a known pole, and is not vacuous.
    #[test]
    fn ellipse_bound_holds_for_a_pole() {
        // f(x) = 1/(2 − x): pole at 2, ρ = 2 + √3; on E_ρ' (ρ' < ρ) |f| ≤ 1/(2 − a'), a' = (ρ'+1/ρ')/2
        let exact = (3.0f64).ln();
        for (rule, &m) in RULES.iter().enumerate() {
            let got = integrate(&|x: f64| 1.0 / (2.0 - x), 0.0, 1.0, rule);
            let rho = 0.999 * (2.0 + 3.0f64.sqrt());
            let a = 0.5 * (rho + 1.0 / rho);
            let bound = ellipse_error_bound(m, rho * rho - 1.0, 1.0 / (2.0 - a));
            assert!((got - exact).abs() <= bound + 4.0 * f64::EPSILON, "m = {m}: {} > {bound}", (got - exact).abs());
            if m <= 8 {
                assert!((got - exact).abs() > bound * 1e-4, "m = {m}: bound vacuous");
            }
        }
    }
}
