//! The six parity residues (paper eq. 6) before and after compensation.
//!
//! Residues are linear combinations of the channels' errors only (the true
//! rate cancels), so they show the gain of a compensation without any rate
//! reference: the paper's Fig. 7.

use nav_sensors::geometry::{Residue, residues};
use serde::Serialize;

/// Residue series on the rows of prepared data, deg/h.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidueSeries {
    /// Time of each row, s.
    pub t: Vec<f64>,
    /// K0..K5 of the pre-processed outputs (calibrated, filtered).
    pub before: [Vec<f64>; 6],
    /// K0..K5 after subtracting each channel's predicted error.
    pub after: [Vec<f64>; 6],
}

/// One residue's rms before and after, deg/h, and their ratio.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ResidueStats {
    /// Which residue.
    pub residue: Residue,
    /// RMS (about zero) before compensation, deg/h.
    pub rms_before: f64,
    /// RMS (about zero) after compensation, deg/h.
    pub rms_after: f64,
    /// `rms_before / rms_after`.
    pub reduction: f64,
}

impl ResidueSeries {
    /// Residues of `outputs` (six channel series, deg/h, per row) before and
    /// after subtracting `predicted` errors.
    ///
    /// ```
    /// use dtg_vib::parity::ResidueSeries;
    /// // An error of 1 deg/h on channel X only: K0 = x0 − x1 and K1 = x0 − x2 see it.
    /// let outputs: [Vec<f64>; 6] = std::array::from_fn(|k| vec![if k == 0 { 1.0 } else { 0.0 }; 3]);
    /// let predicted: [Vec<f64>; 6] = std::array::from_fn(|k| vec![if k == 0 { 1.0 } else { 0.0 }; 3]);
    /// let s = ResidueSeries::new(vec![0.0, 0.02, 0.04], &outputs, &predicted);
    /// assert_eq!(s.before[0], vec![1.0; 3]);
    /// assert_eq!(s.after[0], vec![0.0; 3]);
    /// let stats = s.stats(&[0, 1, 2]);
    /// assert_eq!(stats[0].rms_before, 1.0);
    /// ```
    #[track_caller]
    pub fn new(t: Vec<f64>, outputs: &[Vec<f64>; 6], predicted: &[Vec<f64>; 6]) -> Self {
        let n = t.len();
        assert!(
            outputs.iter().chain(predicted).all(|s| s.len() == n),
            "one value per row"
        );
        let mut before: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(n));
        let mut after: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(n));
        for i in 0..n {
            let m: [f64; 6] = std::array::from_fn(|k| outputs[k][i]);
            let c: [f64; 6] = std::array::from_fn(|k| outputs[k][i] - predicted[k][i]);
            let (kb, ka) = (residues(&m), residues(&c));
            for k in 0..6 {
                before[k].push(kb[k]);
                after[k].push(ka[k]);
            }
        }
        Self { t, before, after }
    }

    /// RMS before and after over the given rows, per residue K0..K5.
    pub fn stats(&self, rows: &[usize]) -> Vec<ResidueStats> {
        Residue::ALL
            .iter()
            .map(|&r| {
                let k = r.index();
                let rms = |s: &[f64]| {
                    (rows.iter().map(|&i| s[i] * s[i]).sum::<f64>() / rows.len().max(1) as f64)
                        .sqrt()
                };
                let (b, a) = (rms(&self.before[k]), rms(&self.after[k]));
                ResidueStats {
                    residue: r,
                    rms_before: b,
                    rms_after: a,
                    reduction: b / a,
                }
            })
            .collect()
    }
}
