//! Chord placement in distance mode: [`ChordPlan`] turns the cells' certified densities into
//! chord ends (the cumulative count, the pauses at cell boundaries, the coarser plans for
//! few chords) and walks them into the caller's buffer.

use super::cells::{CELL, CELLS, CellInputs, HALF_CELL, MIDDLES, max64, unit_scale};
use crate::curve::CubicBezier;
use crate::vector::Vector;

/// Chord ends per pass of the table march; plans with more chords take the long march.
pub(super) const CHUNK: usize = 128;

/// `2⁵²`: adding and subtracting it rounds an `f64` in `[0, 2⁵²)` to an integer.
pub(super) const TWO_52: f64 = 4_503_599_627_370_496.0;

/// How many chord ends the short walk reads ahead of the vertices it writes (see
/// [`ChordPlan::extend_map`]).
pub(super) const AHEAD: usize = 4;

/// `0.0, 1.0, 2.0, …` (`AHEAD` past `CHUNK` for the short walk's look-ahead)
pub(super) const COUNTS: [f64; CHUNK + AHEAD + 1] = {
    let mut k = [0.0; CHUNK + AHEAD + 1];
    let mut i = 0;
    while i < CHUNK + AHEAD + 1 {
        k[i] = i as f64;
        i += 1;
    }
    k
};

/// `⌈x⌉` for `0 ≤ x < 2⁵²`, without a libm call (baseline x86-64 has no rounding instruction).
#[inline(always)]
pub(super) fn ceil(x: f64) -> f64 {
    let r = (x + TWO_52) - TWO_52;
    if r < x { r + 1.0 } else { r }
}

/// `1.5·2⁵²`: an `f64` in `[2⁵², 2⁵³)`, where the spacing is 1, so adding it to an `x` in
/// `[−2⁵¹, 2⁵¹)` rounds `x` to an integer and leaves that integer in the low bits.
pub(super) const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// `⌊x⌋ + 1` as an integer for `0 ≤ x < 2⁵¹`, except that an integer `x` may give `x` instead
/// of `x + 1` (a tie of the rounding; where this is used, both are right: see
/// [`ChordPlan::build`]). Three instructions, no saturating conversion.
#[inline(always)]
pub(super) fn floor_plus_one(x: f64) -> u64 {
    ((x - 0.5) + ROUNDER).to_bits().wrapping_sub(ROUNDER.to_bits()).wrapping_add(1)
}

/// An integer-valued `x` in `[0, 2⁵¹)` as a `u64`, without a saturating conversion.
#[inline(always)]
pub(super) fn integer_to_u64(x: f64) -> u64 {
    (x + ROUNDER).to_bits().wrapping_sub(ROUNDER.to_bits())
}

/// Where the chords of one cubic end: chord end `k` (of `n`) lies in cell `j` and is at
/// `t = max(start_j, a_j + k·b_j)` (the maximum is the pause at the cell's start).
pub(super) struct ChordPlan {
    pub(super) a: [f64; 16],
    pub(super) b: [f64; 16],
    pub(super) start: [f64; 16],
    /// The first chord end of each cell.
    pub(super) first: [u64; 16],
    /// `inc[k − 1]`: 8 × the number of cells whose first chord end is `k` (short plans only):
    /// the step of the walk's byte offset into the `f64` tables (see [`ChordPlan::end`]).
    pub(super) inc: [u8; CHUNK + AHEAD],
    pub(super) n: u64,
    /// At most `CHUNK` chords, and no pause long enough to repeat a chord end.
    pub(super) short: bool,
}

impl ChordPlan {
    /// The certified plan of `c` (see the `flatten` module docs).
    #[inline(never)]
    pub(super) fn new<P: Vector>(c: &CubicBezier<P>, tolerance: f64) -> Self {
        let Some((a, b, cc, e8)) = unit_scale(c, tolerance) else {
            return Self::place(&[0.0; CELLS]);
        };
        let mut rho = [0.0f32; CELLS];
        CellInputs::new(a, b, cc, e8, f64::from(HALF_CELL)).densities(&MIDDLES, HALF_CELL, &mut rho);
        Self::place(&rho)
    }

    /// The plan for the densities `rho` of the cells (each certifying the chords with their
    /// midpoint in the cell; all 0 for a single chord): on the 8 cells, or on 4 cells of
    /// two or on one cell (taking the largest density of the cells in it, which lowers the
    /// floor of a chord per cell width) when that takes fewer chords.
    #[inline(always)]
    pub(super) fn place(rho: &[f32; CELLS]) -> Self {
        if rho[0] == 0.0 {
            return Self::build(&[1.0]);
        }
        let fine: [f64; CELLS] = core::array::from_fn(|j| f64::from(rho[j]));
        // the count of the 8 cells without the pauses, a lower bound of theirs
        let mut base = 0.0;
        for &x in &fine {
            base += x.max(CELLS as f64);
        }
        if base < (2 * CELLS * CELLS) as f64 {
            let n_fine = Self::total(&fine);
            if n_fine < (2 * CELLS) as f64 {
                // nearly straight somewhere, or a coarse tolerance: the floor of a chord per
                // cell width costs more than it saves, so try chords across cells
                const GROUP: usize = CELLS / 4;
                const _: () = assert!(CELLS.is_multiple_of(4));
                let coarse: [f64; 4] =
                    core::array::from_fn(|i| fine[GROUP * i..GROUP * (i + 1)].iter().fold(0.0, |m, &x| max64(m, x)));
                let n_coarse = Self::total(&coarse);
                if let Some(greedy) = Self::greedy(&fine, n_coarse.min(n_fine) as u64) {
                    return greedy;
                }
                if n_coarse < n_fine {
                    return Self::build(&coarse);
                }
            }
        }
        Self::build(&fine)
    }

    /// The fewest chords (if fewer than `limit`, and at most 16) each as wide as the smallest
    /// `1/ρ` of the cells it overlaps, placed from the start: such a chord has its midpoint in
    /// one of those cells, so that cell certifies it. Going as far as allowed from each end is
    /// optimal, as a chord that is allowed stays allowed when its start moves forward.
    #[inline(always)]
    pub(super) fn greedy(rho: &[f64; CELLS], limit: u64) -> Option<Self> {
        let limit = limit.min(17) as usize;
        let mut width = [0.0f64; CELLS];
        for j in 0..CELLS {
            width[j] = 1.0 / rho[j];
        }
        let mut ends = [0.0f64; 17];
        let (mut t, mut j, mut n) = (0.0f64, 0usize, 0usize);
        loop {
            let mut w = width[j];
            let mut k = j + 1;
            while k < CELLS && (k as f64) * CELL < t + w {
                w = w.min(width[k]);
                k += 1;
            }
            n += 1;
            if n >= limit {
                return None;
            }
            if t + w >= 1.0 {
                break;
            }
            t += w;
            ends[n] = t;
            // the cell the next chord starts in (a chord starting on a boundary overlaps only
            // the cells after it)
            while j + 1 < CELLS && ((j + 1) as f64) * CELL <= t {
                j += 1;
            }
        }
        let mut plan = Self::empty();
        plan.n = n as u64;
        plan.a[1..n].copy_from_slice(&ends[1..n]);
        plan.inc[..n - 1].fill(8);
        Some(plan)
    }

    /// A plan of one chord, to be filled in.
    #[inline(always)]
    pub(super) fn empty() -> Self {
        Self {
            a: [0.0; 16],
            b: [0.0; 16],
            start: [0.0; 16],
            first: [u64::MAX; 16],
            inc: [0; CHUNK + AHEAD],
            n: 1,
            short: true,
        }
    }

    /// The cells' count `Σ w·max(ρ, 1/w)` plus the pauses, rounded up.
    #[inline(always)]
    pub(super) fn total<const N: usize>(rho: &[f64; N]) -> f64 {
        let (w, floor) = (1.0 / N as f64, N as f64);
        let r: [f64; N] = core::array::from_fn(|j| rho[j].max(floor));
        let mut total = 0.0;
        for &x in &r {
            total += w * x;
        }
        for j in 1..N {
            total += (r[j - 1] - r[j]).abs() / (r[j - 1] + r[j]);
        }
        ceil(total)
    }

    /// The plan on `N` equal cells with densities `rho` (raised to at least `N`, a chord per
    /// cell width), chords at equal steps of the count with a pause before each cell.
    #[inline(always)]
    pub(super) fn build<const N: usize>(rho: &[f64; N]) -> Self {
        let mut plan = Self::empty();
        let w = 1.0 / N as f64;
        let mut r = [0.0f64; N];
        let mut h = [0.0f64; N];
        for j in 0..N {
            r[j] = rho[j].max(N as f64);
            h[j] = 1.0 / r[j];
        }
        // the pause before cell j: (ρd − ρs)/(ρd + ρs), rounded up
        // (the density before cell 0 is taken as its own: no pause)
        let before: [f64; N] = core::array::from_fn(|j| r[j.saturating_sub(1)]);
        let mut pause = [0.0f64; N];
        let mut len = [0.0f64; N];
        for j in 0..N {
            pause[j] = (before[j] - r[j]).abs() / (before[j] + r[j]) * (1.0 + 1.0 / 262_144.0);
            len[j] = pause[j] + w * r[j];
        }
        // cumulative counts at the cell starts (two halves summed side by side, then joined)
        let mut cum = [0.0f64; N];
        let total = if N.is_multiple_of(2) {
            let half = N / 2;
            let (mut s0, mut s1) = (0.0, 0.0);
            for i in 0..half {
                cum[i] = s0;
                cum[half + i] = s1;
                s0 += len[i];
                s1 += len[half + i];
            }
            for i in 0..half {
                cum[half + i] += s0;
            }
            s0 + s1
        } else {
            let mut s = 0.0;
            for j in 0..N {
                cum[j] = s;
                s += len[j];
            }
            s
        };
        // chord ends at the counts 1, 2, …, n − 1 (the last chord, up to the count `total`,
        // is the shortest): no division by n on the way to the first chord end
        let nf = ceil(total);
        let mut repeat = false;
        // a chord end whose count falls exactly on a cell's start may be given to either
        // cell (`floor_plus_one`): both give that start, to rounding
        for j in 0..N {
            plan.start[j] = j as f64 * w;
            plan.b[j] = h[j];
            plan.a[j] = plan.start[j] - (cum[j] + pause[j]) * h[j];
            plan.first[j] = floor_plus_one(cum[j]);
            repeat |= pause[j] >= 1.0;
        }
        plan.n = integer_to_u64(nf);
        plan.short = plan.n <= CHUNK as u64 && !repeat;
        if plan.short {
            for j in 1..N {
                plan.inc[(plan.first[j] - 1) as usize & (CHUNK - 1)] += 8;
            }
        }
        plan
    }

    /// Calls `emit(t)` for every chord end before the last (`t = 1`), ascending.
    #[inline(always)]
    pub(super) fn for_each_inner(&self, emit: &mut impl FnMut(f64)) {
        if self.short {
            self.short_ends().for_each(emit);
        } else {
            let mut buf = [0.0f64; CHUNK];
            let (mut base, mut j8, mut prev) = (1u64, 0usize, 0.0f64);
            while base < self.n {
                let len = self.chunk(&mut base, &mut j8, &mut prev, &mut buf);
                for &t in &buf[..len] {
                    emit(t);
                }
            }
        }
    }

    /// The chord ends from `base` on (at most `CHUNK` of them) of a long plan, leaving out
    /// any that a pause repeats.
    #[inline(always)]
    pub(super) fn chunk(&self, base: &mut u64, j8: &mut usize, prev: &mut f64, buf: &mut [f64; CHUNK]) -> usize {
        let count = (self.n - *base).min(CHUNK as u64) as usize;
        let mut inc = [0u8; CHUNK + 1];
        for &f in &self.first[1..] {
            inc[f.wrapping_sub(*base).min(CHUNK as u64) as usize] += 8;
        }
        let bf = *base as f64;
        let mut len = 0;
        for (i, &d) in inc[..count].iter().enumerate() {
            let t = self.end(j8, bf + COUNTS[i], d);
            buf[len] = t;
            len += usize::from(t > *prev);
            *prev = if t > *prev { t } else { *prev };
        }
        *base += count as u64;
        len
    }

    /// The chord ends of a short plan before the last, one step of the walk each: slices
    /// zipped and mapped, an exact length, so that `Vec::extend` writes them in place.
    #[inline(always)]
    pub(super) fn short_ends(&self) -> impl Iterator<Item = f64> + '_ {
        let mut j8 = 0usize;
        COUNTS[1..self.n as usize].iter().zip(&self.inc).map(move |(&k, &d)| self.end(&mut j8, k, d))
    }

    /// Chord end `k` of the walk over the cells: `j8` is the current cell's byte offset into
    /// the `f64` tables (8 × its index, which the compiler folds into the addressing: no
    /// shift), stepped by `d` (from `inc`) before the end is read from the cell's line.
    #[inline(always)]
    pub(super) fn end(&self, j8: &mut usize, k: f64, d: u8) -> f64 {
        *j8 = (*j8 + d as usize) & 0x78;
        let j = *j8 >> 3;
        let t = self.a[j] + k * self.b[j];
        if t > self.start[j] { t } else { self.start[j] }
    }

    /// Appends the chord ends to `out`, the last `1.0`.
    ///
    /// Without the look-ahead of [`extend_map`](Self::extend_map): storing a chord end waits for
    /// nothing but the end itself, and the rotation of the read-ahead ends would only add
    /// instructions (parameters 230 against 216 µs a pass on the flatten bench's curves).
    #[inline(always)]
    pub(super) fn extend(&self, out: &mut Vec<f64>) {
        if self.short {
            out.extend(self.short_ends());
            out.push(1.0);
        } else {
            self.extend_map(out, |t| t, 1.0);
        }
    }

    /// Appends `f(t)` for every chord end before the last to `out`, then `last`.
    #[inline(always)]
    pub(super) fn extend_map<T>(&self, out: &mut Vec<T>, f: impl Fn(f64) -> T, last: T) {
        if self.short {
            let n = self.n as usize;
            out.reserve(n);
            // Each chord end is read from the table `AHEAD` steps before `f` takes it, so that
            // the walk runs ahead instead of every evaluation waiting for its own loads (the
            // last steps read past the plan's ends, which is harmless; the state moves into the
            // closure, which keeps it in registers). 2, 3, 4 and 6 steps ahead: polylines 283,
            // 279, 273 and 281 µs a pass on the flatten bench's curves, 296 µs with none.
            let mut j8 = 0usize;
            let [mut t0, mut t1, mut t2, mut t3]: [f64; AHEAD] =
                core::array::from_fn(|i| self.end(&mut j8, COUNTS[i + 1], self.inc[i]));
            // slices zipped and mapped: an exact length, so `extend` writes in place
            let (counts, incs) = (&COUNTS[AHEAD + 1..n + AHEAD], &self.inc[AHEAD..n + AHEAD - 1]);
            out.extend(counts.iter().zip(incs).map(move |(&k, &d)| {
                let next = self.end(&mut j8, k, d);
                let value = f(t0);
                (t0, t1, t2, t3) = (t1, t2, t3, next);
                value
            }));
        } else {
            out.reserve(self.n as usize);
            self.for_each_inner(&mut |t| out.push(f(t)));
        }
        out.push(last);
    }
}
