//! What a model keeps of the options that fitted it: the network settings
//! and the whole recipe it hands back to be fitted again the same way.

use crate::effects::Effect;
use crate::error::DtgVibError;
use crate::pipeline::Preprocess;
use crate::split::Holdout;
use nav_sensors::geometry::Channel;
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

/// How the networks are chosen: the part of [`FitOptions`](crate::fit::FitOptions)
/// a model keeps besides the pre-processing, split and effects of its
/// [`Recipe`].
///
/// ```
/// let o = dtg_vib::fit::FitOptions::default();
/// assert_eq!(o.settings, dtg_vib::fit::FitSettings::default());
/// assert_eq!(o.settings.max_centres, 60);
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

/// Everything that decides a fit besides the data: the pre-processing, the
/// split, each channel's effects and the network settings. A model stores
/// its recipe and hands it back
/// ([`CompensationModel::recipe`](crate::model::CompensationModel::recipe)),
/// so the loop fits it again the same way (the diagnosis's mirror, a longer
/// window) without rebuilding it from the model's parts.
///
/// ```
/// use dtg_vib::fit::FitOptions;
/// use nav_sensors::geometry::Channel;
/// let o = FitOptions {
///     effects: vec!["g_I".parse().unwrap()],
///     add: vec!["Y1=gg_IS".parse().unwrap()],
///     ..FitOptions::default()
/// };
/// let r = o.recipe();
/// assert_eq!(r.effects_of(Channel::X).len(), 1);
/// assert_eq!(r.effects_of(Channel::Y1)[1].id(), "gg_IS");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Recipe {
    /// Pre-processing (filter, window, rate reference).
    pub preprocess: Preprocess,
    /// Training/validation split within each record.
    pub split: Holdout,
    /// Each channel's effects, in X, X1, Y, Y1, Z, Z1 order.
    pub effects: [Vec<Effect>; 6],
    /// How the networks are chosen.
    pub settings: FitSettings,
}

impl Recipe {
    /// The effects of one channel's linear part.
    pub fn effects_of(&self, channel: Channel) -> &[Effect] {
        &self.effects[channel.index()]
    }
}
