//! The certified densities of distance mode: for each of the 8 cells of `[0, 1]`, how many
//! chords per unit of `t` keep every chord with its midpoint in the cell within the
//! tolerance (the chord lemma's bounds in `f32`, with their rounding allowances; see the
//! module docs of `flatten`).

use super::{DEFAULT_TOLERANCE, valid_or};
use crate::curve::CubicBezier;
use crate::vector::Vector;

/// Number of cells of the certified density table.
pub(super) const CELLS: usize = 8;

/// Width of a cell.
pub(super) const CELL: f64 = 1.0 / CELLS as f64;

/// Half-width of a cell in `f32`, rounded up so that `[m − hw, m + hw]` covers the cell
/// around its `f32` middle `m`.
pub(super) const HALF_CELL: f32 = (0.5 * CELL * (1.0 + 1.0 / 262_144.0)) as f32;

/// `8 / (12·√3)`: the third-order term of the chord bound, in units of `h³/8`.
pub(super) const THIRD_ORDER: f32 = 0.384_900_18;

/// `f32` unit roundoff.
pub(super) const F32_ROUNDOFF: f64 = 1.0 / (1u64 << 24) as f64;

/// Share of the tolerance kept back for the relative rounding of the `f32` cell bounds.
pub(super) const F32_SHARE: f64 = 1.0 / (1u64 << 17) as f64;

/// Bits of `1.0f32`.
pub(super) const ONE_BITS: i32 = 0x3f80_0000;

/// Cell middles.
pub(super) const MIDDLES: [f32; CELLS] = {
    let mut m = [0.0; CELLS];
    let mut j = 0;
    while j < CELLS {
        m[j] = ((j as f64 + 0.5) * CELL) as f32;
        j += 1;
    }
    m
};

/// The power form `C′(0) = a`, `b`, `c` of `c` at unit scale (the largest coordinate
/// brought into `[1, 2)` by a power of two, which scales exactly) and `8·limit`, the scaled
/// tolerance less the rounding allowances; `None` for a point at the origin or a curve that
/// is not finite.
pub(super) fn unit_scale<P: Vector>(c: &CubicBezier<P>, tolerance: f64) -> Option<(P, P, P, f64)> {
    let tolerance = valid_or(tolerance, DEFAULT_TOLERANCE);
    if !c.is_finite() {
        return None;
    }
    // the largest |coordinate|, as a tree of maxima
    let per_point = c.points().map(|p| (0..P::DIM).fold(0.0, |m, i| max64(m, p.component(i).abs())));
    let magnitude = max64(max64(per_point[0], per_point[1]), max64(per_point[2], per_point[3]));
    if !(magnitude > 0.0) {
        return None;
    }
    let biased = ((magnitude.to_bits() >> 52) as i64).clamp(1, 2045);
    let scale = f64::from_bits(((2046 - biased) as u64) << 52);
    let m = magnitude * scale;
    // the tolerance floor, and a ceiling far above the size of the curve
    let tol = (tolerance * scale).max(1e-12 * m).min(1e6);
    // rounding allowance: a relative share for the f32 bounds and a few ulps of the coordinates
    let limit = tol * (1.0 - F32_SHARE) - 1e-14 * m;
    let (p0, p1, p2, p3) = (c.p0 * scale, c.p1 * scale, c.p2 * scale, c.p3 * scale);
    let a = (p1 - p0) * 3.0;
    let b = (p2 - p1 * 2.0 + p0) * 3.0;
    let cc = p3 - p0 + (p1 - p2) * 3.0;
    Some((a, b, cc, 8.0 * limit))
}

#[inline(always)]
pub(super) fn max32(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

#[inline(always)]
pub(super) fn max64(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

#[inline(always)]
pub(super) fn min32(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// Per-curve inputs of the cell bounds (`f32`, at unit scale) and their rounding allowances.
#[derive(Clone, Copy)]
pub(super) struct CellInputs {
    /// `a = C′(0)`, `2b` and `c` per coordinate (2D: z is 0).
    pub(super) a: [f32; 3],
    pub(super) b2: [f32; 3],
    pub(super) c: [f32; 3],
    /// `k2 = 6·b×c`, the leading coefficient of `Q` (2D: in z).
    pub(super) k2: [f32; 3],
    /// `|k2| / 12`.
    pub(super) k2n: f32,
    /// `hw·|Λ′|` with `Λ′ = 2·b×c`, plus the allowance of `|Λ|`.
    pub(super) lhw: f32,
    /// Rounding allowances of the Bernstein coefficients of `|Q|`, of `|C′(m)|²`, of the
    /// speed coefficients, and of `c·C′(m)` (scaled by `3hw²`).
    pub(super) eq: f32,
    pub(super) es: f32,
    pub(super) eg: f32,
    pub(super) ecd: f32,
    /// `8·limit` and its reciprocal.
    pub(super) e8: f32,
    pub(super) ie8: f32,
    /// `max|C″|` over `[0, 1]`, `|c|`, and Wang's density `√(max|C″| / (8·limit))`.
    pub(super) dd: f32,
    pub(super) cn: f32,
    pub(super) wang: f32,
    /// 2 or 3.
    pub(super) dim: usize,
}

impl CellInputs {
    /// Inputs for cells of half-width `hw` of the cubic with power form `a`, `b`, `c`
    /// (at unit scale).
    ///
    /// The allowances bound the `f32` rounding of [`densities`](Self::densities): with `D`,
    /// `E`, `Cm` bounds of the coordinates of `C′(m)`, `C″(m)` and `c` on `[0, 1]`, each
    /// coordinate of the computed `C′(m)` is within `5u·D` of the exact one (`u` the `f32`
    /// roundoff), and the products that follow add a few `u` times the product of the
    /// magnitudes; the constants (16 to 48) cover them with room, for 2D and 3D.
    #[inline(always)]
    pub(super) fn new<P: Vector>(a: P, b: P, c: P, e8: f64, hw: f64) -> Self {
        let (a3, b3, c3) = (a.to_dvec3(), b.to_dvec3(), c.to_dvec3());
        let (aa, ba, ca) = (a3.abs(), b3.abs(), c3.abs());
        // largest coordinates (plain comparisons: the curve is finite)
        let max_element = |v: glam::DVec3| max64(max64(v.x, v.y), v.z);
        let dm = max_element(aa + ba * 2.0 + ca * 3.0);
        let em = max_element(ba * 2.0 + ca * 6.0);
        let cm = max_element(ca);
        let bc = b3.cross(c3);
        let bcn = if P::DIM == 2 { bc.z.abs() } else { bc.length() };
        let u = F32_ROUNDOFF;
        let el = 32.0 * u * dm * cm;
        let eg = 32.0 * u * (dm * dm + hw * dm * em + 3.0 * hw * hw * dm * cm);
        let dd = max64((b * 2.0).length_squared(), (b * 2.0 + c * 6.0).length_squared()).sqrt();
        let f = |v: glam::DVec3| [v.x as f32, v.y as f32, v.z as f32];
        Self {
            a: f(a3),
            b2: f(b3 * 2.0),
            c: f(c3),
            k2: f(bc * 6.0),
            k2n: (bcn / 2.0) as f32,
            lhw: (2.0 * bcn * hw + el) as f32,
            eq: (48.0 * u * (dm * em + 6.0 * hw * dm * cm) + 24.0 * u * hw * hw * bcn) as f32,
            es: (16.0 * u * dm * dm) as f32,
            eg: eg as f32,
            ecd: (3.0 * hw * hw * eg) as f32,
            e8: e8 as f32,
            ie8: (1.0 / e8) as f32,
            dd: dd as f32,
            cn: c.length() as f32,
            wang: (dd / e8).sqrt() as f32,
            dim: P::DIM,
        }
    }

    /// For each middle `m`: a density `ρ ≥ 1` (chords per unit of `t`) such that every
    /// chord with its midpoint in `[m − hw, m + hw]` and a width of at most `1/ρ` is within
    /// the tolerance (the module docs explain why); Wang's density where the chord lemma
    /// does not apply.
    #[inline(always)]
    pub(super) fn densities(&self, mid: &[f32; CELLS], hw: f32, out: &mut [f32; CELLS]) {
        let hw2 = hw * hw;
        // (c·C′(m))⁻/4 from cd = 3hw²·c·C′(m), rounded up
        let icd = (1.0 + 1.0 / 65536.0) / (12.0 * hw2);
        // one loop over the cells, which the compiler turns into SIMD instructions
        for j in 0..CELLS {
            out[j] = self.cell(mid[j], hw, hw2, icd);
        }
    }

    /// The density of the cell around `m` (see [`densities`](Self::densities)).
    #[inline(always)]
    pub(super) fn cell(&self, m: f32, hw: f32, hw2: f32, icd: f32) -> f32 {
        // C′(m)·C′(m), C″(m)·C′(m), c·C′(m), and the Bernstein coefficients over the
        // cell of Q = C′×C″ (norms), and |Λ(m)| = |C′(m)×c|
        let (ss, de, dc, n0, n1, n2, lam);
        if self.dim == 2 {
            let dx = self.a[0] + m * (self.b2[0] + (3.0 * m) * self.c[0]);
            let dy = self.a[1] + m * (self.b2[1] + (3.0 * m) * self.c[1]);
            let ex = self.b2[0] + (6.0 * m) * self.c[0];
            let ey = self.b2[1] + (6.0 * m) * self.c[1];
            ss = dx * dx + dy * dy;
            de = dx * ex + dy * ey;
            dc = dx * self.c[0] + dy * self.c[1];
            let q = dx * ey - dy * ex;
            let l = dx * self.c[1] - dy * self.c[0];
            // Q(m ± hw) = Q(m) ± hw·Q′(m) + hw²·k2, Q′ = 6Λ
            let (qd, qq) = ((6.0 * hw) * l, hw2 * self.k2[2]);
            n0 = (q + qq - qd).abs();
            n1 = (q - qq).abs();
            n2 = (q + qq + qd).abs();
            lam = l.abs();
        } else {
            let mut d = [0.0f32; 3];
            let mut e = [0.0f32; 3];
            for k in 0..3 {
                d[k] = self.a[k] + m * (self.b2[k] + (3.0 * m) * self.c[k]);
                e[k] = self.b2[k] + (6.0 * m) * self.c[k];
            }
            ss = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            de = d[0] * e[0] + d[1] * e[1] + d[2] * e[2];
            dc = d[0] * self.c[0] + d[1] * self.c[1] + d[2] * self.c[2];
            let cross = |u: [f32; 3], v: [f32; 3]| {
                [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            };
            let (q, l) = (cross(d, e), cross(d, self.c));
            let (mut s0, mut s1, mut s2, mut sl) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
            for k in 0..3 {
                let (qd, qq) = ((6.0 * hw) * l[k], hw2 * self.k2[k]);
                let (v0, v1, v2) = (q[k] + qq - qd, q[k] - qq, q[k] + qq + qd);
                s0 += v0 * v0;
                s1 += v1 * v1;
                s2 += v2 * v2;
                sl += l[k] * l[k];
            }
            n0 = s0.sqrt();
            n1 = s1.sqrt();
            n2 = s2.sqrt();
            lam = sl.sqrt();
        }
        // Bernstein coefficients over the cell of C′(t)·C′(m), less their allowance
        let g = hw * de;
        let cd = (3.0 * hw2) * dc;
        let base = ss + cd - self.eg;
        let (g0, g1, g2) = (base - g, ss - cd - self.eg, base + g);
        // |C′(m)|², rounded up
        let sse = ss + self.es;
        // cap: at least every width the cell can certify — the leading-order width of the
        // largest |Q| coefficient with the largest speed coefficient, √(e8·g/n)·(ss + es)^(−1/4),
        // from the exponent bits (0 to 15 % above it) — so the higher-order terms only grow.
        // (Wrapping: a cell with a negative speed coefficient fails below, whatever the cap.)
        let eb = (self.e8 * max32(max32(g0, g1), g2)).to_bits() as i32;
        let nb = (max32(max32(n0, n1), n2) + self.eq).to_bits() as i32;
        let sb = sse.to_bits() as i32;
        let cb =
            (eb.wrapping_sub(nb) >> 1).wrapping_sub(sb.wrapping_sub(ONE_BITS) >> 2).wrapping_add(ONE_BITS + 369_099);
        let cap = min32(f32::from_bits(cb as u32), 1.0);
        let cap2 = cap * cap;
        // (A): the terms |k2|·h²/12 and h·|Λ|·8/(12√3) join |Q|, (h²/4)·(c·û)⁻ leaves the speed
        let add = self.k2n * cap2 + THIRD_ORDER * cap * (lam + self.lhw) + self.eq;
        let drop = max32(self.ecd - cd, 0.0) * icd * cap2;
        let (a0, a1, a2) = (g0 - drop, g1 - drop, g2 - drop);
        let (n0, n1, n2) = (n0 + add, n1 + add, n2 + add);
        // the largest ratio nᵢ/aᵢ (all aᵢ > 0 where it counts: gmin > 0); three independent
        // divisions, so that the chain from the coefficients to the density stays short; the
        // least aᵢ is the least gᵢ less the drop, to the bit (rounding is monotonic), one
        // subtraction after the drop instead of a subtraction and two minima
        let gmin = min32(min32(g0, g1), g2) - drop;
        let ratio = max32(max32(n0 / a0, n1 / a1), n2 / a2);
        let s = sse.sqrt();
        let lemma = (s * self.ie8 * ratio).sqrt();
        // (B): with R = 2·gmin/|C′(m)| (gmin is a lower bound for every width up to the cap),
        // h·(max|C″| + h·|c|) ≤ R holds for every width h up to the root hb of the
        // quadratic, and 1/hb ≤ max|C″|/R + √(|c|/R); the chord lemma needs the smaller of
        // its own width and hb, so the larger density.
        let ir = (0.5 * s) / gmin;
        let ib = self.dd * ir + (self.cn * ir).sqrt();
        // 2⁻¹³ on the density (2⁻¹² on its square) covers the rounding of the divisions, the
        // square roots and (B); a NaN lemma density (ib first) falls back to Wang's
        let x = max32(ib, lemma) * (1.0 + 1.0 / 8192.0);
        // x < wang ? x : wang, and Wang's density where gmin ≤ 0 by making x a NaN there (all
        // bits set: the mask is ready long before x, so one `or` instead of a compare and a
        // blend follows x)
        let nan = if gmin > 0.0 { 0 } else { u32::MAX };
        let x = min32(f32::from_bits(x.to_bits() | nan), self.wang);
        max32(x, 1.0)
    }
}
