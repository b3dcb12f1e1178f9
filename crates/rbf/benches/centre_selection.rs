//! Centre-selection methods on windowed data: dimension 50, 2500 training vectors.
//!
//! The data: a seeded white-noise sequence through a resonant second-order low-pass
//! filter (unit variance), windows x_t = [s_t, s_{t−1}, …, s_{t−49}], and a nonlinear
//! target y_t = sin(1.5 s_t)·exp(−s_{t−10}²/2) + 0.3 s_{t−3} s_{t−7} + 0.05 e_t.
//! Every method uses the same Gaussian width β = the median pairwise distance of the
//! training windows (the library's default rule, computed once), so only the centre
//! selection differs:
//!
//! - OLS over all 2500 training vectors, K = 100 (bias forced);
//! - k-means (k-means++, one run, seeded), K = 100, then QR output weights;
//! - a random subset, K = 100, then QR output weights;
//! - all points (N = 2500, Cholesky, smoothing 1e-8): fit, and predict 2500 new windows.
//!
//! Two reference points for the OLS core, which streams the N × M candidate matrix
//! once per pick: the N × M Gaussian kernel matrix itself, and one plain
//! matrix–vector product vᵀP over it (the memory-bandwidth bound of a pick).
//!
//! A second group, `threads`, fits OLS (K = 100) and k-means (K = 100) with one thread
//! and with two, at N = 2500 and N = 5000 (OLS over all 5000 rows as candidates): the
//! passes' threads are the engine's choice (`OlsPath::pass_threads`), the rest of the
//! fit runs as asked.
//!
//! ```sh
//! CARGO_TARGET_DIR=... cargo bench -p rbf --bench centre_selection
//! cargo bench -p rbf --bench centre_selection -- threads     # the thread group only
//! ```

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};
use linfa::ParamGuard;
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::Xoshiro256Plus;
use rbf::{CentreSelection, Kernel, RbfParams, RbfValidParams, WidthRule, Widths, kernel_matrix};

const DIM: usize = 50;
const N_TRAIN: usize = 2500;
const K: usize = 100;
const SEED: u64 = 2024;

/// Windows and targets for `n` consecutive time steps of the filtered signal.
fn windowed(n: usize, seed: u64) -> (Mat<f64>, Mat<f64>) {
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    let burn = 200;
    let len = n + DIM + burn;
    // s_k = 1.6 s_{k−1} − 0.8 s_{k−2} + u_k: poles at radius 0.89, a resonant low-pass
    let mut s = vec![0.0f64; len];
    for k in 2..len {
        let u: f64 = StandardNormal.sample(&mut rng);
        s[k] = 1.6 * s[k - 1] - 0.8 * s[k - 2] + u;
    }
    let s = &s[burn..];
    let sd = (s.iter().map(|v| v * v).sum::<f64>() / s.len() as f64).sqrt();
    let s: Vec<f64> = s.iter().map(|v| v / sd).collect();
    let x = Mat::from_fn(n, DIM, |t, j| s[t + DIM - 1 - j]);
    let y = Mat::from_fn(n, 1, |t, _| {
        let at = |lag: usize| s[t + DIM - 1 - lag];
        let e: f64 = StandardNormal.sample(&mut rng);
        (1.5 * at(0)).sin() * (-at(10) * at(10) / 2.0).exp() + 0.3 * at(3) * at(7) + 0.05 * e
    });
    (x, y)
}

fn params(centres: CentreSelection, beta: f64, ridge: f64) -> RbfValidParams {
    RbfParams::new()
        .kernel(Kernel::Gaussian)
        .centres(centres)
        .width(WidthRule::Fixed(beta))
        .ridge(ridge)
        .seed(SEED)
        .check()
        .expect("valid params")
}

fn matvec(p: MatRef<'_, f64>, v: MatRef<'_, f64>, out: &mut Mat<f64>) {
    matmul(
        out.as_mut(),
        Accum::Replace,
        v.transpose(),
        p,
        1.0,
        faer::get_global_parallelism(),
    );
}

fn bench(c: &mut Criterion) {
    let (x, y) = windowed(2 * N_TRAIN, SEED);
    let (xt, yt) = (x.subrows(0, N_TRAIN), y.subrows(0, N_TRAIN));
    let xv = x.subrows(N_TRAIN, N_TRAIN);
    let beta = match WidthRule::default()
        .widths(xt, faer::get_global_parallelism())
        .expect("median width")
    {
        Widths::Uniform(b) => b,
        Widths::PerCentre(_) => unreachable!("the median rule gives one width"),
    };

    let mut g = c.benchmark_group("centre_selection_d50_n2500");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));

    let phi = kernel_matrix(
        xt,
        xt,
        Kernel::Gaussian,
        &Widths::Uniform(beta),
        faer::get_global_parallelism(),
    );
    g.bench_function("kernel_matrix_2500x2500", |b| {
        b.iter(|| {
            kernel_matrix(
                black_box(xt),
                xt,
                Kernel::Gaussian,
                &Widths::Uniform(beta),
                faer::get_global_parallelism(),
            )
        })
    });
    let v = Mat::from_fn(N_TRAIN, 1, |i, _| (i as f64).sin());
    let mut out = Mat::zeros(1, N_TRAIN);
    g.bench_function("matvec_bound_vT_P_2500x2500", |b| {
        b.iter(|| matvec(black_box(phi.as_ref()), v.as_ref(), &mut out))
    });

    let ols = params(CentreSelection::ols(K), beta, 0.0);
    g.bench_function("ols_k100_fit", |b| {
        b.iter(|| ols.fit(black_box(xt), yt).expect("OLS fits"))
    });
    let kmeans = params(CentreSelection::kmeans(K), beta, 0.0);
    g.bench_function("kmeans_k100_qr_fit", |b| {
        b.iter(|| kmeans.fit(black_box(xt), yt).expect("k-means fits"))
    });
    let random = params(CentreSelection::random(K), beta, 0.0);
    g.bench_function("random_k100_qr_fit", |b| {
        b.iter(|| random.fit(black_box(xt), yt).expect("random fits"))
    });
    let all = params(CentreSelection::AllPoints, beta, 1e-8);
    g.bench_function("all_points_fit", |b| {
        b.iter(|| all.fit(black_box(xt), yt).expect("all points fits"))
    });
    let model = all.fit(xt, yt).expect("all points fits");
    g.bench_function("all_points_predict_2500", |b| {
        b.iter(|| model.predict(black_box(xv)))
    });
    g.finish();
}

/// OLS and k-means on one thread and on two, at two sizes.
fn threads(c: &mut Criterion) {
    let mut g = c.benchmark_group("threads");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(8));
    for n in [N_TRAIN, 2 * N_TRAIN] {
        let (x, y) = windowed(n, SEED);
        let (x, y) = (x.as_ref(), y.as_ref());
        let beta = match WidthRule::default()
            .widths(x, Par::Seq)
            .expect("median width")
        {
            Widths::Uniform(b) => b,
            Widths::PerCentre(_) => unreachable!("the median rule gives one width"),
        };
        for (threads, par) in [(1, Par::Seq), (2, Par::rayon(2))] {
            let ols = RbfParams::from(params(CentreSelection::ols(K), beta, 0.0))
                .parallelism(par)
                .check()
                .expect("valid params");
            g.bench_function(format!("ols_k100_n{n}_{threads}t"), |b| {
                b.iter(|| ols.fit(black_box(x), y).expect("OLS fits"))
            });
            let km = RbfParams::from(params(CentreSelection::kmeans(K), beta, 0.0))
                .parallelism(par)
                .check()
                .expect("valid params");
            g.bench_function(format!("kmeans_k100_n{n}_{threads}t"), |b| {
                b.iter(|| km.fit(black_box(x), y).expect("k-means fits"))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench, threads);
criterion_main!(benches);
