//! The streaming pass: the products of a few f64 vectors with many stored candidate
//! columns, the one operation whose cost grows with n·m.
//!
//! A pick reads every live candidate once, so its cost is the bytes of the candidate
//! matrix. The columns can be streamed as they are (f64) or from a compact copy: each
//! column scaled by a power of two (exact) so that its largest entry lies in [½, 1) and
//! rounded to f32, which halves the bytes. Products always accumulate in f64; what the
//! compact copy changes is bounded per column by [`Compact::error_bound`], and the
//! engine turns that bound into an interval on every candidate's ERR (see `engine.rs`).
//!
//! The kernel takes several columns at a time so that each vector element loaded serves
//! them all: sixteen with AVX-512 (two columns to a 512-bit register), four with AVX2 +
//! FMA, detected at run time, and a portable loop otherwise. A pass is bound by memory,
//! and sixteen columns read at once keep more of it in flight than four: on the peer
//! bench's 2500 × 2500 copy a pass takes about 0.6× the time of the four-column kernel
//! (docs/performance.md). Every kernel sums a column's products in the same order (four
//! lanes of fused multiply–adds, lanes 0 + 1 and 2 + 3 added, then the rows left over), so
//! the results are the same to the bit on every processor and whichever columns share a
//! call. Columns are split between threads by the parallelism value it is given.

use faer::{MatRef, Par};
use rayon::prelude::*;

/// Unit roundoff of f32 (round to nearest).
const U32: f64 = 1.0 / (1u64 << 24) as f64;
/// Unit roundoff of f64.
const U64: f64 = 1.0 / (1u64 << 53) as f64;
/// The largest rounding error of an f32 entry that underflowed (below 2⁻¹²⁶ after
/// scaling), in scaled units.
const UNDERFLOW: f64 = 1.0 / (1u128 << 126) as f64;

/// How far a generated column may move, relative to its norm, when generated again.
const REGENERATE: f64 = 1e-12;

/// The candidate columns as f32, each scaled by a power of two.
pub(crate) struct Compact {
    n: usize,
    /// Column-major, n × m.
    pub(super) data: Vec<f32>,
    /// Column j of the f64 matrix ≈ `scale[j]` × stored column j.
    pub(super) scale: Vec<f64>,
}

impl Compact {
    /// An n × m copy to be filled column by column ([`Compact::chunks_mut`]).
    pub(crate) fn zeroed(n: usize, m: usize) -> Self {
        Self {
            n,
            data: vec![0.0; n * m],
            scale: vec![1.0; m],
        }
    }

    /// Replaces column `j` (after the engine refreshed it).
    pub(crate) fn set(&mut self, j: usize, col: &[f64]) {
        let n = self.n;
        self.scale[j] = fill_slice(col, &mut self.data[j * n..(j + 1) * n]);
    }

    /// A bound on |v_kᵀp̂_j − v_kᵀp_j| for a vector of norm `v_norm`, when the stored
    /// f64 column p_j has norm `p_norm`: the f32 rounding (u·Σ|p_i v_i| ≤ u‖p‖‖v‖),
    /// the entries that underflowed, the f64 accumulation (γ_n on the same sum), and
    /// 10⁻¹² of ‖p‖‖v‖ for a generated column that comes out a few ulps different when
    /// it is generated again.
    pub(crate) fn error_bound(&self, j: usize, p_norm: f64, v_norm: f64) -> f64 {
        let n = self.n as f64;
        let accumulate = 2.0 * n * U64;
        ((U32 + accumulate + REGENERATE) * (1.0 + U32) * p_norm
            + UNDERFLOW * self.scale[j] * n.sqrt())
            * v_norm
            * (1.0 + 1e-6)
    }
}

/// Fills `dst` with `col` scaled into [½, 1) and rounded to f32; returns the scale.
pub(crate) fn fill_slice(col: &[f64], dst: &mut [f32]) -> f64 {
    let max = col.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // A power of two: the scaling itself is exact.
    let scale = if max > 0.0 && max.is_finite() {
        2f64.powi(max.log2().floor() as i32 + 1)
    } else {
        1.0
    };
    let inv = 1.0 / scale;
    for (d, v) in dst.iter_mut().zip(col) {
        *d = (v * inv) as f32;
    }
    scale
}

/// The stored columns a pass reads.
pub(crate) enum Columns<'a> {
    F64(MatRef<'a, f64>),
    F32(&'a Compact),
}

/// `out[t·s + k] = vecs[k]ᵀ column(cols[t])` for every listed column, s = `vecs.len()`.
///
/// # Panics
/// If a vector's length is not the columns' row count, or `out` is not `cols.len()·s`.
#[track_caller]
pub(crate) fn products(
    columns: &Columns<'_>,
    cols: &[usize],
    vecs: &[&[f64]],
    out: &mut [f64],
    par: Par,
) {
    let s = vecs.len();
    assert_eq!(out.len(), cols.len() * s, "output has the wrong length");
    let n = match columns {
        Columns::F64(p) => p.nrows(),
        Columns::F32(c) => c.n,
    };
    assert!(
        vecs.iter().all(|v| v.len() == n),
        "vectors must have the columns' length"
    );
    if s == 0 || cols.is_empty() {
        return;
    }
    // A chunk of columns is a few hundred kB at least: below that a thread costs more
    // than it saves. A few chunks per thread balance the load.
    let threads = par.degree().max(1);
    let least = ((1usize << 16) / n.max(1)).max(4);
    let chunk = least.max(cols.len().div_ceil(threads * 4)).div_ceil(16) * 16;
    let width = Width::detect();
    let run = |c: usize, dst: &mut [f64]| {
        let cs = &cols[c * chunk..c * chunk + dst.len() / s];
        match columns {
            Columns::F64(p) => block(&F64Cols(*p), cs, vecs, dst, width),
            Columns::F32(cm) => block(&F32Cols(cm), cs, vecs, dst, width),
        }
    };
    if threads > 1 && cols.len() > chunk {
        out.par_chunks_mut(chunk * s)
            .enumerate()
            .for_each(|(c, dst)| run(c, dst));
    } else {
        run(0, out);
    }
}

/// Column access for the kernels.
trait Cols: Sync {
    type E: Copy + Into<f64>;
    fn col(&self, j: usize) -> ColData<'_, Self::E>;
    fn scale(&self, j: usize) -> f64;
}

/// A column: contiguous, or a copy when the matrix is not column-major.
enum ColData<'a, E> {
    Slice(&'a [E]),
    Owned(Vec<E>),
}

impl<E> ColData<'_, E> {
    fn as_slice(&self) -> &[E] {
        match self {
            ColData::Slice(s) => s,
            ColData::Owned(v) => v,
        }
    }
}

struct F64Cols<'a>(MatRef<'a, f64>);
struct F32Cols<'a>(&'a Compact);

impl Cols for F64Cols<'_> {
    type E = f64;
    fn col(&self, j: usize) -> ColData<'_, f64> {
        match self.0.col(j).try_as_col_major() {
            Some(c) => ColData::Slice(c.as_slice()),
            None => ColData::Owned((0..self.0.nrows()).map(|i| self.0[(i, j)]).collect()),
        }
    }
    fn scale(&self, _: usize) -> f64 {
        1.0
    }
}

impl Cols for F32Cols<'_> {
    type E = f32;
    fn col(&self, j: usize) -> ColData<'_, f32> {
        let n = self.0.n;
        ColData::Slice(&self.0.data[j * n..(j + 1) * n])
    }
    fn scale(&self, j: usize) -> f64 {
        self.0.scale[j]
    }
}

/// The widest kernel the processor runs.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Width {
    /// Sixteen columns, two to a 512-bit register.
    Avx512,
    /// Four columns, AVX2 + FMA.
    Avx2,
    /// Four columns, portable.
    Portable,
}

impl Width {
    fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            let avx2 = std::arch::is_x86_feature_detected!("avx2")
                && std::arch::is_x86_feature_detected!("fma");
            if avx2 && std::arch::is_x86_feature_detected!("avx512f") {
                return Width::Avx512;
            }
            if avx2 {
                return Width::Avx2;
            }
        }
        Width::Portable
    }
}

/// Products of `vecs` with the columns `cols`: sixteen columns and up to two vectors at
/// a time with AVX-512, then four columns and up to four vectors at a time.
fn block<C: Cols>(cols: &C, js: &[usize], vecs: &[&[f64]], out: &mut [f64], width: Width)
where
    C::E: Lanes,
{
    let s = vecs.len();
    let wide = if width == Width::Avx512 {
        js.len() / 16 * 16
    } else {
        0
    };
    #[cfg(target_arch = "x86_64")]
    for (t16, o16) in js[..wide].chunks(16).zip(out.chunks_mut(16 * s)) {
        let data: Vec<ColData<'_, C::E>> = t16.iter().map(|&j| cols.col(j)).collect();
        let slices: Vec<&[C::E]> = data.iter().map(|d| d.as_slice()).collect();
        for v0 in (0..s).step_by(2) {
            let vs = &vecs[v0..(v0 + 2).min(s)];
            let mut acc = [[0.0f64; 2]; 16];
            // SAFETY: `Width::Avx512` is only detected where AVX-512F, AVX2 and FMA are.
            unsafe { C::E::dots16_avx512(&slices, vs, &mut acc) };
            for (c, &j) in t16.iter().enumerate() {
                let sc = cols.scale(j);
                for (k, a) in acc[c].iter().take(vs.len()).enumerate() {
                    o16[c * s + v0 + k] = a * sc;
                }
            }
        }
    }
    let (js, out) = (&js[wide..], &mut out[wide * s..]);
    let avx2 = width != Width::Portable;
    for (t4, o4) in js.chunks(4).zip(out.chunks_mut(4 * s)) {
        let data: Vec<ColData<'_, C::E>> = t4.iter().map(|&j| cols.col(j)).collect();
        let slices: Vec<&[C::E]> = data.iter().map(|d| d.as_slice()).collect();
        for v0 in (0..s).step_by(4) {
            let vs = &vecs[v0..(v0 + 4).min(s)];
            let mut acc = [[0.0f64; 4]; 4];
            dots(&slices, vs, &mut acc, avx2);
            for (c, &j) in t4.iter().enumerate() {
                let sc = cols.scale(j);
                for (k, a) in acc[c].iter().take(vs.len()).enumerate() {
                    o4[c * s + v0 + k] = a * sc;
                }
            }
        }
    }
}

/// `acc[c][k] = vs[k]ᵀ cols[c]` for up to four columns and four vectors; `avx2` says
/// the processor has AVX2 and FMA.
fn dots<E: Lanes>(cols: &[&[E]], vs: &[&[f64]], acc: &mut [[f64; 4]; 4], avx2: bool) {
    #[cfg(target_arch = "x86_64")]
    {
        if cols.len() == 4 && avx2 {
            // SAFETY: the features the kernel is compiled for were detected (`Width`).
            unsafe { E::dots4_avx2(cols, vs, acc) };
            return;
        }
    }
    let _ = avx2;
    dots_portable(cols, vs, acc);
}

fn dots_portable<E: Lanes>(cols: &[&[E]], vs: &[&[f64]], acc: &mut [[f64; 4]; 4]) {
    for (c, col) in cols.iter().enumerate() {
        for (k, v) in vs.iter().enumerate() {
            let mut lanes = [0.0f64; 4];
            let mut i = 0;
            while i + 4 <= v.len() {
                for l in 0..4 {
                    lanes[l] = E::to_f64(col[i + l]).mul_add(v[i + l], lanes[l]);
                }
                i += 4;
            }
            let mut sum = (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
            for (x, y) in col[i..].iter().zip(&v[i..]) {
                sum += E::to_f64(*x) * y;
            }
            acc[c][k] = sum;
        }
    }
}

/// An element type the kernels read: f64, or f32 widened to f64 on load.
trait Lanes: Copy + Sync {
    fn to_f64(self) -> f64;
    /// # Safety
    /// The processor must have AVX2 and FMA; `cols` has four columns of the vectors'
    /// length and `vs` one to four vectors.
    #[cfg(target_arch = "x86_64")]
    unsafe fn dots4_avx2(cols: &[&[Self]], vs: &[&[f64]], acc: &mut [[f64; 4]; 4]);
    /// # Safety
    /// The processor must have AVX-512F, AVX2 and FMA; `cols` has sixteen columns of the
    /// vectors' length and `vs` one or two vectors.
    #[cfg(target_arch = "x86_64")]
    unsafe fn dots16_avx512(cols: &[&[Self]], vs: &[&[f64]], acc: &mut [[f64; 2]; 16]);
}

impl Lanes for f64 {
    fn to_f64(self) -> f64 {
        self
    }
    #[cfg(target_arch = "x86_64")]
    unsafe fn dots4_avx2(cols: &[&[f64]], vs: &[&[f64]], acc: &mut [[f64; 4]; 4]) {
        // SAFETY: forwarded from the caller.
        unsafe { avx2::dots4(cols, vs, acc, |p: *const f64| avx2::load_f64(p)) }
    }
    #[cfg(target_arch = "x86_64")]
    unsafe fn dots16_avx512(cols: &[&[f64]], vs: &[&[f64]], acc: &mut [[f64; 2]; 16]) {
        // SAFETY: forwarded from the caller.
        unsafe { avx512::dots16(cols, vs, acc, |a, b| avx512::load2_f64(a, b)) }
    }
}

impl Lanes for f32 {
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[cfg(target_arch = "x86_64")]
    unsafe fn dots4_avx2(cols: &[&[f32]], vs: &[&[f64]], acc: &mut [[f64; 4]; 4]) {
        // SAFETY: forwarded from the caller.
        unsafe { avx2::dots4(cols, vs, acc, |p: *const f32| avx2::load_f32(p)) }
    }
    #[cfg(target_arch = "x86_64")]
    unsafe fn dots16_avx512(cols: &[&[f32]], vs: &[&[f64]], acc: &mut [[f64; 2]; 16]) {
        // SAFETY: forwarded from the caller.
        unsafe { avx512::dots16(cols, vs, acc, |a, b| avx512::load2_f32(a, b)) }
    }
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use std::arch::x86_64::*;

    #[inline(always)]
    pub(super) unsafe fn load_f64(p: *const f64) -> __m256d {
        // SAFETY: the caller reads within the column.
        unsafe { _mm256_loadu_pd(p) }
    }

    #[inline(always)]
    pub(super) unsafe fn load_f32(p: *const f32) -> __m256d {
        // SAFETY: the caller reads within the column.
        unsafe { _mm256_cvtps_pd(_mm_loadu_ps(p)) }
    }

    /// Four columns against one to four vectors; the vectors' elements are loaded once
    /// for the four columns.
    #[target_feature(enable = "avx2,fma")]
    pub(super) unsafe fn dots4<E: Copy + Into<f64>>(
        cols: &[&[E]],
        vs: &[&[f64]],
        acc: &mut [[f64; 4]; 4],
        load: impl Fn(*const E) -> __m256d,
    ) {
        match vs.len() {
            1 => unsafe { dots4_s::<E, 1>(cols, vs, acc, load) },
            2 => unsafe { dots4_s::<E, 2>(cols, vs, acc, load) },
            3 => unsafe { dots4_s::<E, 3>(cols, vs, acc, load) },
            _ => unsafe { dots4_s::<E, 4>(cols, vs, acc, load) },
        }
    }

    #[target_feature(enable = "avx2,fma")]
    unsafe fn dots4_s<E: Copy + Into<f64>, const S: usize>(
        cols: &[&[E]],
        vs: &[&[f64]],
        acc: &mut [[f64; 4]; 4],
        load: impl Fn(*const E) -> __m256d,
    ) {
        let n = vs[0].len();
        let pc = [
            cols[0].as_ptr(),
            cols[1].as_ptr(),
            cols[2].as_ptr(),
            cols[3].as_ptr(),
        ];
        let mut pv = [vs[0].as_ptr(); S];
        for (k, p) in pv.iter_mut().enumerate() {
            *p = vs[k].as_ptr();
        }
        let mut a = [[_mm256_setzero_pd(); S]; 4];
        let mut i = 0;
        while i + 4 <= n {
            let mut v = [_mm256_setzero_pd(); S];
            for k in 0..S {
                // SAFETY: i + 4 ≤ n, the vectors' length.
                v[k] = unsafe { _mm256_loadu_pd(pv[k].add(i)) };
            }
            for c in 0..4 {
                // SAFETY: i + 4 ≤ n, the columns' length.
                let p = load(unsafe { pc[c].add(i) });
                for k in 0..S {
                    a[c][k] = _mm256_fmadd_pd(p, v[k], a[c][k]);
                }
            }
            i += 4;
        }
        for c in 0..4 {
            for k in 0..S {
                let mut t = [0.0f64; 4];
                // SAFETY: t has four lanes.
                unsafe { _mm256_storeu_pd(t.as_mut_ptr(), a[c][k]) };
                let mut sum = (t[0] + t[1]) + (t[2] + t[3]);
                for j in i..n {
                    sum += cols[c][j].into() * vs[k][j];
                }
                acc[c][k] = sum;
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod avx512 {
    use std::arch::x86_64::*;

    /// Four f64 of column a in lanes 0–3 and four of column b in lanes 4–7.
    #[inline(always)]
    pub(super) unsafe fn load2_f64(a: *const f64, b: *const f64) -> __m512d {
        // SAFETY: the caller reads within the columns.
        unsafe {
            _mm512_insertf64x4::<1>(
                _mm512_castpd256_pd512(_mm256_loadu_pd(a)),
                _mm256_loadu_pd(b),
            )
        }
    }

    /// Four f32 of column a in lanes 0–3 and four of column b in lanes 4–7, widened.
    #[inline(always)]
    pub(super) unsafe fn load2_f32(a: *const f32, b: *const f32) -> __m512d {
        // SAFETY: the caller reads within the columns.
        unsafe {
            let lo = _mm256_castps128_ps256(_mm_loadu_ps(a));
            _mm512_cvtps_pd(_mm256_insertf128_ps::<1>(lo, _mm_loadu_ps(b)))
        }
    }

    /// Sixteen columns against one or two vectors. A register holds the four lanes of
    /// two columns, so each column's sum is formed exactly as `avx2::dots4` forms it.
    #[target_feature(enable = "avx512f,avx2,fma")]
    pub(super) unsafe fn dots16<E: Copy + Into<f64>>(
        cols: &[&[E]],
        vs: &[&[f64]],
        acc: &mut [[f64; 2]; 16],
        load: impl Fn(*const E, *const E) -> __m512d,
    ) {
        match vs.len() {
            1 => unsafe { dots16_s::<E, 1>(cols, vs, acc, load) },
            _ => unsafe { dots16_s::<E, 2>(cols, vs, acc, load) },
        }
    }

    #[target_feature(enable = "avx512f,avx2,fma")]
    unsafe fn dots16_s<E: Copy + Into<f64>, const S: usize>(
        cols: &[&[E]],
        vs: &[&[f64]],
        acc: &mut [[f64; 2]; 16],
        load: impl Fn(*const E, *const E) -> __m512d,
    ) {
        let n = vs[0].len();
        let pc: [*const E; 16] = std::array::from_fn(|c| cols[c].as_ptr());
        let pv: [*const f64; S] = std::array::from_fn(|k| vs[k].as_ptr());
        let mut a = [[_mm512_setzero_pd(); S]; 8];
        let mut i = 0;
        while i + 4 <= n {
            let mut v = [_mm512_setzero_pd(); S];
            for k in 0..S {
                // SAFETY: i + 4 ≤ n, the vectors' length.
                v[k] = _mm512_broadcast_f64x4(unsafe { _mm256_loadu_pd(pv[k].add(i)) });
            }
            for c in 0..8 {
                // SAFETY: i + 4 ≤ n, the columns' length.
                let p = unsafe { load(pc[2 * c].add(i), pc[2 * c + 1].add(i)) };
                for k in 0..S {
                    a[c][k] = _mm512_fmadd_pd(p, v[k], a[c][k]);
                }
            }
            i += 4;
        }
        for (c, ac) in a.iter().enumerate() {
            for (k, &ack) in ac.iter().enumerate() {
                let mut t = [0.0f64; 8];
                // SAFETY: t has eight lanes.
                unsafe { _mm512_storeu_pd(t.as_mut_ptr(), ack) };
                for h in 0..2 {
                    let col = 2 * c + h;
                    let mut sum = (t[4 * h] + t[4 * h + 1]) + (t[4 * h + 2] + t[4 * h + 3]);
                    for j in i..n {
                        sum += cols[col][j].into() * vs[k][j];
                    }
                    acc[col][k] = sum;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    fn compact_of(p: MatRef<'_, f64>) -> Compact {
        let mut c = Compact::zeroed(p.nrows(), p.ncols());
        for j in 0..p.ncols() {
            let col: Vec<f64> = (0..p.nrows()).map(|i| p[(i, j)]).collect();
            c.set(j, &col);
        }
        c
    }

    fn reference(p: MatRef<'_, f64>, cols: &[usize], vecs: &[&[f64]]) -> Vec<f64> {
        let mut out = Vec::new();
        for &j in cols {
            for v in vecs {
                out.push((0..p.nrows()).map(|i| p[(i, j)] * v[i]).sum());
            }
        }
        out
    }

    #[test]
    fn products_match_the_plain_sums_within_their_bounds() {
        for &(n, m, s) in &[
            (37usize, 11usize, 1usize),
            (64, 9, 2),
            (103, 17, 3),
            (50, 8, 4),
            (29, 13, 6),
        ] {
            let p = Mat::from_fn(n, m, |i, j| {
                ((i * 7 + j * 13) as f64 * 0.173).sin() * 10f64.powi((j % 5) as i32 - 2)
            });
            let vs: Vec<Vec<f64>> = (0..s)
                .map(|k| (0..n).map(|i| ((i + k) as f64 * 0.31).cos()).collect())
                .collect();
            let vr: Vec<&[f64]> = vs.iter().map(|v| v.as_slice()).collect();
            let cols: Vec<usize> = (0..m).rev().collect();
            let want = reference(p.as_ref(), &cols, &vr);
            for par in [Par::Seq, Par::rayon(2)] {
                let mut got = vec![0.0; cols.len() * s];
                products(&Columns::F64(p.as_ref()), &cols, &vr, &mut got, par);
                for (g, w) in got.iter().zip(&want) {
                    assert!((g - w).abs() <= 1e-12 * (1.0 + w.abs()), "f64 {g} vs {w}");
                }
                let c = compact_of(p.as_ref());
                products(&Columns::F32(&c), &cols, &vr, &mut got, par);
                for (t, &j) in cols.iter().enumerate() {
                    let pn = p.col(j).norm_l2();
                    for (k, v) in vr.iter().enumerate() {
                        let vn = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                        let (g, w) = (got[t * s + k], want[t * s + k]);
                        let bound = c.error_bound(j, pn, vn);
                        assert!(
                            (g - w).abs() <= bound,
                            "f32 column {j}: {g} vs {w}, bound {bound}"
                        );
                    }
                }
            }
        }
    }

    /// The kernels' sums agree to the bit (the engine's picks must not depend on the
    /// processor): every width the processor runs, against the portable loop, on column
    /// counts that leave remainders, one to five vectors, lengths not divisible by four.
    #[test]
    fn every_kernel_width_gives_the_same_bits() {
        let have = Width::detect();
        let widths: Vec<Width> = [Width::Avx512, Width::Avx2]
            .into_iter()
            .filter(|w| match have {
                Width::Avx512 => true,
                Width::Avx2 => *w == Width::Avx2,
                Width::Portable => false,
            })
            .collect();
        for &(n, m) in &[(2503usize, 37usize), (64, 16), (7, 35), (3, 17)] {
            let p = Mat::from_fn(n, m, |i, j| {
                ((i * 7 + j * 13) as f64 * 0.173).sin() * (1.0 + j as f64)
            });
            let c = compact_of(p.as_ref());
            let cols: Vec<usize> = (0..m).rev().collect();
            for s in 1..=5usize {
                let vs: Vec<Vec<f64>> = (0..s)
                    .map(|k| (0..n).map(|i| ((i + 3 * k) as f64 * 0.31).cos()).collect())
                    .collect();
                let vr: Vec<&[f64]> = vs.iter().map(|v| v.as_slice()).collect();
                let mut want64 = vec![0.0; m * s];
                let mut want32 = vec![0.0; m * s];
                block(
                    &F64Cols(p.as_ref()),
                    &cols,
                    &vr,
                    &mut want64,
                    Width::Portable,
                );
                block(&F32Cols(&c), &cols, &vr, &mut want32, Width::Portable);
                for &w in &widths {
                    let mut got = vec![0.0; m * s];
                    block(&F64Cols(p.as_ref()), &cols, &vr, &mut got, w);
                    assert!(
                        got.iter()
                            .zip(&want64)
                            .all(|(a, b)| a.to_bits() == b.to_bits()),
                        "f64, {w:?}, n {n}, m {m}, {s} vectors"
                    );
                    block(&F32Cols(&c), &cols, &vr, &mut got, w);
                    assert!(
                        got.iter()
                            .zip(&want32)
                            .all(|(a, b)| a.to_bits() == b.to_bits()),
                        "f32, {w:?}, n {n}, m {m}, {s} vectors"
                    );
                }
            }
        }
    }

    #[test]
    fn scaling_keeps_huge_and_tiny_columns_representable() {
        let p = Mat::from_fn(20, 3, |i, j| [1e300, 1e-300, 0.0][j] * (1.0 + i as f64));
        let c = compact_of(p.as_ref());
        let v = vec![1.0; 20];
        let mut out = vec![0.0; 3];
        products(&Columns::F32(&c), &[0, 1, 2], &[&v], &mut out, Par::Seq);
        let want = [210.0 * 1e300, 210.0 * 1e-300, 0.0];
        for j in 0..2 {
            assert!(
                (out[j] / want[j] - 1.0).abs() < 1e-6,
                "{} vs {}",
                out[j],
                want[j]
            );
        }
        assert_eq!(out[2], 0.0);
    }
}
