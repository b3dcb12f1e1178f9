//! A seeded random subset of the training vectors as centres (or as OLS candidates).

use rand::SeedableRng;
use rand_xoshiro::Xoshiro256Plus;

/// `k` distinct indices of `0..n`, drawn with `Xoshiro256Plus::seed_from_u64(seed)`
/// (the generator linfa uses), in ascending order so the result does not depend on the
/// sampling order.
///
/// # Panics
/// If `k > n`.
///
/// ```
/// let a = rbf::select::random::random_subset(100, 10, 7);
/// assert_eq!(a, rbf::select::random::random_subset(100, 10, 7));
/// assert_eq!(a.len(), 10);
/// assert!(a.windows(2).all(|w| w[0] < w[1]));
/// ```
#[track_caller]
pub fn random_subset(n: usize, k: usize, seed: u64) -> Vec<usize> {
    assert!(k <= n, "cannot draw {k} distinct indices out of {n}");
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    let mut idx = rand::seq::index::sample(&mut rng, n, k).into_vec();
    idx.sort_unstable();
    idx
}
