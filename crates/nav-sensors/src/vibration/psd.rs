//! Single-sided acceleration PSD tables (g²/Hz against Hz), log-log interpolated.

use serde::{Deserialize, Serialize};

/// What is wrong with a PSD table.
///
/// ```
/// let err = nav_sensors::vibration::PsdTable::new(vec![[100.0, 0.1], [50.0, 0.1]]).unwrap_err();
/// assert!(err.to_string().contains("does not increase"));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PsdError {
    /// Fewer than two breakpoints.
    #[error("a PSD table needs at least two breakpoints, got {count}")]
    TooFewPoints {
        /// Number of breakpoints given.
        count: usize,
    },
    /// A frequency or density that is not finite and positive.
    #[error(
        "PSD breakpoint {index} ({frequency_hz} Hz, {density_g2_hz} g²/Hz) must be finite and positive"
    )]
    NotPositive {
        /// Breakpoint index (0-based).
        index: usize,
        /// Its frequency, Hz.
        frequency_hz: f64,
        /// Its density, g²/Hz.
        density_g2_hz: f64,
    },
    /// Frequencies not strictly increasing.
    #[error("PSD breakpoint {index} at {frequency_hz} Hz does not increase on the previous one")]
    NotIncreasing {
        /// Breakpoint index (0-based).
        index: usize,
        /// Its frequency, Hz.
        frequency_hz: f64,
    },
}

/// A single-sided acceleration PSD: breakpoints `(Hz, g²/Hz)`, straight lines
/// between them on log-log axes (constant dB/octave), zero outside.
/// Serialised as a list of `[Hz, g²/Hz]` pairs.
///
/// ```
/// use nav_sensors::vibration::PsdTable;
/// let p = PsdTable::navmat_p9492();
/// assert_eq!(p.density(200.0), 0.04);
/// assert!((p.density(40.0) - 0.02).abs() < 1e-12);      // +3 dB/octave: ∝ f
/// assert_eq!(p.density(10.0), 0.0);
/// let exact = (1.5 + 10.8 + 14.0 * (2000.0f64 / 350.0).ln()).sqrt();
/// assert!((p.grms() - exact).abs() < 1e-12);            // ≈ 6.06 g
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<[f64; 2]>", into = "Vec<[f64; 2]>")]
pub struct PsdTable {
    points: Vec<[f64; 2]>,
}

impl TryFrom<Vec<[f64; 2]>> for PsdTable {
    type Error = PsdError;
    fn try_from(points: Vec<[f64; 2]>) -> Result<Self, PsdError> {
        Self::new(points)
    }
}

impl From<PsdTable> for Vec<[f64; 2]> {
    fn from(p: PsdTable) -> Self {
        p.points
    }
}

impl PsdTable {
    /// A table from `[Hz, g²/Hz]` breakpoints.
    ///
    /// ```
    /// use nav_sensors::vibration::{PsdError, PsdTable};
    /// assert!(PsdTable::new(vec![[10.0, 0.01], [100.0, 0.01]]).is_ok());
    /// assert!(matches!(PsdTable::new(vec![[10.0, 0.01]]), Err(PsdError::TooFewPoints { count: 1 })));
    /// ```
    pub fn new(points: Vec<[f64; 2]>) -> Result<Self, PsdError> {
        if points.len() < 2 {
            return Err(PsdError::TooFewPoints {
                count: points.len(),
            });
        }
        for (index, &[f, s]) in points.iter().enumerate() {
            if !(f.is_finite() && s.is_finite() && f > 0.0 && s > 0.0) {
                return Err(PsdError::NotPositive {
                    index,
                    frequency_hz: f,
                    density_g2_hz: s,
                });
            }
            if index > 0 && f <= points[index - 1][0] {
                return Err(PsdError::NotIncreasing {
                    index,
                    frequency_hz: f,
                });
            }
        }
        Ok(Self { points })
    }

    /// The NAVMAT P-9492 random-vibration screening profile: 20–80 Hz rising
    /// +3 dB/octave from 0.01 g²/Hz, 80–350 Hz flat at 0.04 g²/Hz, 350–2000 Hz
    /// falling −3 dB/octave to 0.007 g²/Hz; 6.06 g rms.
    ///
    /// ```
    /// let p = nav_sensors::vibration::PsdTable::navmat_p9492();
    /// assert_eq!(p.points().len(), 4);
    /// ```
    pub fn navmat_p9492() -> Self {
        Self::new(vec![
            [20.0, 0.01],
            [80.0, 0.04],
            [350.0, 0.04],
            [2000.0, 0.007],
        ])
        .expect("valid built-in table")
    }

    /// The breakpoints, `[Hz, g²/Hz]`.
    ///
    /// ```
    /// assert_eq!(nav_sensors::vibration::PsdTable::navmat_p9492().points()[1], [80.0, 0.04]);
    /// ```
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// Lowest and highest frequency of the table, Hz.
    ///
    /// ```
    /// assert_eq!(nav_sensors::vibration::PsdTable::navmat_p9492().band_hz(), (20.0, 2000.0));
    /// ```
    pub fn band_hz(&self) -> (f64, f64) {
        (self.points[0][0], self.points[self.points.len() - 1][0])
    }

    /// The table with every density multiplied by `10^(db/10)`.
    ///
    /// ```
    /// let p = nav_sensors::vibration::PsdTable::navmat_p9492().scaled_db(-6.0);
    /// assert!((p.grms() / nav_sensors::vibration::PsdTable::navmat_p9492().grms() - 10f64.powf(-0.3)).abs() < 1e-12);
    /// ```
    pub fn scaled_db(&self, db: f64) -> Self {
        let k = 10f64.powf(db / 10.0);
        Self {
            points: self.points.iter().map(|&[f, s]| [f, s * k]).collect(),
        }
    }

    /// The density at `f_hz`, g²/Hz (log-log interpolation; zero outside the table).
    ///
    /// ```
    /// let p = nav_sensors::vibration::PsdTable::navmat_p9492();
    /// assert!((p.density(700.0) - 0.02).abs() < 1e-12); // −3 dB/octave from 350 Hz
    /// ```
    pub fn density(&self, f_hz: f64) -> f64 {
        let (lo, hi) = self.band_hz();
        if !(f_hz >= lo && f_hz <= hi) {
            return 0.0;
        }
        let j = self
            .points
            .partition_point(|p| p[0] <= f_hz)
            .clamp(1, self.points.len() - 1);
        let [f1, s1] = self.points[j - 1];
        let [f2, s2] = self.points[j];
        let slope = (s2 / s1).ln() / (f2 / f1).ln();
        s1 * (f_hz / f1).powf(slope)
    }

    /// The rms acceleration of the table, g: the exact integral of the
    /// piecewise power law, `√∫S df`.
    ///
    /// ```
    /// let flat = nav_sensors::vibration::PsdTable::new(vec![[10.0, 0.01], [110.0, 0.01]]).unwrap();
    /// assert!((flat.grms() - 1.0).abs() < 1e-12);
    /// ```
    pub fn grms(&self) -> f64 {
        self.points
            .windows(2)
            .map(|w| {
                let ([f1, s1], [f2, s2]) = (w[0], w[1]);
                let b = (s2 / s1).ln() / (f2 / f1).ln();
                if (b + 1.0).abs() < 1e-12 {
                    s1 * f1 * (f2 / f1).ln()
                } else {
                    s1 * f1 / (b + 1.0) * ((f2 / f1).powf(b + 1.0) - 1.0)
                }
            })
            .sum::<f64>()
            .sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn navmat_slopes_are_plus_and_minus_3_db_per_octave() {
        let p = PsdTable::navmat_p9492();
        let db = |a: f64, b: f64| 10.0 * (p.density(b) / p.density(a)).log10();
        assert!((db(20.0, 40.0) - 3.0103).abs() < 1e-3);
        assert!((db(500.0, 1000.0) + 3.0103).abs() < 1e-3);
        assert!((p.grms() - 6.058).abs() < 1e-3, "{}", p.grms());
    }

    #[test]
    fn grms_matches_a_numerical_integral() {
        let p = PsdTable::new(vec![[5.0, 0.02], [30.0, 0.1], [60.0, 0.1], [200.0, 0.001]]).unwrap();
        let n = 2_000_000;
        let (lo, hi) = p.band_hz();
        let df = (hi - lo) / n as f64;
        let num: f64 = (0..n)
            .map(|k| p.density(lo + (k as f64 + 0.5) * df) * df)
            .sum();
        assert!((num.sqrt() - p.grms()).abs() < 1e-6 * p.grms());
    }

    #[test]
    fn bad_tables_are_typed_errors() {
        assert!(matches!(
            PsdTable::new(vec![[20.0, 0.01], [10.0, 0.01]]),
            Err(PsdError::NotIncreasing { index: 1, .. })
        ));
        assert!(matches!(
            PsdTable::new(vec![[20.0, 0.0], [30.0, 0.01]]),
            Err(PsdError::NotPositive { index: 0, .. })
        ));
        let from_toml: Result<PsdTable, _> = serde_json::from_str("[[20.0, 0.01]]");
        assert!(from_toml.is_err());
    }
}
