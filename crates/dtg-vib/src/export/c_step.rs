//! The step of the exported C, for any unit: the same operations in the
//! same order as the `dtg-onboard` evaluator (crates/dtg-onboard, which
//! documents each stage), so that C and Rust give the same bits: the
//! ground calibration with the gyros side by side, the effects, the
//! windows, the kernels in lanes ([`super::c_kernels`]), the fade, the
//! smoother, `dtg_step` and `dtg_flush`.

use super::precision::Precision;

/// `dtg_init` … `dtg_flush`, after the tables.
pub(super) fn step_c(precision: Precision) -> String {
    [
        INIT_C,
        FADE_C,
        HELPERS_C,
        &interval_c(),
        CALIBRATION_C,
        &super::c_kernels::kernels(precision),
        PROCESS_C,
        OUTPUTS_C,
        STEP_C,
        FLUSH_C,
    ]
    .concat()
}

const INIT_C: &str = r#"
void dtg_init(dtg_state *s) {
    int i, j;
    s->steps = 0;
    s->processed = 0;
    s->ring_pos = 0;
    for (i = 0; i < 6 * DTG_LOOKAHEAD; i++) s->force[i] = R(0);
    for (j = 0; j < DTG_LOOKAHEAD; j++) {
        for (i = 0; i < NA; i++) s->pending_accel[j][i] = R(0);
        for (i = 0; i < N; i++) s->pending_gyro[j][i] = R(0);
        for (i = 0; i < DTG_N_EXTRA + 1; i++) s->pending_extra[j][i] = R(0);
    }
    for (i = 0; i < 2 * DTG_N_SECTIONS * DTG_N_EFFECTS + 1; i++) s->out_z[i] = R(0);
    for (i = 0; i < 2 * DTG_N_IN_SECTIONS * DTG_N_SIGNALS + 1; i++) s->in_z[i] = R(0);
    for (i = 0; i < DTG_N_SIGNALS; i++)
        for (j = 0; j < 2 * DTG_WINDOW_LEN; j++) s->ring[i][j] = R(0);
    for (i = 0; i < NA; i++)
        for (j = 0; j < 2 * DTG_WINDOW_LEN; j++) s->fade_ring[i][j] = R(0);
    for (i = 0; i < N; i++) s->fade_h[i] = R(0);
    s->fade_w = R(0);
    for (i = 0; i < 2 * DTG_N_SIGNALS; i++) s->sums[i] = R(0);
    for (i = 0; i < 3 * DTG_N_SIGNALS; i++) s->feat[i] = R(0);
    for (i = 0; i < 2 * N * DTG_N_SMOOTH_SECTIONS + 1; i++) s->smooth_z[i] = R(0);
}

"#;

/// The fade's weight (sysid::operating::fade).
const FADE_C: &str = r#"#if DTG_FADE
static dtg_real excess(dtg_real v, dtg_real lo, dtg_real hi) {
    dtg_real e = lo - v > v - hi ? lo - v : v - hi;
    return e > R(0) ? e : R(0);
}

/* The smoothed weight of the network part for the window ending at the
 * newest sample: each accelerometer's window mean and level, the distance
 * beyond the training range, a smoothstep, a one-pole. */
static dtg_real fade_weight(dtg_state *s, int first) {
    const int l = DTG_WINDOW_LEN;
    dtg_real d2 = R(0), d, w0, u;
    int k, i;
    for (k = 0; k < NA; k++) {
        const dtg_real *x = s->fade_ring[k] + s->ring_pos;
        dtg_real sum = R(0), ss = R(0), mean, var, level, em, el;
        for (i = 0; i < l; i++) sum += x[i];
        mean = sum / R(l);
        for (i = 0; i < l; i++) ss += (x[i] - mean) * (x[i] - mean);
        var = ss / R(l);
        level = SQRT(var);
        em = excess(mean, FADE[4 * k], FADE[4 * k + 1]) / FADE[4 * NA];
        el = excess(level, FADE[4 * k + 2], FADE[4 * k + 3]) / FADE[4 * NA];
        d2 += em * em + el * el;
#if DTG_FADE_SHAPE
        {
            /* The vibration's shape (sysid::operating::shape): the rms of
             * the sample-to-sample change over sqrt(2) rms, its excess
             * beyond the training interval in shape scales, gated by the
             * level (0 up to one scale, 1 from two). */
            const dtg_real *sh = FADE + 4 * NA + 4 + N;
            dtg_real dd = R(0), rho = R(0), g, es;
            if (l >= 2 && var > R(0)) {
                for (i = 1; i < l; i++) dd += (x[i] - x[i - 1]) * (x[i] - x[i - 1]);
                rho = SQRT(dd / (R(2) * R(l - 1)) / var);
            }
            g = (level - FADE[4 * NA]) / FADE[4 * NA];
            g = g < R(0) ? R(0) : (g > R(1) ? R(1) : g);
            es = g * excess(rho, sh[2 * k], sh[2 * k + 1]) / sh[2 * NA];
            d2 += es * es;
        }
#endif
    }
    d = SQRT(d2);
    if (d <= FADE[4 * NA + 1]) {
        w0 = R(1);
    } else {
        u = (d - FADE[4 * NA + 1]) / FADE[4 * NA + 2];
        if (u > R(1)) u = R(1);
        w0 = R(1) - u * u * (R(3) - R(2) * u);
    }
    if (first) {
        s->fade_w = w0;
    } else {
        /* Within 1e-9 of its input the one-pole takes it. */
#if DTG_FADE_SHAPE
        /* Toward a lower weight the block's fall gain. */
        dtg_real gain = w0 < s->fade_w ? FADE[4 * NA + 4 + N + 2 * NA + 1] : FADE[4 * NA + 3];
#else
        dtg_real gain = FADE[4 * NA + 3];
#endif
        dtg_real w = s->fade_w + gain * (w0 - s->fade_w);
        s->fade_w = FABS(w0 - w) <= R(1e-9) ? w0 : w;
    }
    return s->fade_w;
}
#endif

"#;

/// The cascade of sections, `dot3`, and `quad` of the covariance's factors.
const HELPERS_C: &str = r#"/* One value through a cascade of second-order sections (transposed direct
 * form II); on the first step the states start in the steady state of x. */
static dtg_real cascade(const dtg_real *sos, int n, dtg_real *z, dtg_real x, int first) {
    int i;
    dtg_real v = x;
    for (i = 0; i < n; i++) {
        const dtg_real *c = sos + 7 * i;
        dtg_real y;
        if (first) {
            z[2 * i] = c[5] * x;
            z[2 * i + 1] = c[6] * x;
        }
        y = c[0] * v + z[2 * i];
        z[2 * i] = c[1] * v - c[3] * y + z[2 * i + 1];
        z[2 * i + 1] = c[2] * v - c[4] * y;
        v = y;
    }
    return v;
}

static dtg_real dot3(const dtg_real *a, const dtg_real *b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* p'Cq of the within-interval covariance C = sum of e_r e_r'. */
static dtg_real quad(const dtg_real *p, dtg_real e[4][3], const dtg_real *q) {
    return dot3(p, e[0]) * dot3(q, e[0]) + dot3(p, e[1]) * dot3(q, e[1]) + dot3(p, e[2]) * dot3(q, e[2])
           + dot3(p, e[3]) * dot3(q, e[3]);
}

"#;

/// The within-interval covariance's factors (dtg_onboard's table, which is
/// nav_sensors') and their sums over a sample's seven neighbouring forces.
fn interval_c() -> String {
    let rows: Vec<String> = dtg_onboard::WITHIN_INTERVAL_FACTORS
        .iter()
        .map(|row| {
            let r: Vec<String> = row.iter().map(|w| format!("R({w:?})")).collect();
            format!("    {{{}}}", r.join(", "))
        })
        .collect();
    format!(
        r#"/* The within-interval covariance's factors over the specific forces of
 * samples n-3 ... n+3 (nav_sensors::dtg::WITHIN_INTERVAL_FACTORS). */
static const dtg_real WITHIN_INTERVAL[4][7] = {{
{}
}};

/* The factors e_r = sum_j F_rj m_j of the oldest pending sample's
 * covariance: the forces of samples n-6 ... n-1 in s->force and the
 * newest's f. */
static void covariance(const dtg_real *forces, const dtg_real *f, dtg_real e[4][3]) {{
    int r, j, k;
    for (r = 0; r < 4; r++)
        for (k = 0; k < 3; k++) {{
            dtg_real v = R(0);
            for (j = 0; j < 7; j++) v += WITHIN_INTERVAL[r][j] * (j < 6 ? forces[3 * j + k] : f[k]);
            e[r][k] = v;
        }}
}}

"#,
        rows.join(",\n")
    )
}

/// The triad's inverse and each gyro's, with the gyros side by side.
const CALIBRATION_C: &str = r#"#if DTG_CALIBRATED
/* Newton stops once its next step would be within 4 ulps of the estimate
 * (the residual checked before the division), or after four steps. */
#define SETTLED (R(4) * DTG_EPSILON)

#if DTG_ACCEL_TRIAD
/* Three Gauss-Seidel sweeps, Newton on each axis; a sweep after the first
 * starts each axis at the last sweep's root. */
static void compensate_triad(const dtg_real *measured, dtg_real *a) {
    dtg_real target[3];
    int pass, k, it;
    for (k = 0; k < 3; k++) a[k] = measured[k];
    for (k = 0; k < 3; k++) target[k] = measured[k] / (R(1) + R(1e-6) * ACCEL_CAL[8 * k + 1]);
    for (pass = 0; pass < 3; pass++) {
        for (k = 0; k < 3; k++) {
            const dtg_real *c = ACCEL_CAL + 8 * k;
            dtg_real ap = a[(k + 1) % 3], ao = a[(k + 2) % 3];
            dtg_real x = pass == 0 ? target[k] : a[k];
            for (it = 0; it < 4; it++) {
                dtg_real core = R(1e-6) * (c[0] + x * x * (c[2] + c[3] * x) + c[4] * ap - c[5] * ao
                                           + x * (c[6] * ap + c[7] * ao));
                dtg_real g = x + core - target[k];
                dtg_real dg = R(1) + R(1e-6) * (R(2) * c[2] * x + R(3) * c[3] * x * x + c[6] * ap + c[7] * ao);
                if (FABS(g) <= SETTLED * FABS(dg * x)) break;
                x -= g / dg;
            }
            a[k] = x;
        }
    }
}
#endif

/* Row r of the calibration lanes: one number per gyro. */
#define CL(r) (CAL_LANES + (r) * N)

/* A DTG's rate about its input axis from
 * measured = a0 + b w + 1e-6 nl |w| w / 3600, Newton from w. */
static dtg_real newton(dtg_real wi, dtg_real a0, dtg_real b, dtg_real nl, dtg_real measured) {
    int it;
    for (it = 0; it < 4; it++) {
        dtg_real per_s = FABS(wi) * (R(1) / R(3600));
        dtg_real fx = a0 + b * wi + R(1e-6) * nl * per_s * wi - measured;
        dtg_real df = b + R(2e-6) * nl * per_s;
        if (FABS(fx) <= SETTLED * FABS(df * wi)) break;
        wi -= fx / df;
    }
    return wi;
}

/* Each gyro's inverse model, two passes (the least-squares rate from the
 * raw outputs, then from the first pass's), the gyros side by side: the
 * drift at rest (bias, g and g^2 terms along each gyro's axes, with the
 * covariance's factors e) once, then per pass a DTG's rate terms, the
 * division, a DTG's Newton steps. */
static void compensate_gyros(const dtg_real *raw, const dtg_real *f, dtg_real e[4][3], dtg_real *out) {
    static const int PAIR_A[6] = {0, 1, 2, 0, 0, 1}, PAIR_B[6] = {0, 1, 2, 1, 2, 2};
    dtg_real p[5][3][N], g[N], cur[N], a0[N], b[N], next[N], rate[3];
    const dtg_real *v[5];
    int i, a, t, k, pass;
    v[0] = f;
    for (i = 0; i < 4; i++) v[1 + i] = e[i];
    for (i = 0; i < 5; i++)
        for (a = 0; a < 3; a++) {
            const dtg_real *x = CL(3 * a), *y = CL(3 * a + 1), *z = CL(3 * a + 2);
            for (k = 0; k < N; k++) p[i][a][k] = x[k] * v[i][0] + y[k] * v[i][1] + z[k] * v[i][2];
        }
    for (k = 0; k < N; k++) g[k] = CL(9)[k];
    for (a = 0; a < 3; a++)
        for (k = 0; k < N; k++) g[k] += p[0][a][k] * CL(10 + a)[k];
    for (t = 0; t < 6; t++) {
        const int pa = PAIR_A[t], pb = PAIR_B[t];
        const dtg_real *c = CL(13 + t);
        for (k = 0; k < N; k++)
            g[k] += (p[0][pa][k] * p[0][pb][k] + p[1][pa][k] * p[1][pb][k] + p[2][pa][k] * p[2][pb][k]
                     + p[3][pa][k] * p[3][pb][k] + p[4][pa][k] * p[4][pb][k]) * c[k];
    }
    for (k = 0; k < N; k++) cur[k] = raw[k];
    for (pass = 0; pass < 2; pass++) {
        for (i = 0; i < 3; i++) {
            dtg_real s = R(0);
            for (k = 0; k < N; k++) s += CL(26 + i)[k] * cur[k];
            rate[i] = s;
        }
        for (k = 0; k < N; k++) {
            dtg_real w1 = CL(3)[k] * rate[0] + CL(4)[k] * rate[1] + CL(5)[k] * rate[2];
            dtg_real w2 = CL(6)[k] * rate[0] + CL(7)[k] * rate[1] + CL(8)[k] * rate[2];
            a0[k] = g[k] + (w1 * CL(20)[k] + w2 * CL(21)[k]) + (w1 * w2) * CL(24)[k];
            b[k] = CL(19)[k] + (w1 * CL(22)[k] + w2 * CL(23)[k]);
            next[k] = (raw[k] - a0[k]) / b[k];
        }
        for (k = 0; k < N; k++)
            if (GYRO_MODEL[k] == 0) next[k] = newton(next[k], a0[k], b[k], CL(25)[k], raw[k]);
        for (k = 0; k < N; k++) cur[k] = next[k];
    }
    for (k = 0; k < N; k++) out[k] = cur[k];
}
#endif

"#;

/// `process` up to its outputs: the calibration, the effects, the windows,
/// the kernels.
const PROCESS_C: &str = r#"/* Compensates the pending sample with its within-interval covariance's
 * factors e. */
static int process(dtg_state *s, dtg_real e[4][3], double rate_deg_h[N], double accel_out_g[NA]) {
    dtg_real f[3], a[NA], g[N], linear[N], ys[N], nets[N], w = R(1);
    int first = s->processed == 0;
    int k, c, ei, sig;
    const int l = DTG_WINDOW_LEN;
    for (k = 0; k < 3; k++) f[k] = s->force[3 * DTG_LOOKAHEAD + k];
    for (k = 0; k < NA; k++) a[k] = s->pending_accel[0][k];
#if DTG_CALIBRATED
    compensate_gyros(s->pending_gyro[0], f, e, g);
#else
    for (k = 0; k < N; k++) g[k] = s->pending_gyro[0][k];
#endif
    for (c = 0; c < N; c++) {
        dtg_real sum = R(0);
        for (ei = 0; ei < N_EFFECTS[c]; ei++) {
            int idx = EFFECT_OFFSET[c] + ei;
            const dtg_real *p = PARAMS + PARAM_OFFSET[idx];
            dtg_real z;
            switch (EFFECT_KIND[idx]) {
            case 0: z = s->pending_extra[0][EFFECT_INDEX[idx]]; break;
            case 1: z = dot3(p, f); break;
            case 2: z = dot3(p, f) * dot3(p + 3, f) + quad(p, e, p + 3); break;
            default: {
                dtg_real r = R(0), q = R(0);
                for (k = 0; k < N; k++) r += p[k] * g[k];
                for (k = 0; k < N; k++) q += p[N + k] * g[k];
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
        dtg_real v = code < NA ? a[code] : s->pending_extra[0][code - NA];
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
    for (k = 0; k < NA; k++) {
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
    /* Without a smoother the kernels add onto bias and effects. */
    for (c = 0; c < N; c++) {
        ys[c] = DTG_N_SMOOTH_SECTIONS > 0 ? R(0) : BIAS[c] + linear[c];
        nets[c] = R(0);
    }
    network_terms(s, ys, nets);
"#;

/// The end of `process`: per channel the fade's cross-fade of the held
/// network part, the prediction smoother, the compensated rate.
const OUTPUTS_C: &str = r#"    for (c = 0; c < N; c++) {
        dtg_real y = ys[c], net = nets[c];
#if DTG_FADE
        {
            /* The held network part follows the network by the weight's
             * one-pole at full weight and stays below it; the output
             * cross-fades from it to the network by the weight. A record
             * starts it at the network's value at rest. Before the smoother
             * (sysid::operating::fade). */
            dtg_real before = s->processed == l ? FADE[4 * NA + 4 + c] : s->fade_h[c];
            dtg_real faded = w >= R(1) ? net : before + w * (net - before);
            s->fade_h[c] = w >= R(1) ? before + FADE[4 * NA + 3] * (net - before) : before;
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
        rate_deg_h[c] = (double)(g[c] - y);
    }
    (void)w;
    for (k = 0; k < NA; k++) accel_out_g[k] = (double)a[k];
    return 1;
}

"#;

/// `dtg_step`: the specific force from the accelerometers, the triad
/// calibrated on it, the pending sample's covariance, `process`, the state
/// moved on one sample.
const STEP_C: &str = r#"/* The pending samples one on, the oldest (just processed) dropped. */
static void shift_pending(dtg_state *s) {
    int j, k;
    for (j = 0; j + 1 < DTG_LOOKAHEAD; j++) {
        for (k = 0; k < NA; k++) s->pending_accel[j][k] = s->pending_accel[j + 1][k];
        for (k = 0; k < N; k++) s->pending_gyro[j][k] = s->pending_gyro[j + 1][k];
        for (k = 0; k < DTG_N_EXTRA + 1; k++) s->pending_extra[j][k] = s->pending_extra[j + 1][k];
    }
}

int dtg_step(dtg_state *s, const double gyro_deg_h[N], const double accel_g[NA],
             const double *extra, double rate_deg_h[N], double accel_out_g[NA]) {
    dtg_real raw_a[NA], f[3], cal[NA], e[4][3];
    int i, k, slot, out = 0;
    for (k = 0; k < NA; k++) raw_a[k] = (dtg_real)accel_g[k];
    for (i = 0; i < 3; i++) {
        dtg_real v = R(0);
        for (k = 0; k < NA; k++) v += FORCE_OP[NA * i + k] * raw_a[k];
        f[i] = v;
    }
#if DTG_CALIBRATED && DTG_ACCEL_TRIAD
    {
        /* The triad's inverse on the specific force; the accelerometers are
         * the unit's axes, so the operator's transpose gives them back. */
        dtg_real m[3];
        for (i = 0; i < 3; i++) m[i] = f[i];
        compensate_triad(m, f);
        for (k = 0; k < NA; k++) {
            dtg_real v = R(0);
            for (i = 0; i < 3; i++) v += FORCE_OP[NA * i + k] * f[i];
            cal[k] = v;
        }
    }
#else
    for (k = 0; k < NA; k++) cal[k] = raw_a[k];
#endif
    if (s->steps >= DTG_LOOKAHEAD) {
        /* The oldest pending sample's covariance, centred on it (n-6 ... n),
         * as its factors; zero for the first three samples, which lack
         * three neighbours before them. */
        for (i = 0; i < 4; i++)
            for (k = 0; k < 3; k++) e[i][k] = R(0);
        if (s->steps >= 2 * DTG_LOOKAHEAD) covariance(s->force, f, e);
        out = process(s, e, rate_deg_h, accel_out_g);
        shift_pending(s);
    }
    for (k = 0; k < 3 * (2 * DTG_LOOKAHEAD - 1); k++) s->force[k] = s->force[k + 3];
    for (k = 0; k < 3; k++) s->force[3 * (2 * DTG_LOOKAHEAD - 1) + k] = f[k];
    slot = s->steps < DTG_LOOKAHEAD ? (int)s->steps : DTG_LOOKAHEAD - 1;
    for (k = 0; k < NA; k++) s->pending_accel[slot][k] = cal[k];
    for (k = 0; k < N; k++) s->pending_gyro[slot][k] = (dtg_real)gyro_deg_h[k];
    for (k = 0; k < DTG_N_EXTRA; k++) s->pending_extra[slot][k] = (dtg_real)extra[k];
    s->steps += 1;
    return out;
}

"#;

const FLUSH_C: &str = r#"int dtg_flush(dtg_state *s, double rate_deg_h[DTG_LOOKAHEAD][N], double accel_out_g[DTG_LOOKAHEAD][NA]) {
    dtg_real e[4][3];
    int i, k, row, got = 0;
    int held = s->steps < DTG_LOOKAHEAD ? (int)s->steps : DTG_LOOKAHEAD;
    for (i = 0; i < 4; i++)
        for (k = 0; k < 3; k++) e[i][k] = R(0);
    /* Fewer samples than the lookahead received: their forces sit in the
     * newest slots; the oldest held one goes to the pending sample's. */
    for (k = 0; k < 3 * (DTG_LOOKAHEAD + held); k++)
        s->force[k] = s->force[k + 3 * (DTG_LOOKAHEAD - held)];
    for (row = DTG_LOOKAHEAD - held; row < DTG_LOOKAHEAD; row++) {
        if (process(s, e, rate_deg_h[row], accel_out_g[row])) got |= 1 << row;
        shift_pending(s);
        /* The next pending sample's force into the oldest's slot. */
        for (k = 0; k < 3 * (2 * DTG_LOOKAHEAD - 1); k++) s->force[k] = s->force[k + 3];
    }
    dtg_init(s);
    return got;
}
"#;
