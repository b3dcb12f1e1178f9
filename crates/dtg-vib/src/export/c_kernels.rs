//! The kernels of the exported C, in the `dtg-onboard` evaluator's lanes
//! (crates/dtg-onboard/src/kernels.rs): per centre set, blocks of
//! [`LANES`] centres whose arguments are summed lane by lane (for the
//! statistics input the sum over the set's inputs unrolled for one, two or
//! three signals, so that a block's lanes stay in vector registers), the
//! exponentials of each block's lanes in branch-free loops (the f64
//! exponential is `fastexp::exp_neg11`, constant for constant), each value
//! times every sharing channel's weight into that channel's partial sum of
//! its lane; the lanes added pairwise at the end. The arguments and the
//! exponentials run over half a block at a time (one AVX2 vector, two SSE2
//! ones) and the weighted terms' loop is unrolled: gcc -O2 keeps such
//! loops in registers, in straight code. The arithmetic is the
//! evaluator's, operation for operation, so C and Rust give the same bits.

use super::precision::Precision;
use dtg_onboard::LANES;

/// The kernels' exponential, `lane_sum`, one centre set's terms (the
/// statistics input's or the window's) and `network_terms`, before
/// `process`.
pub(super) fn kernels(precision: Precision) -> String {
    let exp = match precision {
        Precision::F64 => EXP_NEG11_C,
        Precision::F32 => "#define EXP_NEG(x) expf(x)\n",
    };
    [
        VECTOR_CLONES_C,
        exp,
        &LANE_SUM_C.replace("{LANES}", &LANES.to_string()),
        "#if DTG_INPUT_STATS\n",
        STATISTICS_C,
        "#else\n",
        WINDOW_C,
        "#endif\n\n",
        NETWORK_TERMS_C,
    ]
    .concat()
    .replace("{EXPS_AND_WEIGHTS}", EXPS_AND_WEIGHTS_C)
}

/// `fastexp::exp_neg11` on −708 … 0.
const EXP_NEG11_C: &str = r#"#include <stdint.h>
#include <string.h>
/* e^x for -708 <= x <= 0: fastexp::exp_neg11 of the Rust evaluator,
 * constant for constant (x = n ln 2 + r; a degree-11 polynomial in r by
 * Estrin's scheme; 2^n from the bits), so that both give the same bits.
 * Below -708 its value is not used (the caller takes 0): a loop over it
 * without a branch or clamp is one the compiler vectorises. */
static DTG_INLINE double exp_neg11(double x) {
    const double LOG2E = 0x1.71547652b82fep+0, LN2_HI = 0x1.62e42feep-1;
    const double LN2_LO = 0x1.a39ef35793c76p-33, SHIFT = 0x1.8p+52;
    double t = x * LOG2E + SHIFT, n = t - SHIFT, r = (x - n * LN2_HI) - n * LN2_LO;
    double r2 = r * r, r4 = r2 * r2, q0, q1, q2, p, scale;
    uint64_t bits;
    q0 = (1.0 + 1.0 * r) + (0x1.0000000000011p-1 + 0x1.555555555555ap-3 * r) * r2;
    q1 = (0x1.555555554f0cfp-5 + 0x1.111111110f225p-7 * r) + (0x1.6c16c187fbe02p-10 + 0x1.a01a01b14378fp-13 * r) * r2;
    q2 = (0x1.a01991ac8730ap-16 + 0x1.71ddf5749d126p-19 * r) + (0x1.28b4057f44145p-22 + 0x1.af631d0059becp-26 * r) * r2;
    p = q0 + (q1 + q2 * r4) * r4;
    memcpy(&bits, &t, sizeof bits);
    bits = (bits - UINT64_C(0x4338000000000000) + 1023) << 52;
    memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}
#define EXP_NEG(x) exp_neg11(x)
"#;

/// The kernels compiled twice where the toolchain can choose at load time
/// (gcc or clang on x86-64 ELF with glibc's ifunc): for AVX2, four lanes
/// to a vector instead of SSE2's two, and for the baseline instruction
/// set. AVX2 without FMA rounds every operation as SSE2 does, so both give
/// the same bits; `-DDTG_NO_CLONES` or another target builds the one
/// portable function.
const VECTOR_CLONES_C: &str = r#"/* The kernels for AVX2 and for the baseline x86-64, chosen at load time
 * (ifunc): the same operations in the same order, four lanes to a vector
 * instead of two, so the same bits. Every helper they call (exponential,
 * distance, lane sum) is DTG_INLINE, compiled into each clone: the AVX2
 * clone calling a baseline helper runs that helper's SSE code with the
 * YMM registers' upper halves live (gcc keeps them across a call whose
 * registers it knows, without vzeroupper), which took the raw window's
 * step from 24 to 55 us. Elsewhere, or with -DDTG_NO_CLONES, the one
 * portable function. */
#if defined(__x86_64__) && defined(__ELF__) && defined(__GLIBC__) && !defined(DTG_NO_CLONES) \
    && defined(__has_attribute)
#if __has_attribute(target_clones)
#define DTG_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef DTG_VECTOR_CLONES
#define DTG_VECTOR_CLONES
#endif
/* Compiled into the caller: each clone, and a set's blocks with its
 * dimension a constant (in every build). */
#if defined(__GNUC__)
#define DTG_INLINE __attribute__((always_inline)) inline
#else
#define DTG_INLINE inline
#endif
/* A loop over a set's inputs unrolled where the compiler takes the hint
 * (-O2 does not unroll it by itself): clang, and gcc from 8 on (older gcc
 * warns of the pragma it does not know). */
#if defined(__clang__)
#define DTG_UNROLL _Pragma("unroll")
#elif defined(__GNUC__) && __GNUC__ >= 8
#define DTG_UNROLL _Pragma("GCC unroll 16")
#else
#define DTG_UNROLL
#endif

"#;

/// The lanes' partial sums added pairwise into the first, in the Rust
/// evaluator's order.
const LANE_SUM_C: &str = r#"/* Kernel terms are summed in DTG_LANES partial sums (centre k into lane
 * k % DTG_LANES), added pairwise at the end, as the Rust evaluator does. */
#define DTG_LANES {LANES}
static DTG_INLINE void lane_sum(dtg_real *acc) {
    int w, i;
    for (w = DTG_LANES / 2; w >= 1; w /= 2)
        for (i = 0; i < w; i++) acc[i] += acc[i + w];
}

"#;

/// A block's exponentials and each sharing channel's weighted terms (0
/// below −708: the exponential's argument is not clamped, its value there
/// is not used). Over eight lanes in one loop gcc's AVX2 clone ran both as
/// loops of two iterations through the stack (each block's arguments and
/// values stored and loaded again): the exponentials run over each half of
/// the lanes, as the arguments do, and the terms' loop is unrolled, so
/// that both are straight code in registers in either clone (halves for
/// the terms too cost the SSE2 build two registers a half).
const EXPS_AND_WEIGHTS_C: &str = r#"        for (i = 0; i < DTG_LANES / 2; i++) phi[i] = EXP_NEG(arg[i]);
        for (i = DTG_LANES / 2; i < DTG_LANES; i++) phi[i] = EXP_NEG(arg[i]);
        for (mb = 0; mb < SET_N_MEMBERS[c]; mb++) {
            const int j = SET_MEMBERS[SET_MEMBERS_AT[c] + mb];
            const dtg_real *wt = WEIGHT_LANES + WEIGHT_AT[j] + (long)DTG_LANES * b;
            DTG_UNROLL
            for (i = 0; i < DTG_LANES; i++) acc[j][i] += (arg[i] < R(-708) ? R(0) : phi[i]) * wt[i];
        }
"#;

/// Every set's terms into its members' partial sums, then each channel's
/// lanes added pairwise onto its `ys` and `nets`.
const NETWORK_TERMS_C: &str = r#"/* Adds each channel's kernel terms to ys[c] and nets[c], as the Rust
 * evaluator's network_terms does: each centre set's terms computed once
 * (set_terms), into one partial sum per lane of each channel that shares
 * the set; each channel's lanes added pairwise. */
DTG_VECTOR_CLONES
static void network_terms(const dtg_state *s, dtg_real *ys, dtg_real *nets) {
    dtg_real acc[N][DTG_LANES];
    int c, i;
    for (c = 0; c < N; c++)
        for (i = 0; i < DTG_LANES; i++) acc[c][i] = R(0);
    for (c = 0; c < N; c++) {
        if (CENTRE_SET[c] != c) continue;
        set_terms(s, c, acc);
    }
    for (c = 0; c < N; c++) {
        lane_sum(acc[c]);
        ys[c] += acc[c][0];
        nets[c] += acc[c][0];
    }
}
"#;

/// The statistics input's kernels: x' = x - m (the set's inputs less its
/// mean), q = |x'|^2, each centre's argument V + W q + sum_d x'_d U_d.
const STATISTICS_C: &str = r#"/* One set's blocks of DTG_LANES centres: each argument V + W q +
 * sum_d x'_d U_d, the exponentials, the weighted terms into each member's
 * partial sum per lane. The caller names dim as a constant where it can,
 * so that the sum over the inputs is unrolled with the block's lanes in
 * registers. */
static DTG_INLINE void set_blocks(int c, const dtg_real *ln, const dtg_real *x, dtg_real q, int dim,
                                  dtg_real acc[][DTG_LANES]) {
    const int nb = (N_CENTRES[c] + DTG_LANES - 1) / DTG_LANES;
    int b, i, d, mb;
    for (b = 0; b < nb; b++) {
        const dtg_real *u = ln + dim + (long)(dim + 2) * DTG_LANES * b;
        const dtg_real *v = u + (long)dim * DTG_LANES, *w = v + DTG_LANES;
        dtg_real arg[DTG_LANES], phi[DTG_LANES];
        /* Each half of the lanes a loop of its own: four lanes are one AVX2
         * vector or two SSE2 ones, which -O2 keeps in registers; over eight
         * lanes SSE2's loop would go through memory. */
        for (i = 0; i < DTG_LANES / 2; i++) arg[i] = v[i] + w[i] * q;
        for (i = DTG_LANES / 2; i < DTG_LANES; i++) arg[i] = v[i] + w[i] * q;
        DTG_UNROLL
        for (d = 0; d < dim; d++) {
            for (i = 0; i < DTG_LANES / 2; i++) arg[i] += x[d] * u[d * DTG_LANES + i];
            for (i = DTG_LANES / 2; i < DTG_LANES; i++) arg[i] += x[d] * u[d * DTG_LANES + i];
        }
{EXPS_AND_WEIGHTS}    }
}

/* Set c's terms (the statistics input): its inputs less the set's mean,
 * their squared norm, its blocks. */
static DTG_INLINE void set_terms(const dtg_state *s, int c, dtg_real acc[][DTG_LANES]) {
    const dtg_real *ln = KERNEL_LANES + SET_LANES[c];
    const int dim = SET_N_INPUT[c];
    dtg_real x[DTG_MAX_DIM], q = R(0);
    int d;
    for (d = 0; d < dim; d++) x[d] = s->feat[SET_INPUT[SET_INPUT_AT[c] + d]] - ln[d];
    for (d = 0; d < dim; d++) q += x[d] * x[d];
    /* One, two or three signals' statistics; any other size as it is. */
    switch (dim) {
    case 3: set_blocks(c, ln, x, q, 3, acc); break;
    case 6: set_blocks(c, ln, x, q, 6, acc); break;
    case 9: set_blocks(c, ln, x, q, 9, acc); break;
    default: set_blocks(c, ln, x, q, dim, acc);
    }
}
"#;

/// The raw window's kernels: each centre's squared distance to the windows
/// of its set's signals (four partial sums, as the Rust evaluator sums
/// them), times -1/beta^2.
const WINDOW_C: &str = r#"/* ||x - c||^2 over n numbers; four partial sums (the Rust evaluator sums
 * the same way) keep the adds independent. */
static DTG_INLINE dtg_real sq_dist(const dtg_real *x, const dtg_real *cen, int n) {
    dtg_real acc0 = R(0), acc1 = R(0), acc2 = R(0), acc3 = R(0), tail = R(0), d;
    int i;
    for (i = 0; i + 4 <= n; i += 4) {
        d = x[i] - cen[i]; acc0 += d * d;
        d = x[i + 1] - cen[i + 1]; acc1 += d * d;
        d = x[i + 2] - cen[i + 2]; acc2 += d * d;
        d = x[i + 3] - cen[i + 3]; acc3 += d * d;
    }
    for (; i < n; i++) { d = x[i] - cen[i]; tail += d * d; }
    return (acc0 + acc1) + (acc2 + acc3) + tail;
}

/* Set c's terms (the raw window): per block of DTG_LANES centres each
 * argument (the windows' distance times -1/beta^2; 0 past the set's last
 * centre), the exponentials, the weighted terms into each member's partial
 * sum per lane. */
static DTG_INLINE void set_terms(const dtg_state *s, int c, dtg_real acc[][DTG_LANES]) {
    const dtg_real *w = KERNEL_LANES + SET_LANES[c];
    const int l = DTG_WINDOW_LEN, n = N_CENTRES[c], nb = (n + DTG_LANES - 1) / DTG_LANES;
    const int ns = SET_N_INPUT[c];
    int b, i, t, mb;
    for (b = 0; b < nb; b++) {
        dtg_real arg[DTG_LANES], phi[DTG_LANES];
        for (i = 0; i < DTG_LANES; i++) {
            const int k = b * DTG_LANES + i;
            const dtg_real *cen;
            dtg_real r2 = R(0);
            arg[i] = R(0);
            if (k >= n) continue;
            cen = CENTRES + SET_CENTRES[c] + (long)ns * l * k;
            for (t = 0; t < ns; t++) {
                r2 += sq_dist(s->ring[SET_INPUT[SET_INPUT_AT[c] + t]] + s->ring_pos, cen, l);
                cen += l;
            }
            arg[i] = r2 * w[k];
        }
{EXPS_AND_WEIGHTS}    }
}
"#;

#[cfg(test)]
mod tests {
    use super::*;

    /// The AVX2 clone of `network_terms` calling a helper compiled for the
    /// baseline runs the helper's SSE code with the YMM registers' upper
    /// halves live (2.3× the raw window's step): every helper the kernels
    /// define is compiled into each clone.
    #[test]
    fn every_helper_of_the_kernels_is_compiled_into_each_clone() {
        for precision in [Precision::F64, Precision::F32] {
            let c = kernels(precision);
            let helpers: Vec<&str> = c
                .lines()
                .filter(|l| l.starts_with("static ") && !l.contains(" network_terms("))
                .collect();
            // lane_sum, set_blocks, two set_terms, sq_dist (and exp_neg11).
            assert!(helpers.len() >= 5, "{precision:?}: {helpers:?}");
            for h in helpers {
                assert!(h.starts_with("static DTG_INLINE "), "{precision:?}: {h}");
            }
            assert!(c.contains("DTG_VECTOR_CLONES\nstatic void network_terms("));
        }
    }

    /// A loop of the block's arguments or exponentials over all eight lanes,
    /// or the weighted terms' loop not unrolled, went through the stack in
    /// gcc's AVX2 clone (two iterations of a loop, each block's values
    /// stored and loaded again): the paper's C step took 13 % longer. The
    /// arguments and exponentials run over half a block, the terms' loop is
    /// unrolled.
    #[test]
    fn a_blocks_lanes_are_straight_code() {
        for precision in [Precision::F64, Precision::F32] {
            let c = kernels(precision);
            let lines: Vec<&str> = c.lines().map(str::trim).collect();
            let lane_loop = |l: &str, v: &str| l.starts_with("for (i = ") && l.contains(v);
            let halves: Vec<&str> = lines
                .iter()
                .copied()
                .filter(|l| {
                    lane_loop(l, "arg[i] +=")
                        || lane_loop(l, "arg[i] = v")
                        || lane_loop(l, "phi[i] =")
                })
                .collect();
            // Statistics: arguments 2 + 2, exponentials 2; window: exponentials 2.
            assert_eq!(halves.len(), 8, "{precision:?}: {halves:?}");
            for l in halves {
                assert!(
                    l.contains("i < DTG_LANES / 2;") || l.contains("i = DTG_LANES / 2;"),
                    "{precision:?}: {l}"
                );
            }
            let terms: Vec<usize> = (1..lines.len())
                .filter(|&k| lane_loop(lines[k], "acc[j][i] +="))
                .collect();
            assert_eq!(terms.len(), 2, "{precision:?}");
            for k in terms {
                assert_eq!(lines[k - 1], "DTG_UNROLL", "{precision:?}: {}", lines[k]);
            }
        }
    }
}
