//! Small helpers that turn a [`faer::Par`] value into rayon work splitting.
//!
//! The crate never touches global state: every kernel receives its parallelism as a
//! value, and `Par::Seq` runs on the calling thread only.

use faer::Par;
use rayon::prelude::*;

/// Calls `f(start, chunk)` on consecutive chunks of `out`, in parallel when `par` allows.
///
/// Chunks hold at least `min_chunk` items so that tiny problems stay on one thread
/// (spawning costs more than it saves below a few thousand flops).
pub(crate) fn for_each_chunk_mut<T: Send>(
    out: &mut [T],
    par: Par,
    min_chunk: usize,
    f: impl Fn(usize, &mut [T]) + Sync + Send,
) {
    let n = out.len();
    let threads = par.degree();
    if threads <= 1 || n <= min_chunk.max(1) {
        f(0, out);
        return;
    }
    // A few chunks per thread balance uneven work (columns that need refreshing, ...).
    let chunk = n.div_ceil(threads * 4).max(min_chunk.max(1));
    out.par_chunks_mut(chunk)
        .enumerate()
        .for_each(|(c, slice)| f(c * chunk, slice));
}

/// Dot product with eight independent accumulators so that the compiler vectorises it.
#[inline]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    debug_assert_eq!(a.len(), b.len());
    let n = a.len();
    let (a8, a_rest) = a.split_at(n - n % 8);
    let (b8, b_rest) = b.split_at(n - n % 8);
    let mut acc = [0.0f64; 8];
    for (ca, cb) in a8.chunks_exact(8).zip(b8.chunks_exact(8)) {
        for l in 0..8 {
            acc[l] += ca[l] * cb[l];
        }
    }
    let mut s = ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7]));
    for (x, y) in a_rest.iter().zip(b_rest) {
        s += x * y;
    }
    s
}

/// `y += alpha * x`.
#[inline]
pub(crate) fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    debug_assert_eq!(x.len(), y.len());
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += alpha * xi;
    }
}
