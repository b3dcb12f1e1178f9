//! Train/validation splits: the folds of cross-validation and the single
//! hold-out of an application. Below both [`crate::cv`] and [`crate::model`].

use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_xoshiro::Xoshiro256Plus;
use serde::{Deserialize, Serialize};

/// One train/validation partition (row indices, ascending).
///
/// ```
/// let f = rbf::Fold { train: vec![0, 2], validation: vec![1, 3] };
/// assert_eq!(f.train.len() + f.validation.len(), 4);
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Fold {
    /// Training rows.
    pub train: Vec<usize>,
    /// Validation rows.
    pub validation: Vec<usize>,
}

/// A cross-validation scheme.
///
/// ```
/// use rbf::Split;
/// // the paper's split: even rows train, odd rows validate
/// let f = &Split::Interleaved { k: 2 }.folds(6).unwrap()[0];
/// assert_eq!((f.train.clone(), f.validation.clone()), (vec![0, 2, 4], vec![1, 3, 5]));
/// // blocked with a gap of 1 on each side of the validation block
/// let b = Split::Blocked { k: 3, gap: 1 }.folds(9).unwrap();
/// assert_eq!(b[1].validation, vec![3, 4, 5]);
/// assert_eq!(b[1].train, vec![0, 1, 7, 8]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Split {
    /// Shuffled k-fold (seeded Xoshiro256Plus).
    KFold {
        /// Number of folds.
        k: usize,
        /// Shuffle seed.
        seed: u64,
    },
    /// Fold f validates rows i with i mod k = (f + 1) mod k and trains on the others:
    /// with k = 2 the first fold is the seed paper's even-train/odd-validate split.
    Interleaved {
        /// Number of folds.
        k: usize,
    },
    /// Contiguous blocks; `gap` rows on each side of the validation block are dropped
    /// from training because overlapping windows would leak across the boundary.
    Blocked {
        /// Number of folds.
        k: usize,
        /// Rows dropped on each side of the validation block.
        gap: usize,
    },
}

/// Why a split cannot be made.
///
/// ```
/// let e = rbf::Split::KFold { k: 1, seed: 0 }.folds(10).unwrap_err();
/// assert_eq!(e, rbf::SplitError::TooFewFolds { k: 1 });
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SplitError {
    /// At least two folds are needed.
    #[error("cross-validation needs at least 2 folds, got {k}")]
    TooFewFolds {
        /// Folds asked for.
        k: usize,
    },
    /// More folds than samples: some fold would validate on nothing. Checked
    /// before any fold is built, since k folds of n rows take k·n indices.
    #[error("{k} folds asked for but there are only {n} samples; use 2 to {n} folds")]
    MoreFoldsThanSamples {
        /// Folds asked for.
        k: usize,
        /// Samples.
        n: usize,
    },
    /// A fold would have an empty training or validation set.
    #[error("fold {fold} of {n} samples has {train} training and {validation} validation rows")]
    EmptyFold {
        /// Fold index.
        fold: usize,
        /// Samples.
        n: usize,
        /// Training rows.
        train: usize,
        /// Validation rows.
        validation: usize,
    },
    /// The training fraction of a hold-out split must lie in (0, 1).
    #[error("training fraction must lie in (0, 1), got {fraction}")]
    Fraction {
        /// Value given.
        fraction: f64,
    },
    /// A hold-out split's name that is not one of [`Holdout::NAMES`].
    #[error("unknown split {name:?}: use blocked or interleaved")]
    UnknownHoldout {
        /// Name given.
        name: String,
    },
}

impl Split {
    /// The folds for `n` samples.
    ///
    /// # Errors
    /// [`SplitError::TooFewFolds`] for k < 2, [`SplitError::EmptyFold`] when a fold's
    /// training or validation set is empty (k > n, or a gap that eats the training set).
    ///
    /// ```
    /// let f = rbf::Split::KFold { k: 5, seed: 1 }.folds(23).unwrap();
    /// let mut all: Vec<usize> = f.iter().flat_map(|f| f.validation.clone()).collect();
    /// all.sort();
    /// assert_eq!(all, (0..23).collect::<Vec<_>>());
    /// ```
    pub fn folds(&self, n: usize) -> Result<Vec<Fold>, SplitError> {
        let k = match *self {
            Split::KFold { k, .. } | Split::Interleaved { k } | Split::Blocked { k, .. } => k,
        };
        if k < 2 {
            return Err(SplitError::TooFewFolds { k });
        }
        if k > n {
            return Err(SplitError::MoreFoldsThanSamples { k, n });
        }
        let folds: Vec<Fold> = match *self {
            Split::KFold { seed, .. } => {
                let mut idx: Vec<usize> = (0..n).collect();
                idx.shuffle(&mut Xoshiro256Plus::seed_from_u64(seed));
                (0..k)
                    .map(|f| {
                        let (s, e) = bounds(n, k, f);
                        let mut validation = idx[s..e].to_vec();
                        let mut train: Vec<usize> =
                            idx[..s].iter().chain(&idx[e..]).copied().collect();
                        validation.sort_unstable();
                        train.sort_unstable();
                        Fold { train, validation }
                    })
                    .collect()
            }
            Split::Interleaved { .. } => (0..k)
                .map(|f| {
                    let v = (f + 1) % k;
                    let (validation, train) = (0..n).partition(|i| i % k == v);
                    Fold { train, validation }
                })
                .collect(),
            Split::Blocked { gap, .. } => (0..k)
                .map(|f| {
                    let (s, e) = bounds(n, k, f);
                    let validation = (s..e).collect();
                    let train = (0..n).filter(|&i| i + gap < s || i >= e + gap).collect();
                    Fold { train, validation }
                })
                .collect(),
        };
        for (fold, f) in folds.iter().enumerate() {
            if f.train.is_empty() || f.validation.is_empty() {
                return Err(SplitError::EmptyFold {
                    fold,
                    n,
                    train: f.train.len(),
                    validation: f.validation.len(),
                });
            }
        }
        Ok(folds)
    }
}

/// [s, e) of block f when n items are cut into k near-equal contiguous blocks.
fn bounds(n: usize, k: usize, f: usize) -> (usize, usize) {
    (f * n / k, (f + 1) * n / k)
}

/// One train/validation partition of rows in time order: what an
/// application holds out once, as opposed to the folds of a [`Split`].
///
/// The serialised form (`{"kind": "blocked", "train_fraction": 0.5}` or
/// `{"kind": "interleaved"}`) is what model files store.
///
/// ```
/// use rbf::Holdout;
/// let s: Holdout = "interleaved".parse().unwrap();
/// let f = s.fold(100, 3).unwrap();
/// assert_eq!((&f.train[..3], &f.validation[..3]), (&[0, 2, 4][..], &[1, 3, 5][..]));
/// // Blocked: the first half trains; the gap keeps rows 50..53 out of both.
/// let f = Holdout::Blocked { train_fraction: 0.5 }.fold(100, 3).unwrap();
/// assert_eq!((f.train.len(), f.validation[0]), (50, 53));
/// assert_eq!(Holdout::default().to_string(), "blocked (50% train)");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Holdout {
    /// The first `train_fraction` of the rows (rounded to the nearest row)
    /// train; after a gap, the rest validate.
    Blocked {
        /// Fraction of rows that train, in (0, 1).
        train_fraction: f64,
    },
    /// Even rows train, odd rows validate (the seed paper's alternate vectors).
    Interleaved,
}

impl Default for Holdout {
    /// Blocked, half and half.
    fn default() -> Self {
        Holdout::Blocked {
            train_fraction: 0.5,
        }
    }
}

impl Holdout {
    /// The names [`FromStr`](std::str::FromStr) accepts.
    pub const NAMES: [&'static str; 2] = ["blocked", "interleaved"];

    /// Training and validation rows of `n` rows; `gap` rows after the
    /// training block are dropped (blocked only).
    ///
    /// # Errors
    /// [`SplitError::Fraction`] outside (0, 1), [`SplitError::EmptyFold`] if a side is empty.
    pub fn fold(&self, n: usize, gap: usize) -> Result<Fold, SplitError> {
        let fold = match *self {
            Holdout::Interleaved => Fold {
                train: (0..n).step_by(2).collect(),
                validation: (1..n).step_by(2).collect(),
            },
            Holdout::Blocked { train_fraction } => {
                if !(train_fraction > 0.0 && train_fraction < 1.0) {
                    return Err(SplitError::Fraction {
                        fraction: train_fraction,
                    });
                }
                let t = ((n as f64) * train_fraction).round() as usize;
                Fold {
                    train: (0..t).collect(),
                    validation: ((t + gap).min(n)..n).collect(),
                }
            }
        };
        if fold.train.is_empty() || fold.validation.is_empty() {
            return Err(SplitError::EmptyFold {
                fold: 0,
                n,
                train: fold.train.len(),
                validation: fold.validation.len(),
            });
        }
        Ok(fold)
    }
}

impl std::fmt::Display for Holdout {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Holdout::Blocked { train_fraction } => {
                write!(f, "blocked ({:.0}% train)", train_fraction * 100.0)
            }
            Holdout::Interleaved => f.write_str("interleaved"),
        }
    }
}

impl std::str::FromStr for Holdout {
    type Err = SplitError;
    /// `blocked` (half and half) or `interleaved`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "blocked" => Ok(Holdout::default()),
            "interleaved" => Ok(Holdout::Interleaved),
            other => Err(SplitError::UnknownHoldout {
                name: other.to_string(),
            }),
        }
    }
}

/// A blocked hold-out: the first `train_fraction` of `n` rows (rounded)
/// train, `gap` rows are dropped, the rest validate.
///
/// # Errors
/// [`SplitError::Fraction`] outside (0, 1), [`SplitError::EmptyFold`] if a side is empty.
///
/// ```
/// let f = rbf::holdout(10, 0.6, 2).unwrap();
/// assert_eq!(f.train, vec![0, 1, 2, 3, 4, 5]);
/// assert_eq!(f.validation, vec![8, 9]);
/// ```
pub fn holdout(n: usize, train_fraction: f64, gap: usize) -> Result<Fold, SplitError> {
    Holdout::Blocked { train_fraction }.fold(n, gap)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_partition_the_rows() {
        for split in [
            Split::KFold { k: 4, seed: 3 },
            Split::Interleaved { k: 3 },
            Split::Blocked { k: 5, gap: 0 },
        ] {
            let folds = split.folds(37).unwrap();
            let mut seen = [0; 37];
            for f in &folds {
                for &i in &f.validation {
                    seen[i] += 1;
                }
                assert_eq!(f.train.len() + f.validation.len(), 37, "{split:?}");
                assert!(f.train.iter().all(|i| !f.validation.contains(i)));
            }
            assert!(seen.iter().all(|&c| c == 1), "{split:?}");
        }
    }

    #[test]
    fn blocked_gap_keeps_neighbours_out_of_training() {
        let folds = Split::Blocked { k: 4, gap: 3 }.folds(40).unwrap();
        for f in &folds {
            let (s, e) = (f.validation[0], *f.validation.last().unwrap());
            assert!(f.train.iter().all(|&i| i + 3 < s || i > e + 2));
        }
        assert!(matches!(
            Split::Blocked { k: 2, gap: 10 }.folds(10),
            Err(SplitError::EmptyFold { .. })
        ));
    }

    #[test]
    fn kfold_is_seeded() {
        let a = Split::KFold { k: 3, seed: 9 }.folds(20).unwrap();
        assert_eq!(a, Split::KFold { k: 3, seed: 9 }.folds(20).unwrap());
        assert_ne!(a, Split::KFold { k: 3, seed: 10 }.folds(20).unwrap());
    }

    #[test]
    fn bad_splits_are_errors() {
        assert_eq!(
            Split::Interleaved { k: 0 }.folds(5),
            Err(SplitError::TooFewFolds { k: 0 })
        );
        assert_eq!(
            Split::KFold { k: 6, seed: 0 }.folds(5),
            Err(SplitError::MoreFoldsThanSamples { k: 6, n: 5 })
        );
        // Refused before k folds are allocated (this aborted before).
        assert_eq!(
            Split::Blocked {
                k: 1_000_000_000,
                gap: 0
            }
            .folds(5),
            Err(SplitError::MoreFoldsThanSamples {
                k: 1_000_000_000,
                n: 5
            })
        );
        assert_eq!(
            holdout(10, 1.0, 0),
            Err(SplitError::Fraction { fraction: 1.0 })
        );
        assert!(matches!(
            holdout(10, 0.5, 5),
            Err(SplitError::EmptyFold { .. })
        ));
    }
}
