//! The arithmetic a step needs besides `+ − × ÷`: little-endian reads of
//! the tables, √, |x|, a cascade of second-order sections, the squared
//! distance of a raw window, the pairwise sum of a block's lanes. `no_std`
//! has no `sqrt` or `abs` on `f64`; each is written out so that the
//! exported C can do the same operations in the same order.

use crate::error::Error;
use crate::layout::LANES;

/// `f64` numbers of one second-order section: b0 b1 b2 a1 a2 zi1 zi2.
pub(crate) const SECTION: usize = 7;

/// Reads a little-endian `f64` at byte `at`.
#[inline(always)]
pub(crate) fn rd(b: &[u8], at: usize) -> f64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[at..at + 8]);
    f64::from_le_bytes(a)
}

/// Header word `i`, or how many bytes the tables would need to hold it.
pub(crate) fn word(b: &[u8], i: usize) -> Result<u32, Error> {
    let at = 4 * i;
    if b.len() < at + 4 {
        return Err(Error::Truncated {
            need: at + 4,
            have: b.len(),
        });
    }
    Ok(u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]))
}

/// |x|, exactly (clears the sign bit).
#[inline(always)]
pub(crate) fn abs(x: f64) -> f64 {
    f64::from_bits(x.to_bits() & !(1u64 << 63))
}

/// √x by Newton's iteration from the exponent-halved guess (no_std has no
/// `sqrt`): correctly rounded to within an ulp for the window levels and
/// distances here (x ≥ 0; 0 gives 0).
pub(crate) fn sqrt(x: f64) -> f64 {
    if x <= 0.0 || x.is_nan() || x.is_infinite() {
        return if x == 0.0 || x.is_infinite() { x } else { 0.0 };
    }
    let bits = x.to_bits();
    let mut y = f64::from_bits((bits >> 1) + (1023u64 << 51));
    for _ in 0..6 {
        y = 0.5 * (y + x / y);
    }
    y
}

/// One value through a cascade of `n` second-order sections (transposed
/// direct form II) whose numbers start at byte `at` of `bytes` and whose
/// states start at `state`; on the first step the states are set to the
/// steady state of that value first.
#[inline(always)]
pub(crate) fn cascade(
    bytes: &[u8],
    (at, n): (usize, usize),
    state: &mut [f64],
    x: f64,
    first: bool,
) -> f64 {
    let mut v = x;
    for s in 0..n {
        let o = at + 8 * SECTION * s;
        let f = |i: usize| rd(bytes, o + 8 * i);
        let z = &mut state[2 * s..2 * s + 2];
        if first {
            z[0] = f(5) * x;
            z[1] = f(6) * x;
        }
        let y = f(0) * v + z[0];
        z[0] = f(1) * v - f(3) * y + z[1];
        z[1] = f(2) * v - f(4) * y;
        v = y;
    }
    v
}

/// ‖x − c‖² of a window against a centre's bytes; four partial sums (the
/// exported C sums the same way) keep the adds independent.
#[inline(always)]
pub(crate) fn sq_dist(centre: &[u8], x: &[f64]) -> f64 {
    let mut acc = [0.0f64; 4];
    let mut cs = centre.chunks_exact(32);
    let mut xs = x.chunks_exact(4);
    for (c4, x4) in (&mut cs).zip(&mut xs) {
        for j in 0..4 {
            let d = x4[j] - rd(c4, 8 * j);
            acc[j] += d * d;
        }
    }
    let mut tail = 0.0;
    for (c, &v) in cs.remainder().chunks_exact(8).zip(xs.remainder()) {
        let d = v - rd(c, 0);
        tail += d * d;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// The lanes of a block summed pairwise (the C sums them in this order).
#[inline(always)]
pub(crate) fn lane_sum(a: &[f64; LANES]) -> f64 {
    let mut v = *a;
    let mut w = LANES;
    while w > 1 {
        w /= 2;
        for i in 0..w {
            v[i] += v[i + w];
        }
    }
    v[0]
}

#[inline(always)]
pub(crate) fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sqrt_is_within_two_ulps_of_the_library() {
        let mut x = 1e-30f64;
        while x < 1e30 {
            let (got, want) = (sqrt(x), x.sqrt());
            let ulps = (got.to_bits() as i64 - want.to_bits() as i64).abs();
            assert!(ulps <= 2, "x = {x}: {got} vs {want}");
            x *= 1.37;
        }
        assert_eq!(abs(-2.5), 2.5);
    }
}
