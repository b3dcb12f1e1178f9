//! k-means on the 8 blob data sets of `peers/scripts/kmeans_blobs.py` (generated in-tree,
//! the same numbers): prints each set's inertia (sum of squared distances, scikit-learn's
//! definition) and whether every blob is one cluster, then the median time of fitting
//! all 8 sets over `REPS` repetitions (default 5), on one thread.
//!
//! ```sh
//! cargo run --release -p rbf --example kmeans_blobs            # default settings
//! cargo run --release -p rbf --example kmeans_blobs -- plusplus 1   # seeding, n_init
//! ```

#[path = "../tests/common/blobs.rs"]
mod blobs;

use std::time::Instant;

use faer::Par;
use rbf::select::kmeans::kmeans_centres;
use rbf::{KMeansInit, KMeansSettings};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut settings = KMeansSettings::new(blobs::K);
    if let Some(init) = args.first() {
        settings.init = init.parse::<KMeansInit>().expect("plusplus or greedy");
    }
    if let Some(n) = args.get(1) {
        settings.n_runs = n.parse().expect("n_init: a count");
    }
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(5);
    let sets: Vec<_> = (0..blobs::SETS).map(blobs::blob_set).collect();
    for (s, (x, truth)) in sets.iter().enumerate() {
        let r = kmeans_centres(x.as_ref(), &settings, s as u64, Par::Seq).unwrap();
        println!(
            "{{\"set\": {s}, \"inertia\": {}, \"all_blobs\": {}, \"iterations\": {}}}",
            r.inertia * blobs::N as f64,
            blobs::same_partition(truth, &r.memberships),
            r.iterations.unwrap_or(0)
        );
    }
    let mut times = Vec::with_capacity(reps);
    for _ in 0..reps {
        let t = Instant::now();
        for (s, (x, _)) in sets.iter().enumerate() {
            std::hint::black_box(
                kmeans_centres(x.as_ref(), &settings, s as u64, Par::Seq).unwrap(),
            );
        }
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{{\"init\": \"{}\", \"n_init\": {}, \"reps\": {reps}, \"seconds_all_sets\": {}}}",
        settings.init,
        settings.n_runs,
        times[reps / 2]
    );
}
