//! The cost of greedy k-means++ against plain k-means++ at the bench's size (N = 2500
//! windows of 50 samples of seeded resonant filtered noise, K = 100, one thread): the
//! median of 5 whole k-means fits and of 5 seedings alone, and the inertia reached.
//!
//! ```sh
//! cargo run --release -p rbf --example kmeans_seeding
//! ```

use std::time::Instant;

use faer::{Mat, Par};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256Plus;
use rbf::select::kmeans::{greedy_kmeans_plusplus, kmeans_centres, kmeans_plusplus};
use rbf::{KMeansInit, KMeansSettings};

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    let (n, d, k) = (2500, 50, 100);
    // s_t = 1.6 s_{t−1} − 0.8 s_{t−2} + u_t, u uniform on [−0.5, 0.5) from an LCG
    let mut s = vec![0.0f64; n + d + 200];
    let mut z = 12345u64;
    for t in 2..s.len() {
        z = z
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let u = (z >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        s[t] = 1.6 * s[t - 1] - 0.8 * s[t - 2] + u;
    }
    let x = Mat::from_fn(n, d, |i, j| s[200 + i + d - 1 - j]);
    for init in KMeansInit::ALL {
        let settings = KMeansSettings::new(k).init(init);
        let mut fits = Vec::new();
        let mut seeds = Vec::new();
        let mut last = None;
        for _ in 0..5 {
            let t = Instant::now();
            last = Some(kmeans_centres(x.as_ref(), &settings, 42, Par::Seq).unwrap());
            fits.push(t.elapsed().as_secs_f64());
            let mut rng = Xoshiro256Plus::seed_from_u64(42);
            let t = Instant::now();
            std::hint::black_box(match init {
                KMeansInit::KMeansPlusPlus => kmeans_plusplus(x.as_ref(), k, &mut rng),
                KMeansInit::GreedyKMeansPlusPlus => greedy_kmeans_plusplus(x.as_ref(), k, &mut rng),
            });
            seeds.push(t.elapsed().as_secs_f64());
        }
        let r = last.unwrap();
        println!(
            "{init}: fit {:.4} s, seeding {:.4} s, inertia {:.5}, {} iterations",
            median(fits),
            median(seeds),
            r.inertia,
            r.iterations.unwrap_or(0)
        );
    }
}
