//! The kernels of a statistics model in the exported C, laid out for vector
//! lanes as the `dtg-onboard` evaluator lays them out in its state (issue
//! 25): per centre set, blocks of [`LANES`] centres holding input number j
//! of each centre side by side, then each centre's 1/β²; each channel's
//! weights padded to whole blocks with zeros. The loops over a block's
//! lanes have a fixed trip count and no branches, so `cc -O2` vectorises
//! them; the arithmetic is the evaluator's, operation for operation, and
//! the f64 exponential is `fastexp::exp_neg11`, constant for constant, so
//! C and Rust give the same bits. A raw-window model keeps the plain loop.

use super::c::{Precision, arr, iarr};
use super::layout::Layout;
use dtg_onboard::LANES;

// LANE_KERNELS_C names one distance sum per lane.
const _: () = assert!(LANES == 8, "write LANE_KERNELS_C's sums for the new LANES");

/// `text` (the raw window's centre arrays) for a raw-window model; nothing
/// for a statistics model, whose kernels read only the lane arrays.
pub(super) fn raw_only(layout: &Layout, text: String) -> String {
    if layout.input == dtg_onboard::input::STATISTICS as usize {
        String::new()
    } else {
        text
    }
}

/// The lane arrays of a statistics model (nothing for the raw window).
pub(super) fn arrays(layout: &Layout) -> String {
    if layout.input != dtg_onboard::input::STATISTICS as usize {
        return String::new();
    }
    let (n, dim) = (layout.n, layout.dim);
    let (mut centres, mut weights) = (Vec::new(), Vec::new());
    let (mut set_block, mut weight_block) = (vec![0; n], vec![0; n]);
    let mut first_width = 0;
    for c in 0..n {
        let k_n = layout.n_centres[c];
        let blocks = k_n.div_ceil(LANES);
        let widths = &layout.widths[first_width..first_width + k_n];
        if layout.centre_set[c] == c {
            set_block[c] = centres.len() / ((dim + 1) * LANES);
            let block = &layout.centres[layout.centre_offset[c] * dim..][..k_n * dim];
            for b in 0..blocks {
                let lane = |i: usize| (b * LANES + i < k_n).then_some(b * LANES + i);
                for j in 0..dim {
                    centres.extend((0..LANES).map(|i| lane(i).map_or(0.0, |k| block[k * dim + j])));
                }
                // As the evaluator computes it (dtg_onboard::fill_lanes).
                centres.extend(
                    (0..LANES).map(|i| lane(i).map_or(0.0, |k| 1.0 / (widths[k] * widths[k]))),
                );
            }
        } else {
            set_block[c] = set_block[layout.centre_set[c]];
        }
        weight_block[c] = weights.len() / LANES;
        weights.extend(&layout.weights[first_width..first_width + k_n]);
        weights.resize(weights.len() + blocks * LANES - k_n, 0.0);
        first_width += k_n;
    }
    format!(
        r#"/* The kernels in lanes (dtg-onboard's layout): per centre set, blocks of
 * DTG_LANES centres, input number j of each side by side, then each 1/beta^2
 * (zeros past the last centre); each channel's weights padded with zeros.
 * Per channel where its set's blocks and its weights' blocks start. */
static const int LANE_SET_BLOCK[N] = {set_block};
static const int LANE_WEIGHT_BLOCK[N] = {weight_block};
static const dtg_real LANE_CENTRES[{nc}] = {centres};
static const dtg_real LANE_WEIGHT[{nw}] = {weights};
"#,
        set_block = iarr(&set_block),
        weight_block = iarr(&weight_block),
        nc = centres.len().max(1),
        centres = arr(&centres),
        nw = weights.len().max(1),
        weights = arr(&weights),
    )
}

/// The kernels' exponential (f64: `fastexp::exp_neg11`), `lane_sum` and
/// the statistics input's `lane_kernels`, before `process`.
pub(super) fn kernels(precision: Precision) -> String {
    let exp = match precision {
        Precision::F64 => EXP_NEG11_C,
        Precision::F32 => "#define EXP_NEG(x) expf(x)\n",
    };
    [
        exp,
        &LANE_SUM_C.replace("{LANES}", &LANES.to_string()),
        "#if DTG_INPUT_STATS\n",
        LANE_KERNELS_C,
        "#endif\n\n",
    ]
    .concat()
}

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

/// `fastexp::exp_neg11` for −708 ≤ x ≤ 0 (the caller clamps and zeroes).
const EXP_NEG11_C: &str = r#"#include <stdint.h>
#include <string.h>
/* e^x for -708 <= x <= 0: fastexp::exp_neg11 of the Rust evaluator, constant
 * for constant (x = n ln 2 + r; a degree-11 polynomial in r by Estrin's
 * scheme; 2^n from the bits), so that both give the same bits. */
static double exp_neg11(double x) {
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

/// Each centre set's kernels a chunk of four blocks of lanes (32 centres,
/// the Rust evaluator's `KERNEL_BLOCK`) at a time: a block's eight
/// distances in eight named sums, input number by input number (the
/// compiler keeps them in vector registers and pairs them into vector
/// operations; an array of sums indexed in a loop stayed in memory, each
/// add waiting on the store before it: a fifth of the step), the
/// exponentials of the chunk's blocks (not of all four: a set of 100
/// centres has 13 blocks, its last chunk one), each value times every sharing
/// channel's weight into that channel's partial sum of its lane; the lanes
/// are added pairwise at the end onto `ys` and `nets`. The eight sums are
/// written out for [`LANES`] = 8.
const LANE_KERNELS_C: &str = r#"/* Adds each channel's kernel terms to ys[c] and nets[c] (x: the statistics
 * inputs), as the Rust evaluator's network_terms does, operation for
 * operation: per centre, its squared distance summed over the inputs in
 * order, times 1/beta^2, the exponential; one partial sum per lane and
 * channel, the lanes added pairwise. */
static void lane_kernels(const dtg_real *x, dtg_real *ys, dtg_real *nets) {
    enum { BLOCKS = 4, CHUNK = BLOCKS * DTG_LANES, STRIDE = (DTG_DIM + 1) * DTG_LANES };
    dtg_real acc[N][DTG_LANES];
    int c, j, b, b0, nb, i, d;
    for (c = 0; c < N; c++) {
        if (CENTRE_SET[c] != c) continue;
        for (j = c; j < N; j++)
            for (i = 0; i < DTG_LANES; i++) acc[j][i] = R(0);
        nb = (N_CENTRES[c] + DTG_LANES - 1) / DTG_LANES;
        for (b0 = 0; b0 < nb; b0 += BLOCKS) {
            const dtg_real *blk = LANE_CENTRES + (long)STRIDE * (LANE_SET_BLOCK[c] + b0);
            dtg_real arg[CHUNK], xc[CHUNK], phi[CHUNK];
            int blocks = nb - b0 < BLOCKS ? nb - b0 : BLOCKS;
            for (b = 0; b < blocks; b++) {
                const dtg_real *cb = blk + STRIDE * b, *inv = cb + DTG_DIM * DTG_LANES;
                dtg_real r0 = R(0), r1 = R(0), r2 = R(0), r3 = R(0), r4 = R(0), r5 = R(0), r6 = R(0),
                         r7 = R(0), t, *ab = arg + b * DTG_LANES;
                for (d = 0; d < DTG_DIM; d++) {
                    const dtg_real xd = x[d], *cd = cb + d * DTG_LANES;
                    t = xd - cd[0]; r0 += t * t;
                    t = xd - cd[1]; r1 += t * t;
                    t = xd - cd[2]; r2 += t * t;
                    t = xd - cd[3]; r3 += t * t;
                    t = xd - cd[4]; r4 += t * t;
                    t = xd - cd[5]; r5 += t * t;
                    t = xd - cd[6]; r6 += t * t;
                    t = xd - cd[7]; r7 += t * t;
                }
                ab[0] = -(r0 * inv[0]); ab[1] = -(r1 * inv[1]); ab[2] = -(r2 * inv[2]); ab[3] = -(r3 * inv[3]);
                ab[4] = -(r4 * inv[4]); ab[5] = -(r5 * inv[5]); ab[6] = -(r6 * inv[6]); ab[7] = -(r7 * inv[7]);
            }
            /* The chunk's blocks only (a set's last chunk may hold one); the
             * clamp and the underflow to 0 in loops of their own, so that
             * each loop stays one the compiler vectorises. */
            for (b = 0; b < blocks; b++) {
                const dtg_real *ab = arg + b * DTG_LANES;
                dtg_real *xb = xc + b * DTG_LANES, *pb = phi + b * DTG_LANES;
                for (i = 0; i < DTG_LANES; i++) xb[i] = ab[i] < R(-708) ? R(-708) : ab[i];
                for (i = 0; i < DTG_LANES; i++) pb[i] = EXP_NEG(xb[i]);
                for (i = 0; i < DTG_LANES; i++) pb[i] = ab[i] < R(-708) ? R(0) : pb[i];
            }
            for (j = c; j < N; j++) {
                if (CENTRE_SET[j] != c) continue;
                for (b = 0; b < blocks; b++) {
                    const dtg_real *wt = LANE_WEIGHT + (long)DTG_LANES * (LANE_WEIGHT_BLOCK[j] + b0 + b);
                    for (i = 0; i < DTG_LANES; i++) acc[j][i] += phi[b * DTG_LANES + i] * wt[i];
                }
            }
        }
        for (j = c; j < N; j++) {
            if (CENTRE_SET[j] != c) continue;
            lane_sum(acc[j]);
            ys[j] += acc[j][0];
            nets[j] += acc[j][0];
        }
    }
}
"#;
