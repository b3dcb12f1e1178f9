//! f32 streaming picks what f64 streaming picks: on the peer bench's kind of data
//! (Gaussian kernels of overlapping windows of a resonant process, whose neighbouring
//! candidates are nearly equal), on Chen's series with wide ill-conditioned widths, on
//! random kernels (property test), and with candidate columns generated on demand.

mod common;

use faer::{Mat, MatRef, Par};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_xoshiro::Xoshiro256Plus;
use rbf::{
    Kernel, KernelColumns, OlsOptions, OlsPath, StreamPrecision, Widths, forward_select,
    forward_select_columns, kernel_matrix,
};

/// Windows of `d` consecutive samples of unit white noise through a resonant
/// second-order low-pass (s_k = 1.6 s_{k−1} − 0.8 s_{k−2} + u_k), and a nonlinear target:
/// the recipe of `peers/scripts/peer.py gen`.
fn windows(n: usize, d: usize, seed: u64) -> (Mat<f64>, Mat<f64>) {
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    let len = n + d + 20;
    let mut s = vec![0.0f64; len];
    for k in 2..len {
        let u: f64 = rng.sample(StandardNormal);
        s[k] = 1.6 * s[k - 1] - 0.8 * s[k - 2] + u;
    }
    let sd = (s.iter().map(|v| v * v).sum::<f64>() / len as f64).sqrt();
    let s: Vec<f64> = s.iter().map(|v| v / sd).collect();
    let x = Mat::from_fn(n, d, |i, k| s[i + 20 + k]);
    let y = Mat::from_fn(n, 1, |i, _| {
        let t = i + 20 + d - 1;
        (1.5 * s[t]).sin() * (-s[t - 10].powi(2) / 2.0).exp() + 0.3 * s[t - 3] * s[t - 7]
    });
    (x, y)
}

fn median_width(x: MatRef<'_, f64>) -> f64 {
    let n = x.nrows();
    let mut d2: Vec<f64> = Vec::new();
    for i in (0..n).step_by(7) {
        for j in (i + 1..n).step_by(5) {
            d2.push(
                (0..x.ncols())
                    .map(|k| (x[(i, k)] - x[(j, k)]).powi(2))
                    .sum(),
            );
        }
    }
    d2.sort_by(f64::total_cmp);
    d2[d2.len() / 2].sqrt()
}

fn select(phi: MatRef<'_, f64>, y: MatRef<'_, f64>, k: usize, p: StreamPrecision) -> OlsPath {
    let ones = Mat::<f64>::ones(phi.nrows(), 1);
    forward_select(
        phi,
        ones.as_ref(),
        y,
        &OlsOptions::new(k).stream(p).par(Par::Seq),
    )
    .unwrap()
}

/// The bench's kind of data at a size CI affords: the same 80 picks in the same order
/// from the stored matrix in f32 and f64, and from generated kernel columns; the ERRs of
/// the picks agree to rounding (they are exact evaluations on both sides).
#[test]
fn the_picks_on_bench_like_windows_do_not_depend_on_the_precision() {
    let (x, y) = windows(900, 50, 2026);
    let beta = median_width(x.as_ref());
    let widths = Widths::Uniform(beta);
    let phi = kernel_matrix(x.as_ref(), x.as_ref(), Kernel::Gaussian, &widths, Par::Seq);
    let f64_path = select(phi.as_ref(), y.as_ref(), 80, StreamPrecision::F64);
    let f32_path = select(phi.as_ref(), y.as_ref(), 80, StreamPrecision::F32);
    assert_eq!(f64_path.selected(), f32_path.selected());
    let cols = KernelColumns::new(x.as_ref(), x.as_ref(), Kernel::Gaussian, &widths, Par::Seq);
    let ones = Mat::<f64>::ones(x.nrows(), 1);
    for par in [Par::Seq, Par::rayon(2)] {
        let generated = forward_select_columns(
            &cols,
            ones.as_ref(),
            y.as_ref(),
            &OlsOptions::new(80).par(par),
        )
        .unwrap();
        assert_eq!(f64_path.selected(), generated.selected());
        for (a, b) in f64_path.picks().iter().zip(generated.picks()) {
            assert!(
                (a.err - b.err).abs() <= 1e-12 * a.err.max(1e-3),
                "{} vs {}",
                a.err,
                b.err
            );
        }
    }
}

/// Chen's series with wide Gaussian widths, where classical Gram–Schmidt goes astray:
/// both precisions pick what the Householder reference picks.
#[test]
fn the_picks_on_chens_series_do_not_depend_on_the_precision() {
    for &(beta, sd, k) in &[(1.0, 0.1, 40), (3.0, 0.2, 40), (0.3, 0.2, 30)] {
        let s = common::chen_series(302, sd, 1);
        let (x, y) = common::lagged(&s);
        let phi = kernel_matrix(
            x.as_ref(),
            x.as_ref(),
            Kernel::Gaussian,
            &Widths::Uniform(beta),
            Par::Seq,
        );
        let none = Mat::<f64>::zeros(x.nrows(), 0);
        let paths: Vec<OlsPath> = [StreamPrecision::F64, StreamPrecision::F32]
            .into_iter()
            .map(|p| {
                forward_select(
                    phi.as_ref(),
                    none.as_ref(),
                    y.as_ref(),
                    &OlsOptions::new(k).stream(p),
                )
                .unwrap()
            })
            .collect();
        assert_eq!(paths[0].selected(), paths[1].selected(), "β = {beta}");
        let (reference, _) = common::reference_select(
            phi.as_ref(),
            none.as_ref(),
            y.as_ref(),
            paths[1].len(),
            1e-12,
        );
        assert_eq!(paths[1].selected(), reference, "β = {beta}");
    }
}

/// Kernel values far outside f32's range (thin-plate splines of points 10³⁰ apart, and
/// Gaussians underflowing) are scaled per column, so f32 streaming still picks the same.
#[test]
fn extreme_column_scales_pick_the_same() {
    let mut rng = Xoshiro256Plus::seed_from_u64(4);
    let n = 120;
    let x = Mat::from_fn(n, 2, |_, _| rng.gen_range(-1.0f64..1.0) * 1e30);
    let y = Mat::from_fn(n, 1, |i, _| {
        (x[(i, 0)] * 1e-30).sin() + (x[(i, 1)] * 2e-30).cos()
    });
    for (kernel, width) in [(Kernel::ThinPlateSpline, 1.0), (Kernel::Gaussian, 3e29)] {
        let phi = kernel_matrix(
            x.as_ref(),
            x.as_ref(),
            kernel,
            &Widths::Uniform(width),
            Par::Seq,
        );
        let a = select(phi.as_ref(), y.as_ref(), 25, StreamPrecision::F64);
        let b = select(phi.as_ref(), y.as_ref(), 25, StreamPrecision::F32);
        assert_eq!(a.selected(), b.selected(), "{kernel:?}");
    }
}

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(20261125),
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(24))]

    /// Any data, any kernel, any width from very narrow to very wide, one or two outputs:
    /// the same picks in both precisions.
    #[test]
    fn f32_streaming_picks_what_f64_picks(
        seed in 0u64..10_000,
        n in 30usize..160,
        d in 1usize..6,
        log_width in -1.5f64..1.5,
        kernel in prop::sample::select(vec![
            Kernel::Gaussian, Kernel::Multiquadric, Kernel::InverseMultiquadric,
            Kernel::ThinPlateSpline, Kernel::Cubic,
        ]),
        outputs in 1usize..3,
    ) {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let x = Mat::from_fn(n, d, |_, _| rng.gen_range(-1.0f64..1.0));
        let y = Mat::from_fn(n, outputs, |i, o| {
            (3.0 * x[(i, 0)]).sin() * (1.0 + o as f64) + x[(i, d - 1)].powi(2) + 0.05 * rng.gen_range(-1.0..1.0)
        });
        let phi = kernel_matrix(x.as_ref(), x.as_ref(), kernel, &Widths::Uniform(10f64.powf(log_width)), Par::Seq);
        let ones = Mat::<f64>::ones(n, 1);
        let k = n / 3;
        let run = |p| forward_select(phi.as_ref(), ones.as_ref(), y.as_ref(), &OlsOptions::new(k).stream(p));
        match (run(StreamPrecision::F64), run(StreamPrecision::F32)) {
            (Ok(a), Ok(b)) => prop_assert_eq!(a.selected(), b.selected()),
            (Err(a), Err(b)) => prop_assert_eq!(a.to_string(), b.to_string()),
            (a, b) => prop_assert!(false, "f64 {:?} but f32 {:?}", a.map(|p| p.selected()), b.map(|p| p.selected())),
        }
    }
}
