//! What every channel's diagnosis shares: the record's inputs on the
//! validation rows, the rates the residual tests run at, and the rows far
//! enough from a record's ends to test.

use crate::error::SysidError;
use crate::prepared::Prepared;
use crate::sensor::{OperatingStats, Sensor};

/// What every channel's diagnosis shares: inputs on the validation rows.
pub(super) struct Context {
    pub(super) t: Vec<f64>,
    /// The record samples of the validation rows (where a window ends).
    pub(super) samples: Vec<usize>,
    /// Filtered operating signals (an inertial unit's ax, ay, az) on the
    /// validation rows.
    pub(super) operating: Vec<(String, Vec<f64>)>,
    /// Filtered extra columns on the validation rows.
    pub(super) extras: Vec<(String, Vec<f64>)>,
    /// The operating signals' means and variances on the validation rows.
    pub(super) stats: OperatingStats,
    /// The validation series' sample rate, Hz.
    pub(super) fs: f64,
    /// The model's memory in decimated samples: a window plus the filter's
    /// reach. The whiteness test looks beyond it.
    pub(super) memory: usize,
    /// Decimation of the whiteness test: to about twice the filter's cut-off
    /// (the lags in between carry no information).
    pub(super) decimation: usize,
    /// Positions of the validation rows the correlation tests use: those
    /// whose window lies beyond the filter's reach of the record's ends. At
    /// an end the zero-phase filter's reflected extension makes the filtered
    /// input (and the residual with it) several times its usual size, and
    /// the fourth-power Billings–Voon products of one such row can decide a
    /// test on their own. With several records, the ends of each record.
    pub(super) steady: Vec<usize>,
    pub(super) band_edges: Vec<f64>,
    pub(super) shape: Box<dyn Fn(f64) -> f64 + Send + Sync>,
}

impl Context {
    pub(super) fn new<S: Sensor>(
        prepared: &Prepared<S>,
        val: &[usize],
    ) -> Result<Self, SysidError> {
        let first = prepared.first_sample();
        let on_val = |x: &[f64]| -> Vec<f64> { val.iter().map(|&r| x[first + r]).collect() };
        let rec = prepared.calibrated();
        let sensor = prepared.sensor();
        let filtered = |names: Vec<String>| -> Result<Vec<(String, Vec<f64>)>, SysidError> {
            names
                .into_iter()
                .map(|n| {
                    let v = on_val(&prepared.signal_full(&n)?);
                    Ok((n, v))
                })
                .collect()
        };
        let operating = filtered(sensor.operating_signals())?;
        let extras = filtered(sensor.extra_columns(rec))?;
        // The validation series' own rate: alternate rows (an interleaved
        // split) are two samples apart.
        let spacing = crate::split::row_spacing(val);
        let fs = 1.0 / (rec.dt() * spacing as f64);
        let nyquist = fs / 2.0;
        let (decimation, cutoff) = match prepared.filter() {
            // Decimation in validation rows.
            Some(f) => (
                ((fs / (2.0 * f.cutoff_hz())).floor() as usize).max(1),
                f.cutoff_hz().min(nyquist),
            ),
            None => (1, nyquist),
        };
        let mut band_edges: Vec<f64> = vec![0.0, 0.1, 0.5, 2.0];
        band_edges.retain(|&e| e < cutoff);
        band_edges.push(cutoff);
        if cutoff < nyquist {
            band_edges.push(nyquist);
        }
        let shape: Box<dyn Fn(f64) -> f64 + Send + Sync> = match prepared.filter() {
            Some(f) => {
                let f = f.clone();
                Box::new(move |hz| f.gain_at(hz).powi(4))
            }
            None => Box::new(|_| 1.0),
        };
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        let var = |v: &[f64]| {
            let m = mean(v);
            v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len().max(1) as f64
        };
        let stats = OperatingStats {
            names: operating.iter().map(|(n, _)| n.clone()).collect(),
            means: operating.iter().map(|(_, v)| mean(v)).collect(),
            variances: operating.iter().map(|(_, v)| var(v)).collect(),
        };
        let fm = prepared.filter_memory();
        // A row's window starts `first` samples before the sample it ends at.
        let steady: Vec<usize> = val
            .iter()
            .enumerate()
            .filter(|&(_, &r)| {
                let (record, sample) = prepared.locate(r);
                sample >= first + fm && sample + fm < record.len()
            })
            .map(|(i, _)| i)
            .collect();
        // Too little left (a record barely longer than the filter): test all rows.
        let steady = if steady.len() >= val.len() / 2 {
            steady
        } else {
            (0..val.len()).collect()
        };
        let reach = prepared.first_sample() + 1 + prepared.filter_memory();
        let memory = reach.div_ceil(spacing * decimation);
        Ok(Self {
            t: on_val(rec.t()),
            samples: val.iter().map(|&r| first + r).collect(),
            memory,
            operating,
            extras,
            stats,
            fs,
            decimation,
            steady,
            band_edges,
            shape,
        })
    }
}
