//! The k-means quality data sets, generated in-tree by the integer recipe that
//! `peers/scripts/kmeans_blobs.py` repeats in Python (SplitMix64 → uniforms → Box–Muller
//! normals), so that scikit-learn's reference inertias are for the same numbers.
//!
//! Set `s` (seed 1000 + s): K = 10 blob centres uniform in [−15, 15]⁵, each redrawn
//! until it is at least 10 from the ones before; N = 1000 points, point i in blob
//! i mod 10, the centre plus N(0, 1) noise on each axis.

use faer::Mat;

/// Blobs per set.
pub const K: usize = 10;
/// Dimension.
pub const D: usize = 5;
/// Points per set.
pub const N: usize = 1000;
/// Number of sets.
pub const SETS: usize = 8;

struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// In (0, 1): the top 53 bits, offset by half a step.
    fn uniform(&mut self) -> f64 {
        ((self.next() >> 11) as f64 + 0.5) * 2f64.powi(-53)
    }

    fn normal(&mut self) -> f64 {
        let u1 = self.uniform();
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

/// Set `s`: the N × D points and each point's blob.
pub fn blob_set(s: usize) -> (Mat<f64>, Vec<usize>) {
    let mut rng = SplitMix64(1000 + s as u64);
    let mut centres: Vec<[f64; D]> = Vec::with_capacity(K);
    while centres.len() < K {
        let mut c = [0.0; D];
        for v in &mut c {
            *v = 15.0 * (2.0 * rng.uniform() - 1.0);
        }
        let far = centres.iter().all(|o| {
            let d2: f64 = (0..D).map(|t| (c[t] - o[t]).powi(2)).sum();
            d2.sqrt() >= 10.0
        });
        if far {
            centres.push(c);
        }
    }
    let mut x = Mat::zeros(N, D);
    for i in 0..N {
        for t in 0..D {
            x[(i, t)] = centres[i % K][t] + rng.normal();
        }
    }
    (x, (0..N).map(|i| i % K).collect())
}

/// Whether two labellings are the same partition (equal up to renaming).
pub fn same_partition(a: &[usize], b: &[usize]) -> bool {
    let mut map = std::collections::HashMap::new();
    let mut back = std::collections::HashMap::new();
    a.iter()
        .zip(b)
        .all(|(&p, &q)| *map.entry(p).or_insert(q) == q && *back.entry(q).or_insert(p) == p)
}
