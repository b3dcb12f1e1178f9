//! The kernels of the exported C, in the `dtg-onboard` evaluator's lanes
//! (crates/dtg-onboard/src/kernels.rs): per centre set, blocks of
//! [`LANES`] centres whose arguments are eight named sums (the compiler
//! keeps them in vector registers and pairs them into vector operations),
//! the exponentials of each block's lanes in one branch-free loop (the f64
//! exponential is `fastexp::exp_neg11`, constant for constant), each value
//! times every sharing channel's weight into that channel's partial sum of
//! its lane; the lanes added pairwise at the end. The arithmetic is the
//! evaluator's, operation for operation, so C and Rust give the same bits.

use super::precision::Precision;
use dtg_onboard::LANES;

// The kernels name one sum per lane.
const _: () = assert!(
    LANES == 8,
    "write the kernels' eight sums for the new LANES"
);

/// The kernels' exponential, `lane_sum` and `network_terms` (the statistics
/// input's or the window's), before `process`.
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
    ]
    .concat()
    .replace("{EXPS_AND_WEIGHTS}", EXPS_AND_WEIGHTS_C)
    .replace("{LANE_SUMS}", LANE_SUMS_C)
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
 * instead of two, so the same bits; the exponential inlined into both.
 * Elsewhere, or with -DDTG_NO_CLONES, the one portable function. */
#if defined(__x86_64__) && defined(__ELF__) && defined(__GLIBC__) && !defined(DTG_NO_CLONES) \
    && defined(__has_attribute)
#if __has_attribute(target_clones)
#define DTG_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#define DTG_INLINE __attribute__((always_inline)) inline
#endif
#endif
#ifndef DTG_VECTOR_CLONES
#define DTG_VECTOR_CLONES
#define DTG_INLINE
#endif

"#;

/// The lanes' partial sums added pairwise into the first, in the Rust
/// evaluator's order.
const LANE_SUM_C: &str = r#"/* Kernel terms are summed in DTG_LANES partial sums (centre k into lane
 * k % DTG_LANES), added pairwise at the end, as the Rust evaluator does. */
#define DTG_LANES {LANES}
static void lane_sum(dtg_real *acc) {
    int w, i;
    for (w = DTG_LANES / 2; w >= 1; w /= 2)
        for (i = 0; i < w; i++) acc[i] += acc[i + w];
}

"#;

/// A block's exponentials and each sharing channel's weighted terms (0
/// below −708: the exponential's argument is not clamped, its value there
/// is not used).
const EXPS_AND_WEIGHTS_C: &str = r#"            for (i = 0; i < DTG_LANES; i++) phi[i] = EXP_NEG(arg[i]);
            for (mb = 0; mb < SET_N_MEMBERS[c]; mb++) {
                const int j = SET_MEMBERS[SET_MEMBERS_AT[c] + mb];
                const dtg_real *wt = WEIGHT_LANES + WEIGHT_AT[j] + (long)DTG_LANES * b;
                for (i = 0; i < DTG_LANES; i++) acc[j][i] += (arg[i] < R(-708) ? R(0) : phi[i]) * wt[i];
            }
"#;

/// Each channel's lanes added pairwise onto its `ys` and `nets`.
const LANE_SUMS_C: &str = r#"    for (c = 0; c < N; c++) {
        lane_sum(acc[c]);
        ys[c] += acc[c][0];
        nets[c] += acc[c][0];
    }
"#;

/// The statistics input's kernels: x' = x - m (the set's inputs less its
/// mean), q = |x'|^2, each centre's argument V + W q + sum_d x'_d U_d.
const STATISTICS_C: &str = r#"/* Adds each channel's kernel terms to ys[c] and nets[c] (the statistics
 * input), as the Rust evaluator's network_terms does: per set the input
 * less the set's mean and its squared norm; per block of DTG_LANES centres
 * each argument V + W q + sum_d x'_d U_d in eight named sums, the
 * exponentials, the weighted terms into one partial sum per lane. */
DTG_VECTOR_CLONES
static void network_terms(const dtg_state *s, dtg_real *ys, dtg_real *nets) {
    dtg_real acc[N][DTG_LANES];
    int c, b, i, d, mb;
    for (c = 0; c < N; c++)
        for (i = 0; i < DTG_LANES; i++) acc[c][i] = R(0);
    for (c = 0; c < N; c++) {
        const dtg_real *ln = KERNEL_LANES + SET_LANES[c];
        const int dim = SET_N_INPUT[c], nb = (N_CENTRES[c] + DTG_LANES - 1) / DTG_LANES;
        dtg_real x[DTG_MAX_DIM], q = R(0);
        if (CENTRE_SET[c] != c) continue;
        for (d = 0; d < dim; d++) x[d] = s->feat[SET_INPUT[SET_INPUT_AT[c] + d]] - ln[d];
        for (d = 0; d < dim; d++) q += x[d] * x[d];
        for (b = 0; b < nb; b++) {
            const dtg_real *u = ln + dim + (long)(dim + 2) * DTG_LANES * b;
            const dtg_real *v = u + (long)dim * DTG_LANES, *w = v + DTG_LANES;
            dtg_real a0 = v[0] + w[0] * q, a1 = v[1] + w[1] * q, a2 = v[2] + w[2] * q,
                     a3 = v[3] + w[3] * q, a4 = v[4] + w[4] * q, a5 = v[5] + w[5] * q,
                     a6 = v[6] + w[6] * q, a7 = v[7] + w[7] * q;
            dtg_real arg[DTG_LANES], phi[DTG_LANES];
            for (d = 0; d < dim; d++) {
                const dtg_real xd = x[d], *ud = u + d * DTG_LANES;
                a0 += xd * ud[0]; a1 += xd * ud[1]; a2 += xd * ud[2]; a3 += xd * ud[3];
                a4 += xd * ud[4]; a5 += xd * ud[5]; a6 += xd * ud[6]; a7 += xd * ud[7];
            }
            arg[0] = a0; arg[1] = a1; arg[2] = a2; arg[3] = a3;
            arg[4] = a4; arg[5] = a5; arg[6] = a6; arg[7] = a7;
{EXPS_AND_WEIGHTS}        }
    }
{LANE_SUMS}}
"#;

/// The raw window's kernels: each centre's squared distance to the windows
/// of its set's signals (four partial sums, as the Rust evaluator sums
/// them), times -1/beta^2.
const WINDOW_C: &str = r#"/* ||x - c||^2 over n numbers; four partial sums (the Rust evaluator sums
 * the same way) keep the adds independent. */
static dtg_real sq_dist(const dtg_real *x, const dtg_real *cen, int n) {
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

/* Adds each channel's kernel terms to ys[c] and nets[c] (the raw window),
 * as the Rust evaluator's network_terms does: per block of DTG_LANES
 * centres each argument (the windows' distance times -1/beta^2; 0 past the
 * set's last centre), the exponentials, the weighted terms into one
 * partial sum per lane. */
DTG_VECTOR_CLONES
static void network_terms(const dtg_state *s, dtg_real *ys, dtg_real *nets) {
    dtg_real acc[N][DTG_LANES];
    const int l = DTG_WINDOW_LEN;
    int c, b, i, t, mb;
    for (c = 0; c < N; c++)
        for (i = 0; i < DTG_LANES; i++) acc[c][i] = R(0);
    for (c = 0; c < N; c++) {
        const dtg_real *w = KERNEL_LANES + SET_LANES[c];
        const int n = N_CENTRES[c], nb = (n + DTG_LANES - 1) / DTG_LANES, ns = SET_N_INPUT[c];
        if (CENTRE_SET[c] != c) continue;
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
{EXPS_AND_WEIGHTS}        }
    }
{LANE_SUMS}}
"#;
