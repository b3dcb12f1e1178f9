//! What a model keeps of the options that fitted it.

use crate::error::DtgVibError;
use rbf::Kernel;
use serde::{Deserialize, Serialize};

/// How centres are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CentreMethod {
    /// OLS forward selection by error-reduction ratio (Chen, Cowan & Grant 1991).
    Ols,
    /// k-means centroids.
    #[serde(rename = "kmeans")]
    KMeans,
}

impl std::str::FromStr for CentreMethod {
    type Err = DtgVibError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "ols" => Ok(CentreMethod::Ols),
            "kmeans" => Ok(CentreMethod::KMeans),
            other => Err(DtgVibError::InvalidOption {
                name: "centers",
                value: other.to_string(),
                reason: "use ols or kmeans",
            }),
        }
    }
}

/// What a model keeps of its [`FitOptions`](crate::fit::FitOptions) besides the pre-processing,
/// split and effects it stores anyway: enough to fit it again the same way
/// (the diagnosis cross-fits and tries settings).
///
/// ```
/// let s = dtg_vib::fit::FitOptions::default().settings();
/// assert_eq!(s, dtg_vib::fit::FitSettings::default());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FitSettings {
    /// Centre selection.
    pub centres: CentreMethod,
    /// Largest number of centres tried.
    pub max_centres: usize,
    /// OLS candidates.
    pub candidates: usize,
    /// Gaussian widths tried, as multiples of the median distance between windows.
    pub width_scales: Vec<f64>,
    /// Ridge λ on the output weights.
    pub ridge: f64,
    /// Folds of the inner cross-validation.
    pub inner_folds: usize,
    /// The kernel.
    pub kernel: Kernel,
    /// Seed.
    pub seed: u64,
}

impl Default for FitSettings {
    /// The defaults of every fit command.
    fn default() -> Self {
        Self {
            centres: CentreMethod::Ols,
            max_centres: 60,
            candidates: 400,
            width_scales: vec![0.5, 1.0, 2.0],
            ridge: 1e-8,
            inner_folds: 3,
            kernel: Kernel::Gaussian,
            seed: 1,
        }
    }
}
