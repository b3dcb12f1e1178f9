//! Unit tests of the k-means steps.

use faer::{Mat, Par, mat};
use linfa::prelude::*;
use linfa_clustering::{KMeans, KMeansInit as LinfaInit};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256Plus;

use super::*;

/// Greedy k-means++ keeps, at each step, the candidate with the lowest potential, so its
/// start has a potential no worse than plain k-means++'s on well-separated data, and both
/// seedings are deterministic for a seed.
#[test]
fn greedy_seeding_is_deterministic_and_covers_separated_groups() {
    let x = Mat::from_fn(300, 2, |i, j| {
        (i % 6) as f64 * 50.0 * (j as f64 + 1.0) + ((i * 31 + j * 7) % 13) as f64 * 0.1
    });
    let mut a = Xoshiro256Plus::seed_from_u64(4);
    let mut b = Xoshiro256Plus::seed_from_u64(4);
    let ga = greedy_kmeans_plusplus(x.as_ref(), 6, &mut a);
    assert_eq!(ga, greedy_kmeans_plusplus(x.as_ref(), 6, &mut b));
    let mut groups: Vec<usize> = (0..6)
        .map(|c| (ga[[c, 0]] / 50.0).round() as usize)
        .collect();
    groups.sort_unstable();
    assert_eq!(groups, vec![0, 1, 2, 3, 4, 5]);
}
use crate::convert::as_array;

/// The linear-time seeding draws what linfa's own k-means++ draws (same generator,
/// same D² weights), so linfa's whole k-means run is unchanged.
#[test]
fn seeding_matches_linfas_kmeans_plusplus() {
    let x = Mat::from_fn(400, 6, |i, j| {
        ((i * (j + 3)) as f64 * 0.731).sin() + (i % 7) as f64
    });
    for (k, seed) in [(5, 1), (20, 7), (60, 42)] {
        let settings = KMeansSettings::new(k)
            .algorithm(KMeansAlgorithm::Linfa)
            .init(KMeansInit::KMeansPlusPlus);
        let ours = kmeans_centres(x.as_ref(), &settings, seed, Par::Seq).unwrap();
        let records = as_array(x.as_ref());
        let linfa = KMeans::params_with_rng(k, Xoshiro256Plus::seed_from_u64(seed))
            .n_runs(1)
            .max_n_iterations(settings.max_iterations)
            .tolerance(settings.tolerance)
            .init_method(LinfaInit::KMeansPlusPlus)
            .fit(&DatasetBase::from(records.view()))
            .unwrap();
        let c = linfa.centroids();
        for i in 0..k {
            for j in 0..6 {
                assert!(
                    (ours.centres[(i, j)] - c[[i, j]]).abs() < 1e-12,
                    "k {k} seed {seed}"
                );
            }
        }
    }
}

/// Both algorithms start from the same k-means++ centres: one Lloyd iteration from
/// that start is the mean of the samples nearest each seed.
#[test]
fn both_algorithms_share_the_seeded_start() {
    let x = Mat::from_fn(200, 3, |i, j| ((i * (j + 2)) as f64 * 0.53).cos());
    let mut rng = Xoshiro256Plus::seed_from_u64(9);
    let start = kmeans_plusplus(x.as_ref(), 6, &mut rng);
    let start = Mat::from_fn(6, 3, |i, j| start[[i, j]]);
    let one = lloyd(x.as_ref(), start.as_ref(), 1, 1e-4, Par::Seq);
    let settings = KMeansSettings {
        max_iterations: 1,
        ..KMeansSettings::new(6).init(KMeansInit::KMeansPlusPlus)
    };
    let ours = kmeans_centres(x.as_ref(), &settings, 9, Par::Seq).unwrap();
    assert_eq!(ours.centres, one.centres);
    assert_eq!(ours.iterations, Some(1));
}

#[test]
fn several_runs_keep_the_lowest_inertia() {
    let x = Mat::from_fn(300, 2, |i, j| ((i * (j + 5)) as f64 * 0.37).sin());
    for alg in KMeansAlgorithm::ALL {
        let one = KMeansSettings::new(8).algorithm(alg);
        let one = kmeans_centres(x.as_ref(), &one, 3, Par::Seq).unwrap();
        let many = KMeansSettings {
            n_runs: 5,
            ..KMeansSettings::new(8).algorithm(alg)
        };
        let best = kmeans_centres(x.as_ref(), &many, 3, Par::Seq).unwrap();
        assert!(best.inertia <= one.inertia, "{alg}");
    }
}

#[test]
fn more_clusters_than_samples_is_left_to_linfa_not_a_panic() {
    let x = Mat::from_fn(3, 1, |i, _| i as f64);
    for alg in KMeansAlgorithm::ALL {
        let s = KMeansSettings::new(5).algorithm(alg);
        let _ = kmeans_centres(x.as_ref(), &s, 0, Par::Seq);
        let bad = KMeansSettings { n_centres: 0, ..s };
        assert!(kmeans_centres(x.as_ref(), &bad, 0, Par::Seq).is_err());
    }
}

/// linfa's rules for the settings hold for the library's Lloyd iterations too.
#[test]
fn lloyd_settings_are_checked_by_linfas_rules() {
    let x = Mat::from_fn(20, 1, |i, _| i as f64);
    let ok = KMeansSettings::new(2);
    for bad in [
        KMeansSettings { n_runs: 0, ..ok },
        KMeansSettings {
            tolerance: 0.0,
            ..ok
        },
        KMeansSettings {
            max_iterations: 0,
            ..ok
        },
    ] {
        let e = kmeans_centres(x.as_ref(), &bad, 0, Par::Seq).unwrap_err();
        assert!(
            matches!(
                e,
                KMeansError::NoRuns | KMeansError::NoIterations | KMeansError::Tolerance { .. }
            ),
            "{e}"
        );
    }
}

/// An empty cluster takes the sample farthest from its centroid (among clusters with
/// two members or more), then the iterations go on as usual.
#[test]
fn an_empty_cluster_takes_the_farthest_sample() {
    let x = mat![[0.0], [1.0], [2.0], [3.4], [10.0], [11.0]];
    // centre 1 at 100 attracts nothing; sample 3 (3.4 from centre 0) is the farthest
    let start = mat![[0.0], [100.0], [10.0]];
    let r = lloyd(x.as_ref(), start.as_ref(), 100, 1e-4, Par::Seq);
    assert_eq!(r.centres, mat![[1.0], [3.4], [10.5]]);
    assert_eq!(r.memberships, vec![0, 0, 0, 1, 2, 2]);
    assert_eq!(r.iterations, Some(2));
    assert!((r.inertia - (1.0 + 0.0 + 1.0 + 0.0 + 0.25 + 0.25) / 6.0).abs() < 1e-15);
}

/// Two empty clusters in one step: in index order, each takes the farthest sample
/// left (a relocated sample is not taken again).
#[test]
fn empty_clusters_are_filled_in_index_order() {
    let x = mat![[0.0], [1.0], [2.0], [3.0], [10.0], [11.0]];
    let start = mat![[0.0], [100.0], [200.0], [10.0]];
    let r = lloyd(x.as_ref(), start.as_ref(), 100, 1e-4, Par::Seq);
    // cluster 1 takes sample 3 (9 from centre 0), cluster 2 sample 2 (4 from it)
    assert_eq!(r.centres, mat![[0.5], [3.0], [2.0], [10.5]]);
    assert_eq!(r.memberships, vec![0, 0, 2, 1, 3, 3]);
}

/// Fewer distinct samples than clusters: the relocation still finds members (the
/// lowest indices on the all-zero tie), no cluster stays empty, nothing panics.
#[test]
fn duplicate_samples_fill_every_cluster() {
    let x = Mat::from_fn(5, 2, |_, j| j as f64);
    let start = mat![[0.0, 1.0], [0.0, 1.0], [0.0, 1.0]];
    let r = lloyd(x.as_ref(), start.as_ref(), 10, 1e-4, Par::Seq);
    assert_eq!(r.inertia, 0.0);
    assert_eq!(r.memberships.len(), 5);
    let s = KMeansSettings::new(3);
    let r = kmeans_centres(x.as_ref(), &s, 1, Par::Seq).unwrap();
    assert_eq!(r.inertia, 0.0);
    assert!(r.centres.col(1).iter().all(|&v| v == 1.0));
}

/// The assignment does not depend on the parallelism, nor do the centres (bit for
/// bit), and the maximum number of iterations is respected.
#[test]
fn lloyd_is_bit_identical_across_parallelism() {
    let x = Mat::from_fn(3000, 7, |i, j| {
        ((i * (j + 3)) as f64 * 0.0731).sin() * (1.0 + (i % 5) as f64)
    });
    let start = Mat::from_fn(130, 7, |i, j| x[(i * 23, j)]);
    let a = lloyd(x.as_ref(), start.as_ref(), 300, 1e-4, Par::Seq);
    let b = lloyd(x.as_ref(), start.as_ref(), 300, 1e-4, Par::rayon(2));
    assert_eq!(a.centres, b.centres);
    assert_eq!(a.memberships, b.memberships);
    assert_eq!(a.inertia, b.inertia);
    let two = lloyd(x.as_ref(), start.as_ref(), 2, 1e-4, Par::Seq);
    assert_eq!(two.iterations, Some(2));
    assert!(a.iterations.unwrap() > 2 && a.inertia <= two.inertia);
}

/// The memberships are the nearest final centroids, and the inertia is theirs.
#[test]
fn memberships_and_inertia_belong_to_the_final_centres() {
    let x = Mat::from_fn(500, 4, |i, j| ((i * (j + 1)) as f64 * 0.917).sin());
    for (alg, max_iterations) in [
        (KMeansAlgorithm::Lloyd, 300),
        (KMeansAlgorithm::Lloyd, 3),
        (KMeansAlgorithm::Linfa, 300),
    ] {
        let s = KMeansSettings {
            max_iterations,
            ..KMeansSettings::new(12).algorithm(alg)
        };
        let r = kmeans_centres(x.as_ref(), &s, 5, Par::Seq).unwrap();
        let mut total = 0.0;
        for i in 0..500 {
            let d2 = |c: usize| {
                (0..4)
                    .map(|t| (x[(i, t)] - r.centres[(c, t)]).powi(2))
                    .sum::<f64>()
            };
            let best = (0..12).map(d2).fold(f64::INFINITY, f64::min);
            let own = d2(r.memberships[i]);
            assert!(own <= best * (1.0 + 1e-12) + 1e-14, "{alg} sample {i}");
            total += own;
        }
        assert!((r.inertia - total / 500.0).abs() < 1e-12, "{alg}");
    }
}

/// The f32 product cannot tell two centroids 10⁻³ apart at 1000 from the samples'
/// mean (its error there is about 10⁻², the distances differ by 10⁻⁶): the samples
/// between them are checked in f64 and go to the nearer one, at every iteration.
#[test]
fn near_ties_are_decided_in_f64() {
    let mut rows = vec![[0.0, 0.0]; 10];
    rows.extend((0..=20).map(|s| [1000.0, s as f64 * 5e-5]));
    let x = Mat::from_fn(rows.len(), 2, |i, t| rows[i][t]);
    let start = mat![[0.0, 0.0], [1000.0, 0.0], [1000.0, 1e-3]];
    for max_iterations in [1, 2, 100] {
        let r = lloyd(x.as_ref(), start.as_ref(), max_iterations, 1e-4, Par::Seq);
        for i in 0..x.nrows() {
            let d2 = |c: usize| {
                (0..2)
                    .map(|t| (x[(i, t)] - r.centres[(c, t)]).powi(2))
                    .sum::<f64>()
            };
            let best = (0..3).map(d2).fold(f64::INFINITY, f64::min);
            assert!(
                d2(r.memberships[i]) <= best,
                "{max_iterations} iterations, sample {i}: {:?}",
                r.memberships
            );
        }
        // both near centroids keep members
        assert!(r.memberships.contains(&1) && r.memberships.contains(&2));
    }
}
