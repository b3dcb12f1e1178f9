//! What decides a fit besides the data: the recipe a model stores and hands
//! back to be fitted again the same way, and the options of one fit.

use crate::error::SysidError;
use crate::preprocess::Preprocess;
use crate::split::Holdout;
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
    type Err = SysidError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "ols" => Ok(CentreMethod::Ols),
            "kmeans" => Ok(CentreMethod::KMeans),
            other => Err(SysidError::InvalidOption {
                // The command line's flag (`--centers`, the alias the CLI keeps).
                name: "centers",
                value: other.to_string(),
                reason: "use ols or kmeans",
            }),
        }
    }
}

/// How the networks are chosen: what a model keeps of its options besides
/// the pre-processing, split and effects of its [`Recipe`].
///
/// ```
/// let s = sysid::FitSettings::default();
/// assert_eq!((s.max_centres, s.inner_folds), (60, 3));
/// assert!(!s.shared_centres);
/// let old: sysid::FitSettings = serde_json::from_str(r#"{"max_centres": 60}"#).unwrap();
/// assert!(!old.shared_centres, "files without the key were fitted per channel");
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FitSettings {
    /// Centre selection.
    pub centres: CentreMethod,
    /// Largest number of centres tried.
    pub max_centres: usize,
    /// OLS candidates: a seeded subsample of this many training windows.
    pub candidates: usize,
    /// Gaussian widths tried, as multiples of the median distance between windows.
    pub width_scales: Vec<f64>,
    /// Ridge λ on the output weights.
    pub ridge: f64,
    /// Folds of the blocked cross-validation inside the training rows.
    pub inner_folds: usize,
    /// The kernel.
    pub kernel: Kernel,
    /// Seed of every random choice (candidate subsample, k-means).
    pub seed: u64,
    /// The network inputs and prediction smoothers to choose among, by
    /// validation rms under the Allan-deviation constraint
    /// ([`ModelChoice`]); none: the pre-processing's as they are.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub choice: Option<ModelChoice>,
    /// One centre selection (and width and number of centres) for every
    /// channel, on their targets together (summed ERR, the validation error
    /// per channel normalised), each channel keeping its own least-squares
    /// weights; `false` (the default): a selection per channel. Shared, a
    /// z-axis model extrapolated to the flight 3× worse (the campaign test
    /// `a_z_run_model_warns_on_the_flight_and_its_fade_holds_the_residues`),
    /// so it is asked for. Models written before the field was stored were
    /// fitted per channel and read as such.
    #[serde(default = "per_channel_in_older_files")]
    pub shared_centres: bool,
}

/// What a model file without `shared_centres` was fitted with.
fn per_channel_in_older_files() -> bool {
    false
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
            choice: None,
            shared_centres: false,
        }
    }
}

impl FitSettings {
    /// Refuses settings no fit can use, naming the setting.
    ///
    /// ```
    /// let s = sysid::FitSettings { inner_folds: 1, ..Default::default() };
    /// assert!(s.check().unwrap_err().to_string().contains("at least 2 folds"));
    /// ```
    pub fn check(&self) -> Result<(), SysidError> {
        let bad = |name, value: String, reason| {
            Err(SysidError::InvalidOption {
                name,
                value,
                reason,
            })
        };
        if self.max_centres == 0 {
            return bad("max centres", "0".into(), "need at least one centre");
        }
        if self.width_scales.is_empty()
            || self
                .width_scales
                .iter()
                .any(|s| !(s.is_finite() && *s > 0.0))
        {
            return bad(
                "width scales",
                format!("{:?}", self.width_scales),
                "need positive finite multiples",
            );
        }
        if !(self.ridge.is_finite() && self.ridge >= 0.0) {
            return bad(
                "ridge",
                self.ridge.to_string(),
                "must be a finite number ≥ 0",
            );
        }
        if self.inner_folds < 2 {
            return bad(
                "inner folds",
                self.inner_folds.to_string(),
                "cross-validation needs at least 2 folds",
            );
        }
        Ok(())
    }
}

/// Everything that decides a fit besides the data and the sensor: the
/// pre-processing, the split, each channel's effects and the network
/// settings. A model stores its recipe and hands it back
/// ([`crate::Model::recipe`]), so the loop fits it again the same way (the
/// diagnosis's mirror, a longer window) without rebuilding it.
///
/// ```
/// let mut r = sysid::Recipe::<String>::new(2);
/// r.effects[1].push("temp".to_string());
/// assert_eq!((r.effects_of(0).len(), r.effects_of(1).len()), (0, 1));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Recipe<E> {
    /// Pre-processing (filters, windows).
    pub preprocess: Preprocess,
    /// Training/validation split within each record.
    pub split: Holdout,
    /// Each channel's effects, in the sensor's channel order.
    pub effects: Vec<Vec<E>>,
    /// How the networks are chosen.
    pub settings: FitSettings,
}

impl<E> Recipe<E> {
    /// The default recipe for `channels` channels, without effects.
    pub fn new(channels: usize) -> Self {
        Self {
            preprocess: Preprocess::default(),
            split: Holdout::default(),
            effects: (0..channels).map(|_| Vec::new()).collect(),
            settings: FitSettings::default(),
        }
    }

    /// The effects of channel `channel` (none for a channel it does not name).
    pub fn effects_of(&self, channel: usize) -> &[E] {
        self.effects.get(channel).map_or(&[], Vec::as_slice)
    }
}

/// Everything one fit can be told: the recipe and, of several records, the
/// one that only validates.
///
/// ```
/// let o = sysid::FitOptions::<String>::new(6);
/// assert_eq!(o.recipe.effects.len(), 6);
/// assert!(o.validate_on.is_none());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions<E> {
    /// The recipe.
    pub recipe: Recipe<E>,
    /// Of several records, the one that only validates (the others only
    /// train); `None`: the recipe's split within each record.
    pub validate_on: Option<String>,
}

impl<E> FitOptions<E> {
    /// The default options for `channels` channels.
    pub fn new(channels: usize) -> Self {
        Self {
            recipe: Recipe::new(channels),
            validate_on: None,
        }
    }
}

/// The candidates a fit chooses among (a setting: the model keeps it, so a
/// refit by the explain loop chooses again).
///
/// ```
/// let c = sysid::fit::ModelChoice::default();
/// assert_eq!(c.inputs.len(), 2);
/// assert_eq!(c.smoothers.len(), 5); // none, 0.5, 0.2, 0.1, 0.05 Hz
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelChoice {
    /// Inputs tried.
    pub inputs: Vec<crate::input::ModelInput>,
    /// Smoothers tried (`None`: no smoother).
    pub smoothers: Vec<Option<crate::smoother::Smoother>>,
    /// On a record large enough to choose on a sample, also try one centre
    /// selection for every channel there, and fit the record so where it
    /// costs at most `SHARED_CENTRES_TOLERANCE` ([`crate::fit`]).
    #[serde(default = "yes")]
    pub try_shared_centres: bool,
}

fn yes() -> bool {
    true
}

impl Default for ModelChoice {
    /// Both inputs, and no smoother or one of [`crate::smoother::SMOOTHER_LADDER_HZ`].
    fn default() -> Self {
        Self {
            inputs: crate::input::ModelInput::ALL.to_vec(),
            smoothers: std::iter::once(None)
                .chain(
                    crate::smoother::SMOOTHER_LADDER_HZ
                        .iter()
                        .map(|&cutoff_hz| Some(crate::smoother::Smoother { cutoff_hz })),
                )
                .collect(),
            try_shared_centres: true,
        }
    }
}
