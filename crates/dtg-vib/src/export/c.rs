//! C99 sources of a causal model: `dtg_model.h` (the state struct, `init`,
//! `step`), `dtg_model.c` (the tables as `static const` arrays and the same
//! step as the `dtg-onboard` evaluator) and `main.c` (record CSV on standard
//! input to the compensated CSV of `dtg-vib compensate` on standard output).
//! Only the C99 library (`fabs`, `sqrt`, `expf` in f32, `memcpy`; the f64
//! exponential is written out, [`super::c_lanes`]); no dynamic memory, no
//! globals but the tables.

use super::c_process::{Shape, fade_weight_c, process_c, step_end_c};
use super::layout::Layout;
use crate::model::CompensationModel;
use crate::onboard::{ExportError, Tables, tables};
use std::fmt::Write;

/// Arithmetic and table precision of the exported C.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// `double` tables and arithmetic: equal to the desktop tool.
    F64,
    /// `float` tables and arithmetic: half the table size; the difference
    /// from the desktop tool is measured in docs/dtg-vib.md.
    F32,
}

impl std::str::FromStr for Precision {
    type Err = crate::DtgVibError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "f64" => Ok(Precision::F64),
            "f32" => Ok(Precision::F32),
            other => Err(sysid::SysidError::InvalidOption {
                name: "precision",
                value: other.to_string(),
                reason: "use f64 or f32",
            }
            .into()),
        }
    }
}

/// The three C files.
#[derive(Debug, Clone, PartialEq)]
pub struct CSources {
    /// `dtg_model.h`.
    pub header: String,
    /// `dtg_model.c`.
    pub source: String,
    /// `main.c`.
    pub main: String,
}

impl CSources {
    /// File names and contents, in writing order.
    pub fn files(&self) -> [(&'static str, &str); 3] {
        [
            ("dtg_model.h", &self.header),
            ("dtg_model.c", &self.source),
            ("main.c", &self.main),
        ]
    }
}

/// A C array initialiser; a single 0 for an empty list (C99 has no empty arrays).
pub(super) fn arr(v: &[f64]) -> String {
    if v.is_empty() {
        return "{0}".into();
    }
    let mut s = String::from("{");
    for (i, x) in v.iter().enumerate() {
        if i % 4 == 0 {
            s.push_str("\n    ");
        }
        // Shortest text that reads back to the same double.
        let _ = write!(s, "{x:e}, ");
    }
    s.push_str("\n}");
    s
}

pub(super) fn iarr(v: &[usize]) -> String {
    if v.is_empty() {
        return "{0}".into();
    }
    let items: Vec<String> = v.iter().map(|x| x.to_string()).collect();
    format!("{{{}}}", items.join(", "))
}

pub(super) fn words(b: &[u8], from: usize, n: usize) -> Vec<usize> {
    (from..from + n)
        .map(|i| u32::from_le_bytes([b[4 * i], b[4 * i + 1], b[4 * i + 2], b[4 * i + 3]]) as usize)
        .collect()
}

pub(super) fn floats(b: &[u8], from_byte: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let at = from_byte + 8 * i;
            f64::from_le_bytes(b[at..at + 8].try_into().expect("8 bytes"))
        })
        .collect()
}

/// The C sources of a causal model, generated from its onboard tables so
/// that C and Rust read the same numbers.
pub fn c_sources(model: &CompensationModel, precision: Precision) -> Result<CSources, ExportError> {
    c_sources_from_tables(&tables(model)?, precision)
}

/// The C sources of any onboard tables (those of [`tables`], or tables built
/// by hand, as the step bench does).
pub fn c_sources_from_tables(t: &Tables, precision: Precision) -> Result<CSources, ExportError> {
    let layout = Layout::read(&t.bytes)?;
    let mut source = tables_c(&layout);
    // Channels that share a centre set compute each kernel value once; a
    // model without (every model fitted before shared centres) keeps the
    // C it always had, byte for byte.
    let shared = layout.centre_set.iter().enumerate().any(|(c, &l)| l != c);
    // The statistics input's kernels run in lanes over centre sets
    // (super::c_lanes), a set of one channel when none is shared.
    let sets = shared || layout.input == dtg_onboard::input::STATISTICS as usize;
    if sets {
        source.push_str(&super::c_shared::arrays(&layout));
        source.push_str(&super::c_lanes::arrays(&layout));
    }
    source.push_str(&with_maths(
        &step_c(precision, Shape::paper(sets)),
        precision,
    ));
    Ok(CSources {
        header: header_h(&layout, &t.extra, real_type(precision)),
        source,
        main: MAIN_C.to_string(),
    })
}

/// The C type of `precision`.
pub(super) fn real_type(precision: Precision) -> &'static str {
    match precision {
        Precision::F64 => "double",
        Precision::F32 => "float",
    }
}

/// Step code with its `FABS(`, `SQRT(` and `DTG_EPSILON` the maths of
/// `precision` (the kernels' `EXP_NEG` is [`super::c_lanes::kernels`]').
pub(super) fn with_maths(step: &str, precision: Precision) -> String {
    let (fabs, sqrt, eps) = match precision {
        Precision::F64 => ("fabs", "sqrt", "DBL_EPSILON"),
        Precision::F32 => ("fabsf", "sqrtf", "FLT_EPSILON"),
    };
    step.replace("FABS(", &format!("{fabs}("))
        .replace("SQRT(", &format!("{sqrt}("))
        .replace("DTG_EPSILON", eps)
}

/// `dtg_model.h`: the sizes, the state and the three calls.
fn header_h(layout: &Layout, extra: &[String], real: &str) -> String {
    let Layout {
        dt,
        l,
        n_signals,
        n_sections,
        n_in_sections,
        fade,
        input,
        n_smooth,
        ..
    } = layout;
    let total_effects = layout.kinds.len();
    let names: Vec<String> = extra.iter().map(|n| format!("\"{n}\"")).collect();
    format!(
        r#"/* DTG vibration-error compensator, exported by `dtg-vib export --lang c`.
 * C99, needs only <math.h>. Layout: docs/formats.md ("Onboard tables").
 * One call of dtg_step per output period ({dt} s) with sample n: raw gyro
 * outputs X, X1, Y, Y1, Z, Z1 (deg/h), raw accelerations x, y, z (g) and the
 * extra columns below, in this order; out come the compensated rates (deg/h)
 * and calibrated accelerations (g) of sample n - 1 (one period of latency:
 * the g² terms' within-interval covariance of a sample needs its two
 * neighbours). The first {first} calls return 0 (no output yet; the windows
 * fill); every later call returns 1. At the end of a record, dtg_flush gives
 * the last sample's output. */
#ifndef DTG_MODEL_H
#define DTG_MODEL_H

typedef {real} dtg_real;

#define DTG_DT_S {dt:e}
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
/* Extra columns, in the order dtg_step takes them. */
#define DTG_EXTRA_NAMES {{{extra_names}}}

/* All the state: its size is fixed at compile time. */
typedef struct {{
    long steps;     /* samples received */
    long processed; /* samples compensated */
    int ring_pos;
    dtg_real prev_accel[6]; /* calibrated accelerations of the pending sample and the one before, g */
    dtg_real pending_gyro[6]; /* the pending sample's raw outputs, deg/h */
    dtg_real pending_extra[DTG_N_EXTRA + 1];
    dtg_real out_z[2 * DTG_N_SECTIONS * DTG_N_EFFECTS + 1];
    dtg_real in_z[2 * DTG_N_IN_SECTIONS * DTG_N_SIGNALS + 1];
    dtg_real ring[DTG_N_SIGNALS][2 * DTG_WINDOW_LEN];
    dtg_real fade_ring[3][2 * DTG_WINDOW_LEN]; /* calibrated ax, ay, az: the per-axis range */
    dtg_real fade_h[6]; /* held network part per channel, deg/h */
    dtg_real fade_w;    /* smoothed weight of the network part */
    dtg_real sums[2 * DTG_N_SIGNALS];     /* running sum and sum of squares per signal */
    dtg_real feat[3 * DTG_N_SIGNALS];     /* the statistics inputs */
    dtg_real smooth_z[12 * DTG_N_SMOOTH_SECTIONS + 1];
}} dtg_state;

void dtg_init(dtg_state *s);
int dtg_step(dtg_state *s, const double gyro_deg_h[6], const double accel_g[3],
             const double *extra, double rate_deg_h[6], double accel_out_g[3]);
/* The last sample's output (returns 1) or nothing (0); leaves s at rest. */
int dtg_flush(dtg_state *s, double rate_deg_h[6], double accel_out_g[3]);

#endif
"#,
        first = l,
        fades = i32::from(!fade.is_empty()),
        n_extra = extra.len(),
        extra_names = if names.is_empty() {
            "\"\"".to_string()
        } else {
            names.join(", ")
        },
    )
}

/// The tables as C arrays, before the step code.
fn tables_c(layout: &Layout) -> String {
    let Layout {
        calibrated,
        dim,
        frames,
        ls,
        gyro_cal,
        accel_cal,
        out_sos,
        in_sos,
        smooth_sos,
        signal_codes,
        n_effects,
        kinds,
        indices,
        param_offset,
        params,
        bias,
        coeff,
        n_centres,
        widths,
        weights,
        centres,
        fade,
        ..
    } = layout;
    let c_offsets: Vec<usize> = (0..6).map(|c| n_centres[..c].iter().sum()).collect();
    let e_offsets: Vec<usize> = (0..6).map(|c| n_effects[..c].iter().sum()).collect();
    format!(
        r#"/* Generated by `dtg-vib export --lang c`; the same step as the dtg-onboard
 * Rust evaluator (crates/dtg-onboard/src/lib.rs), which documents each stage. */
#include <float.h>
#include <math.h>
#include "dtg_model.h"

#define R(x) ((dtg_real)(x))
#define DTG_CALIBRATED {cal}
#define DTG_DIM {dim}

static const dtg_real FRAMES[54] = {frames};
static const dtg_real LS[18] = {ls};
static const dtg_real GYRO_CAL[6 * 19 + 1] = {gyro_cal};
static const dtg_real ACCEL_CAL[3 * 8 + 1] = {accel_cal};
static const dtg_real OUT_SOS[7 * DTG_N_SECTIONS + 1] = {out_sos};
static const dtg_real IN_SOS[7 * DTG_N_IN_SECTIONS + 1] = {in_sos};
#if DTG_N_SMOOTH_SECTIONS > 0
static const dtg_real SMOOTH_SOS[7 * DTG_N_SMOOTH_SECTIONS + 1] = {smooth_sos};
#endif
static const int SIGNAL_CODE[DTG_N_SIGNALS] = {codes};
static const int N_EFFECTS[6] = {n_eff};
static const int EFFECT_OFFSET[6] = {e_off};
static const int EFFECT_KIND[DTG_N_EFFECTS + 1] = {kinds};
static const int EFFECT_INDEX[DTG_N_EFFECTS + 1] = {indices};
static const int PARAM_OFFSET[DTG_N_EFFECTS + 1] = {poff};
static const dtg_real PARAMS[{np}] = {params};
static const dtg_real BIAS[6] = {bias};
static const dtg_real COEFF[DTG_N_EFFECTS + 1] = {coeff};
static const int N_CENTRES[6] = {n_cen};
{raw_arrays}/* Per axis: mean min, max, level min, max (g); scale (g), tolerance, width,
 * smoother gain; each channel's network at rest (deg/h). */
static const dtg_real FADE[{nf}] = {fade};
"#,
        cal = *calibrated as i32,
        frames = arr(frames),
        ls = arr(ls),
        gyro_cal = arr(gyro_cal),
        accel_cal = arr(accel_cal),
        out_sos = arr(out_sos),
        in_sos = arr(in_sos),
        smooth_sos = arr(smooth_sos),
        codes = iarr(signal_codes),
        n_eff = iarr(n_effects),
        e_off = iarr(&e_offsets),
        kinds = iarr(kinds),
        indices = iarr(indices),
        poff = iarr(param_offset),
        np = params.len().max(1),
        params = arr(params),
        bias = arr(bias),
        coeff = arr(coeff),
        n_cen = iarr(n_centres),
        raw_arrays = super::c_lanes::raw_only(
            layout,
            format!(
                "static const int CENTRE_OFFSET[6] = {};\nstatic const dtg_real WIDTH[{nk}] = {};\nstatic const dtg_real WEIGHT[{nk}] = {};\nstatic const dtg_real CENTRES[{}] = {};\n",
                iarr(&c_offsets),
                arr(widths),
                arr(weights),
                centres.len().max(1),
                arr(centres),
                nk = widths.len().max(1),
            )
        ),
        nf = fade.len().max(1),
        fade = arr(fade),
    )
}

/// The step code of the paper's C, in pieces that the C of any unit
/// ([`super::c_unit`]) shares where it is the same text.
fn step_c(precision: Precision, shape: Shape) -> String {
    [
        STEP_INIT_C,
        EXCESS_C,
        &fade_weight_c(shape),
        HELPERS_C,
        CAL_HELPERS_C,
        GYROS_C,
        SQ_DIST_C,
        &super::c_lanes::kernels(precision),
        &process_c(shape),
        STEP_C,
        &step_end_c(shape),
    ]
    .concat()
}

/// `dtg_init` of the paper's state.
const STEP_INIT_C: &str = r#"
void dtg_init(dtg_state *s) {
    int i, j;
    s->steps = 0;
    s->processed = 0;
    s->ring_pos = 0;
    for (i = 0; i < 6; i++) s->prev_accel[i] = R(0);
    for (i = 0; i < 6; i++) s->pending_gyro[i] = R(0);
    for (i = 0; i < DTG_N_EXTRA + 1; i++) s->pending_extra[i] = R(0);
    for (i = 0; i < 2 * DTG_N_SECTIONS * DTG_N_EFFECTS + 1; i++) s->out_z[i] = R(0);
    for (i = 0; i < 2 * DTG_N_IN_SECTIONS * DTG_N_SIGNALS + 1; i++) s->in_z[i] = R(0);
    for (i = 0; i < DTG_N_SIGNALS; i++)
        for (j = 0; j < 2 * DTG_WINDOW_LEN; j++) s->ring[i][j] = R(0);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 2 * DTG_WINDOW_LEN; j++) s->fade_ring[i][j] = R(0);
    for (i = 0; i < 6; i++) s->fade_h[i] = R(0);
    s->fade_w = R(0);
    for (i = 0; i < 2 * DTG_N_SIGNALS; i++) s->sums[i] = R(0);
    for (i = 0; i < 3 * DTG_N_SIGNALS; i++) s->feat[i] = R(0);
    for (i = 0; i < 12 * DTG_N_SMOOTH_SECTIONS + 1; i++) s->smooth_z[i] = R(0);
}

"#;

/// The fade's excess beyond an interval (opens `#if DTG_FADE`).
pub(super) const EXCESS_C: &str = r#"#if DTG_FADE
static dtg_real excess(dtg_real v, dtg_real lo, dtg_real hi) {
    dtg_real e = lo - v > v - hi ? lo - v : v - hi;
    return e > R(0) ? e : R(0);
}

"#;

/// The cascade of sections, `dot3`, `quad`.
pub(super) const HELPERS_C: &str = r#"/* One value through a cascade of second-order sections (transposed direct
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

static inline dtg_real quad(const dtg_real *p, dtg_real c[3][3], const dtg_real *q) {
    dtg_real t0 = p[0] * c[0][0] + p[1] * c[1][0] + p[2] * c[2][0];
    dtg_real t1 = p[0] * c[0][1] + p[1] * c[1][1] + p[2] * c[2][1];
    dtg_real t2 = p[0] * c[0][2] + p[1] * c[1][2] + p[2] * c[2][2];
    return t0 * q[0] + t1 * q[1] + t2 * q[2];
}

"#;

/// The triad's inverse and a DTG's drift terms (opens `#if DTG_CALIBRATED`).
pub(super) const CAL_HELPERS_C: &str = r#"#if DTG_CALIBRATED
/* Newton stops once its next step would be within 4 ulps of the estimate
 * (the residual checked before the division), or after four steps. */
#define SETTLED (R(4) * DTG_EPSILON)

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

/* A DTG's drift terms (DtgTerm order) at the rate wi about its input axis:
 * w the rates about its I, O, S axes, fr the specific force along them, cv
 * their covariances; term t at r[t * stride]. */
static inline void drift_terms(dtg_real wi, const dtg_real *w, const dtg_real *fr, const dtg_real *cv, dtg_real *r, int stride) {
    const dtg_real per_s = R(1) / R(3600);
    r[0 * stride] = R(1);
    r[1 * stride] = R(1e-6) * wi;
    r[2 * stride] = R(1e-6) * w[1];
    r[3 * stride] = R(1e-6) * w[2];
    r[4 * stride] = fr[0];
    r[5 * stride] = fr[1];
    r[6 * stride] = fr[2];
    r[7 * stride] = fr[0] * fr[0] + cv[0];
    r[8 * stride] = fr[1] * fr[1] + cv[1];
    r[9 * stride] = fr[2] * fr[2] + cv[2];
    r[10 * stride] = fr[0] * fr[1] + cv[3];
    r[11 * stride] = fr[0] * fr[2] + cv[4];
    r[12 * stride] = fr[1] * fr[2] + cv[5];
    r[13 * stride] = (wi * per_s) * (w[1] * per_s);
    r[14 * stride] = (wi * per_s) * (w[2] * per_s);
    r[15 * stride] = (w[1] * per_s) * (w[2] * per_s);
    r[16 * stride] = R(0);
    r[17 * stride] = R(0);
}

"#;

/// A DTG's drift at one rate: its terms (from [`CAL_HELPERS_C`]) times its
/// calibration, summed in term order (the C of a unit; the paper's sums
/// six gyros side by side in [`GYROS_C`]).
pub(super) const DRIFT_C: &str = r#"static inline dtg_real drift(const dtg_real *c, dtg_real wi, const dtg_real *w, const dtg_real *fr, const dtg_real *cv) {
    dtg_real r[18];
    dtg_real s = R(0);
    int t;
    drift_terms(wi, w, fr, cv, r, 1);
    for (t = 0; t < 18; t++) s += r[t] * c[t];
    return s;
}

"#;

/// The paper's six DTGs' inverse (closes `#if DTG_CALIBRATED`): the twelve
/// drift sums of a pass (a0 and the drift at unit rate for each gyro) term
/// by term with the gyros side by side, a loop the compiler vectorises,
/// instead of one gyro's two sums after another's (each sum is a chain of
/// 18 dependent adds: a tenth of the step). Each sum adds the same terms in
/// the same order as [`DRIFT_C`], so the bits are the same.
const GYROS_C: &str = r#"/* The six DTGs' inverse, two passes (the least-squares rate from the raw
 * outputs, then from the first pass's). A gyro's drift at wi = 0 and at
 * wi = 1 (a0, and b = 1 + drift(1) - a0) are sums of 18 terms; the twelve
 * sums run side by side, term by term with the gyros in lanes, each added
 * in the order drift() adds it; then Newton on each gyro. */
static void compensate_gyros(const dtg_real *raw, const dtg_real *f, dtg_real cov[3][3], dtg_real *out) {
    dtg_real current[6], next[6], rate[3], cal[18 * 6], r0[18 * 6], r1[18 * 6], s0[6], s1[6];
    int pass, i, j, k, it, t;
    for (k = 0; k < 6; k++) current[k] = raw[k];
    for (k = 0; k < 6; k++)
        for (t = 0; t < 18; t++) cal[6 * t + k] = GYRO_CAL[19 * k + t];
    for (pass = 0; pass < 2; pass++) {
        for (i = 0; i < 3; i++) {
            dtg_real s = R(0);
            for (j = 0; j < 6; j++) s += LS[6 * i + j] * current[j];
            rate[i] = s;
        }
        for (k = 0; k < 6; k++) {
            const dtg_real *ia = FRAMES + 9 * k, *oa = ia + 3, *sa = ia + 6;
            dtg_real w[3], fr[3], cv[6];
            w[0] = dot3(ia, rate); w[1] = dot3(oa, rate); w[2] = dot3(sa, rate);
            fr[0] = dot3(ia, f); fr[1] = dot3(oa, f); fr[2] = dot3(sa, f);
            cv[0] = quad(ia, cov, ia); cv[1] = quad(oa, cov, oa); cv[2] = quad(sa, cov, sa);
            cv[3] = quad(ia, cov, oa); cv[4] = quad(ia, cov, sa); cv[5] = quad(oa, cov, sa);
            drift_terms(R(0), w, fr, cv, r0 + k, 6);
            drift_terms(R(1), w, fr, cv, r1 + k, 6);
        }
        for (k = 0; k < 6; k++) s0[k] = s1[k] = R(0);
        for (t = 0; t < 18; t++)
            for (k = 0; k < 6; k++) {
                s0[k] += r0[6 * t + k] * cal[6 * t + k];
                s1[k] += r1[6 * t + k] * cal[6 * t + k];
            }
        for (k = 0; k < 6; k++) {
            dtg_real a0 = s0[k], b = R(1) + s1[k] - a0, wi = (raw[k] - a0) / b, nl = GYRO_CAL[19 * k + 18];
            for (it = 0; it < 4; it++) {
                dtg_real per_s = FABS(wi) * (R(1) / R(3600));
                dtg_real fx = a0 + b * wi + R(1e-6) * nl * per_s * wi - raw[k];
                dtg_real df = b + R(2e-6) * nl * per_s;
                if (FABS(fx) <= SETTLED * FABS(df * wi)) break;
                wi -= fx / df;
            }
            next[k] = wi;
        }
        for (k = 0; k < 6; k++) current[k] = next[k];
    }
    for (k = 0; k < 6; k++) out[k] = current[k];
}
#endif

"#;

/// The squared distance of four partial sums (the raw window's).
pub(super) const SQ_DIST_C: &str = r#"#if !DTG_INPUT_STATS
/* ||x - c||^2 over n numbers; four partial sums (the Rust evaluator sums
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
#endif

"#;

/// The paper's `dtg_step` up to the pending sample's covariance
/// ([`super::c_process::step_end_c`]): the triad calibrated.
const STEP_C: &str = r#"int dtg_step(dtg_state *s, const double gyro_deg_h[6], const double accel_g[3],
             const double *extra, double rate_deg_h[6], double accel_out_g[3]) {
    dtg_real raw_a[3], a[3], cov[3][3];
    int i, j, k, out = 0;
    for (k = 0; k < 3; k++) raw_a[k] = (dtg_real)accel_g[k];
#if DTG_CALIBRATED
    compensate_triad(raw_a, a);
#else
    for (k = 0; k < 3; k++) a[k] = raw_a[k];
#endif
"#;

const MAIN_C: &str = r#"/* Reads a record CSV (t,X,X1,Y,Y1,Z,Z1,ax,ay,az[,extra...]) on standard
 * input and writes the compensated CSV of `dtg-vib compensate` on standard
 * output: the same columns, rows from the first full window on, compensated
 * rates and calibrated accelerations, other columns as given. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "dtg_model.h"

#define MAX_COLS 256
#define MAX_LINE 65536

static const char *BASE[10] = {"t", "X", "X1", "Y", "Y1", "Z", "Z1", "ax", "ay", "az"};

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

static void print_row(const double *v, int t, const double *rate, const double *acc,
                      const int *other, int n_other) {
    int k;
    printf("%.17g", v[t]);
    for (k = 0; k < 6; k++) printf(",%.17g", rate[k]);
    for (k = 0; k < 3; k++) printf(",%.17g", acc[k]);
    for (k = 0; k < n_other; k++) printf(",%.17g", v[other[k]]);
    printf("\n");
}

int main(void) {
    static char line[MAX_LINE];
    static char header[MAX_LINE];
    char *cells[MAX_COLS];
    char *names[MAX_COLS];
    int base[10], extra_col[DTG_N_EXTRA + 1], other[MAX_COLS], n_other = 0;
    static const char *extra_names[] = DTG_EXTRA_NAMES;
    int ncols, i, k, row = 1;
    dtg_state s;
    if (!fgets(header, sizeof header, stdin)) {
        fprintf(stderr, "dtg: empty input: expected a record CSV header\n");
        return 2;
    }
    ncols = split(header, names);
    if (ncols < 0) {
        fprintf(stderr, "dtg: more than %d columns\n", MAX_COLS);
        return 2;
    }
    for (k = 0; k < 10; k++) {
        base[k] = -1;
        for (i = 0; i < ncols; i++)
            if (strcmp(names[i], BASE[k]) == 0) base[k] = i;
        if (base[k] < 0) {
            fprintf(stderr, "dtg: line 1: no column '%s'\n", BASE[k]);
            return 2;
        }
    }
    for (k = 0; k < DTG_N_EXTRA; k++) {
        extra_col[k] = -1;
        for (i = 0; i < ncols; i++)
            if (strcmp(names[i], extra_names[k]) == 0) extra_col[k] = i;
        if (extra_col[k] < 0) {
            fprintf(stderr, "dtg: line 1: no column '%s' (the model reads it)\n", extra_names[k]);
            return 2;
        }
    }
    for (i = 0; i < ncols; i++) {
        int is_base = 0;
        for (k = 0; k < 10; k++) is_base |= base[k] == i;
        if (!is_base) other[n_other++] = i;
    }
    printf("t,X,X1,Y,Y1,Z,Z1,ax,ay,az");
    for (i = 0; i < n_other; i++) printf(",%s", names[other[i]]);
    printf("\n");
    dtg_init(&s);
    /* Outputs lag one row: pv holds the previous row, whose output comes next. */
    static double v[MAX_COLS], pv[MAX_COLS];
    double rate[6], acc_out[3];
    while (fgets(line, sizeof line, stdin)) {
        double gyro[6], acc[3], extra[DTG_N_EXTRA + 1];
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
        for (k = 0; k < 6; k++) gyro[k] = v[base[1 + k]];
        for (k = 0; k < 3; k++) acc[k] = v[base[7 + k]];
        for (k = 0; k < DTG_N_EXTRA; k++) extra[k] = v[extra_col[k]];
        if (dtg_step(&s, gyro, acc, extra, rate, acc_out))
            print_row(pv, base[0], rate, acc_out, other, n_other);
        for (i = 0; i < ncols; i++) pv[i] = v[i];
    }
    if (dtg_flush(&s, rate, acc_out)) print_row(pv, base[0], rate, acc_out, other, n_other);
    return 0;
}
"#;
