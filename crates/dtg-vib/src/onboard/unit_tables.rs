//! A causal model of any unit (`fit --unit …`) as onboard tables of layout
//! [`dtg_onboard::UNIT_VERSION`]: n channels, each a DTG or a rate gyro
//! with its own calibration table, the unit's least-squares rate and
//! specific-force operators and the log's units (docs/formats.md,
//! "Onboard tables"). The paper's models keep their own layout
//! ([`super::tables`]), byte for byte.

use super::error::ExportError;
use super::tables::{
    Tables, accel_floats, assemble, input_and_smoother_words, input_filter, network_floats,
    sections, smoother_filter,
};
use crate::unit_sensor::{UnitEffect, UnitModel, rate_without};
use dtg_onboard::{
    FLAG_ACCEL_TRIAD, FLAG_CALIBRATION, FLAG_FADE, MAGIC, MAX_ACCELS, MAX_CHANNELS,
    UNIT_FIXED_HEADER_WORDS, UNIT_VERSION, gyro, kind,
};
use nalgebra::Vector3;
use nav_sensors::calibration::GyroCoefficients;
use nav_sensors::dtg::DtgTerm;
use nav_sensors::geometry::Axis;
use nav_sensors::rate::RateTerm;
use nav_sensors::unit::{GyroModel, GyroTerm, Unit};

/// The extra record columns a unit model reads: windowed extra signals
/// first, then effect columns, each once, in order of first use.
pub fn unit_extra_columns(model: &UnitModel) -> Vec<String> {
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
            if let UnitEffect::Column(n) = e {
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

/// The unit-frame axis a rate-gyro term's id letter names.
fn unit_axis(c: char) -> Vector3<f64> {
    match c {
        'x' => Vector3::x(),
        'y' => Vector3::y(),
        _ => Vector3::z(),
    }
}

/// One effect of channel `k` in the tables: kind, index, parameters.
fn effect_entry(
    unit: &Unit,
    k: usize,
    effect: &UnitEffect,
    extra: &[String],
) -> Result<(u32, u32, Vec<f64>), ExportError> {
    let g = &unit.gyros()[k];
    let v3 = |v: Vector3<f64>| vec![v.x, v.y, v.z];
    let unsupported = |id: String| ExportError::Unsupported {
        channel: g.name.clone(),
        what: format!("effect {id}"),
        supported: "g_*, gg_*, ai_* and col:NAME effects",
    };
    let letters = |id: &str| -> Vec<char> { id.rsplit('_').next().unwrap_or("").chars().collect() };
    match effect {
        UnitEffect::Column(name) => {
            let idx = extra
                .iter()
                .position(|e| e == name)
                .expect("extra columns are collected from the effects");
            Ok((kind::COLUMN, idx as u32, vec![]))
        }
        UnitEffect::Term(GyroTerm::Rate(t)) => {
            let axes = letters(t.id());
            if RateTerm::SPECIFIC_FORCE[..3].contains(t) {
                Ok((kind::LINEAR_G, 0, v3(unit_axis(axes[0]))))
            } else if RateTerm::SPECIFIC_FORCE.contains(t) {
                let mut p = v3(unit_axis(axes[0]));
                p.extend(v3(unit_axis(axes[1])));
                Ok((kind::QUADRATIC_G, 0, p))
            } else {
                Err(unsupported(t.id().to_string()))
            }
        }
        UnitEffect::Term(GyroTerm::Dtg(t)) => {
            let Some(frame) = g.dtg_axes() else {
                return Err(unsupported(t.id().to_string()));
            };
            let ax = |c: char| match c {
                'I' => frame.input,
                'O' => frame.output,
                _ => frame.spin,
            };
            let axes = letters(t.id());
            if DtgTerm::SPECIFIC_FORCE[..3].contains(t) {
                Ok((kind::LINEAR_G, 0, v3(ax(axes[0]))))
            } else if DtgTerm::SPECIFIC_FORCE.contains(t) {
                let mut p = v3(ax(axes[0]));
                p.extend(v3(ax(axes[1])));
                Ok((kind::QUADRATIC_G, 0, p))
            } else if DtgTerm::ANISOINERTIA.contains(t) {
                // (a·op·m/3600)(b·op·m/3600): the rate of the other gyros,
                // resolved, in deg/s (the plug-in's regressor).
                let op = rate_without(unit, k).ok_or_else(|| unsupported(t.id().to_string()))?;
                let row = |c: char| {
                    let r = ax(c).transpose() * &op / 3600.0;
                    r.iter().copied().collect::<Vec<f64>>()
                };
                let mut p = row(axes[0]);
                p.extend(row(axes[1]));
                Ok((kind::RATE_PRODUCT, 0, p))
            } else {
                Err(unsupported(t.id().to_string()))
            }
        }
    }
}

/// A unit's causal model as onboard tables of layout
/// [`dtg_onboard::UNIT_VERSION`]. Refuses a zero-phase model, a unit of
/// more than [`dtg_onboard::MAX_CHANNELS`] gyros or
/// [`dtg_onboard::MAX_ACCELS`] accelerometers, a window over a gyro, and
/// what the evaluator does not compute.
pub fn unit_tables(model: &UnitModel) -> Result<Tables, ExportError> {
    let m = model.inner();
    let pre = m.preprocess();
    if !pre.causal {
        return Err(ExportError::NotCausal);
    }
    let unit = model.unit();
    let (n_g, n_a) = (unit.gyros().len(), unit.accels().len());
    for (what, found, max) in [
        ("gyros", n_g, MAX_CHANNELS),
        ("accelerometers", n_a, MAX_ACCELS),
    ] {
        if found > max {
            return Err(ExportError::TooMany { what, found, max });
        }
    }
    let extra = unit_extra_columns(model);
    let dt = m.dt_s();
    let in_filter = input_filter(&pre.input_filter, dt)?;
    let calibration = m.sensor().calibration.as_ref();
    let triad = calibration.and(accel_axes(unit));
    let fade = super::fade::fade_block_of(
        m.operating_points(),
        pre.window.length(),
        dt,
        (&sysid::Sensor::operating_signals(m.sensor()), n_g),
        (
            unit.gyros()[0].name.clone(),
            "a training range over the unit's accelerometers' windows of the model's length",
        ),
    )?;
    let flags = calibration.map_or(0, |_| FLAG_CALIBRATION)
        | fade.as_ref().map_or(0, |_| FLAG_FADE)
        | triad.map_or(0, |_| FLAG_ACCEL_TRIAD);
    let signals = pre.window.signals();
    let mut words: Vec<u32> = vec![
        u32::from_le_bytes(MAGIC),
        UNIT_VERSION,
        0, // header words, below
        flags,
        extra.len() as u32,
        0, // the effects are subtracted unfiltered, as for the paper's unit
        in_filter.as_ref().map_or(0, |f| f.sections().len()) as u32,
        pre.window.length() as u32,
        signals.len() as u32,
        n_g as u32,
        n_a as u32,
    ];
    debug_assert_eq!(words.len(), UNIT_FIXED_HEADER_WORDS);
    words.extend(m.channels().iter().map(|c| c.effects().len() as u32));
    words.extend(m.channels().iter().map(|c| c.n_centres() as u32));
    words.extend(unit.gyros().iter().map(|g| match g.model {
        GyroModel::Dtg { .. } => gyro::DTG,
        GyroModel::Rate => gyro::RATE,
    }));
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
            let (kd, i, v) = effect_entry(unit, k, e, &extra)?;
            words.extend([kd, i]);
            p.extend(v);
        }
        params.push(p);
    }
    words.extend(input_and_smoother_words(pre.input, pre.smoother, dt));
    if !words.len().is_multiple_of(2) {
        words.push(0);
    }
    words[2] = words.len() as u32;

    let mut f = geometry_and_calibration(model, triad);
    f.extend(sections(&in_filter));
    f.extend(sections(&smoother_filter(pre.smoother, dt)));
    for (c, p) in m.channels().iter().zip(&params) {
        network_floats(c, p, &mut f)?;
    }
    if let Some(block) = fade {
        f.extend(block);
    }
    assemble(&words, &f, extra)
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
