//! Estimates a user acts on, with their uncertainty: physical coefficients
//! estimated with the RBF network as a nuisance that must not absorb them
//! (cross-fitted partialling out), and standard errors that hold for the
//! coloured, autocorrelated residuals of a vibration test (Newey–West).
//!
//! The model is partially linear: y = Zθ + g(x) + e, with Z the effect
//! columns, x the acceleration window and g the network. Fitting θ and g
//! jointly lets g take the part of Zθ that happens to correlate with the
//! window on the training rows (a temperature that rose while the vibration
//! level stepped up), and the coefficient shrinks. Partialling out (Robinson
//! 1988; Chernozhukov et al. 2018) instead projects y and each column of Z on
//! the network's function space fitted on one block of rows, takes the
//! residuals on another block, and regresses one residual on the other: what
//! the network can predict of Z from the window is removed from both sides,
//! and what it merely memorised on its own block is not.

mod blocks;
pub mod derived;
mod hac;

pub use blocks::{Blocks, residualise};
pub use derived::{Derived, DerivedError};
pub use hac::{HacFit, andrews_bandwidth, hac_regression};

use serde::{Deserialize, Serialize};

/// Why an inference could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InferenceError {
    /// Fewer rows than the regression needs.
    #[error("{rows} rows, need at least {need}")]
    TooFewRows { rows: usize, need: usize },
    /// A regressor is (nearly) a combination of the ones before it.
    #[error("regressor {column} is (nearly) a combination of the ones before it")]
    Collinear { column: usize },
    /// A value is NaN or infinite.
    #[error("a value is not finite")]
    NonFinite,
}

/// An estimated coefficient with its uncertainty, in `unit`.
///
/// ```
/// use sysid::inference::Coefficient;
/// let c = Coefficient::new(0.8, 0.05, [0.7, 0.9], "deg/h/°C");
/// assert!(c.covers(0.75));
/// assert_eq!(serde_json::to_value(&c).unwrap()["ci95"][1], 0.9);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Coefficient {
    /// The estimate.
    pub value: f64,
    /// Its unit.
    pub unit: String,
    /// Standard error (HAC), same unit.
    pub se: f64,
    /// 95% confidence interval, same unit.
    pub ci95: [f64; 2],
    /// Its covariance with each coefficient of the same fit, in the fit's
    /// effect order (this one's own entry is `se`²): the row of the joint
    /// covariance that intervals of derived quantities need
    /// ([`derived`]). Empty where the fit kept none (files written before).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub cov: Vec<f64>,
}

impl Coefficient {
    /// A coefficient from its parts.
    pub fn new(value: f64, se: f64, ci95: [f64; 2], unit: impl Into<String>) -> Self {
        Self {
            value,
            unit: unit.into(),
            se,
            ci95,
            cov: Vec::new(),
        }
    }

    /// The same coefficient with its row of the fit's joint covariance.
    pub fn with_covariance(mut self, row: Vec<f64>) -> Self {
        self.cov = row;
        self
    }

    /// Whether the 95% interval contains `v`.
    pub fn covers(&self, v: f64) -> bool {
        self.ci95[0] <= v && v <= self.ci95[1]
    }
}
