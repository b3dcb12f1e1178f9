//! C99 sources of a causal model of any unit, the paper's included:
//! `dtg_model.h` (the sizes, the log's columns and units, the state struct,
//! `init`, `step`, `flush`), `dtg_model.c` (the tables as `static const`
//! arrays, [`super::c_tables`], and the same step as the `dtg-onboard`
//! evaluator, [`super::c_step`]) and `main.c` (the log on standard input to
//! the compensated log of `dtg-vib compensate` on standard output,
//! [`super::c_main`]). Only the C99 library (`fabs`, `sqrt`, `expf` in f32,
//! `memcpy`; the f64 exponential is written out); no dynamic memory, no
//! globals but the tables. On x86-64 with glibc, gcc and clang build the
//! kernels twice (`target_clones`: AVX2 and the baseline, chosen at load
//! time, the same bits; [`super::c_kernels`]); `-DDTG_NO_CLONES` or any
//! other target builds the one portable function.

use super::precision::Precision;
use crate::onboard::{ExportError, Tables, tables};
use crate::unit_sensor::UnitModel;
use dtg_onboard::Model;
use nav_sensors::unit::Unit;

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

/// The C sources of a causal model, generated from its onboard tables so
/// that C and Rust read the same numbers.
pub fn c_sources(model: &UnitModel, precision: Precision) -> Result<CSources, ExportError> {
    c_sources_from_tables(&tables(model)?, model.unit(), precision)
}

/// The C sources of onboard tables of any layout the evaluator reads (a
/// model's, or tables built by hand, as the step bench does), `unit`
/// naming the log's columns (its gyros and accelerometers must be the
/// tables' channels and accelerometers).
pub fn c_sources_from_tables(
    t: &Tables,
    unit: &Unit,
    precision: Precision,
) -> Result<CSources, ExportError> {
    let m = Model::parse(&t.bytes).map_err(|e| ExportError::Tables(e.to_string()))?;
    if (unit.gyros().len(), unit.accels().len()) != (m.n_channels(), m.n_accels()) {
        return Err(ExportError::Tables(format!(
            "the tables have {} gyros and {} accelerometers, the unit '{}' {} and {}",
            m.n_channels(),
            m.n_accels(),
            unit.name(),
            unit.gyros().len(),
            unit.accels().len()
        )));
    }
    let source = [
        super::c_tables::arrays(&m),
        with_maths(&super::c_step::step_c(precision), precision),
    ]
    .concat();
    Ok(CSources {
        header: header_h(&m, &t.extra, unit, precision),
        source,
        main: super::c_main::MAIN_C.to_string(),
    })
}

/// Step code with its `FABS(`, `SQRT(` and `DTG_EPSILON` the maths of
/// `precision`.
fn with_maths(step: &str, precision: Precision) -> String {
    let (fabs, sqrt, eps) = match precision {
        Precision::F64 => ("fabs", "sqrt", "DBL_EPSILON"),
        Precision::F32 => ("fabsf", "sqrtf", "FLT_EPSILON"),
    };
    step.replace("FABS(", &format!("{fabs}("))
        .replace("SQRT(", &format!("{sqrt}("))
        .replace("DTG_EPSILON", eps)
}

/// A list of C string literals; `""` for an empty one.
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
fn header_h(m: &Model, extra: &[String], unit: &Unit, precision: Precision) -> String {
    let [n_sections, n_in_sections, n_smooth] = m.n_sections();
    let (rate_to_deg_h, force_to_g) = m.log_units();
    let extra: Vec<&str> = extra.iter().map(String::as_str).collect();
    let n_effects: usize = (0..m.n_channels()).map(|c| m.n_effects(c)).sum();
    format!(
        r#"/* Vibration-error compensator of the unit '{name}', exported by
 * `dtg-vib export --lang c`. C99, needs only <math.h>. Layout:
 * docs/formats.md ("Onboard tables"). One call of dtg_step per output
 * period ({dt:e} s) with sample n: the raw gyro outputs (deg/h) and
 * accelerations (g) in the unit's order (DTG_GYRO_NAMES, DTG_ACCEL_NAMES)
 * and the extra columns below; out come the compensated rates (deg/h) and
 * calibrated accelerations (g) of sample n - 3 (DTG_LOOKAHEAD periods of
 * latency, 60 ms at 50 Hz: the g² terms' within-interval covariance of a
 * sample needs the three samples on each side). The first {l} + 2 calls
 * return 0 (the windows fill); every later call returns 1. At the end of a
 * record, dtg_flush gives the last three samples' outputs. The log's
 * columns are in the units below (main.c converts). */
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
#define DTG_N_EFFECTS {n_effects}
/* Samples after the one compensated that its covariance reads. */
#define DTG_LOOKAHEAD 3
/* 1: outside the training range the network part holds (docs/formats.md). */
#define DTG_FADE {fades}
/* 1: the fade also judges each window's vibration shape (its spectrum). */
#define DTG_FADE_SHAPE {fade_shape}
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
    dtg_real force[6 * DTG_LOOKAHEAD]; /* calibrated specific forces of the 6 samples before the newest, oldest first, g */
    /* The pending samples, oldest first: calibrated accelerations (g), raw
     * outputs (deg/h), extra columns. */
    dtg_real pending_accel[DTG_LOOKAHEAD][DTG_N_ACCELS];
    dtg_real pending_gyro[DTG_LOOKAHEAD][DTG_N_GYROS];
    dtg_real pending_extra[DTG_LOOKAHEAD][DTG_N_EXTRA + 1];
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
/* The last DTG_LOOKAHEAD samples' outputs, row k for sample N - 3 + k of N
 * received; returns a mask whose bit k says row k holds one (a record
 * shorter than 3 samples, or windows not full, leave rows out); leaves s
 * at rest. */
int dtg_flush(dtg_state *s, double rate_deg_h[DTG_LOOKAHEAD][DTG_N_GYROS],
              double accel_out_g[DTG_LOOKAHEAD][DTG_N_ACCELS]);

#endif
"#,
        name = unit.name().replace("*/", "* /"),
        real = match precision {
            Precision::F64 => "double",
            Precision::F32 => "float",
        },
        dt = m.dt_s(),
        n = m.n_channels(),
        n_a = m.n_accels(),
        l = m.window_len(),
        n_signals = m.n_signals(),
        n_extra = extra.len(),
        fades = i32::from(m.fades()),
        fade_shape = i32::from(m.fades_by_shape()),
        input = m.input_kind(),
        time = unit.columns().time,
        gyros = names(&unit.gyro_names()),
        accels = names(&unit.accel_names()),
        extra_names = names(&extra),
    )
}
