//! What every channel's diagnosis shares: the record's inputs on the
//! validation rows, the rates the residual tests run at, and the rows far
//! enough from a record's ends to test.

use crate::error::DtgVibError;
use crate::pipeline::Prepared;
use nav_sensors::geometry::Axis;

/// What every channel's diagnosis shares: inputs on the validation rows.
pub(super) struct Context {
    pub(super) t: Vec<f64>,
    /// Filtered accelerations (ax, ay, az) on the validation rows.
    pub(super) accel: [Vec<f64>; 3],
    /// Filtered extra columns on the validation rows.
    pub(super) extras: Vec<(String, Vec<f64>)>,
    /// Largest standard deviation of the least-squares rate, deg/s.
    pub(super) rate_std_deg_s: f64,
    /// Mean filtered specific force on the validation rows (cluster frame), g.
    pub(super) gravity_g: nalgebra::Vector3<f64>,
    /// RMS of the filtered specific force about its mean, g.
    pub(super) vibration_g: f64,
    /// The axis along which the filtered specific force varies most.
    pub(super) vibration_axis: Axis,
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
    pub(super) shape: Box<dyn Fn(f64) -> f64>,
}

impl Context {
    pub(super) fn new(prepared: &Prepared, val: &[usize]) -> Result<Self, DtgVibError> {
        let first = prepared.first_sample();
        let on_val = |x: &[f64]| -> Vec<f64> { val.iter().map(|&r| x[first + r]).collect() };
        let rec = prepared.calibrated();
        let accel = [
            on_val(&prepared.signal_full(Axis::X.column())?),
            on_val(&prepared.signal_full(Axis::Y.column())?),
            on_val(&prepared.signal_full(Axis::Z.column())?),
        ];
        let extras = rec
            .extra_names()
            .iter()
            .map(|n| Ok((n.to_string(), on_val(&prepared.signal_full(n)?))))
            .collect::<Result<Vec<_>, DtgVibError>>()?;
        let rate_std_deg_s =
            crate::effects::rate_variation_deg_s(rec, val.iter().map(|&r| first + r));
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
        let shape: Box<dyn Fn(f64) -> f64> = match prepared.filter() {
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
        let gravity_g = nalgebra::Vector3::new(mean(&accel[0]), mean(&accel[1]), mean(&accel[2]));
        let variances = [var(&accel[0]), var(&accel[1]), var(&accel[2])];
        let vibration_axis = Axis::ALL
            .into_iter()
            .max_by(|a, b| variances[a.index()].total_cmp(&variances[b.index()]))
            .expect("three axes");
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
            memory,
            gravity_g,
            vibration_g: variances.iter().sum::<f64>().sqrt(),
            vibration_axis,
            accel,
            extras,
            rate_std_deg_s,
            fs,
            decimation,
            steady,
            band_edges,
            shape,
        })
    }
}
