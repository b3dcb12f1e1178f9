//! A causal model of any unit, the paper's included, as the onboard tables
//! of layout [`dtg_onboard::VERSION`] the `dtg-onboard` evaluator and the
//! exported C read: n channels, each a DTG or a rate gyro with its own
//! calibration table and its network on its own window signals, the
//! unit's least-squares rate and specific-force operators and the log's
//! units (docs/formats.md, "Onboard tables").

use super::effects::effect_entry;
use super::error::ExportError;
use crate::signal::LowPass;
use crate::unit_sensor::effect::UnitEffect;
use crate::unit_sensor::model::UnitModel;
use dtg_onboard::{
    FIXED_HEADER_WORDS, FLAG_ACCEL_TRIAD, FLAG_CALIBRATION, FLAG_FADE, FLAG_FADE_SHAPE, MAGIC,
    MAX_ACCELS, MAX_CHANNELS, MAX_SIGNALS, VERSION, gyro,
};
use nalgebra::Vector3;
use nav_sensors::calibration::GyroCoefficients;
use nav_sensors::geometry::Axis;
use nav_sensors::unit::{GyroModel, Unit};

/// A model as onboard tables, with the names of the extra columns each step
/// takes (in order).
#[derive(Debug, Clone, PartialEq)]
pub struct Tables {
    /// The bytes (layout version [`dtg_onboard::VERSION`]).
    pub bytes: Vec<u8>,
    /// Extra record columns a step takes, in order.
    pub extra: Vec<String>,
}

/// The extra record columns a model reads: windowed extra signals first,
/// then effect columns, each once, in order of first use.
pub fn extra_columns(model: &UnitModel) -> Vec<String> {
    let unit = model.unit();
    let mut out: Vec<String> = Vec::new();
    let mut add = |n: &str| {
        if !out.iter().any(|e| e == n) {
            out.push(n.to_string());
        }
    };
    for s in model.inner().preprocess().window.signals() {
        if !unit.accel_names().contains(&s.as_str()) {
            add(s);
        }
    }
    for c in model.inner().channels() {
        for e in c.effects() {
            if let Some(n) = e.column_name() {
                add(n);
            }
        }
    }
    out
}

/// Each accelerometer's axis when the three are the unit's x, y, z (in any
/// order): then their triad calibration applies (as
/// `UnitCalibration::compensate` applies it).
fn accel_axes(unit: &Unit) -> Option<[usize; 3]> {
    let axis_of: Vec<Option<usize>> = unit
        .accels()
        .iter()
        .map(|a| Axis::ALL.iter().position(|x| a.input == x.unit_vector()))
        .collect();
    if axis_of.len() != 3 {
        return None;
    }
    let by_axis: Vec<usize> = (0..3)
        .map(|x| axis_of.iter().position(|a| *a == Some(x)))
        .collect::<Option<_>>()?;
    Some([by_axis[0], by_axis[1], by_axis[2]])
}

/// Refuses a calibration of accelerometers the tables cannot carry: they
/// hold one triad's, along the unit's x, y, z; the batch calibrates every
/// accelerometer it has coefficients for (each IMU's triad of a unit of
/// several), and an evaluator reading them raw would feed its networks
/// other inputs than the fit's.
fn accels_calibrated_onboard(
    unit: &Unit,
    cal: &nav_sensors::calibration::UnitCalibration,
    triad: Option<[usize; 3]>,
) -> Result<(), ExportError> {
    if triad.is_some() {
        return Ok(());
    }
    let calibrated: Vec<&str> = unit
        .accels()
        .iter()
        .filter(|a| {
            cal.accels
                .get(&a.name)
                .is_some_and(|c| *c != nav_sensors::accel::AccelCoefficients::default())
        })
        .map(|a| a.name.as_str())
        .collect();
    if calibrated.is_empty() {
        return Ok(());
    }
    Err(ExportError::Unsupported {
        channel: unit.gyros()[0].name.clone(),
        what: format!(
            "a calibration of the accelerometers {} (the unit has {} accelerometers, not one triad along x, y, z)",
            calibrated.join(", "),
            unit.accels().len()
        ),
        supported: "one accelerometer triad's calibration, along the unit's x, y, z: fit without the accelerometers' coefficients in --calib, or compensate with dtg-vib compensate --model",
    })
}

/// A unit's causal model as onboard tables of layout
/// [`dtg_onboard::VERSION`]. Refuses a zero-phase model, a unit of more
/// than [`dtg_onboard::MAX_CHANNELS`] gyros or [`dtg_onboard::MAX_ACCELS`]
/// accelerometers, more than [`dtg_onboard::MAX_SIGNALS`] window signals, a
/// window over a gyro, and what the evaluator does not compute (a kernel
/// other than the Gaussian, input scaling, a polynomial tail).
pub fn tables(model: &UnitModel) -> Result<Tables, ExportError> {
    let m = model.inner();
    let pre = m.preprocess();
    if !pre.causal {
        return Err(ExportError::NotCausal);
    }
    let unit = model.unit();
    let (n_g, n_a) = (unit.gyros().len(), unit.accels().len());
    let n_s = pre.window.signals().len();
    for (what, found, max) in [
        ("gyros", n_g, MAX_CHANNELS),
        ("accelerometers", n_a, MAX_ACCELS),
        ("window signals", n_s, MAX_SIGNALS),
    ] {
        if found > max {
            return Err(ExportError::TooMany { what, found, max });
        }
    }
    let extra = extra_columns(model);
    let dt = m.dt_s();
    let in_filter = input_filter(&pre.input_filter, dt)?;
    let calibration = m.sensor().calibration.as_ref();
    let triad = calibration.and(accel_axes(unit));
    if let Some(cal) = calibration {
        accels_calibrated_onboard(unit, cal, triad)?;
    }
    let fade = super::fade::fade_block(model)?;
    let flags = calibration.map_or(0, |_| FLAG_CALIBRATION)
        | fade.as_ref().map_or(0, |(_, shape)| {
            FLAG_FADE | if *shape { FLAG_FADE_SHAPE } else { 0 }
        })
        | triad.map_or(0, |_| FLAG_ACCEL_TRIAD);
    let (words, params) = header_words(model, &extra, flags, &in_filter)?;
    let mut f = geometry_and_calibration(model, triad);
    f.extend(sections(&in_filter));
    f.extend(sections(&smoother_filter(pre.smoother, dt)));
    for (c, p) in m.channels().iter().zip(&params) {
        network_floats(c, p, &mut f)?;
    }
    if let Some((block, _)) = fade {
        f.extend(block);
    }
    assemble(&words, &f, extra)
}

/// The header words (sizes, per-channel lists, signal codes, each
/// effect's kind and index, input and smoother words) and each channel's
/// effect parameters, in the layout's order.
fn header_words(
    model: &UnitModel,
    extra: &[String],
    flags: u32,
    in_filter: &Option<LowPass>,
) -> Result<(Vec<u32>, Vec<Vec<f64>>), ExportError> {
    let (m, unit) = (model.inner(), model.unit());
    let pre = m.preprocess();
    let signals = pre.window.signals();
    let n_a = unit.accels().len();
    let mut words: Vec<u32> = vec![
        u32::from_le_bytes(MAGIC),
        VERSION,
        0, // header words, below
        flags,
        extra.len() as u32,
        0, // the effects are subtracted unfiltered (θ·z), as the batch does
        in_filter.as_ref().map_or(0, |f| f.sections().len()) as u32,
        pre.window.length() as u32,
        signals.len() as u32,
        unit.gyros().len() as u32,
        n_a as u32,
    ];
    debug_assert_eq!(words.len(), FIXED_HEADER_WORDS);
    words.extend(m.channels().iter().map(|c| c.effects().len() as u32));
    words.extend(m.channels().iter().map(|c| c.n_centres() as u32));
    words.extend(unit.gyros().iter().map(|g| match g.model {
        GyroModel::Dtg { .. } => gyro::DTG,
        GyroModel::Rate => gyro::RATE,
    }));
    // Each channel's network reads its own signals among the model's list
    // (every one of them when the channels share one window).
    for k in 0..unit.gyros().len() {
        words.push(signal_mask(
            signals,
            pre.window.signals_of(k),
            &unit.gyros()[k].name,
        )?);
    }
    for s in signals {
        let code = match unit.accel_names().iter().position(|a| a == s) {
            Some(i) => i,
            None if unit.gyro_names().contains(&s.as_str()) => {
                return Err(ExportError::Unsupported {
                    channel: unit.gyros()[0].name.clone(),
                    what: format!("a window over the gyro {s}"),
                    supported: "windows over accelerometers and extra columns",
                });
            }
            None => n_a + extra.iter().position(|e| e == s).expect("collected above"),
        };
        words.push(code as u32);
    }
    let mut params: Vec<Vec<f64>> = Vec::new();
    for (k, c) in m.channels().iter().enumerate() {
        let mut p = Vec::new();
        for e in c.effects() {
            let (kd, i, v) = effect_entry(unit, k, e, extra)?;
            words.extend([kd, i]);
            p.extend(v);
        }
        params.push(p);
    }
    words.extend(input_and_smoother_words(pre.input, pre.smoother, m.dt_s()));
    if !words.len().is_multiple_of(2) {
        words.push(0);
    }
    words[2] = words.len() as u32;
    Ok((words, params))
}

/// The mask of `own` (a channel's window signals) among the model's
/// `signals`: bit i for signal i. The evaluator feeds a channel's network
/// its signals in the model's order, so a channel whose own order differs
/// is refused.
fn signal_mask(signals: &[String], own: &[String], channel: &str) -> Result<u32, ExportError> {
    let at: Vec<usize> = own
        .iter()
        .filter_map(|s| signals.iter().position(|t| t == s))
        .collect();
    if at.len() != own.len() || !at.is_sorted() {
        return Err(ExportError::Unsupported {
            channel: channel.to_string(),
            what: format!("a window over {} (in this order)", own.join(", ")),
            supported: "each channel's window signals in the order of the model's list",
        });
    }
    Ok(at.iter().fold(0, |m, &i| m | (1u32 << i)))
}

/// The sample interval, the log's units, each gyro's (I, O, S) axes (a
/// rate gyro's I and two zero rows), the least-squares rate operator
/// (3 × n), the specific-force operator (3 × n_a), and the ground
/// calibration: each gyro's table, then the triad's (x, y, z order) when
/// the accelerometers are the unit's axes (`triad`: each axis's
/// accelerometer).
fn geometry_and_calibration(model: &UnitModel, triad: Option<[usize; 3]>) -> Vec<f64> {
    let unit = model.unit();
    let units = unit.units();
    let mut f: Vec<f64> = vec![
        model.inner().dt_s(),
        units.rate.to_deg_h(),
        units.specific_force.to_g(),
    ];
    for g in unit.gyros() {
        let (o, s) = match g.dtg_axes() {
            Some(a) => (a.output, a.spin),
            None => (Vector3::zeros(), Vector3::zeros()),
        };
        for v in [g.input, o, s] {
            f.extend([v.x, v.y, v.z]);
        }
    }
    let ls = unit.geometry().least_squares_operator();
    for i in 0..3 {
        f.extend((0..unit.gyros().len()).map(|j| ls[(i, j)]));
    }
    let n_a = unit.accels().len();
    let columns: Vec<Vector3<f64>> = (0..n_a)
        .map(|k| {
            let mut e = vec![0.0; n_a];
            e[k] = 1.0;
            unit.specific_force(&e)
        })
        .collect();
    for i in 0..3 {
        f.extend(columns.iter().map(|c| c[i]));
    }
    let Some(cal) = model.inner().sensor().calibration.as_ref() else {
        return f;
    };
    for g in unit.gyros() {
        match cal
            .gyros
            .get(&g.name)
            .copied()
            .unwrap_or(GyroCoefficients::zero(&g.model))
        {
            GyroCoefficients::Dtg(c) => {
                f.extend(c.to_array());
                f.push(c.scale_factor_nonlinearity_ppm_per_deg_s);
            }
            GyroCoefficients::Rate(c) => f.extend(c.to_array()),
        }
    }
    if let Some(by_axis) = triad {
        for k in by_axis {
            let c = cal
                .accels
                .get(&unit.accels()[k].name)
                .copied()
                .unwrap_or_default();
            f.extend(accel_floats(&c));
        }
    }
    f
}

/// An accelerometer's calibration in the layout's order (K0, K1, K2, K3,
/// δo, δp, Kip, Kio; the text export names them in it too).
pub(crate) fn accel_floats(c: &nav_sensors::accel::AccelCoefficients) -> [f64; 8] {
    [
        c.bias_ug,
        c.scale_factor_ppm,
        c.k2_ug_per_g2,
        c.k3_ug_per_g3,
        c.misalignment_o_urad,
        c.misalignment_p_urad,
        c.kip_ug_per_g2,
        c.kio_ug_per_g2,
    ]
}

/// A low-pass's sections as the layout's numbers (b0 b1 b2 a1 a2 and the
/// steady state of a unit input, each).
fn sections(lp: &Option<LowPass>) -> Vec<f64> {
    let Some(lp) = lp else { return vec![] };
    let zi = lp.steady_state();
    lp.sections()
        .iter()
        .zip(zi)
        .flat_map(|(s, z)| [s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], z[0], z[1]])
        .collect()
}

/// The tables' bytes: the header `words`, then the numbers `f`, checked by
/// the evaluator (a refusal is an exporter bug).
fn assemble(words: &[u32], f: &[f64], extra: Vec<String>) -> Result<Tables, ExportError> {
    let mut bytes = Vec::with_capacity(4 * words.len() + 8 * f.len());
    for w in words {
        bytes.extend(w.to_le_bytes());
    }
    for v in f {
        bytes.extend(v.to_le_bytes());
    }
    dtg_onboard::Model::parse(&bytes).map_err(|e| ExportError::Tables(e.to_string()))?;
    Ok(Tables { bytes, extra })
}

/// The words after the effect pairs: the network's input kind and the
/// prediction smoother's sections.
fn input_and_smoother_words(
    input: sysid::ModelInput,
    smoother: Option<sysid::Smoother>,
    dt_s: f64,
) -> [u32; 2] {
    let input = match input {
        sysid::ModelInput::Raw => dtg_onboard::input::RAW,
        sysid::ModelInput::Statistics => dtg_onboard::input::STATISTICS,
    };
    [
        input,
        smoother_filter(smoother, dt_s).map_or(0, |f| f.sections().len()) as u32,
    ]
}

/// The prediction smoother's filter, as the loop designs it.
fn smoother_filter(smoother: Option<sysid::Smoother>, dt_s: f64) -> Option<LowPass> {
    smoother?.design(dt_s).ok()
}

/// The causal low-pass of the windowed signals, as the loop designs it.
fn input_filter(
    spec: &Option<sysid::FilterSpec>,
    dt_s: f64,
) -> Result<Option<LowPass>, ExportError> {
    spec.map(|f| LowPass::butterworth(f.order, f.cutoff_hz, 1.0 / dt_s))
        .transpose()
        .map_err(|e| ExportError::Tables(e.to_string()))
}

/// One channel's bias, effect coefficients and parameters `p`, widths,
/// weights and centres; refuses what the evaluator does not compute (a
/// kernel other than the Gaussian, input scaling, a polynomial tail).
fn network_floats(
    c: &sysid::ChannelModel<String, UnitEffect>,
    p: &[f64],
    f: &mut Vec<f64>,
) -> Result<(), ExportError> {
    let rbf = c.rbf();
    let unsupported = |what: String, supported| ExportError::Unsupported {
        channel: c.channel(),
        what,
        supported,
    };
    if rbf.kernel() != rbf::Kernel::Gaussian {
        return Err(unsupported(
            format!("the {:?} kernel", rbf.kernel()),
            "the Gaussian kernel",
        ));
    }
    if rbf.scaling().is_some() {
        return Err(unsupported(
            "input scaling".into(),
            "unscaled windows (dtg-vib fit does not scale)",
        ));
    }
    // A unit-box tail (rbf's `degree`) has its own map and terms that
    // the onboard layout does not carry; dtg-vib fit never sets one, but
    // a model file may come from elsewhere.
    if rbf.tail().is_some() || rbf.degree().is_some() {
        return Err(unsupported("a polynomial tail".into(), "no tail"));
    }
    f.push(c.bias());
    f.extend(c.effect_coefficients());
    f.extend(p);
    let k = rbf.n_centres();
    f.extend((0..k).map(|j| rbf.widths().get(j)));
    f.extend((0..k).map(|j| rbf.weights()[(j, 0)]));
    let centres = rbf.centres();
    for j in 0..k {
        f.extend((0..centres.ncols()).map(|d| centres[(j, d)]));
    }
    Ok(())
}
