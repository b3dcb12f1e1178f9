//! Width rules: how β is chosen.

use faer::{MatRef, Par};
use serde::{Deserialize, Serialize};

use crate::design::Widths;
use crate::neighbours::{median_pairwise_distance, nearest_neighbour_distances};

/// Pairwise distances for [`WidthRule::MedianPairwise`] use at most this many points.
///
/// ```
/// assert_eq!(rbf::width::MEDIAN_SUBSAMPLE, 1000);
/// ```
pub const MEDIAN_SUBSAMPLE: usize = 1000;

/// How the kernel width β is chosen, in input units (standardised units when the model
/// standardises its inputs).
///
/// For OLS the rule is applied to the *candidate* centres (the selected ones are not
/// known yet) and each selected centre keeps its candidate's width.
///
/// ```
/// use faer::{mat, Par};
/// use rbf::{WidthRule, Widths};
/// let c = mat![[0.0], [1.0], [3.0]];
/// assert_eq!(WidthRule::Fixed(2.0).widths(c.as_ref(), Par::Seq).unwrap(), Widths::Uniform(2.0));
/// // nearest-neighbour distances 1, 1, 2: mean 4/3
/// let w = WidthRule::MeanNearestNeighbour { scale: 3.0 }.widths(c.as_ref(), Par::Seq).unwrap();
/// assert!((w.get(0) - 4.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WidthRule {
    /// A fixed β (the seed paper's eq. 8 constant).
    Fixed(f64),
    /// β = scale × the mean distance from each centre to its nearest other centre.
    MeanNearestNeighbour {
        /// Multiplier.
        scale: f64,
    },
    /// βⱼ = scale × the distance from centre j to its nearest other centre (duplicated
    /// centres, at distance 0, get the mean of the positive distances).
    PerCentreNearestNeighbour {
        /// Multiplier.
        scale: f64,
    },
    /// β = scale × the median pairwise distance between centres (on a seeded subsample
    /// of [`MEDIAN_SUBSAMPLE`] centres above that count): robust to dense clumps, a good
    /// default when every training vector is a candidate.
    MedianPairwise {
        /// Multiplier.
        scale: f64,
    },
    /// k-means only: βⱼ = scale × the RMS distance of cluster j's members to its centroid
    /// (clusters with fewer than two members or no spread fall back to the nearest-centre
    /// distance).
    ClusterSpread {
        /// Multiplier.
        scale: f64,
    },
}

impl Default for WidthRule {
    /// `MedianPairwise { scale: 1.0 }`.
    fn default() -> Self {
        WidthRule::MedianPairwise { scale: 1.0 }
    }
}

/// Why widths could not be computed.
///
/// ```
/// let e = rbf::WidthError::TooFewCentres { centres: 1 };
/// assert!(e.to_string().contains("2"));
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WidthError {
    /// Distance-based rules need at least two centres.
    #[error("a distance-based width rule needs at least 2 centres, got {centres}")]
    TooFewCentres {
        /// Number of centres.
        centres: usize,
    },
    /// All centres coincide, so every distance-based width is 0.
    #[error("all centres coincide: distance-based widths would be 0; use a fixed width")]
    Degenerate,
    /// `ClusterSpread` needs k-means memberships.
    #[error("the cluster-spread width rule needs k-means centres")]
    NeedsClusters,
}

impl WidthRule {
    /// The scale (or fixed β) the rule carries.
    ///
    /// ```
    /// assert_eq!(rbf::WidthRule::Fixed(0.7).value(), 0.7);
    /// ```
    pub fn value(&self) -> f64 {
        match *self {
            WidthRule::Fixed(b) => b,
            WidthRule::MeanNearestNeighbour { scale }
            | WidthRule::PerCentreNearestNeighbour { scale }
            | WidthRule::MedianPairwise { scale }
            | WidthRule::ClusterSpread { scale } => scale,
        }
    }

    /// Widths for `centres` (rows).
    ///
    /// # Errors
    /// [`WidthError`] for fewer than two centres, coincident centres, or
    /// [`WidthRule::ClusterSpread`] (use [`WidthRule::cluster_widths`]).
    ///
    /// ```
    /// use faer::{mat, Par};
    /// let c = mat![[0.0], [1.0], [3.0]];
    /// let w = rbf::WidthRule::PerCentreNearestNeighbour { scale: 1.0 }.widths(c.as_ref(), Par::Seq).unwrap();
    /// assert_eq!(w, rbf::Widths::PerCentre(vec![1.0, 1.0, 2.0]));
    /// ```
    pub fn widths(&self, centres: MatRef<'_, f64>, par: Par) -> Result<Widths, WidthError> {
        let m = centres.nrows();
        match *self {
            WidthRule::Fixed(b) => Ok(Widths::Uniform(b)),
            WidthRule::ClusterSpread { .. } => Err(WidthError::NeedsClusters),
            _ if m < 2 => Err(WidthError::TooFewCentres { centres: m }),
            WidthRule::MeanNearestNeighbour { scale } => {
                let nn = nearest_neighbour_distances(centres, par);
                let mean = nn.iter().sum::<f64>() / m as f64;
                if mean > 0.0 {
                    Ok(Widths::Uniform(scale * mean))
                } else {
                    Err(WidthError::Degenerate)
                }
            }
            WidthRule::PerCentreNearestNeighbour { scale } => {
                let nn = nearest_neighbour_distances(centres, par);
                per_centre(nn, scale)
            }
            WidthRule::MedianPairwise { scale } => {
                let med = median_remembered(centres).unwrap_or(0.0);
                if med > 0.0 {
                    Ok(Widths::Uniform(scale * med))
                } else {
                    // More than half the pairs coincide: fall back to the mean of the positive ones.
                    let nn = nearest_neighbour_distances(centres, par);
                    let pos: Vec<f64> = nn.into_iter().filter(|&d| d > 0.0).collect();
                    if pos.is_empty() {
                        Err(WidthError::Degenerate)
                    } else {
                        Ok(Widths::Uniform(
                            scale * pos.iter().sum::<f64>() / pos.len() as f64,
                        ))
                    }
                }
            }
        }
    }

    /// Widths for k-means centres given the samples `x` and their `memberships`:
    /// [`WidthRule::ClusterSpread`] uses them, every other rule defers to
    /// [`WidthRule::widths`].
    ///
    /// # Errors
    /// As [`WidthRule::widths`].
    ///
    /// # Panics
    /// If `memberships.len() != x.nrows()` or a membership is not a row of `centres`.
    ///
    /// ```
    /// use faer::{mat, Par};
    /// let x = mat![[0.0], [2.0], [10.0], [14.0]];
    /// let c = mat![[1.0], [12.0]];
    /// let w = rbf::WidthRule::ClusterSpread { scale: 1.0 }
    ///     .cluster_widths(x.as_ref(), c.as_ref(), &[0, 0, 1, 1], Par::Seq)
    ///     .unwrap();
    /// assert_eq!(w, rbf::Widths::PerCentre(vec![1.0, 2.0]));
    /// ```
    #[track_caller]
    pub fn cluster_widths(
        &self,
        x: MatRef<'_, f64>,
        centres: MatRef<'_, f64>,
        memberships: &[usize],
        par: Par,
    ) -> Result<Widths, WidthError> {
        let WidthRule::ClusterSpread { scale } = *self else {
            return self.widths(centres, par);
        };
        assert_eq!(memberships.len(), x.nrows(), "one membership per sample");
        let (k, d) = (centres.nrows(), centres.ncols());
        let mut sum = vec![0.0; k];
        let mut count = vec![0usize; k];
        for (i, &c) in memberships.iter().enumerate() {
            assert!(c < k, "membership {c} out of {k} centres");
            sum[c] += (0..d)
                .map(|t| (x[(i, t)] - centres[(c, t)]).powi(2))
                .sum::<f64>();
            count[c] += 1;
        }
        let nn = if k >= 2 {
            nearest_neighbour_distances(centres, par)
        } else {
            vec![0.0; k]
        };
        let spread: Vec<f64> = (0..k)
            .map(|c| {
                let s = if count[c] >= 2 {
                    (sum[c] / count[c] as f64).sqrt()
                } else {
                    0.0
                };
                if s > 0.0 { s } else { nn[c] }
            })
            .collect();
        per_centre(spread, scale)
    }
}

/// Scales per-centre widths, replacing zeros by the mean of the positive ones.
fn per_centre(mut w: Vec<f64>, scale: f64) -> Result<Widths, WidthError> {
    let pos: Vec<f64> = w
        .iter()
        .copied()
        .filter(|&d| d > 0.0 && d.is_finite())
        .collect();
    if pos.is_empty() {
        return Err(WidthError::Degenerate);
    }
    let fill = pos.iter().sum::<f64>() / pos.len() as f64;
    for v in &mut w {
        if !(*v > 0.0 && v.is_finite()) {
            *v = fill;
        }
        *v *= scale;
    }
    Ok(Widths::PerCentre(w))
}

/// [`median_pairwise_distance`] of `centres` (on [`MEDIAN_SUBSAMPLE`] of
/// them), remembered within the process by a 128-bit digest of their
/// values: a cross-validation asks it for the same candidates once per
/// width scale, and a fit of several targets on the same inputs once per
/// target; the distances are O(m²·d) where the digest is O(m·d).
fn median_remembered(centres: MatRef<'_, f64>) -> Option<f64> {
    use std::hash::{DefaultHasher, Hasher};
    use std::sync::Mutex;
    /// A digest of the centres and their median.
    type Seen = ((u64, u64), Option<f64>);
    static SEEN: Mutex<Vec<Seen>> = Mutex::new(Vec::new());
    const CAPACITY: usize = 256;
    let (mut a, mut b) = (DefaultHasher::new(), DefaultHasher::new());
    b.write_u64(0x9e37_79b9_7f4a_7c15);
    for h in [&mut a, &mut b] {
        h.write_usize(centres.nrows());
        h.write_usize(centres.ncols());
    }
    for i in 0..centres.nrows() {
        for j in 0..centres.ncols() {
            let w = centres[(i, j)].to_bits();
            a.write_u64(w);
            b.write_u64(w);
        }
    }
    let key = (a.finish(), b.finish());
    let lock = || {
        SEEN.lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    };
    if let Some(&(_, med)) = lock().iter().find(|(k, _)| *k == key) {
        return med;
    }
    let med = median_pairwise_distance(centres, MEDIAN_SUBSAMPLE, 0);
    let mut seen = lock();
    if seen.len() >= CAPACITY {
        seen.remove(0);
    }
    seen.push((key, med));
    med
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::mat;

    #[test]
    fn coincident_centres_are_degenerate() {
        let c = mat![[1.0, 1.0], [1.0, 1.0]];
        for rule in [
            WidthRule::MeanNearestNeighbour { scale: 1.0 },
            WidthRule::PerCentreNearestNeighbour { scale: 1.0 },
            WidthRule::MedianPairwise { scale: 1.0 },
        ] {
            assert_eq!(
                rule.widths(c.as_ref(), Par::Seq),
                Err(WidthError::Degenerate)
            );
        }
    }

    #[test]
    fn duplicated_centres_get_the_mean_width() {
        let c = mat![[0.0], [0.0], [2.0], [5.0]];
        // nn: 0, 0, 2, 3 → zeros become 2.5
        let w = WidthRule::PerCentreNearestNeighbour { scale: 2.0 }
            .widths(c.as_ref(), Par::Seq)
            .unwrap();
        assert_eq!(w, Widths::PerCentre(vec![5.0, 5.0, 4.0, 6.0]));
    }

    #[test]
    fn one_centre_is_too_few() {
        let c = mat![[0.0, 1.0]];
        assert_eq!(
            WidthRule::MedianPairwise { scale: 1.0 }.widths(c.as_ref(), Par::Seq),
            Err(WidthError::TooFewCentres { centres: 1 })
        );
        assert_eq!(
            WidthRule::Fixed(1.0).widths(c.as_ref(), Par::Seq),
            Ok(Widths::Uniform(1.0))
        );
    }
}
