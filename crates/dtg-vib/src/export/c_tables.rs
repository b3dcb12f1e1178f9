//! The tables as the exported C's `static const` arrays, read back through
//! the evaluator's own parser (`dtg_onboard::Model`), so that C and Rust
//! read the same numbers: the specific-force operator, the calibration
//! and each centre set's kernels in lanes (`Model::calibration_lanes`,
//! `Model::kernel_lanes`, `Model::weight_lanes`), the filters, the effects,
//! the fade block. Only what the step uses is written (C compilers warn of
//! an unused array).

use dtg_onboard::{Model, Part, input};
use std::fmt::Write;

/// Effects of every channel as the C's flat arrays: each channel's first
/// effect, each effect's kind, index and first parameter, the parameters.
struct Effects {
    offset: Vec<usize>,
    kinds: Vec<usize>,
    indices: Vec<usize>,
    param_offset: Vec<usize>,
    params: Vec<f64>,
    coeff: Vec<f64>,
}

fn effects(m: &Model) -> Effects {
    let mut e = Effects {
        offset: vec![],
        kinds: vec![],
        indices: vec![],
        param_offset: vec![],
        params: vec![],
        coeff: vec![],
    };
    let n = m.n_channels();
    for c in 0..n {
        e.offset.push(e.kinds.len());
        let p: Vec<f64> = m.floats(Part::Params(c)).collect();
        let mut at = 0;
        for i in 0..m.n_effects(c) {
            let (kind, index) = m.effect(c, i);
            let np = dtg_onboard::kind_params_of(kind, n).unwrap_or(0);
            e.kinds.push(kind as usize);
            e.indices.push(index);
            e.param_offset.push(e.params.len());
            e.params.extend(&p[at..at + np]);
            at += np;
        }
        e.coeff.extend(m.floats(Part::Coefficients(c)));
    }
    e
}

/// The centre sets as the C's arrays: per channel its set, centres, the
/// number and list of its set's inputs (statistics: feature indices; the
/// raw window: signals), where its set's lanes and its weights start; the
/// lanes; for the raw window the leaders' centres.
struct Kernels {
    set: Vec<usize>,
    members_at: Vec<usize>,
    n_members: Vec<usize>,
    members: Vec<usize>,
    n_centres: Vec<usize>,
    n_input: Vec<usize>,
    input_at: Vec<usize>,
    inputs: Vec<usize>,
    lanes_at: Vec<usize>,
    lanes: Vec<f64>,
    weight_at: Vec<usize>,
    weights: Vec<f64>,
    centres_at: Vec<usize>,
    centres: Vec<f64>,
}

fn kernels(m: &Model) -> Kernels {
    let stats = m.input_kind() == input::STATISTICS;
    let mut k = Kernels {
        set: vec![],
        members_at: vec![],
        n_members: vec![],
        members: vec![],
        n_centres: vec![],
        n_input: vec![],
        input_at: vec![],
        inputs: vec![],
        lanes_at: vec![],
        lanes: vec![],
        weight_at: vec![],
        weights: vec![],
        centres_at: vec![],
        centres: vec![],
    };
    for c in 0..m.n_channels() {
        let leader = m.centre_set(c);
        k.set.push(leader);
        k.members_at.push(k.members.len());
        let members: Vec<usize> = (c..m.n_channels())
            .filter(|&j| m.centre_set(j) == c)
            .collect();
        k.n_members.push(members.len());
        k.members.extend(members);
        k.n_centres.push(m.n_centres(c));
        k.input_at.push(k.inputs.len());
        for s in (0..m.n_signals()).filter(|s| m.signal_mask(c) & (1 << s) != 0) {
            if stats {
                k.inputs.extend([3 * s, 3 * s + 1, 3 * s + 2]);
            } else {
                k.inputs.push(s);
            }
        }
        k.n_input.push(k.inputs.len() - k.input_at[c]);
        if leader == c {
            k.lanes_at.push(k.lanes.len());
            let mut lanes = vec![0.0; m.kernel_lanes_len(c)];
            m.kernel_lanes(c, &mut lanes);
            k.lanes.extend(lanes);
            k.centres_at.push(k.centres.len());
            k.centres.extend(m.floats(Part::Centres(c)));
        } else {
            k.lanes_at.push(k.lanes_at[leader]);
            k.centres_at.push(k.centres_at[leader]);
        }
        k.weight_at.push(k.weights.len());
        let mut w = vec![0.0; m.n_centres(c).div_ceil(dtg_onboard::LANES) * dtg_onboard::LANES];
        m.weight_lanes(c, &mut w);
        k.weights.extend(w);
    }
    k
}

/// A `static const` array of `dtg_real` named `name` with a comment.
fn reals(doc: &str, name: &str, v: &[f64]) -> String {
    format!(
        "/* {doc} */\nstatic const dtg_real {name}[{}] = {};\n",
        v.len().max(1),
        arr(v)
    )
}

/// A `static const` array of `int`.
fn ints(name: &str, v: &[usize]) -> String {
    format!(
        "static const int {name}[{}] = {};\n",
        v.len().max(1),
        iarr(v)
    )
}

/// The tables as C arrays, before the step code.
pub(super) fn arrays(m: &Model) -> String {
    let (calibrated, triad) = m.calibration();
    let stats = m.input_kind() == input::STATISTICS;
    let n = m.n_channels();
    let mut force_op: Vec<f64> = m.floats(Part::ForceOperator).collect();
    if force_op.is_empty() {
        // Layout 2: the accelerometers are x, y, z.
        force_op = (0..9).map(|i| f64::from(i % 4 == 0)).collect();
    }
    let e = effects(m);
    let k = kernels(m);
    let mut s = format!(
        r#"/* Generated by `dtg-vib export --lang c`; the same step as the dtg-onboard
 * Rust evaluator (crates/dtg-onboard), which documents each stage. */
#include <float.h>
#include <math.h>
#include "dtg_model.h"

#define R(x) ((dtg_real)(x))
#define DTG_CALIBRATED {cal}
#define DTG_ACCEL_TRIAD {triad}
#define N DTG_N_GYROS
#define NA DTG_N_ACCELS
/* The largest input of a centre set (statistics: 3 per signal). */
#define DTG_MAX_DIM {max_dim}

"#,
        cal = i32::from(calibrated),
        triad = i32::from(calibrated && triad),
        max_dim = k.n_input.iter().copied().max().unwrap_or(1).max(1),
    );
    s += &reals(
        "The unit-frame specific force from the accelerometers, 3 × NA.",
        "FORCE_OP",
        &force_op,
    );
    if calibrated {
        let mut lanes = vec![0.0; m.calibration_lanes_len()];
        m.calibration_lanes(&mut lanes);
        s += &format!(
            "/* Per gyro its model (0 = DTG, 1 = rate). */\n{}",
            ints(
                "GYRO_MODEL",
                &(0..n).map(|c| m.gyro_model(c) as usize).collect::<Vec<_>>()
            )
        );
        s += &reals(
            "The calibration with the gyros side by side (row r of N at r·N;\n * docs/formats.md, \"State\").",
            "CAL_LANES",
            &lanes,
        );
    }
    if calibrated && triad {
        let accel: Vec<f64> = m.floats(Part::AccelCalibration).collect();
        s += &reals(
            "The accelerometer triad, x, y, z: 8 each.",
            "ACCEL_CAL",
            &accel,
        );
    }
    for (doc, name, part) in [
        (
            "Effect low-pass sections: b0 b1 b2 a1 a2 zi1 zi2.",
            "OUT_SOS",
            Part::EffectFilter,
        ),
        ("Window low-pass sections.", "IN_SOS", Part::InputFilter),
        (
            "Prediction smoother sections.",
            "SMOOTH_SOS",
            Part::Smoother,
        ),
    ] {
        let v: Vec<f64> = m.floats(part).collect();
        if name != "SMOOTH_SOS" || !v.is_empty() {
            s += &reals(doc, name, &v);
        }
    }
    let codes: Vec<usize> = (0..m.n_signals()).map(|i| m.signal_code(i)).collect();
    let bias: Vec<f64> = (0..n).flat_map(|c| m.floats(Part::Bias(c))).collect();
    s += &ints("SIGNAL_CODE", &codes);
    s += "/* Per channel its effects: where they start, each one's kind, index and\n * first parameter. */\n";
    s += &ints(
        "N_EFFECTS",
        &(0..n).map(|c| m.n_effects(c)).collect::<Vec<_>>(),
    );
    s += &ints("EFFECT_OFFSET", &e.offset);
    s += &ints("EFFECT_KIND", &e.kinds);
    s += &ints("EFFECT_INDEX", &e.indices);
    s += &ints("PARAM_OFFSET", &e.param_offset);
    // Room for a rate product's 2N reads past any effect's start, so that
    // the compiler's bounds analysis of the unused kinds holds.
    let mut params = e.params.clone();
    params.resize(params.len() + 2 * n, 0.0);
    s += &reals("The effects' parameters.", "PARAMS", &params);
    s += &reals("Per channel its bias, deg/h.", "BIAS", &bias);
    s += &reals("The effects' coefficients.", "COEFF", &e.coeff);
    s += &kernel_arrays(&k, stats);
    if m.fades() {
        let fade: Vec<f64> = m.floats(Part::Fade).collect();
        s += &reals(
            "Per accelerometer: mean min, max, level min, max (g); scale (g),\n * tolerance, width, smoother gain; each channel's network at rest (deg/h);\n * with DTG_FADE_SHAPE per accelerometer shape min, max, then the shape scale\n * and the smoother's gain toward a lower weight.",
            "FADE",
            &fade,
        );
    }
    s
}

/// The centre sets' arrays.
fn kernel_arrays(k: &Kernels, stats: bool) -> String {
    let mut s = String::from(
        "/* Per channel: its centres, the first channel with the same signals,\n * centres and widths (whose kernel values it takes), its set's inputs\n * (statistics: feature indices; the window: signals) and where they start,\n * where its set's lanes and its weights in lanes start. */\n",
    );
    s += &ints("N_CENTRES", &k.n_centres);
    s += &ints("CENTRE_SET", &k.set);
    s += "/* Per set (a leader's) the channels that share it. */\n";
    s += &ints("SET_N_MEMBERS", &k.n_members);
    s += &ints("SET_MEMBERS_AT", &k.members_at);
    s += &ints("SET_MEMBERS", &k.members);
    s += &ints("SET_N_INPUT", &k.n_input);
    s += &ints("SET_INPUT_AT", &k.input_at);
    s += &ints("SET_INPUT", &k.inputs);
    s += &ints("SET_LANES", &k.lanes_at);
    s += &ints("WEIGHT_AT", &k.weight_at);
    s += &reals(
        if stats {
            "Each centre set in lanes (dtg-onboard's Model::kernel_lanes): its mean m,\n * then per block of DTG_LANES centres U = 2(c - m)/beta^2 (one row per input),\n * V = -|c - m|^2/beta^2 and W = -1/beta^2, zeros past the last centre."
        } else {
            "Each centre set's -1/beta^2 in blocks of DTG_LANES (Model::kernel_lanes)."
        },
        "KERNEL_LANES",
        &k.lanes,
    );
    s += &reals(
        "Each channel's weights, padded with zeros to whole blocks.",
        "WEIGHT_LANES",
        &k.weights,
    );
    if !stats {
        s += &ints("SET_CENTRES", &k.centres_at);
        s += &reals(
            "The sets' centres, centre by centre, signal by signal, oldest sample first.",
            "CENTRES",
            &k.centres,
        );
    }
    s
}

/// A C array initialiser; a single 0 for an empty list (C99 has no empty arrays).
fn arr(v: &[f64]) -> String {
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

/// An `int` array initialiser; a single 0 for an empty list.
fn iarr(v: &[usize]) -> String {
    if v.is_empty() {
        return "{0}".into();
    }
    let items: Vec<String> = v.iter().map(|x| x.to_string()).collect();
    format!("{{{}}}", items.join(", "))
}
