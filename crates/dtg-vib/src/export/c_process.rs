//! The per-sample `process` of the exported C, the fade weight it takes,
//! and the end of `dtg_step` and `dtg_flush` that call it: one text for
//! the paper's layout ([`super::c`]: six channels, three accelerometers
//! whose calibrated values are the specific force, sizes written as
//! numbers) and a unit's ([`super::c_unit`]: `N` gyros, `NA`
//! accelerometers, the specific force `f` apart from them), filled in by
//! [`Shape`]. Each fill gives its layout's C byte for byte as it was when
//! the two were written apart.

/// Which layout's C to write.
#[derive(Debug, Clone, Copy)]
pub(super) struct Shape {
    /// A unit's layout (else the paper's).
    unit: bool,
    /// The kernel loop over centre sets, each value weighted by every
    /// sharing channel (else each channel's own loop, a raw-window paper
    /// model without shared sets only).
    shared: bool,
}

impl Shape {
    /// The paper's `process`; `shared`: the loop over centre sets
    /// ([`super::c_shared`]).
    pub(super) fn paper(shared: bool) -> Self {
        Shape {
            unit: false,
            shared,
        }
    }

    /// A unit's `process` (always the loop over centre sets).
    pub(super) fn unit() -> Self {
        Shape {
            unit: true,
            shared: true,
        }
    }

    /// `text` with its `{...}` marks filled for this shape: the layout's
    /// pieces first, then the sizes and the specific force's name.
    fn fill(&self, text: &str) -> String {
        let (unit, shared) = (self.unit, self.shared);
        let pick = |yes: bool, a: &'static str| if yes { a } else { "" };
        [
            ("{force_local}", pick(unit, "f[3], ")),
            ("{shared_locals}", pick(shared, ", ys[{N}], nets[{N}]")),
            ("{j}", pick(shared, ", j")),
            ("{force_state}", if unit { "force" } else { "prev_accel" }),
            (
                "{load_accel}",
                pick(
                    unit,
                    "    for (k = 0; k < {NA}; k++) a[k] = s->pending_accel[k];\n",
                ),
            ),
            (
                "{fade_doc}",
                if unit { UNIT_FADE_DOC } else { PAPER_FADE_DOC },
            ),
            // The FADE table after the per-axis ranges: the scale, the
            // tolerance, the width, the hold's gain, each channel's
            // network at rest.
            ("{scale}", if unit { "4 * NA" } else { "12" }),
            ("{tol}", if unit { "4 * NA + 1" } else { "13" }),
            ("{width}", if unit { "4 * NA + 2" } else { "14" }),
            ("{gain}", if unit { "4 * NA + 3" } else { "15" }),
            ("{rest}", if unit { "4 * NA + 4 + c" } else { "16 + c" }),
            ("{void_w}", pick(unit, "        (void)w;\n")),
            (
                "{store_accel}",
                pick(
                    unit,
                    "    for (k = 0; k < {NA}; k++) s->pending_accel[k] = cal[k];\n",
                ),
            ),
            ("{NA}", if unit { "NA" } else { "3" }),
            ("{N}", if unit { "N" } else { "6" }),
            ("{F}", if unit { "f" } else { "a" }),
        ]
        .iter()
        .fold(text.to_string(), |s, (mark, by)| s.replace(mark, by))
    }
}

/// `fade_weight` (closes `#if DTG_FADE`, which
/// [`super::c::EXCESS_C`] opens).
pub(super) fn fade_weight_c(shape: Shape) -> String {
    shape.fill(FADE_WEIGHT_C)
}

/// `process`: the effects, the window, the kernels (each channel's own or
/// per centre set), the fade, the smoother and the outputs.
pub(super) fn process_c(shape: Shape) -> String {
    let kernels = if shape.shared {
        super::c_shared::SHARED_KERNELS
    } else {
        OWN_KERNELS_C
    };
    shape.fill(&[PROCESS_C, kernels, FADE_AND_SMOOTHER_C, PROCESS_END_C].concat())
}

/// The end of `dtg_step` after the layout's own start (the pending
/// sample's covariance, `process`, the state moved on one sample), then
/// `dtg_flush`.
pub(super) fn step_end_c(shape: Shape) -> String {
    shape.fill(&[STEP_END_C, FLUSH_C].concat())
}

/// The smoothed weight of the network part (sysid::operating::fade), over
/// the paper's three axes or a unit's `NA` accelerometers.
const FADE_WEIGHT_C: &str = r#"{fade_doc}static dtg_real fade_weight(dtg_state *s, int first) {
    const int l = DTG_WINDOW_LEN;
    dtg_real d2 = R(0), d, w0, u;
    int k, i;
    for (k = 0; k < {NA}; k++) {
        const dtg_real *x = s->fade_ring[k] + s->ring_pos;
        dtg_real sum = R(0), ss = R(0), mean, level, em, el;
        for (i = 0; i < l; i++) sum += x[i];
        mean = sum / R(l);
        for (i = 0; i < l; i++) ss += (x[i] - mean) * (x[i] - mean);
        level = SQRT(ss / R(l));
        em = excess(mean, FADE[4 * k], FADE[4 * k + 1]) / FADE[{scale}];
        el = excess(level, FADE[4 * k + 2], FADE[4 * k + 3]) / FADE[{scale}];
        d2 += em * em + el * el;
    }
    d = SQRT(d2);
    if (d <= FADE[{tol}]) {
        w0 = R(1);
    } else {
        u = (d - FADE[{tol}]) / FADE[{width}];
        if (u > R(1)) u = R(1);
        w0 = R(1) - u * u * (R(3) - R(2) * u);
    }
    if (first) {
        s->fade_w = w0;
    } else {
        /* Within 1e-9 of its input the one-pole takes it. */
        dtg_real w = s->fade_w + FADE[{gain}] * (w0 - s->fade_w);
        s->fade_w = FABS(w0 - w) <= R(1e-9) ? w0 : w;
    }
    return s->fade_w;
}
#endif

"#;

/// [`FADE_WEIGHT_C`]'s comment for the paper's C.
const PAPER_FADE_DOC: &str = r#"/* The smoothed weight of the network part for the window ending at the
 * newest sample (sysid::operating::fade): each axis's window mean and
 * level, the distance beyond the training range, a smoothstep, a one-pole. */
"#;

/// [`FADE_WEIGHT_C`]'s comment for a unit's C.
const UNIT_FADE_DOC: &str = r#"/* The smoothed weight of the network part for the window ending at the
 * newest sample (sysid::operating::fade): each accelerometer's window mean
 * and level, the distance beyond the training range, a smoothstep, a
 * one-pole. */
"#;

/// `process` up to its kernels; the pending sample's calibrated
/// accelerations `a`, its specific force `{F}` (the paper's `a`).
const PROCESS_C: &str = r#"/* Compensates the pending sample with its within-interval covariance. */
static int process(dtg_state *s, dtg_real cov[3][3], double rate_deg_h[{N}], double accel_out_g[{NA}]) {
    dtg_real {force_local}a[{NA}], g[{N}], linear[{N}]{shared_locals}, w = R(1);
    int first = s->processed == 0;
    int k, c, e, sig{j};
    const int l = DTG_WINDOW_LEN;
    for (k = 0; k < 3; k++) {F}[k] = s->{force_state}[k];
{load_accel}#if DTG_CALIBRATED
    compensate_gyros(s->pending_gyro, {F}, cov, g);
#else
    for (k = 0; k < {N}; k++) g[k] = s->pending_gyro[k];
#endif
    for (c = 0; c < {N}; c++) {
        dtg_real sum = R(0);
        for (e = 0; e < N_EFFECTS[c]; e++) {
            int idx = EFFECT_OFFSET[c] + e;
            const dtg_real *p = PARAMS + PARAM_OFFSET[idx];
            dtg_real z;
            switch (EFFECT_KIND[idx]) {
            case 0: z = s->pending_extra[EFFECT_INDEX[idx]]; break;
            case 1: z = dot3(p, {F}); break;
            case 2: z = dot3(p, {F}) * dot3(p + 3, {F}) + quad(p, cov, p + 3); break;
            default: {
                dtg_real r = R(0), q = R(0);
                for (k = 0; k < {N}; k++) r += p[k] * g[k];
                for (k = 0; k < {N}; k++) q += p[{N} + k] * g[k];
                z = r * q;
            }
            }
            z = cascade(OUT_SOS, DTG_N_SECTIONS, s->out_z + 2 * DTG_N_SECTIONS * idx, z, first);
            sum += z * COEFF[idx];
        }
        linear[c] = sum;
    }
    for (sig = 0; sig < DTG_N_SIGNALS; sig++) {
        int code = SIGNAL_CODE[sig];
        dtg_real v = code < {NA} ? a[code] : s->pending_extra[code - {NA}];
        v = cascade(IN_SOS, DTG_N_IN_SECTIONS, s->in_z + 2 * DTG_N_IN_SECTIONS * sig, v, first);
        {
            /* Running sums: the sample L steps back (0 while the window
             * fills) leaves as this one enters. */
            dtg_real old = s->ring[sig][s->ring_pos];
            s->sums[2 * sig] = (s->sums[2 * sig] + v) - old;
            s->sums[2 * sig + 1] = (s->sums[2 * sig + 1] + v * v) - old * old;
#if DTG_INPUT_STATS
            {
                dtg_real mean = s->sums[2 * sig] / (dtg_real)l;
                dtg_real var = s->sums[2 * sig + 1] / (dtg_real)l - mean * mean;
                s->feat[3 * sig] = v;
                s->feat[3 * sig + 1] = mean;
                s->feat[3 * sig + 2] = var > R(0) ? SQRT(var) : R(0);
            }
#endif
        }
        s->ring[sig][s->ring_pos] = v;
        s->ring[sig][s->ring_pos + l] = v;
    }
#if DTG_FADE
    for (k = 0; k < {NA}; k++) {
        s->fade_ring[k][s->ring_pos] = a[k];
        s->fade_ring[k][s->ring_pos + l] = a[k];
    }
#endif
    s->ring_pos = (s->ring_pos + 1) % l;
    s->processed += 1;
    if (s->processed < l) return 0;
#if DTG_FADE
    w = fade_weight(s, s->processed == l);
#endif
"#;

/// Each channel's own kernel loop (a raw-window paper model without shared
/// centre sets).
const OWN_KERNELS_C: &str = r#"    for (c = 0; c < 6; c++) {
        /* Without a smoother the kernels add onto bias and effects. */
        dtg_real y = DTG_N_SMOOTH_SECTIONS > 0 ? R(0) : BIAS[c] + linear[c], net = R(0);
        dtg_real acc[DTG_LANES];
        for (k = 0; k < DTG_LANES; k++) acc[k] = R(0);
        for (k = 0; k < N_CENTRES[c]; k++) {
            int kk = CENTRE_OFFSET[c] + k;
            const dtg_real *cen = CENTRES + (long)DTG_DIM * kk;
            dtg_real r2 = R(0), beta = WIDTH[kk], arg;
            for (sig = 0; sig < DTG_N_SIGNALS; sig++) {
                r2 += sq_dist(s->ring[sig] + s->ring_pos, cen, l);
                cen += l;
            }
            arg = -(r2 / (beta * beta));
            /* One partial sum per lane, as the Rust evaluator keeps them. */
            acc[k % DTG_LANES] += (arg < R(-708) ? R(0) : EXP_NEG(arg)) * WEIGHT[kk];
        }
        lane_sum(acc);
        y += acc[0];
        net += acc[0];
"#;

/// The end of a channel's step: the fade's cross-fade of the held network
/// part (sysid::operating::fade), then the prediction smoother on the
/// network part. `{rest}` and `{gain}` index the FADE table: a channel's
/// network at rest and the hold's one-pole gain.
const FADE_AND_SMOOTHER_C: &str = r#"#if DTG_FADE
        {
            /* The held network part follows the network by the weight's
             * one-pole at full weight and stays below it; the output
             * cross-fades from it to the network by the weight. A record
             * starts it at the network's value at rest. Before the smoother
             * (sysid::operating::fade). */
            dtg_real before = s->processed == l ? FADE[{rest}] : s->fade_h[c];
            dtg_real faded = w >= R(1) ? net : before + w * (net - before);
            s->fade_h[c] = w >= R(1) ? before + FADE[{gain}] * (net - before) : before;
#if DTG_N_SMOOTH_SECTIONS == 0
            y -= net - faded;
#endif
            net = faded;
        }
#endif
#if DTG_N_SMOOTH_SECTIONS > 0
        /* The prediction smoother, on the network part only. */
        net = cascade(SMOOTH_SOS, DTG_N_SMOOTH_SECTIONS, s->smooth_z + 2 * DTG_N_SMOOTH_SECTIONS * c,
                      net, s->processed == l);
        y = BIAS[c] + linear[c] + net;
#endif
        (void)net;
"#;

/// The channel's output and the end of `process`.
const PROCESS_END_C: &str = r#"{void_w}        rate_deg_h[c] = (double)(g[c] - y);
    }
    for (k = 0; k < {NA}; k++) accel_out_g[k] = (double)a[k];
    return 1;
}

"#;

/// `dtg_step` from the pending sample's covariance on: the covariance
/// centred on it (n−2, n−1, n) from the specific force `{F}`, `process`, the
/// state moved on one sample.
const STEP_END_C: &str = r#"    if (s->steps >= 1) {
        /* The pending sample's covariance, centred on it (n-2, n-1, n); zero
         * for the first sample, which has one neighbour. */
        for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) cov[i][j] = R(0);
        if (s->steps >= 2) {
            dtg_real c1[3], c2[3];
            for (k = 0; k < 3; k++) {
                c1[k] = ({F}[k] - s->{force_state}[3 + k]) / R(2);
                c2[k] = ({F}[k] + s->{force_state}[3 + k] - R(2) * s->{force_state}[k]) / R(2);
            }
            for (i = 0; i < 3; i++)
                for (j = 0; j < 3; j++) cov[i][j] = c1[i] * c1[j] / R(12) + c2[i] * c2[j] / R(180);
        }
        out = process(s, cov, rate_deg_h, accel_out_g);
    }
    for (k = 0; k < 3; k++) {
        s->{force_state}[3 + k] = s->{force_state}[k];
        s->{force_state}[k] = {F}[k];
    }
{store_accel}    for (k = 0; k < {N}; k++) s->pending_gyro[k] = (dtg_real)gyro_deg_h[k];
    for (k = 0; k < DTG_N_EXTRA; k++) s->pending_extra[k] = (dtg_real)extra[k];
    s->steps += 1;
    return out;
}

"#;

const FLUSH_C: &str = r#"int dtg_flush(dtg_state *s, double rate_deg_h[{N}], double accel_out_g[{NA}]) {
    dtg_real cov[3][3];
    int i, j, out = 0;
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) cov[i][j] = R(0);
    if (s->steps >= 1) out = process(s, cov, rate_deg_h, accel_out_g);
    dtg_init(s);
    return out;
}
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_mark_is_filled_in_every_shape() {
        for shape in [Shape::paper(false), Shape::paper(true), Shape::unit()] {
            let c = fade_weight_c(shape) + &process_c(shape) + &step_end_c(shape);
            for mark in [
                "{N}",
                "{NA}",
                "{F}",
                "{j}",
                "{rest}",
                "{gain}",
                "{void_w}",
                "{scale}",
                "{tol}",
                "{width}",
                "{fade_doc}",
            ] {
                assert!(!c.contains(mark), "{shape:?}: {mark} left");
            }
            assert!(!c.contains("{force_") && !c.contains("{shared_") && !c.contains("{load_"));
            assert!(!c.contains("{store_"));
        }
        // The paper's sizes are numbers, a unit's its macros.
        assert!(process_c(Shape::paper(true)).contains("double rate_deg_h[6]"));
        assert!(process_c(Shape::unit()).contains("double rate_deg_h[N]"));
    }
}
