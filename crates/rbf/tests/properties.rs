//! Property tests (proptest with a fixed seed and modest case counts, no persistence
//! files): invariances and bounds that must hold for any data.

mod common;

use faer::{Mat, Par};
use linfa::ParamGuard;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256Plus;
use rbf::{
    CentreSelection, Kernel, LstsqOptions, OlsOptions, RbfParams, WidthRule, forward_select, lstsq,
};

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(20260101),
        failure_persistence: None,
        ..Config::default()
    }
}

fn random(n: usize, m: usize, rng: &mut Xoshiro256Plus) -> Mat<f64> {
    Mat::from_fn(n, m, |_, _| rng.gen_range(-1.0..1.0))
}

/// Points on a jittered grid in [0, 1]^d (d = 1 or 2): distinct, at least 0.4 of a grid
/// step apart, so interpolation matrices stay reasonably conditioned.
fn jittered(d: usize, per_axis: usize, rng: &mut Xoshiro256Plus) -> Mat<f64> {
    let h = 1.0 / per_axis as f64;
    let n = per_axis.pow(d as u32);
    Mat::from_fn(n, d, |i, k| {
        let cell = if k == 0 { i % per_axis } else { i / per_axis };
        (cell as f64 + 0.5 + rng.gen_range(-0.3..0.3)) * h
    })
}

proptest! {
    #![proptest_config(config(12))]

    /// Permuting the training rows permutes nothing in the model: predictions agree to
    /// rounding (1e-9 relative; sums are merely reordered) for OLS, all points and
    /// given centres.
    #[test]
    fn row_order_does_not_change_the_fit(seed in 0u64..1000, n in 20usize..60, d in 1usize..4) {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let x = random(n, d, &mut rng);
        let y = Mat::from_fn(n, 1, |i, _| (3.0 * x[(i, 0)]).sin() + x[(i, d - 1)].powi(2));
        let mut perm: Vec<usize> = (0..n).collect();
        perm.shuffle(&mut rng);
        let xp = Mat::from_fn(n, d, |i, k| x[(perm[i], k)]);
        let yp = Mat::from_fn(n, 1, |i, _| y[(perm[i], 0)]);
        let given = random(6, d, &mut rng);
        for sel in [CentreSelection::ols(8), CentreSelection::AllPoints, CentreSelection::Given(given)] {
            let p = RbfParams::new()
                .kernel(Kernel::InverseMultiquadric)
                .width(WidthRule::Fixed(0.7))
                .centres(sel)
                .ridge(1e-8)
                .parallelism(Par::Seq)
                .check()
                .unwrap();
            let a = p.fit(x.as_ref(), y.as_ref()).unwrap().predict(x.as_ref());
            let b = p.fit(xp.as_ref(), yp.as_ref()).unwrap().predict(x.as_ref());
            prop_assert!((&a - &b).norm_max() <= 1e-9 * (1.0 + a.norm_max()));
        }
    }

    /// Every training vector as a centre, no ridge: the network interpolates the
    /// training targets (|y| ≤ 1), for every kernel. The solves are backward stable, so
    /// the residual is O(ε‖Φ‖‖a‖) ≤ O(ε·κ); the bound allows 100·ε·κ̂ + 1e-12 with the
    /// model's own condition estimate κ̂ (≲ 1e6 on these jittered grids).
    #[test]
    fn all_centres_without_ridge_interpolate(seed in 0u64..1000, d in 1usize..3) {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let per_axis = if d == 1 { 30 } else { 6 };
        let h = 1.0 / per_axis as f64;
        let x = jittered(d, per_axis, &mut rng);
        let n = x.nrows();
        let y = Mat::from_fn(n, 1, |_, _| rng.gen_range(-1.0..1.0));
        for kernel in Kernel::ALL {
            // Shape parameters of a few grid steps: flatter kernels (β ≫ spacing) make
            // the interpolation matrix numerically singular, which is refused, not wrong.
            let width = match kernel {
                Kernel::Gaussian | Kernel::Multiquadric | Kernel::InverseMultiquadric | Kernel::InverseQuadratic => 1.5 * h,
                Kernel::WendlandC2 => 0.5,
                Kernel::ThinPlateSpline | Kernel::Cubic => 1.0,
            };
            let m = RbfParams::new()
                .kernel(kernel)
                .width(WidthRule::Fixed(width))
                .centres(CentreSelection::AllPoints)
                .parallelism(Par::Seq)
                .check()
                .unwrap()
                .fit(x.as_ref(), y.as_ref());
            prop_assert!(m.is_ok(), "{kernel} d={d}: {:?}", m.as_ref().err());
            let m = m.unwrap();
            let res = (&m.predict(x.as_ref()) - &y).norm_max();
            let bound = 1e-12 + 100.0 * f64::EPSILON * m.condition();
            prop_assert!(res < bound, "{kernel}: {res} > {bound} (condition {:.1e})", m.condition());
        }
    }

    /// ERRs lie in [0, 1] and sum (forced columns included) to at most 1, with or without
    /// forced columns, regularisation and several outputs (1e-12 slack for rounding).
    #[test]
    fn errs_are_fractions_that_sum_to_at_most_one(
        seed in 0u64..1000, n in 5usize..80, m in 1usize..40, p in 0usize..3, q in 1usize..3, lam in prop_oneof![Just(0.0), 0.0f64..2.0],
    ) {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let cand = random(n, m, &mut rng);
        let forced = random(n, p.min(n - 1), &mut rng);
        let y = random(n, q, &mut rng);
        let path = forward_select(cand.as_ref(), forced.as_ref(), y.as_ref(), &OlsOptions::new(m).regularisation(lam)).unwrap();
        let all: Vec<f64> = path.forced_errs().iter().copied().chain(path.picks().iter().map(|p| p.err)).collect();
        for e in all.iter().chain(path.first_step_errs()) {
            prop_assert!((-1e-12..=1.0 + 1e-12).contains(e), "ERR {e}");
        }
        prop_assert!(all.iter().sum::<f64>() <= 1.0 + 1e-12);
        prop_assert!((path.cumulative_err() - all.iter().sum::<f64>()).abs() < 1e-12);
    }

    /// On well-conditioned data the engine and the Householder reference pick the same
    /// candidates in the same order.
    #[test]
    fn engine_and_reference_qr_pick_alike(seed in 0u64..1000, n in 30usize..120, m in 5usize..60, k in 1usize..15) {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let cand = random(n, m, &mut rng);
        let y = Mat::from_fn(n, 1, |i, _| cand[(i, 0)] - 2.0 * cand[(i, m / 2)] + rng.gen_range(-0.5..0.5));
        let ones = Mat::<f64>::ones(n, 1);
        let path = forward_select(cand.as_ref(), ones.as_ref(), y.as_ref(), &OlsOptions::new(k)).unwrap();
        let (picks, _) = common::reference_select(cand.as_ref(), ones.as_ref(), y.as_ref(), k.min(m), 1e-12);
        prop_assert_eq!(path.selected(), picks);
    }

    /// Least-squares residuals are orthogonal to the columns over random sizes, with and
    /// without ridge (where the optimality condition has the λx term).
    #[test]
    fn lstsq_residuals_are_orthogonal(seed in 0u64..1000, n in 1usize..150, c in 1usize..40, q in 1usize..4, ridge in prop_oneof![Just(0.0), 1e-6f64..1.0]) {
        prop_assume!(ridge > 0.0 || n >= c);
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let a = random(n, c, &mut rng);
        let b = random(n, q, &mut rng);
        let s = lstsq(a.as_ref(), b.as_ref(), &LstsqOptions { ridge, par: Par::Seq, ..Default::default() }).unwrap();
        let mut g = a.transpose() * (&a * &s.coefficients - &b);
        g += &s.coefficients * ridge;
        let scale = (a.norm_l2() + ridge.sqrt()).powi(2) * (s.coefficients.norm_l2() + 1.0) + a.norm_l2() * b.norm_l2();
        prop_assert!(g.norm_l2() <= 1e-12 * scale, "{}", g.norm_l2() / scale);
    }
}
