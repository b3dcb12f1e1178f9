//! Where one-thread k-means + least squares time goes on the peer data file
//! (`peers/scripts/peer.py gen`): the median of REPS runs of the seeding, the Lloyd
//! iterations, the whole k-means and the whole fit (K = 100, seed 42, the given width).
//!
//! ```sh
//! python peers/scripts/peer.py gen --train 2500 --val 2500 --out /tmp/w.csv
//! cargo run --release -p rbf --example kmeans_peer -- /tmp/w.csv 9.5874
//! ```

use std::time::Instant;

use faer::{Mat, Par};
use linfa::ParamGuard;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256Plus;
use rbf::select::kmeans::{greedy_kmeans_plusplus, kmeans_centres, lloyd};
use rbf::{CentreSelection, KMeansSettings, RbfParams, WidthRule};

/// The median and, in brackets, the least: on a shared machine the least is the
/// run the neighbours disturbed least.
fn median(mut t: Vec<f64>) -> String {
    t.sort_by(f64::total_cmp);
    format!("{:.2} [{:.2}]", t[t.len() / 2] * 1e3, t[0] * 1e3)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).expect("usage: kmeans_peer FILE WIDTH [REPS]");
    let width: f64 = args.get(2).expect("a width").parse().expect("a number");
    let reps: usize = args.get(3).map_or(21, |r| r.parse().expect("a count"));
    let text = std::fs::read_to_string(path).expect("the data file");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let d = header.iter().filter(|h| h.starts_with('x')).count();
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        if f[d + 1] == "train" {
            xs.push(
                f[..d]
                    .iter()
                    .map(|v| v.parse::<f64>().unwrap())
                    .collect::<Vec<_>>(),
            );
            ys.push(f[d].parse::<f64>().unwrap());
        }
    }
    let n = xs.len();
    let x = Mat::from_fn(n, d, |i, j| xs[i][j]);
    let y = Mat::from_fn(n, 1, |i, _| ys[i]);
    let k = 100;
    let settings = KMeansSettings::new(k);
    let (mut seed_t, mut lloyd_t, mut km_t, mut fit_t) = (vec![], vec![], vec![], vec![]);
    let mut last = None;
    for _ in 0..reps {
        let mut rng = Xoshiro256Plus::seed_from_u64(42);
        let t = Instant::now();
        let start = greedy_kmeans_plusplus(x.as_ref(), k, &mut rng);
        seed_t.push(t.elapsed().as_secs_f64());
        let start = Mat::from_fn(k, d, |i, j| start[[i, j]]);
        let t = Instant::now();
        std::hint::black_box(lloyd(x.as_ref(), start.as_ref(), 300, 1e-4, Par::Seq));
        lloyd_t.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        last = Some(kmeans_centres(x.as_ref(), &settings, 42, Par::Seq).unwrap());
        km_t.push(t.elapsed().as_secs_f64());
        let p = RbfParams::new()
            .centres(CentreSelection::KMeans(settings))
            .width(WidthRule::Fixed(width))
            .seed(42)
            .parallelism(Par::Seq)
            .check()
            .unwrap();
        let t = Instant::now();
        std::hint::black_box(p.fit(x.as_ref(), y.as_ref()).unwrap());
        fit_t.push(t.elapsed().as_secs_f64());
    }
    let r = last.unwrap();
    println!(
        "n {n}, d {d}, k {k}, ms: seeding {}, lloyd {} ({} iterations), k-means {}, fit {}; inertia {:.6}",
        median(seed_t),
        median(lloyd_t),
        r.iterations.unwrap_or(0),
        median(km_t),
        median(fit_t),
        r.inertia
    );
}
