//! A unit's parity residues before and after compensation, by name (the
//! paper's K0 … K5 of eq. 6, another unit's P0, …; none for three gyros).
//!
//! Residues are linear combinations of the channels' errors only (the true
//! rate cancels), so they show the gain of a compensation without any rate
//! reference: the paper's Fig. 7.

use nav_sensors::unit::Unit;
use serde::Serialize;

/// Residue series on the rows of prepared data, deg/h.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidueSeries {
    /// The residues' names, in the unit's order.
    pub names: Vec<String>,
    /// Time of each row, s.
    pub t: Vec<f64>,
    /// Each residue of the pre-processed outputs (calibrated, filtered).
    pub before: Vec<Vec<f64>>,
    /// Each residue after subtracting each channel's predicted error.
    pub after: Vec<Vec<f64>>,
}

/// One residue's rms before and after, deg/h, and their ratio.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResidueStats {
    /// Which residue.
    pub residue: String,
    /// RMS (about zero) before compensation, deg/h.
    pub rms_before: f64,
    /// RMS (about zero) after compensation, deg/h.
    pub rms_after: f64,
    /// `rms_before / rms_after`.
    pub reduction: f64,
}

impl ResidueSeries {
    /// Residues of `outputs` (one series per gyro, deg/h, per row) before
    /// and after subtracting `predicted` errors.
    ///
    /// ```
    /// use dtg_vib::unit_sensor::ResidueSeries;
    /// let unit = nav_sensors::unit::Unit::paper();
    /// // An error of 1 deg/h on channel X only: K0 = x0 − x1 and K1 = x0 − x2 see it.
    /// let outputs: Vec<Vec<f64>> = (0..6).map(|k| vec![if k == 0 { 1.0 } else { 0.0 }; 3]).collect();
    /// let s = ResidueSeries::new(&unit, vec![0.0, 0.02, 0.04], &outputs, &outputs);
    /// assert_eq!(s.before[0], vec![1.0; 3]);
    /// assert_eq!(s.after[0], vec![0.0; 3]);
    /// let stats = s.stats(&[0, 1, 2]);
    /// assert_eq!((stats[0].residue.as_str(), stats[0].rms_before), ("K0", 1.0));
    /// ```
    #[track_caller]
    pub fn new(unit: &Unit, t: Vec<f64>, outputs: &[Vec<f64>], predicted: &[Vec<f64>]) -> Self {
        let n = t.len();
        assert!(
            outputs.iter().chain(predicted).all(|s| s.len() == n),
            "one value per row"
        );
        let names = unit.residue_names().to_vec();
        let mut before = vec![Vec::with_capacity(n); names.len()];
        let mut after = vec![Vec::with_capacity(n); names.len()];
        let (mut m, mut c) = (vec![0.0; outputs.len()], vec![0.0; outputs.len()]);
        for i in 0..n {
            for k in 0..outputs.len() {
                m[k] = outputs[k][i];
                c[k] = outputs[k][i] - predicted[k][i];
            }
            for (s, v) in before.iter_mut().zip(unit.residues(&m)) {
                s.push(v);
            }
            for (s, v) in after.iter_mut().zip(unit.residues(&c)) {
                s.push(v);
            }
        }
        Self {
            names,
            t,
            before,
            after,
        }
    }

    /// RMS before and after over the given rows, per residue.
    pub fn stats(&self, rows: &[usize]) -> Vec<ResidueStats> {
        let rms = |s: &[f64]| {
            (rows.iter().map(|&i| s[i] * s[i]).sum::<f64>() / rows.len().max(1) as f64).sqrt()
        };
        self.names
            .iter()
            .enumerate()
            .map(|(k, name)| {
                let (b, a) = (rms(&self.before[k]), rms(&self.after[k]));
                ResidueStats {
                    residue: name.clone(),
                    rms_before: b,
                    rms_after: a,
                    reduction: b / a,
                }
            })
            .collect()
    }
}

/// The rms of several residues together (before or after, as `rms` picks):
/// the one figure a campaign compares models by.
pub fn pooled(stats: &[ResidueStats], rms: fn(&ResidueStats) -> f64) -> f64 {
    (stats.iter().map(|s| rms(s).powi(2)).sum::<f64>() / stats.len().max(1) as f64).sqrt()
}
