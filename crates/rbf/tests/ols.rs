//! The OLS/ERR engine against references, on well- and ill-conditioned problems.

mod common;

use faer::{Mat, Par};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256Plus;
use rbf::{
    Kernel, OlsError, OlsOptions, StopReason, Widths, forward_select, forward_select_owned,
    kernel_matrix, lstsq,
};

fn random(n: usize, m: usize, seed: u64) -> Mat<f64> {
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    Mat::from_fn(n, m, |_, _| rng.gen_range(-1.0..1.0))
}

/// On well-conditioned random candidates (with a forced bias and two outputs) the engine
/// picks exactly what the Householder reference picks, with the same ERRs (to 1e-12,
/// rounding of O(k·ε) in sums of magnitude ≤ 1).
#[test]
fn matches_the_householder_reference_on_well_conditioned_data() {
    for &(n, m, k, seed) in &[(120, 60, 25, 1), (300, 150, 40, 2), (60, 80, 30, 3)] {
        let cand = random(n, m, seed);
        let y = Mat::from_fn(n, 2, |i, o| {
            cand[(i, 3 + o)] * 2.0 - cand[(i, 7)] + 0.1 * cand[(i, 11)].powi(2) + 0.3
        });
        let ones = Mat::<f64>::ones(n, 1);
        for par in [Par::Seq, Par::rayon(2)] {
            let path = forward_select(
                cand.as_ref(),
                ones.as_ref(),
                y.as_ref(),
                &OlsOptions::new(k).par(par),
            )
            .unwrap();
            let (picks, errs) = common::reference_select(
                cand.as_ref(),
                ones.as_ref(),
                y.as_ref(),
                path.len(),
                1e-12,
            );
            assert_eq!(path.selected(), picks, "n={n} m={m}");
            for (p, e) in path.picks().iter().zip(&errs) {
                assert!((p.err - e).abs() < 1e-12, "{} vs {}", p.err, e);
            }
        }
    }
}

/// Gaussian kernel columns of the Chen series with wide widths are numerically low-rank:
/// classical Gram–Schmidt loses orthogonality and picks differently from the reference
/// (at pick 8 for β = 3, pick 35 for β = 1 in this data), while the engine agrees with
/// the reference at every pick until no candidate is left outside the selected span.
#[test]
fn matches_the_reference_where_classical_gram_schmidt_fails() {
    for &(beta, sd, k) in &[(1.0, 0.1, 40), (3.0, 0.2, 40)] {
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
        let path =
            forward_select(phi.as_ref(), none.as_ref(), y.as_ref(), &OlsOptions::new(k)).unwrap();
        let ours = path.selected();
        let (reference, _) =
            common::reference_select(phi.as_ref(), none.as_ref(), y.as_ref(), ours.len(), 1e-12);
        assert_eq!(ours, reference, "β = {beta}");
        let cgs = common::classical_gram_schmidt_select(phi.as_ref(), y.as_ref(), ours.len());
        assert_ne!(
            cgs, reference,
            "β = {beta}: expected classical Gram–Schmidt to go astray here"
        );
    }
}

/// One run gives every model size: weights(k) equals a QR least-squares solve on the
/// forced columns plus the first k picks, for every k (relative 1e-9: both are
/// backward-stable solves of systems with condition numbers up to ~1e3 here).
#[test]
fn path_weights_equal_least_squares_for_every_k() {
    let (n, m) = (200, 50);
    let cand = random(n, m, 5);
    let mut rng = Xoshiro256Plus::seed_from_u64(6);
    let y = Mat::from_fn(n, 1, |i, _| {
        cand[(i, 1)] - 0.5 * cand[(i, 9)] + rng.gen_range(-0.1..0.1)
    });
    let forced = Mat::from_fn(n, 2, |i, j| if j == 0 { 1.0 } else { i as f64 / n as f64 });
    let path = forward_select(
        cand.as_ref(),
        forced.as_ref(),
        y.as_ref(),
        &OlsOptions::new(20),
    )
    .unwrap();
    for k in 0..=path.len() {
        let sel = path.selected();
        let a = Mat::from_fn(n, 2 + k, |i, j| {
            if j < 2 {
                forced[(i, j)]
            } else {
                cand[(i, sel[j - 2])]
            }
        });
        let want = lstsq(a.as_ref(), y.as_ref(), &Default::default())
            .unwrap()
            .coefficients;
        let got = path.weights(k);
        assert!((&got - &want).norm_max() <= 1e-9 * want.norm_max(), "k={k}");
        let rss = lstsq(a.as_ref(), y.as_ref(), &Default::default())
            .unwrap()
            .residual_sum_squares[0];
        assert!((path.residual_sum_squares(k) - rss).abs() <= 1e-9 * path.target_energy());
    }
}

/// First-step ERRs are each candidate's own ERR after the forced columns:
/// (p̃ᵀd)² / (‖p̃‖² dᵀd) with p̃ = p minus its projection on the forced columns.
#[test]
fn first_step_errs_are_individual_errs() {
    let (n, m) = (80, 12);
    let cand = random(n, m, 8);
    let y = Mat::from_fn(n, 1, |i, _| cand[(i, 0)] + 2.0);
    let ones = Mat::<f64>::ones(n, 1);
    let path = forward_select(
        cand.as_ref(),
        ones.as_ref(),
        y.as_ref(),
        &OlsOptions::new(3),
    )
    .unwrap();
    let dd: f64 = (0..n).map(|i| y[(i, 0)].powi(2)).sum();
    for j in 0..m {
        let mean = (0..n).map(|i| cand[(i, j)]).sum::<f64>() / n as f64;
        let pt: Vec<f64> = (0..n).map(|i| cand[(i, j)] - mean).collect();
        let num: f64 = pt.iter().enumerate().map(|(i, v)| v * y[(i, 0)]).sum();
        let den: f64 = pt.iter().map(|v| v * v).sum::<f64>() * dd;
        assert!(
            (path.first_step_errs()[j] - num * num / den).abs() < 1e-12,
            "candidate {j}"
        );
    }
    // forced ERR of the bias: (Σy)²/(n dᵀd)
    let s: f64 = (0..n).map(|i| y[(i, 0)]).sum();
    assert!((path.forced_errs()[0] - s * s / (n as f64 * dd)).abs() < 1e-12);
}

/// Multi-output ERR is the sum over outputs as Chen defines it: Σ_o (wᵀd_o)² / (wᵀw Σ_o d_oᵀd_o).
#[test]
fn multi_output_err_sums_over_outputs() {
    let n = 50;
    let cand = random(n, 4, 9);
    let y = random(n, 3, 10);
    let none = Mat::<f64>::zeros(n, 0);
    let path = forward_select(
        cand.as_ref(),
        none.as_ref(),
        y.as_ref(),
        &OlsOptions::new(1),
    )
    .unwrap();
    let dd: f64 = (0..3)
        .map(|o| (0..n).map(|i| y[(i, o)].powi(2)).sum::<f64>())
        .sum();
    let want: Vec<f64> = (0..4)
        .map(|j| {
            let pp: f64 = (0..n).map(|i| cand[(i, j)].powi(2)).sum();
            (0..3)
                .map(|o| {
                    (0..n)
                        .map(|i| cand[(i, j)] * y[(i, o)])
                        .sum::<f64>()
                        .powi(2)
                })
                .sum::<f64>()
                / (pp * dd)
        })
        .collect();
    for (got, want) in path.first_step_errs().iter().zip(&want) {
        assert!((got - want).abs() < 1e-13);
    }
    let best = (0..4).max_by(|&a, &b| want[a].total_cmp(&want[b])).unwrap();
    assert_eq!(path.selected(), vec![best]);
}

/// Regularised ERR (Chen, Chng & Alkadhimi 1996): (wᵀd)² / ((wᵀw + λ) dᵀd), and the
/// path's weights shrink gᵢ by ‖wᵢ‖²/(‖wᵢ‖² + λ).
#[test]
fn regularised_err_follows_its_formula() {
    let n = 40;
    let cand = random(n, 3, 11);
    let y = Mat::from_fn(n, 1, |i, _| cand[(i, 2)]);
    let none = Mat::<f64>::zeros(n, 0);
    let lam = 2.5;
    let path = forward_select(
        cand.as_ref(),
        none.as_ref(),
        y.as_ref(),
        &OlsOptions::new(1).regularisation(lam),
    )
    .unwrap();
    let j = path.selected()[0];
    let pp: f64 = (0..n).map(|i| cand[(i, j)].powi(2)).sum();
    let pd: f64 = (0..n).map(|i| cand[(i, j)] * y[(i, 0)]).sum();
    let dd: f64 = (0..n).map(|i| y[(i, 0)].powi(2)).sum();
    assert!((path.picks()[0].err - pd * pd / ((pp + lam) * dd)).abs() < 1e-14);
    assert!((path.weights(1)[(0, 0)] - pd / (pp + lam)).abs() < 1e-13);
}

/// Candidates collinear with what is in (a duplicate, a combination of forced columns, a
/// zero column) are never picked, and selection stops when only such candidates remain.
#[test]
fn collinear_candidates_are_never_picked() {
    let n = 30;
    let base = random(n, 3, 12);
    let forced = Mat::from_fn(n, 1, |i, _| base[(i, 0)]);
    // 0: forced column ×2, 1: base1, 2: duplicate of base1, 3: zero, 4: base2, 5: base1 + forced
    let cand = Mat::from_fn(n, 6, |i, j| match j {
        0 => 2.0 * base[(i, 0)],
        1 | 2 => base[(i, 1)],
        3 => 0.0,
        4 => base[(i, 2)],
        _ => base[(i, 1)] + base[(i, 0)],
    });
    let y = Mat::from_fn(n, 1, |i, _| {
        base[(i, 0)] + base[(i, 1)] - base[(i, 2)] + 0.01 * (i as f64).sin()
    });
    let path = forward_select(
        cand.as_ref(),
        forced.as_ref(),
        y.as_ref(),
        &Default::default(),
    )
    .unwrap();
    assert_eq!(path.len(), 2);
    let mut sel = path.selected();
    sel.sort();
    assert!(
        sel == vec![1, 4] || sel == vec![2, 4] || sel == vec![4, 5],
        "{sel:?}"
    );
    assert_eq!(path.stop_reason(), StopReason::Exhausted);
    assert_eq!(path.first_step_errs()[0], 0.0);
    assert_eq!(path.first_step_errs()[3], 0.0);
}

#[test]
fn collinear_forced_columns_are_an_error() {
    let n = 10;
    let f = Mat::from_fn(n, 2, |i, _| i as f64);
    let y = Mat::<f64>::ones(n, 1);
    let c = Mat::<f64>::ones(n, 1);
    assert_eq!(
        forward_select(c.as_ref(), f.as_ref(), y.as_ref(), &Default::default()).unwrap_err(),
        OlsError::ForcedCollinear { column: 1 }
    );
}

#[test]
fn bad_data_and_options_are_typed_errors() {
    let n = 5;
    let mut c = Mat::<f64>::ones(n, 2);
    let none = Mat::<f64>::zeros(n, 0);
    let y = Mat::<f64>::ones(n, 1);
    c[(3, 1)] = f64::INFINITY;
    assert_eq!(
        forward_select(c.as_ref(), none.as_ref(), y.as_ref(), &Default::default()).unwrap_err(),
        OlsError::NonFinite {
            matrix: "candidates",
            row: 3,
            col: 1
        }
    );
    let c = Mat::<f64>::ones(n, 2);
    assert_eq!(
        forward_select(
            c.as_ref(),
            none.as_ref(),
            Mat::<f64>::zeros(n, 1).as_ref(),
            &Default::default()
        )
        .unwrap_err(),
        OlsError::ZeroTarget
    );
    assert!(matches!(
        forward_select(
            c.as_ref(),
            none.as_ref(),
            y.as_ref(),
            &OlsOptions::new(1).tol(1.5)
        ),
        Err(OlsError::InvalidOption { option: "tol", .. })
    ));
    let e = Mat::<f64>::zeros(0, 2);
    assert_eq!(
        forward_select(
            e.as_ref(),
            Mat::<f64>::zeros(0, 0).as_ref(),
            Mat::<f64>::zeros(0, 1).as_ref(),
            &Default::default()
        )
        .unwrap_err(),
        OlsError::NoSamples
    );
}

#[test]
#[should_panic(expected = "targets have")]
fn mismatched_rows_panic() {
    let c = Mat::<f64>::ones(4, 2);
    let _ = forward_select(
        c.as_ref(),
        Mat::<f64>::zeros(4, 0).as_ref(),
        Mat::<f64>::ones(3, 1).as_ref(),
        &Default::default(),
    );
}

/// The tolerance stops at the first pick with 1 − ΣERR < ρ; the progress callback sees
/// every pick; owned, borrowed, transposed-view and sequential/parallel runs agree exactly.
#[test]
fn tolerance_progress_and_storage_variants() {
    let s = common::chen_series(402, 0.1, 2);
    let (x, y) = common::lagged(&s);
    let phi = kernel_matrix(
        x.as_ref(),
        x.as_ref(),
        Kernel::ThinPlateSpline,
        &Widths::Uniform(1.0),
        Par::Seq,
    );
    let ones = Mat::<f64>::ones(x.nrows(), 1);
    let rho = 0.05;
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let count = |_: rbf::OlsProgress| {
        calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    };
    let path = forward_select(
        phi.as_ref(),
        ones.as_ref(),
        y.as_ref(),
        &OlsOptions::new(100).tol(rho).progress(&count),
    )
    .unwrap();
    assert_eq!(path.stop_reason(), StopReason::Tolerance);
    assert!(1.0 - path.cumulative_err() < rho);
    assert!(1.0 - path.cumulative_err_at(path.len() - 1) >= rho);
    assert_eq!(calls.load(std::sync::atomic::Ordering::Relaxed), path.len());
    assert_eq!(path.terms_for_tol(rho), path.len());

    let owned = forward_select_owned(
        phi.clone(),
        ones.as_ref(),
        y.as_ref(),
        &OlsOptions::new(30).par(Par::rayon(2)),
    )
    .unwrap();
    let borrowed = forward_select(
        phi.as_ref(),
        ones.as_ref(),
        y.as_ref(),
        &OlsOptions::new(30).par(Par::Seq),
    )
    .unwrap();
    let phit = phi.transpose().to_owned();
    let strided = forward_select(
        phit.transpose(),
        ones.as_ref(),
        y.as_ref(),
        &OlsOptions::new(30),
    )
    .unwrap();
    assert_eq!(owned.selected(), borrowed.selected());
    assert_eq!(owned.selected(), strided.selected());
    for (a, b) in owned.picks().iter().zip(borrowed.picks()) {
        assert!((a.err - b.err).abs() < 1e-14);
    }
}

/// The known-truth system of SysIdentPy's examples,
/// y[k] = 0.2 y[k−1] + 0.1 y[k−1] x[k−1] + 0.9 x[k−2] + e, x ~ U(−1, 1), e ~ N(0, 0.05²):
/// among all monomials up to degree 2 in y[k−1], y[k−2], x[k−1], x[k−2] (15 candidates,
/// the constant included), the engine ranks the three true terms first, for several seeds.
#[test]
fn ranks_the_known_true_terms_first() {
    use rand_distr::{Distribution, Normal};
    for seed in [1u64, 2, 3] {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let noise = Normal::new(0.0, 0.05).unwrap();
        let n = 1000;
        let xs: Vec<f64> = (0..n).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let mut ys = vec![0.0; n];
        for k in 2..n {
            let e: f64 = noise.sample(&mut rng);
            ys[k] = 0.2 * ys[k - 1] + 0.1 * ys[k - 1] * xs[k - 1] + 0.9 * xs[k - 2] + e;
        }
        let rows = n - 2;
        let vars = |i: usize| [ys[i + 1], ys[i], xs[i + 1], xs[i]]; // y1, y2, x1, x2 for target k = i + 2
        let mut names = vec!["1".to_string()];
        let label = ["y1", "y2", "x1", "x2"];
        for l in label {
            names.push(l.into());
        }
        for a in 0..4 {
            for b in a..4 {
                names.push(format!("{}*{}", label[a], label[b]));
            }
        }
        let cand = Mat::from_fn(rows, names.len(), |i, j| {
            let v = vars(i);
            match j {
                0 => 1.0,
                1..=4 => v[j - 1],
                _ => {
                    let mut t = 5;
                    for a in 0..4 {
                        for b in a..4 {
                            if t == j {
                                return v[a] * v[b];
                            }
                            t += 1;
                        }
                    }
                    unreachable!()
                }
            }
        });
        let y = Mat::from_fn(rows, 1, |i, _| ys[i + 2]);
        let path = forward_select(
            cand.as_ref(),
            Mat::<f64>::zeros(rows, 0).as_ref(),
            y.as_ref(),
            &OlsOptions::new(6),
        )
        .unwrap();
        let mut first: Vec<&str> = path.selected()[..3]
            .iter()
            .map(|&j| names[j].as_str())
            .collect();
        first.sort();
        assert_eq!(
            first,
            vec!["x2", "y1", "y1*x1"],
            "seed {seed}: {:?}",
            path.selected()
        );
    }
}

/// Values whose squares overflow (≥ 1e155) used to make every score NaN and
/// the selection loop spin for ever; now each is a typed error, at once.
#[test]
fn overflowing_columns_end_selection_with_an_error() {
    let n = 40;
    let none = Mat::<f64>::zeros(n, 0);
    let cand = random(n, 10, 7);
    let mut y = Mat::from_fn(n, 1, |i, _| cand[(i, 2)]);
    y[(5, 0)] = 1e155;
    assert!(matches!(
        forward_select(
            cand.as_ref(),
            none.as_ref(),
            y.as_ref(),
            &OlsOptions::new(5)
        ),
        Err(OlsError::Overflow {
            what: "targets",
            ..
        })
    ));
    let y = Mat::from_fn(n, 1, |i, _| cand[(i, 2)]);
    let mut big = cand.clone();
    big[(9, 4)] = 1e160;
    assert!(matches!(
        forward_select(big.as_ref(), none.as_ref(), y.as_ref(), &OlsOptions::new(5)),
        Err(OlsError::Overflow {
            what: "candidates",
            ..
        })
    ));
    let mut forced = Mat::<f64>::ones(n, 1);
    forced[(0, 0)] = -1e200;
    assert!(matches!(
        forward_select(
            cand.as_ref(),
            forced.as_ref(),
            y.as_ref(),
            &OlsOptions::new(5)
        ),
        Err(OlsError::Overflow {
            what: "forced columns",
            ..
        })
    ));
    // Large values whose ERR products stay finite still select normally.
    let scaled = Mat::from_fn(n, 10, |i, j| cand[(i, j)] * 1e50);
    let ys = Mat::from_fn(n, 1, |i, _| scaled[(i, 2)]);
    let path = forward_select(
        scaled.as_ref(),
        none.as_ref(),
        ys.as_ref(),
        &OlsOptions::new(3),
    )
    .unwrap();
    assert_eq!(path.picks()[0].index, 2);
}
