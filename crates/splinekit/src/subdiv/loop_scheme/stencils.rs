//! Loop's even-vertex stencil, shared by the level-by-level passes and those two and three
//! levels down.

use crate::mesh::NONE;
use crate::subdiv::attribute::Attribute;
use crate::subdiv::options::Rules;
use crate::subdiv::topology::{Table, prev};

/// The new value of even vertex `v`, whose value is `pv`, walking its ring in `topo`: `out(h)`
/// is the ring value across the half-edge `h` leaving `v`, `inc(h)` the one across the
/// half-edge `h` coming into `v` (they differ only where the ring is not made of `topo`'s own
/// vertices, as in the grandchild pass, which reads the midpoints of `topo`'s edges).
#[inline]
pub(super) fn even_ring<T: Attribute>(
    topo: &Table<'_>,
    pv: T,
    v: u32,
    rules: &Rules,
    out: impl Fn(u32) -> T,
    inc: impl Fn(u32) -> T,
) -> T {
    let start = topo.vertex_start(v);
    if start == NONE {
        return pv;
    }
    let mut h = start;
    let mut n = 0u32;
    let mut sum = T::default();
    loop {
        sum = sum + out(h);
        n += 1;
        let pr = h - h % 3 + prev(h % 3);
        let tw = topo.twin(pr);
        if tw == NONE {
            if rules.corners && n == 1 {
                return pv;
            }
            return pv * 0.75 + (out(start) + inc(pr)) * 0.125;
        }
        if tw == start {
            break;
        }
        h = tw;
    }
    let beta = rules.beta(n);
    pv * (1.0 - f64::from(n) * beta) + sum * beta
}
