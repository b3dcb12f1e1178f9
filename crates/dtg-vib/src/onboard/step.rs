//! A causal model run over a record sample by sample through the
//! `dtg-onboard` evaluator, as a flight computer would: what `compensate`
//! does with a causal model, and what the exported C is checked against.

use super::error::ExportError;
use super::tables;
use crate::error::DtgVibError;
use crate::model::CompensationModel;
use nav_sensors::record::Record;

/// A record run through the onboard evaluator, from the first sample with a
/// full window on.
#[derive(Debug, Clone, PartialEq)]
pub struct Stepped {
    /// Record sample of the first output.
    pub first_sample: usize,
    /// Compensated rates per channel, deg/h.
    pub rate_deg_h: [Vec<f64>; 6],
    /// Predicted errors per channel, deg/h.
    pub error_deg_h: [Vec<f64>; 6],
    /// Calibrated accelerations per axis, g.
    pub accel_g: [Vec<f64>; 3],
}

/// Runs a causal model over a record sample by sample with the `dtg-onboard`
/// evaluator, as a flight computer would.
pub fn step_record(model: &CompensationModel, record: &Record) -> Result<Stepped, DtgVibError> {
    let t = tables(model)?;
    let m = dtg_onboard::Model::parse(&t.bytes).map_err(|e| ExportError::Tables(e.to_string()))?;
    let extra_cols: Vec<&[f64]> = t
        .extra
        .iter()
        .map(|n| crate::pipeline::signal(record, n))
        .collect::<Result<_, _>>()?;
    let mut state = vec![0.0; m.state_len()];
    let mut ev = dtg_onboard::Evaluator::new(m, &mut state)
        .map_err(|e| ExportError::Tables(e.to_string()))?;
    let mut out = Stepped {
        first_sample: m.window_len() - 1,
        rate_deg_h: Default::default(),
        error_deg_h: Default::default(),
        accel_g: Default::default(),
    };
    let mut extra = vec![0.0; t.extra.len()];
    let mut push = |o: dtg_onboard::Output| {
        for k in 0..6 {
            out.rate_deg_h[k].push(o.rate_deg_h[k]);
            out.error_deg_h[k].push(o.error_deg_h[k]);
        }
        for k in 0..3 {
            out.accel_g[k].push(o.accel_g[k]);
        }
    };
    for i in 0..record.len() {
        for (e, c) in extra.iter_mut().zip(&extra_cols) {
            *e = c[i];
        }
        let a = record.accel_sample(i);
        let o = ev
            .step(&record.gyro_sample(i), &[a.x, a.y, a.z], &extra)
            .map_err(|e| ExportError::Tables(e.to_string()))?;
        if let Some(o) = o {
            push(o);
        }
    }
    if let Some(o) = ev.flush() {
        push(o);
    }
    Ok(out)
}
