//! C99 sources of a causal model of any unit (onboard tables of layout
//! [`dtg_onboard::UNIT_VERSION`]): the same three files as the paper's
//! ([`super::c`]), for n channels of DTG or rate gyros, the unit's
//! operators and calibration, channels sharing a centre set computing each
//! kernel value once, and a `main.c` that reads and writes the log in the
//! unit's column names and units, as `dtg-vib compensate --unit` does.

use super::c::{
    CAL_HELPERS_C, CSources, DRIFT_C, EXCESS_C, HELPERS_C, Precision, SQ_DIST_C, arr, iarr,
    real_type, with_maths,
};
use super::c_process::{Shape, fade_weight_c, process_c, step_end_c};
use super::layout::Layout;
use crate::onboard::{ExportError, Tables};
use nav_sensors::unit::Unit;

/// The C sources of a unit model's onboard tables `t` (from
/// [`crate::onboard::unit_tables`]); `unit` names the log's columns.
pub fn unit_c_sources(
    t: &Tables,
    unit: &Unit,
    precision: Precision,
) -> Result<CSources, ExportError> {
    let layout = Layout::read(&t.bytes)?;
    let mut source = tables_c(&layout);
    source.push_str(&super::c_lanes::arrays(&layout));
    let step = [
        INIT_C,
        EXCESS_C,
        &fade_weight_c(Shape::unit()),
        HELPERS_C,
        CAL_HELPERS_C,
        DRIFT_C,
        GYROS_C,
        SQ_DIST_C,
        &super::c_lanes::kernels(precision),
        &process_c(Shape::unit()),
        STEP_C,
        &step_end_c(Shape::unit()),
    ]
    .concat();
    source.push_str(&with_maths(&step, precision));
    Ok(CSources {
        header: header_h(&layout, &t.extra, unit, real_type(precision)),
        source,
        main: MAIN_C.to_string(),
    })
}

fn names(v: &[&str]) -> String {
    let q: Vec<String> = v.iter().map(|n| format!("\"{n}\"")).collect();
    if q.is_empty() {
        "\"\"".into()
    } else {
        q.join(", ")
    }
}

/// `dtg_model.h`: the sizes, the log's columns and units, the state and
/// the three calls.
fn header_h(layout: &Layout, extra: &[String], unit: &Unit, real: &str) -> String {
    let Layout {
        n,
        n_a,
        dt,
        l,
        n_signals,
        n_sections,
        n_in_sections,
        fade,
        input,
        n_smooth,
        rate_to_deg_h,
        force_to_g,
        ..
    } = layout;
    let extra: Vec<&str> = extra.iter().map(String::as_str).collect();
    format!(
        r#"/* Vibration-error compensator of the unit '{name}', exported by
 * `dtg-vib export --lang c`. C99, needs only <math.h>. Layout:
 * docs/formats.md ("Onboard tables", version 3). One call of dtg_step per
 * output period ({dt} s) with sample n: the raw gyro outputs (deg/h) and
 * accelerations (g) in the unit's order (DTG_GYRO_NAMES, DTG_ACCEL_NAMES)
 * and the extra columns below; out come the compensated rates (deg/h) and
 * calibrated accelerations (g) of sample n - 1 (one period of latency: the
 * g² terms' within-interval covariance of a sample needs its two
 * neighbours). The first {l} calls return 0 (the windows fill); every later
 * call returns 1. At the end of a record, dtg_flush gives the last sample's
 * output. The log's columns are in the units below (main.c converts). */
#ifndef DTG_MODEL_H
#define DTG_MODEL_H

typedef {real} dtg_real;

#define DTG_DT_S {dt:e}
#define DTG_N_GYROS {n}
#define DTG_N_ACCELS {n_a}
#define DTG_WINDOW_LEN {l}
#define DTG_N_SIGNALS {n_signals}
#define DTG_N_EXTRA {n_extra}
#define DTG_N_SECTIONS {n_sections}
#define DTG_N_IN_SECTIONS {n_in_sections}
#define DTG_N_EFFECTS {total_effects}
/* 1: outside the training range the network part holds (docs/formats.md). */
#define DTG_FADE {fades}
/* The network's input: 0 = the window, 1 = per signal its current sample,
 * window mean and window rms about the mean. */
#define DTG_INPUT_STATS {input}
/* Second-order sections of the prediction smoother (network part only). */
#define DTG_N_SMOOTH_SECTIONS {n_smooth}
/* The log: its time column, gyros and accelerometers, and their units (a
 * gyro column times DTG_RATE_TO_DEG_H is deg/h, an accelerometer column
 * times DTG_FORCE_TO_G is g). */
#define DTG_TIME_NAME "{time}"
#define DTG_GYRO_NAMES {{{gyros}}}
#define DTG_ACCEL_NAMES {{{accels}}}
#define DTG_RATE_TO_DEG_H {rate_to_deg_h:e}
#define DTG_FORCE_TO_G {force_to_g:e}
/* Extra columns, in the order dtg_step takes them. */
#define DTG_EXTRA_NAMES {{{extra_names}}}

/* All the state: its size is fixed at compile time. */
typedef struct {{
    long steps;     /* samples received */
    long processed; /* samples compensated */
    int ring_pos;
    dtg_real force[6]; /* calibrated specific force of the pending sample and the one before, g */
    dtg_real pending_accel[DTG_N_ACCELS]; /* the pending sample's calibrated accelerations, g */
    dtg_real pending_gyro[DTG_N_GYROS];   /* the pending sample's raw outputs, deg/h */
    dtg_real pending_extra[DTG_N_EXTRA + 1];
    dtg_real out_z[2 * DTG_N_SECTIONS * DTG_N_EFFECTS + 1];
    dtg_real in_z[2 * DTG_N_IN_SECTIONS * DTG_N_SIGNALS + 1];
    dtg_real ring[DTG_N_SIGNALS][2 * DTG_WINDOW_LEN];
    dtg_real fade_ring[DTG_N_ACCELS][2 * DTG_WINDOW_LEN]; /* calibrated accelerations: the range */
    dtg_real fade_h[DTG_N_GYROS]; /* held network part per channel, deg/h */
    dtg_real fade_w;              /* smoothed weight of the network part */
    dtg_real sums[2 * DTG_N_SIGNALS]; /* running sum and sum of squares per signal */
    dtg_real feat[3 * DTG_N_SIGNALS]; /* the statistics inputs */
    dtg_real smooth_z[2 * DTG_N_GYROS * DTG_N_SMOOTH_SECTIONS + 1];
}} dtg_state;

void dtg_init(dtg_state *s);
int dtg_step(dtg_state *s, const double gyro_deg_h[DTG_N_GYROS], const double accel_g[DTG_N_ACCELS],
             const double *extra, double rate_deg_h[DTG_N_GYROS], double accel_out_g[DTG_N_ACCELS]);
/* The last sample's output (returns 1) or nothing (0); leaves s at rest. */
int dtg_flush(dtg_state *s, double rate_deg_h[DTG_N_GYROS], double accel_out_g[DTG_N_ACCELS]);

#endif
"#,
        name = unit.name().replace("*/", "* /"),
        n_extra = extra.len(),
        total_effects = layout.kinds.len(),
        fades = i32::from(!fade.is_empty()),
        time = unit.columns().time,
        gyros = names(&unit.gyro_names()),
        accels = names(&unit.accel_names()),
        extra_names = names(&extra),
    )
}

/// The tables as C arrays, before the step code.
fn tables_c(layout: &Layout) -> String {
    let n = layout.n;
    let c_offsets: Vec<usize> = (0..n).map(|c| layout.n_centres[..c].iter().sum()).collect();
    let e_offsets: Vec<usize> = (0..n).map(|c| layout.n_effects[..c].iter().sum()).collect();
    format!(
        r#"/* Generated by `dtg-vib export --lang c`; the same step as the dtg-onboard
 * Rust evaluator (crates/dtg-onboard/src/lib.rs), which documents each stage. */
#include <float.h>
#include <math.h>
#include "dtg_model.h"

#define R(x) ((dtg_real)(x))
#define DTG_CALIBRATED {cal}
#define DTG_ACCEL_TRIAD {triad}
#define DTG_DIM {dim}
#define N DTG_N_GYROS
#define NA DTG_N_ACCELS

/* Per gyro its (I, O, S) axes (a rate gyro: I and two zero rows). */
static const dtg_real FRAMES[9 * N] = {frames};
/* The least-squares rate (HᵀH)⁻¹Hᵀ, 3 × N, and the specific force from the
 * accelerometers, 3 × NA. */
static const dtg_real LS[3 * N] = {ls};
static const dtg_real FORCE_OP[3 * NA] = {force_op};
/* Per gyro its model (0 = DTG, 1 = rate) and where its calibration starts. */
static const int GYRO_MODEL[N] = {models};
static const int GYRO_CAL_OFFSET[N] = {cal_off};
static const dtg_real GYRO_CAL[{ngc}] = {gyro_cal};
static const dtg_real ACCEL_CAL[3 * 8 + 1] = {accel_cal};
static const dtg_real OUT_SOS[7 * DTG_N_SECTIONS + 1] = {out_sos};
static const dtg_real IN_SOS[7 * DTG_N_IN_SECTIONS + 1] = {in_sos};
#if DTG_N_SMOOTH_SECTIONS > 0
static const dtg_real SMOOTH_SOS[7 * DTG_N_SMOOTH_SECTIONS + 1] = {smooth_sos};
#endif
static const int SIGNAL_CODE[DTG_N_SIGNALS] = {codes};
static const int N_EFFECTS[N] = {n_eff};
static const int EFFECT_OFFSET[N] = {e_off};
static const int EFFECT_KIND[DTG_N_EFFECTS + 1] = {kinds};
static const int EFFECT_INDEX[DTG_N_EFFECTS + 1] = {indices};
static const int PARAM_OFFSET[DTG_N_EFFECTS + 1] = {poff};
static const dtg_real PARAMS[{np}] = {params};
static const dtg_real BIAS[N] = {bias};
static const dtg_real COEFF[DTG_N_EFFECTS + 1] = {coeff};
/* Per channel: its centres, where its widths and weights start, the first
 * channel with the same centres and widths (whose kernel values it takes),
 * and where that set's centres start (in centres). */
static const int N_CENTRES[N] = {n_cen};
static const int CENTRE_SET[N] = {sets};
{raw_arrays}/* Per accelerometer: mean min, max, level min, max (g); scale (g),
 * tolerance, width, smoother gain; each channel's network at rest (deg/h). */
static const dtg_real FADE[{nf}] = {fade};
"#,
        cal = layout.calibrated as i32,
        triad = layout.triad as i32,
        dim = layout.dim,
        frames = arr(&layout.frames),
        ls = arr(&layout.ls),
        force_op = arr(&layout.force_op),
        models = iarr(&layout.models),
        cal_off = iarr(&layout.cal_offset),
        ngc = layout.gyro_cal.len().max(1),
        gyro_cal = arr(&layout.gyro_cal),
        accel_cal = arr(&layout.accel_cal),
        out_sos = arr(&layout.out_sos),
        in_sos = arr(&layout.in_sos),
        smooth_sos = arr(&layout.smooth_sos),
        codes = iarr(&layout.signal_codes),
        n_eff = iarr(&layout.n_effects),
        e_off = iarr(&e_offsets),
        kinds = iarr(&layout.kinds),
        indices = iarr(&layout.indices),
        poff = iarr(&layout.param_offset),
        // Room for a rate product's 2N reads past any effect's start, so
        // that the compiler's bounds analysis of the unused kinds holds.
        np = layout.params.len() + 2 * n,
        params = arr(&layout.params),
        bias = arr(&layout.bias),
        coeff = arr(&layout.coeff),
        n_cen = iarr(&layout.n_centres),
        sets = iarr(&layout.centre_set),
        raw_arrays = super::c_lanes::raw_only(
            layout,
            format!(
                "static const int CENTRE_OFFSET[N] = {};\nstatic const int SET_OFFSET[N] = {};\nstatic const dtg_real WIDTH[{nk}] = {};\nstatic const dtg_real WEIGHT[{nk}] = {};\nstatic const dtg_real CENTRES[{}] = {};\n",
                iarr(&c_offsets),
                iarr(&layout.centre_offset),
                arr(&layout.widths),
                arr(&layout.weights),
                layout.centres.len().max(1),
                arr(&layout.centres),
                nk = layout.widths.len().max(1),
            )
        ),
        nf = layout.fade.len().max(1),
        fade = arr(&layout.fade),
    )
}

const INIT_C: &str = r#"
void dtg_init(dtg_state *s) {
    int i, j;
    s->steps = 0;
    s->processed = 0;
    s->ring_pos = 0;
    for (i = 0; i < 6; i++) s->force[i] = R(0);
    for (i = 0; i < NA; i++) s->pending_accel[i] = R(0);
    for (i = 0; i < N; i++) s->pending_gyro[i] = R(0);
    for (i = 0; i < DTG_N_EXTRA + 1; i++) s->pending_extra[i] = R(0);
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

const GYROS_C: &str = r#"/* A rate gyro's inverse: the drift at zero rate removed, divided by the
 * scale factor (RateTerm::ALL order: bias, scale factor, g_x ... gg_yz, temp). */
static dtg_real rate_inverse(const dtg_real *c, dtg_real measured, const dtg_real *f, dtg_real cov[3][3]) {
    dtg_real r[12], s = R(0);
    int t;
    r[0] = R(1);
    r[1] = R(0);
    r[2] = f[0];
    r[3] = f[1];
    r[4] = f[2];
    r[5] = f[0] * f[0] + cov[0][0];
    r[6] = f[1] * f[1] + cov[1][1];
    r[7] = f[2] * f[2] + cov[2][2];
    r[8] = f[0] * f[1] + cov[0][1];
    r[9] = f[0] * f[2] + cov[0][2];
    r[10] = f[1] * f[2] + cov[1][2];
    r[11] = R(0);
    for (t = 0; t < 12; t++) s += c[t] * r[t];
    return (measured - s) / (R(1) + R(1e-6) * c[1]);
}

/* Gyro k's inverse DTG model at the least-squares rate. */
static dtg_real dtg_inverse(int k, dtg_real measured, const dtg_real *rate, const dtg_real *f, dtg_real cov[3][3]) {
    const dtg_real *ia = FRAMES + 9 * k, *oa = ia + 3, *sa = ia + 6;
    const dtg_real *c = GYRO_CAL + GYRO_CAL_OFFSET[k];
    dtg_real w[3], fr[3], cv[6], a0, b, wi, nl = c[18];
    int it;
    w[0] = dot3(ia, rate); w[1] = dot3(oa, rate); w[2] = dot3(sa, rate);
    fr[0] = dot3(ia, f); fr[1] = dot3(oa, f); fr[2] = dot3(sa, f);
    cv[0] = quad(ia, cov, ia); cv[1] = quad(oa, cov, oa); cv[2] = quad(sa, cov, sa);
    cv[3] = quad(ia, cov, oa); cv[4] = quad(ia, cov, sa); cv[5] = quad(oa, cov, sa);
    a0 = drift(c, R(0), w, fr, cv);
    b = R(1) + drift(c, R(1), w, fr, cv) - a0;
    wi = (measured - a0) / b;
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
 * raw outputs, then from the first pass's). */
static void compensate_gyros(const dtg_real *raw, const dtg_real *f, dtg_real cov[3][3], dtg_real *out) {
    dtg_real current[N], next[N], rate[3];
    int pass, i, j, k;
    (void)compensate_triad;
    (void)dtg_inverse;
    (void)rate_inverse;
    for (k = 0; k < N; k++) current[k] = raw[k];
    for (pass = 0; pass < 2; pass++) {
        for (i = 0; i < 3; i++) {
            dtg_real s = R(0);
            for (j = 0; j < N; j++) s += LS[N * i + j] * current[j];
            rate[i] = s;
        }
        for (k = 0; k < N; k++)
            next[k] = GYRO_MODEL[k] == 1 ? rate_inverse(GYRO_CAL + GYRO_CAL_OFFSET[k], raw[k], f, cov)
                                         : dtg_inverse(k, raw[k], rate, f, cov);
        for (k = 0; k < N; k++) current[k] = next[k];
    }
    for (k = 0; k < N; k++) out[k] = current[k];
}
#endif

"#;

/// A unit's `dtg_step` up to the pending sample's covariance
/// ([`super::c_process::step_end_c`]): the specific force from the
/// accelerometers, the triad calibrated on it.
const STEP_C: &str = r#"int dtg_step(dtg_state *s, const double gyro_deg_h[N], const double accel_g[NA],
             const double *extra, double rate_deg_h[N], double accel_out_g[NA]) {
    dtg_real raw_a[NA], f[3], cal[NA], cov[3][3];
    int i, j, k, out = 0;
    for (k = 0; k < NA; k++) raw_a[k] = (dtg_real)accel_g[k];
    /* The specific force (unit frame), the triad calibrated on it when the
     * accelerometers are the unit's axes. */
    for (i = 0; i < 3; i++) {
        dtg_real v = R(0);
        for (k = 0; k < NA; k++) v += FORCE_OP[NA * i + k] * raw_a[k];
        f[i] = v;
    }
#if DTG_CALIBRATED && DTG_ACCEL_TRIAD
    {
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
"#;

const MAIN_C: &str = r#"/* Reads a log of the unit (its time column, gyros, accelerometers and any
 * other columns, in its units) on standard input and writes the compensated
 * log of `dtg-vib compensate --unit` on standard output: the time, gyro and
 * accelerometer columns, then the others as given; rows from the first full
 * window on; compensated rates and calibrated accelerations in the log's
 * units. The log is one segment: split a log at its gaps before (as
 * `compensate` does, docs/formats.md "Record of any unit"). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "dtg_model.h"

#define MAX_COLS 256
#define MAX_LINE 65536

static int split(char *line, char **cells) {
    int n = 0;
    char *p = line;
    char *end = line + strlen(line);
    while (end > line && (end[-1] == '\n' || end[-1] == '\r')) *--end = '\0';
    cells[n++] = p;
    for (; *p; p++) {
        if (*p == ',') {
            *p = '\0';
            if (n == MAX_COLS) return -1;
            cells[n++] = p + 1;
        }
    }
    return n;
}

static int find(char **names, int ncols, const char *want) {
    int i;
    for (i = 0; i < ncols; i++)
        if (strcmp(names[i], want) == 0) return i;
    return -1;
}

static void print_row(const double *v, int t, const double *rate, const double *acc,
                      const int *other, int n_other) {
    int k;
    printf("%.17g", v[t]);
    for (k = 0; k < DTG_N_GYROS; k++) printf(",%.17g", rate[k] / DTG_RATE_TO_DEG_H);
    for (k = 0; k < DTG_N_ACCELS; k++) printf(",%.17g", acc[k] / DTG_FORCE_TO_G);
    for (k = 0; k < n_other; k++) printf(",%.17g", v[other[k]]);
    printf("\n");
}

int main(void) {
    static char line[MAX_LINE];
    static char header[MAX_LINE];
    static const char *gyro_names[] = DTG_GYRO_NAMES;
    static const char *accel_names[] = DTG_ACCEL_NAMES;
    static const char *extra_names[] = DTG_EXTRA_NAMES;
    char *cells[MAX_COLS];
    char *names[MAX_COLS];
    int time_col, gyro_col[DTG_N_GYROS], accel_col[DTG_N_ACCELS], extra_col[DTG_N_EXTRA + 1];
    int other[MAX_COLS], n_other = 0;
    int ncols, i, k, row = 1;
    dtg_state s;
    if (!fgets(header, sizeof header, stdin)) {
        fprintf(stderr, "dtg: empty input: expected a log CSV header\n");
        return 2;
    }
    ncols = split(header, names);
    if (ncols < 0) {
        fprintf(stderr, "dtg: more than %d columns\n", MAX_COLS);
        return 2;
    }
    time_col = find(names, ncols, DTG_TIME_NAME);
    if (time_col < 0) {
        fprintf(stderr, "dtg: line 1: no time column '%s'\n", DTG_TIME_NAME);
        return 2;
    }
    for (k = 0; k < DTG_N_GYROS; k++) {
        gyro_col[k] = find(names, ncols, gyro_names[k]);
        if (gyro_col[k] < 0) {
            fprintf(stderr, "dtg: line 1: no gyro column '%s'\n", gyro_names[k]);
            return 2;
        }
    }
    for (k = 0; k < DTG_N_ACCELS; k++) {
        accel_col[k] = find(names, ncols, accel_names[k]);
        if (accel_col[k] < 0) {
            fprintf(stderr, "dtg: line 1: no accelerometer column '%s'\n", accel_names[k]);
            return 2;
        }
    }
    for (k = 0; k < DTG_N_EXTRA; k++) {
        extra_col[k] = find(names, ncols, extra_names[k]);
        if (extra_col[k] < 0) {
            fprintf(stderr, "dtg: line 1: no column '%s' (the model reads it)\n", extra_names[k]);
            return 2;
        }
    }
    for (i = 0; i < ncols; i++) {
        int own = i == time_col;
        for (k = 0; k < DTG_N_GYROS; k++) own |= gyro_col[k] == i;
        for (k = 0; k < DTG_N_ACCELS; k++) own |= accel_col[k] == i;
        if (!own) other[n_other++] = i;
    }
    printf("%s", DTG_TIME_NAME);
    for (k = 0; k < DTG_N_GYROS; k++) printf(",%s", gyro_names[k]);
    for (k = 0; k < DTG_N_ACCELS; k++) printf(",%s", accel_names[k]);
    for (i = 0; i < n_other; i++) printf(",%s", names[other[i]]);
    printf("\n");
    dtg_init(&s);
    /* Outputs lag one row: pv holds the previous row, whose output comes next. */
    static double v[MAX_COLS], pv[MAX_COLS];
    double rate[DTG_N_GYROS], acc_out[DTG_N_ACCELS];
    while (fgets(line, sizeof line, stdin)) {
        double gyro[DTG_N_GYROS], acc[DTG_N_ACCELS], extra[DTG_N_EXTRA + 1];
        row++;
        if (split(line, cells) != ncols) {
            fprintf(stderr, "dtg: line %d: expected %d cells\n", row, ncols);
            return 2;
        }
        for (i = 0; i < ncols; i++) {
            char *end;
            v[i] = strtod(cells[i], &end);
            if (end == cells[i] || *end != '\0') {
                fprintf(stderr, "dtg: line %d, column %d: '%s' is not a number\n", row, i + 1, cells[i]);
                return 2;
            }
        }
        for (k = 0; k < DTG_N_GYROS; k++) gyro[k] = v[gyro_col[k]] * DTG_RATE_TO_DEG_H;
        for (k = 0; k < DTG_N_ACCELS; k++) acc[k] = v[accel_col[k]] * DTG_FORCE_TO_G;
        for (k = 0; k < DTG_N_EXTRA; k++) extra[k] = v[extra_col[k]];
        if (dtg_step(&s, gyro, acc, extra, rate, acc_out))
            print_row(pv, time_col, rate, acc_out, other, n_other);
        for (i = 0; i < ncols; i++) pv[i] = v[i];
    }
    if (dtg_flush(&s, rate, acc_out)) print_row(pv, time_col, rate, acc_out, other, n_other);
    return 0;
}
"#;
