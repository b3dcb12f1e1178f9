//! k-means settings: which seeding, which Lloyd iterations, how many runs.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::error::KMeansError;
use crate::check::positive;

/// Which Lloyd iterations follow the (shared, seeded) k-means++ start.
///
/// ```
/// use rbf::select::kmeans::KMeansAlgorithm;
/// assert_eq!(KMeansAlgorithm::default(), KMeansAlgorithm::Lloyd);
/// assert_eq!("linfa".parse::<KMeansAlgorithm>().unwrap(), KMeansAlgorithm::Linfa);
/// assert_eq!(serde_json::to_string(&KMeansAlgorithm::Lloyd).unwrap(), "\"lloyd\"");
/// assert!("elkan".parse::<KMeansAlgorithm>().unwrap_err().to_string().contains("lloyd, linfa"));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KMeansAlgorithm {
    /// [`lloyd`]: distances by one f32 faer product per iteration (near ties in f64), centroids as plain means,
    /// scikit-learn's stopping rule (`tolerance` relative to the mean feature variance).
    /// Parallel as the fit's [`Par`].
    #[default]
    Lloyd,
    /// linfa-clustering's `KMeans` (its update counts the old centroid as one more
    /// member; `tolerance` is absolute, on the Euclidean norm of the centroids' movement).
    /// Runs on rayon's global pool.
    Linfa,
}

impl KMeansAlgorithm {
    /// Every algorithm, in the order of [`KMeansAlgorithm::NAMES`].
    pub const ALL: [KMeansAlgorithm; 2] = [KMeansAlgorithm::Lloyd, KMeansAlgorithm::Linfa];
    /// The names [`FromStr`] accepts.
    pub const NAMES: [&'static str; 2] = ["lloyd", "linfa"];

    /// The name of this algorithm.
    ///
    /// ```
    /// assert_eq!(rbf::KMeansAlgorithm::Linfa.name(), "linfa");
    /// ```
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl fmt::Display for KMeansAlgorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A k-means algorithm name that [`KMeansAlgorithm::from_str`] does not know.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown k-means algorithm {name:?}; valid names: {}", KMeansAlgorithm::NAMES.join(", "))]
pub struct UnknownKMeansAlgorithm {
    /// The name given.
    pub name: String,
}

impl FromStr for KMeansAlgorithm {
    type Err = UnknownKMeansAlgorithm;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|a| a.name() == s)
            .ok_or_else(|| UnknownKMeansAlgorithm {
                name: s.to_string(),
            })
    }
}

/// Settings of a k-means run.
///
/// `n_runs` (scikit-learn's `n_init`) defaults to 1 with greedy k-means++ seeding, as
/// scikit-learn's `KMeans` defaults (`n_init="auto"`; linfa's default is 10 plain
/// k-means++ runs): on the blob sets of `tests/kmeans_blobs.rs` one greedy start reaches
/// scikit-learn's inertia on every set; raise it when the centres themselves matter.
///
/// ```
/// let s = rbf::select::kmeans::KMeansSettings::new(20);
/// assert_eq!((s.n_runs, s.max_iterations), (1, 300));
/// assert_eq!(s.algorithm, rbf::KMeansAlgorithm::Lloyd);
/// assert_eq!(s.init, rbf::KMeansInit::GreedyKMeansPlusPlus);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KMeansSettings {
    /// Number of clusters (centres).
    pub n_centres: usize,
    /// Independent seeded starts (scikit-learn's `n_init`); the lowest inertia wins.
    pub n_runs: usize,
    /// Lloyd iterations per start.
    pub max_iterations: u64,
    /// Convergence tolerance on the centroids' movement: for [`KMeansAlgorithm::Lloyd`]
    /// relative (stop once the summed squared movement is at most `tolerance` × the mean
    /// variance of the input columns, scikit-learn's rule), for [`KMeansAlgorithm::Linfa`]
    /// absolute (linfa's rule). 1e-4 is both libraries' default.
    pub tolerance: f64,
    /// Whose Lloyd iterations run (default [`KMeansAlgorithm::Lloyd`]).
    pub algorithm: KMeansAlgorithm,
    /// How each run's start is drawn (default [`KMeansInit::GreedyKMeansPlusPlus`]).
    pub init: KMeansInit,
}

impl KMeansSettings {
    /// Defaults for `n_centres` clusters.
    ///
    /// ```
    /// assert_eq!(rbf::select::kmeans::KMeansSettings::new(3).tolerance, 1e-4);
    /// ```
    pub fn new(n_centres: usize) -> Self {
        Self {
            n_centres,
            n_runs: 1,
            max_iterations: 300,
            tolerance: 1e-4,
            algorithm: KMeansAlgorithm::default(),
            init: KMeansInit::default(),
        }
    }

    /// The same settings with another seeding.
    ///
    /// ```
    /// use rbf::{KMeansInit, KMeansSettings};
    /// let s = KMeansSettings::new(5).init(KMeansInit::GreedyKMeansPlusPlus);
    /// assert_eq!(s.init, KMeansInit::GreedyKMeansPlusPlus);
    /// ```
    pub fn init(self, init: KMeansInit) -> Self {
        Self { init, ..self }
    }

    /// The same settings with `n_runs` starts (scikit-learn's `n_init`).
    ///
    /// ```
    /// assert_eq!(rbf::KMeansSettings::new(5).n_init(4).n_runs, 4);
    /// ```
    pub fn n_init(self, n_runs: usize) -> Self {
        Self { n_runs, ..self }
    }

    /// Checks the settings by linfa-clustering's rules (which hold for both
    /// algorithms): at least one cluster, one run and one iteration, a finite positive
    /// tolerance. [`crate::RbfParams`]' `check` applies the same rules with its own
    /// error variants.
    ///
    /// # Errors
    /// The first rule broken, as a [`KMeansError`].
    ///
    /// ```
    /// use rbf::{KMeansSettings, select::kmeans::KMeansError};
    /// assert!(KMeansSettings::new(2).check().is_ok());
    /// assert_eq!(KMeansSettings::new(0).check(), Err(KMeansError::NoClusters));
    /// ```
    pub fn check(&self) -> Result<(), KMeansError> {
        if self.n_centres == 0 {
            return Err(KMeansError::NoClusters);
        }
        if self.n_runs == 0 {
            return Err(KMeansError::NoRuns);
        }
        if self.max_iterations == 0 {
            return Err(KMeansError::NoIterations);
        }
        if !positive(self.tolerance) {
            return Err(KMeansError::Tolerance {
                value: self.tolerance,
            });
        }
        Ok(())
    }

    /// The same settings with another algorithm.
    ///
    /// ```
    /// use rbf::{KMeansAlgorithm, KMeansSettings};
    /// let s = KMeansSettings::new(5).algorithm(KMeansAlgorithm::Linfa);
    /// assert_eq!((s.n_centres, s.algorithm), (5, KMeansAlgorithm::Linfa));
    /// ```
    pub fn algorithm(self, algorithm: KMeansAlgorithm) -> Self {
        Self { algorithm, ..self }
    }
}

/// How the start of each k-means run is drawn.
///
/// ```
/// use rbf::KMeansInit;
/// assert_eq!("greedy".parse::<KMeansInit>().unwrap(), KMeansInit::GreedyKMeansPlusPlus);
/// assert_eq!(KMeansInit::KMeansPlusPlus.to_string(), "plusplus");
/// assert!("random".parse::<KMeansInit>().is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KMeansInit {
    /// k-means++ (Arthur & Vassilvitskii 2007): each next centre one D² draw
    /// ([`super::kmeans_plusplus`]; the draws linfa's `KMeansPlusPlus` makes).
    KMeansPlusPlus,
    /// Greedy k-means++, scikit-learn's default and this library's: 2 + ⌊ln k⌋ D² draws
    /// per centre, the one that lowers the potential most is kept
    /// ([`super::greedy_kmeans_plusplus`]). With one run it finds all 80 blobs of the
    /// 8 blob sets of `tests/kmeans_blobs.rs`, where plain k-means++ misses one.
    #[default]
    GreedyKMeansPlusPlus,
}

impl KMeansInit {
    /// Every seeding, in the order of [`KMeansInit::NAMES`].
    pub const ALL: [KMeansInit; 2] = [KMeansInit::KMeansPlusPlus, KMeansInit::GreedyKMeansPlusPlus];
    /// The names [`FromStr`] accepts.
    pub const NAMES: [&'static str; 2] = ["plusplus", "greedy"];

    /// The name of this seeding.
    ///
    /// ```
    /// assert_eq!(rbf::KMeansInit::GreedyKMeansPlusPlus.name(), "greedy");
    /// ```
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl fmt::Display for KMeansInit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A k-means seeding name that [`KMeansInit::from_str`] does not know.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown k-means seeding {name:?}; valid names: {}", KMeansInit::NAMES.join(", "))]
pub struct UnknownKMeansInit {
    /// The name given.
    pub name: String,
}

impl FromStr for KMeansInit {
    type Err = UnknownKMeansInit;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|a| a.name() == s)
            .ok_or_else(|| UnknownKMeansInit {
                name: s.to_string(),
            })
    }
}
