//! The paper's C when its channels share centre sets (the fit's one
//! selection for all channels that share an input, issue 25): each kernel
//! value is computed once per set and weighted by every sharing channel,
//! and a set's centres are written once. Only models with shared sets get
//! this variant, so a model without keeps its C byte for byte.

use super::c::iarr;
use super::layout::Layout;

/// The arrays the shared step reads besides the paper's (whose `CENTRES`
/// the layout holds once per set): each channel's set and where its set's
/// centres start in `CENTRES` (in centres).
pub(super) fn arrays(layout: &Layout) -> String {
    format!(
        "/* Channels sharing centres and widths: each channel's set (the first channel\n * with the same ones), and where the set's centres start in CENTRES. */\n#define N 6\nstatic const int CENTRE_SET[N] = {};\n{}",
        iarr(&layout.centre_set),
        super::c_lanes::raw_only(
            layout,
            format!(
                "static const int SET_OFFSET[N] = {};\n",
                iarr(&layout.centre_offset)
            )
        )
    )
}

/// The kernels of each set once, each value times every sharing channel's
/// weight, added in centre order as the paper's loop adds them (the kernel
/// part of [`super::c_process::process_c`] for shared sets).
/// N is the number of channels (6 here, `DTG_N_GYROS` in a unit's C),
/// `CENTRE_OFFSET` where a channel's widths and weights start and
/// `SET_OFFSET` where its set's centres start (in centres).
pub(super) const SHARED_KERNELS: &str = r#"    /* Without a smoother the kernels add onto bias and effects. */
    for (c = 0; c < N; c++) {
        ys[c] = DTG_N_SMOOTH_SECTIONS > 0 ? R(0) : BIAS[c] + linear[c];
        nets[c] = R(0);
    }
#if DTG_INPUT_STATS
    lane_kernels(s->feat, ys, nets);
    (void)j;
#else
    /* The kernels of each centre set once, times each sharing channel's
     * weight into its partial sum of the centre's lane (as the Rust
     * evaluator keeps them). */
    for (c = 0; c < N; c++) {
        dtg_real acc[N][DTG_LANES];
        if (CENTRE_SET[c] != c) continue;
        for (j = c; j < N; j++)
            for (k = 0; k < DTG_LANES; k++) acc[j][k] = R(0);
        for (k = 0; k < N_CENTRES[c]; k++) {
            const dtg_real *cen = CENTRES + (long)DTG_DIM * (SET_OFFSET[c] + k);
            dtg_real r2 = R(0), beta = WIDTH[CENTRE_OFFSET[c] + k], arg, phi;
            for (sig = 0; sig < DTG_N_SIGNALS; sig++) {
                r2 += sq_dist(s->ring[sig] + s->ring_pos, cen, l);
                cen += l;
            }
            arg = -(r2 / (beta * beta));
            phi = arg < R(-708) ? R(0) : EXP_NEG(arg);
            for (j = c; j < N; j++)
                if (CENTRE_SET[j] == c) acc[j][k % DTG_LANES] += phi * WEIGHT[CENTRE_OFFSET[j] + k];
        }
        for (j = c; j < N; j++) {
            if (CENTRE_SET[j] != c) continue;
            lane_sum(acc[j]);
            ys[j] += acc[j][0];
            nets[j] += acc[j][0];
        }
    }
#endif
    for (c = 0; c < N; c++) {
        dtg_real y = ys[c], net = nets[c];
"#;
