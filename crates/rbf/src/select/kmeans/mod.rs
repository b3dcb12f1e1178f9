//! k-means centres: a seeded k-means++ start, then Lloyd iterations — the library's own
//! ([`KMeansAlgorithm::Lloyd`], the default: distances by one f32 faer product per
//! iteration, near ties checked in f64) or linfa-clustering's `KMeans` ([`KMeansAlgorithm::Linfa`]).
//!
//! The k-means++ seeding is done here for both: linfa 0.8's own k-means++ recomputes
//! every sample's distance to *all* centres chosen so far at each of the k steps
//! (O(n·k²·d): 0.25 s of a 0.3 s fit for n = 2500, d = 50, k = 100), where keeping each
//! sample's nearest distance and updating it with the one new centre gives the same D²
//! sampling in O(n·k·d). Both algorithms start from the same centres for the same seed.
//!
//! Why the library has its own Lloyd iterations: linfa's assignment step computes every
//! sample–centroid distance in a scalar loop (≈ 7 ms an iteration for n = 2500, d = 50,
//! k = 100 on one core), and its update step counts the old centroid as one more member
//! of its cluster, which slows convergence (34 iterations against 19 for scikit-learn on
//! the bench data). [`lloyd`] ranks the centroids of every sample by ‖c‖² − 2·x·c from
//! one f32 product (twice the vector lanes of f64), decides in f64 where f32 cannot
//! tell, and updates the centroids as plain means; the seeding's distances come from
//! f64 products too (one per step for its 2 + ln k trials). At one thread on the peer
//! data (n = 2500, d = 50, k = 100) that took Lloyd's 16 iterations from 11.2 to 6.4 ms
//! and the seeding from 7.0 to 4.3 ms (`cargo run --release -p rbf --example
//! kmeans_peer`, least of 101 runs).
//!
//! | step | file | items |
//! |---|---|---|
//! | settings | `hyperparams.rs` | [`KMeansSettings`], [`KMeansAlgorithm`], [`KMeansInit`] |
//! | seeded start | `init.rs` | [`kmeans_plusplus`], [`greedy_kmeans_plusplus`] |
//! | assignment | `assign.rs` | the f32 product and its f64 check |
//! | Lloyd iterations | `iterate.rs` | [`lloyd`] |
//! | errors | `error.rs` | [`KMeansError`] |
//! | best of `n_runs` | this file | [`kmeans_centres`], [`KMeansCentres`] |

mod assign;
mod error;
mod hyperparams;
mod init;
mod iterate;
#[cfg(test)]
mod tests;

use faer::{Mat, MatRef, Par};
use linfa::prelude::*;
use linfa_clustering::{KMeans, KMeansInit as LinfaInit};
use ndarray::Array2;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256Plus;

use crate::convert::as_array;
use iterate::inertia;

pub use error::KMeansError;
pub use hyperparams::{
    KMeansAlgorithm, KMeansInit, KMeansSettings, UnknownKMeansAlgorithm, UnknownKMeansInit,
};
pub use init::{greedy_kmeans_plusplus, kmeans_plusplus};
pub use iterate::lloyd;

/// Centres found by k-means.
///
/// ```
/// use faer::{Mat, Par};
/// use rbf::select::kmeans::{kmeans_centres, KMeansSettings};
/// let x = Mat::from_fn(40, 1, |i, _| if i < 20 { i as f64 * 0.01 } else { 10.0 + i as f64 * 0.01 });
/// for alg in rbf::KMeansAlgorithm::ALL {
///     let c = kmeans_centres(x.as_ref(), &KMeansSettings::new(2).algorithm(alg), 1, Par::Seq).unwrap();
///     let mut cs = [c.centres[(0, 0)], c.centres[(1, 0)]];
///     cs.sort_by(f64::total_cmp);
///     // converged to the cluster means
///     assert!((cs[0] - 0.095).abs() < 1e-4 && (cs[1] - 10.295).abs() < 1e-4);
///     assert_eq!(c.memberships.len(), 40);
/// }
/// ```
#[derive(Clone, Debug)]
pub struct KMeansCentres {
    /// Centroids, k × d.
    pub centres: Mat<f64>,
    /// Cluster of every sample: its nearest centroid.
    pub memberships: Vec<usize>,
    /// Mean squared distance of the samples to their assigned centroid.
    pub inertia: f64,
    /// Lloyd iterations of the run kept ([`KMeansAlgorithm::Lloyd`]; linfa does not
    /// report them).
    pub iterations: Option<u64>,
}

/// Runs k-means on the rows of `x`: `n_runs` seeded starts (one `Xoshiro256Plus`
/// seeded with `seed` draws them all; k-means++ or greedy k-means++ as
/// `settings.init`), each followed by the Lloyd iterations of `settings.algorithm`;
/// the run with the lowest inertia is kept (the first on a tie). `par` is the
/// parallelism of [`KMeansAlgorithm::Lloyd`].
///
/// With fewer samples than clusters (or none) the call goes to linfa whichever the
/// algorithm, for linfa's behaviour.
///
/// # Errors
/// [`KMeansError`]: invalid settings (linfa's rules, for both algorithms), or linfa's
/// failure with fewer samples than clusters.
///
/// ```
/// use rbf::select::kmeans::{kmeans_centres, KMeansSettings};
/// let x = faer::Mat::from_fn(30, 2, |i, j| ((i * (j + 1)) % 11) as f64);
/// let a = kmeans_centres(x.as_ref(), &KMeansSettings::new(4), 3, faer::Par::Seq).unwrap();
/// let b = kmeans_centres(x.as_ref(), &KMeansSettings::new(4), 3, faer::Par::rayon(2)).unwrap();
/// assert_eq!(a.centres, b.centres); // same seed, same centres
/// assert!(a.memberships.iter().all(|&c| c < 4));
/// ```
pub fn kmeans_centres(
    x: MatRef<'_, f64>,
    settings: &KMeansSettings,
    seed: u64,
    par: Par,
) -> Result<KMeansCentres, KMeansError> {
    settings.check()?;
    let k = settings.n_centres;
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    let params = |init, rng: Xoshiro256Plus| {
        KMeans::params_with_rng(k, rng)
            .n_runs(1)
            .max_n_iterations(settings.max_iterations)
            .tolerance(settings.tolerance)
            .init_method(init)
    };
    if x.nrows() < k {
        // what the seeding cannot do: linfa's own behaviour
        let model = params(LinfaInit::KMeansPlusPlus, rng)
            .n_runs(settings.n_runs)
            .fit(&DatasetBase::from(as_array(x)))?;
        return Ok(linfa_result(
            x,
            model.centroids(),
            model.predict(&as_array(x)).to_vec(),
        ));
    }
    let mut best: Option<KMeansCentres> = None;
    for _ in 0..settings.n_runs {
        let start = match settings.init {
            KMeansInit::KMeansPlusPlus => kmeans_plusplus(x, k, &mut rng),
            KMeansInit::GreedyKMeansPlusPlus => greedy_kmeans_plusplus(x, k, &mut rng),
        };
        let run = match settings.algorithm {
            KMeansAlgorithm::Lloyd => {
                let start = Mat::from_fn(k, x.ncols(), |i, j| start[[i, j]]);
                lloyd(
                    x,
                    start.as_ref(),
                    settings.max_iterations,
                    settings.tolerance,
                    par,
                )
            }
            KMeansAlgorithm::Linfa => {
                // linfa draws from its generator only to initialise, which a
                // precomputed start skips
                let model = params(LinfaInit::Precomputed(start), rng.clone())
                    .fit(&DatasetBase::from(as_array(x)))?;
                linfa_result(x, model.centroids(), model.predict(&as_array(x)).to_vec())
            }
        };
        if best.as_ref().is_none_or(|b| run.inertia < b.inertia) {
            best = Some(run);
        }
    }
    Ok(best.expect("n_runs ≥ 1 was checked"))
}

/// Centres and memberships from linfa, with the inertia of those memberships.
fn linfa_result(x: MatRef<'_, f64>, c: &Array2<f64>, memberships: Vec<usize>) -> KMeansCentres {
    let centres = Mat::from_fn(c.nrows(), c.ncols(), |i, j| c[[i, j]]);
    KMeansCentres {
        inertia: inertia(x, centres.as_ref(), &memberships),
        centres,
        memberships,
        iterations: None,
    }
}
