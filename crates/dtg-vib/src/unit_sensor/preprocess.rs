//! How a record is prepared for the models, as model files and the
//! command line say it: the loop's pre-processing ([`sysid::Preprocess`])
//! with the unit's rate reference, which the plug-in removes from every
//! gyro (each output less the reference rate along its input axis).

use crate::error::DtgVibError;
use nav_sensors::sim::Site;
use serde::{Deserialize, Serialize};
use sysid::{FilterSpec, WindowSpec};

/// The angular rate subtracted from every channel (eq. 4) so the model
/// learns errors only: the true rate where known, the unit's own
/// least-squares rate on a moving redundant unit. Without one, the
/// constant rate of a stationary test is absorbed by each channel's bias.
///
/// ```
/// use dtg_vib::unit_sensor::RateReference;
/// let r = RateReference::Table { rate_deg_s: [0.0, 0.0, 10.0] };
/// assert_eq!(r.rate_deg_h().unwrap().z, 36000.0);
/// assert!(RateReference::None.rate_deg_h().is_none());
/// let tetra = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// // A rate common to the gyros leaves nothing in parity.
/// let m: Vec<f64> = tetra.gyros().iter().map(|g| g.input.dot(&nalgebra::Vector3::new(10.0, -3.0, 2.0))).collect();
/// let w = RateReference::Parity.rates_deg_h(&tetra, &[m]).unwrap();
/// assert!((w[0] - nalgebra::Vector3::new(10.0, -3.0, 2.0)).norm() < 1e-9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum RateReference {
    /// No reference.
    #[default]
    None,
    /// Earth rate at a site (latitude, cluster orientation).
    Earth {
        /// The site.
        site: Site,
    },
    /// A known constant table rate in the cluster frame, deg/s.
    Table {
        /// Rate about cluster x, y, z, deg/s.
        rate_deg_s: [f64; 3],
    },
    /// No true rate, on a moving unit of four or more gyros: the unit's own
    /// least-squares rate H⁺m, sample by sample, so each channel's target
    /// is its parity-projected output (P m)_j, P = I − H H⁺. What every
    /// gyro sees alike (the error's component in H's column space, such as
    /// a misalignment common to all gyros) is not observable.
    Parity,
}

/// The one line that says what a parity-referenced model cannot see.
pub const PARITY_NOTE: &str = "each channel's target is its output less the unit's least-squares rate along its input axis (its parity-projected output, P = I - H H+): only the differences between gyros are observable; an error common to the gyros (H's column space: a bias, scale factor, misalignment or delay all gyros share) is not, and is not fitted";

impl RateReference {
    /// Checks the reference can be a rate: a latitude in [−90°, 90°] with
    /// perpendicular x and z axes, or three finite table rates.
    pub fn check(&self) -> Result<(), DtgVibError> {
        let bad = |name, value: String, reason| {
            Err(sysid::SysidError::InvalidOption {
                name,
                value,
                reason,
            }
            .into())
        };
        match self {
            RateReference::None | RateReference::Parity => Ok(()),
            RateReference::Earth { site } => {
                if !(-90.0..=90.0).contains(&site.latitude_deg) {
                    return bad(
                        "latitude",
                        site.latitude_deg.to_string(),
                        "must be a number of degrees in [-90, 90]",
                    );
                }
                if site.orientation.axes_enu().is_none() {
                    return bad(
                        "orientation",
                        format!("{:?}", site.orientation),
                        "the cluster's x and z axes must be perpendicular",
                    );
                }
                Ok(())
            }
            RateReference::Table { rate_deg_s } => {
                if rate_deg_s.iter().all(|w| w.is_finite()) {
                    Ok(())
                } else {
                    bad(
                        "table rate",
                        format!("{rate_deg_s:?}"),
                        "must be three finite rates, deg/s",
                    )
                }
            }
        }
    }

    /// The known constant reference rate in the cluster frame, deg/h
    /// (`None` without one, and for the unit's own rate, which varies).
    pub fn rate_deg_h(&self) -> Option<nalgebra::Vector3<f64>> {
        match self {
            RateReference::None | RateReference::Parity => None,
            RateReference::Earth { site } => site.earth_rate_cluster_deg_h(),
            RateReference::Table { rate_deg_s } => {
                Some(nalgebra::Vector3::from(*rate_deg_s) * 3600.0)
            }
        }
    }

    /// The reference rate at each sample of the gyro outputs `rows`
    /// (deg/h, file order), cluster frame, deg/h; `None` without one.
    pub fn rates_deg_h(
        &self,
        unit: &nav_sensors::unit::Unit,
        rows: &[Vec<f64>],
    ) -> Option<Vec<nalgebra::Vector3<f64>>> {
        match self {
            RateReference::Parity => {
                Some(rows.iter().map(|m| unit.least_squares_rate(m)).collect())
            }
            r => r.rate_deg_h().map(|w| vec![w; rows.len()]),
        }
    }

    /// Whether the reference is a true rate (a known Earth or table rate).
    pub fn is_true_rate(&self) -> bool {
        self.rate_deg_h().is_some()
    }
}

/// How a record is prepared for the models, as a model file stores it:
/// the loop's [`sysid::Preprocess`] and the unit's rate reference.
///
/// ```
/// let p = dtg_vib::unit_sensor::StoredPreprocess::default();
/// assert_eq!(p.window.length(), 50);
/// assert!(p.window.is_auto()); // the signals the records choose
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StoredPreprocess {
    /// Zero-phase low-pass of the gyro outputs and effect columns, or none.
    pub filter: Option<FilterSpec>,
    /// Zero-phase low-pass of the windowed input signals, or none. None by
    /// default: the vibration level the rectified error follows is carried
    /// by the acceleration's energy across the whole 0–25 Hz band, and a
    /// low-pass on the window throws most of it away (measured: residue
    /// reduction 3.7× with a 5-Hz input filter against 4.2× without).
    pub input_filter: Option<FilterSpec>,
    /// Input windows of the RBF.
    pub window: WindowSpec,
    /// Known true rate.
    pub rate_reference: RateReference,
    /// Causal mode: the model runs on-line with three output periods of
    /// latency (60 ms at 50 Hz; the `dtg-onboard` evaluator, the exported
    /// C): the correction of sample n uses samples up to n + 3. The
    /// low-passes are one forward pass started in the steady state of the
    /// first sample instead of forward–backward; the g² terms'
    /// within-interval covariance (ground calibration and effects) keeps
    /// its centred estimate from samples n − 3 … n + 3
    /// (`nav_sensors::dtg::within_interval_covariance`), hence the latency.
    /// Absent in model files written before it: zero-phase.
    #[serde(default)]
    pub causal: bool,
    /// What the networks read of the windows (`raw`: the window;
    /// `statistics`: per signal the current sample, window mean and window
    /// rms, in g). Absent in model files written before it: the window.
    #[serde(default, skip_serializing_if = "sysid::ModelInput::is_raw")]
    pub input: sysid::ModelInput,
    /// 2nd-order Butterworth low-pass of the network part of each predicted
    /// error (zero-phase, or causal in causal mode), or none (absent in
    /// model files written before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub smoother: Option<sysid::Smoother>,
}

impl StoredPreprocess {
    /// The loop's part of it (all but the rate reference, which is the
    /// plug-in's).
    pub fn sysid(&self) -> sysid::Preprocess {
        sysid::Preprocess {
            filter: self.filter,
            input_filter: self.input_filter,
            window: self.window.clone(),
            causal: self.causal,
            input: self.input,
            smoother: self.smoother,
        }
    }

    /// The loop's pre-processing with the unit's rate reference.
    pub fn of(pre: &sysid::Preprocess, rate_reference: RateReference) -> Self {
        Self {
            filter: pre.filter,
            input_filter: pre.input_filter,
            window: pre.window.clone(),
            rate_reference,
            causal: pre.causal,
            input: pre.input,
            smoother: pre.smoother,
        }
    }
}

impl Default for StoredPreprocess {
    /// The loop's default (low-pass of the outputs, unfiltered 50-sample
    /// windows of the signals the records choose, as the CLI's
    /// `--window-signals auto`), no rate reference.
    fn default() -> Self {
        Self::of(&sysid::Preprocess::default(), RateReference::None)
    }
}
