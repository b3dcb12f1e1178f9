//! The kernels' vector width, chosen at run time: on x86-64 a CPU with
//! AVX2 (and an OS that saves its registers) runs [`kernels`]' one
//! function compiled for four lanes to a vector, any other the same
//! function for the baseline's two (SSE2). AVX2 without FMA rounds every
//! addition and multiplication as SSE2 does, so both give the same bits.
//! The exported C chooses the same way (gcc's `target_clones`).
//!
//! [`kernels`]: crate::kernels

use crate::kernels;
use crate::layout::MAX_CHANNELS;
use crate::model::Model;

/// Every channel's kernel terms added to its `ys` and `nets`
/// ([`kernels::network_terms`]), at the widest vectors the CPU runs.
#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
#[inline]
pub(crate) fn network_terms(
    m: &Model,
    st: &[f64],
    ring_pos: usize,
    ys: &mut [f64; MAX_CHANNELS],
    nets: &mut [f64; MAX_CHANNELS],
) {
    if avx2() {
        // SAFETY: avx2() has read from cpuid that this CPU runs AVX2 and
        // from XCR0 that the OS saves the YMM registers.
        unsafe { network_terms_avx2(m, st, ring_pos, ys, nets) }
    } else {
        kernels::network_terms(m, st, ring_pos, ys, nets);
    }
}

#[cfg(not(target_arch = "x86_64"))]
pub(crate) use kernels::network_terms;

/// [`kernels::network_terms`] compiled for AVX2 (not FMA: the same bits).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn network_terms_avx2(
    m: &Model,
    st: &[f64],
    ring_pos: usize,
    ys: &mut [f64; MAX_CHANNELS],
    nets: &mut [f64; MAX_CHANNELS],
) {
    kernels::network_terms(m, st, ring_pos, ys, nets);
}

/// Whether this CPU runs AVX2 and the OS saves its registers (cpuid leaf
/// 1's OSXSAVE and AVX, XCR0's SSE and AVX state, leaf 7's AVX2), asked
/// once and remembered.
#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
fn avx2() -> bool {
    use core::arch::x86_64::{__cpuid, __cpuid_count, _xgetbv};
    use core::sync::atomic::{AtomicU8, Ordering};
    // 0: not asked yet; 1: no; 2: yes.
    static KNOWN: AtomicU8 = AtomicU8::new(0);
    match KNOWN.load(Ordering::Relaxed) {
        1 => return false,
        2 => return true,
        _ => {}
    }
    let bit = |word: u32, b: u32| word & (1 << b) != 0;
    let leaf1 = __cpuid(1);
    let yes = bit(leaf1.ecx, 27)
        && bit(leaf1.ecx, 28)
        // SAFETY: OSXSAVE (leaf 1, ecx bit 27) says XGETBV runs.
        && unsafe { _xgetbv(0) } & 0b110 == 0b110
        && __cpuid(0).eax >= 7
        && bit(__cpuid_count(7, 0).ebx, 5);
    KNOWN.store(if yes { 2 } else { 1 }, Ordering::Relaxed);
    yes
}
