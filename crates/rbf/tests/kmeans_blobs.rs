//! k-means of scikit-learn's quality: on 8 seeded sets of 10 well-separated Gaussian blobs
//! in 5 dimensions (tests/common/blobs.rs), the default settings (greedy k-means++, one
//! run) find every blob, with an inertia within 2 % of scikit-learn's default `KMeans`.
//!
//! The reference inertias (scikit-learn 1.9.1, numpy 2.4.6, Python 3.11.7) were printed by
//!
//! ```sh
//! python3 peers/scripts/kmeans_blobs.py
//! ```
//!
//! which generates the same numbers by the same integer recipe (it found every blob on
//! every set too).

mod common;

use common::blobs::{N, SETS, blob_set, same_partition};
use faer::Par;
use rbf::select::kmeans::kmeans_centres;
use rbf::{KMeansInit, KMeansSettings};

/// scikit-learn's `KMeans(n_clusters=10, random_state=s).fit(X).inertia_` on set s.
const SKLEARN_INERTIA: [f64; SETS] = [
    5042.931065429897,
    4914.785321928093,
    5095.251664695192,
    4875.665094963726,
    5052.933884157375,
    4901.794133012388,
    4749.675997945013,
    4939.817773083692,
];

#[test]
fn default_kmeans_finds_every_blob_with_sklearns_inertia() {
    let settings = KMeansSettings::new(10);
    assert_eq!(
        (settings.init, settings.n_runs),
        (KMeansInit::GreedyKMeansPlusPlus, 1)
    );
    for (s, &reference) in SKLEARN_INERTIA.iter().enumerate() {
        let (x, truth) = blob_set(s);
        let r = kmeans_centres(x.as_ref(), &settings, s as u64, Par::Seq).unwrap();
        assert!(
            same_partition(&truth, &r.memberships),
            "set {s}: a blob missed"
        );
        // inertia as scikit-learn defines it (a sum); with every blob found both are
        // the same optimum (measured to 1e-14 relative), so 2 % is the issue's bound,
        // not a measured spread
        let ours = r.inertia * N as f64;
        assert!(
            (ours - reference).abs() <= 0.02 * reference,
            "set {s}: {ours} against scikit-learn's {reference}"
        );
    }
}

/// Why greedy: plain k-means++ (one D² draw per centre) with one run puts two centres
/// in one blob on set 7 (inertia 18 413 against 4 940); ten runs repair it.
#[test]
fn plain_kmeans_plusplus_misses_a_blob_that_greedy_finds() {
    let (x, truth) = blob_set(7);
    let plain = KMeansSettings::new(10).init(KMeansInit::KMeansPlusPlus);
    let r = kmeans_centres(x.as_ref(), &plain, 7, Par::Seq).unwrap();
    assert!(!same_partition(&truth, &r.memberships));
    assert!(r.inertia * N as f64 > 3.0 * SKLEARN_INERTIA[7]);
    let r = kmeans_centres(x.as_ref(), &plain.n_init(10), 7, Par::Seq).unwrap();
    assert!(same_partition(&truth, &r.memberships));
}
