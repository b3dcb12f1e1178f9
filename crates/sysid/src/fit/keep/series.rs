//! The series the keep step holds to their bias instability: every channel
//! and every residue the sensor defines ([`crate::Sensor::residues`], an
//! inertial unit's parity residues), each as weights over the channels.

use crate::sensor::Sensor;

/// A judged series: its name and one weight per channel.
pub(super) struct Series {
    pub(super) name: String,
    pub(super) weights: Vec<f64>,
}

/// Every channel (a unit weight) and then every residue of `sensor`.
pub(super) fn judged_series<S: Sensor>(sensor: &S) -> Vec<Series> {
    let channels = sensor.channels();
    let n = channels.len();
    let own = channels.iter().enumerate().map(|(k, c)| Series {
        name: c.to_string(),
        weights: (0..n).map(|j| f64::from(u8::from(j == k))).collect(),
    });
    let residues = sensor
        .residues()
        .into_iter()
        .filter(|(_, w)| w.len() == n)
        .map(|(name, weights)| Series { name, weights });
    own.chain(residues).collect()
}

/// `Σ_k w_k · series_k(i)` over `range` of each channel's `series`.
pub(super) fn combine(
    weights: &[f64],
    series: &[&[f64]],
    range: std::ops::Range<usize>,
) -> Vec<f64> {
    range
        .map(|i| {
            weights
                .iter()
                .zip(series)
                .filter(|(w, _)| **w != 0.0)
                .map(|(w, s)| w * s[i])
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_residue_is_its_weighted_sum() {
        let a = [1.0, 2.0, 3.0];
        let b = [10.0, 20.0, 30.0];
        assert_eq!(combine(&[1.0, -1.0], &[&a, &b], 1..3), vec![-18.0, -27.0]);
    }

    #[test]
    fn channels_then_residues() {
        let s = judged_series(&crate::example::Line);
        assert_eq!(s.len(), 1);
        assert_eq!(
            (s[0].name.as_str(), s[0].weights.as_slice()),
            ("y", &[1.0][..])
        );
    }
}
