//! The fitted model: strategies, linear regressors, persistence, errors.

mod common;

use faer::{Mat, Par};
use linfa::ParamGuard;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256Plus;
use rbf::{
    Candidates, CentreSelection, Kernel, OlsOptions, PersistError, RbfError, RbfModel, RbfParams,
    SolveError, Stage, WidthRule, Widths, forward_select, kernel_matrix,
};

fn data(n: usize, d: usize, seed: u64) -> (Mat<f64>, Mat<f64>) {
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    let x: Mat<f64> = Mat::from_fn(n, d, |_, _| rng.gen_range(-1.0..1.0));
    let y = Mat::from_fn(n, 1, |i, _| {
        (2.0 * x[(i, 0)]).sin() + (0..d).map(|k| x[(i, k)].powi(2)).sum::<f64>() * 0.3
    });
    (x, y)
}

fn params() -> RbfParams {
    RbfParams::new()
        .width(WidthRule::Fixed(0.8))
        .parallelism(Par::Seq)
}

/// One model per strategy (and per optional part: standardisation, tail, linear regressors).
fn models() -> Vec<(String, RbfModel, Mat<f64>, Mat<f64>)> {
    let (x, y) = data(120, 2, 1);
    let z = Mat::from_fn(120, 2, |i, k| ((i * (k + 3)) % 7) as f64 - 3.0);
    let given = Mat::from_fn(9, 2, |i, k| {
        (i / 3 * (1 - k) + (i % 3) * k) as f64 * 0.8 - 0.8
    });
    let fits: Vec<(&str, RbfParams)> = vec![
        ("ols", params().centres(CentreSelection::ols(15))),
        (
            "ols-standardised-tail",
            params()
                .centres(CentreSelection::ols(15))
                .standardise(true)
                .linear_tail(true),
        ),
        (
            "ols-subsample",
            params().centres(CentreSelection::Ols {
                max_centres: 10,
                tol: 0.0,
                regularisation: 1e-3,
                candidates: Candidates::Subsample { size: 40 },
            }),
        ),
        (
            "kmeans-spread",
            params()
                .centres(CentreSelection::kmeans(10))
                .width(WidthRule::ClusterSpread { scale: 2.0 }),
        ),
        (
            "random",
            params().centres(CentreSelection::random(10)).ridge(1e-6),
        ),
        ("given", params().centres(CentreSelection::Given(given))),
        (
            "all-points-thin-plate",
            params()
                .kernel(Kernel::ThinPlateSpline)
                .centres(CentreSelection::AllPoints)
                .ridge(1e-3),
        ),
        (
            "all-points-gaussian",
            params()
                .kernel(Kernel::Gaussian)
                .width(WidthRule::Fixed(0.3))
                .centres(CentreSelection::AllPoints),
        ),
    ];
    let mut out = Vec::new();
    for (name, p) in fits {
        let p = p.check().unwrap();
        out.push((
            name.to_string(),
            p.fit(x.as_ref(), y.as_ref()).unwrap(),
            x.clone(),
            Mat::zeros(120, 0),
        ));
        if name.starts_with("ols") || name == "random" {
            let yz = Mat::from_fn(120, 1, |i, _| {
                y[(i, 0)] + 0.5 * z[(i, 0)] - 0.25 * z[(i, 1)]
            });
            out.push((
                format!("{name}+z"),
                p.fit_with_linear(x.as_ref(), z.as_ref(), yz.as_ref())
                    .unwrap(),
                x.clone(),
                z.clone(),
            ));
        }
    }
    out
}

/// Saving and loading gives the same model and bit-identical predictions, through a
/// writer and through a file, for every strategy.
#[test]
fn save_load_round_trip_is_bit_identical() {
    let dir = std::env::temp_dir().join(format!("rbf-model-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (xq, _) = data(57, 2, 99);
    for (name, m, _, z) in models() {
        let zq = Mat::from_fn(57, z.ncols(), |i, k| (i % (k + 2)) as f64);
        let before = m.predict_with_linear(xq.as_ref(), zq.as_ref());
        let mut buf = Vec::new();
        m.to_writer(&mut buf).unwrap();
        let back = RbfModel::from_reader(buf.as_slice()).unwrap();
        assert_eq!(back, m, "{name}");
        assert_eq!(
            back.predict_with_linear(xq.as_ref(), zq.as_ref()),
            before,
            "{name}"
        );
        let path = dir.join(format!("{name}.json"));
        m.save_json(&path).unwrap();
        let file = RbfModel::load_json(&path).unwrap();
        assert_eq!(
            file.predict_with_linear(xq.as_ref(), zq.as_ref()),
            before,
            "{name}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn corrupt_and_foreign_files_are_typed_errors() {
    let m = rbf::doc_model();
    let mut buf = Vec::new();
    m.to_writer(&mut buf).unwrap();
    let text = String::from_utf8(buf).unwrap();
    // truncated
    assert!(matches!(
        RbfModel::from_reader(&text.as_bytes()[..text.len() / 2]),
        Err(PersistError::Corrupt(_))
    ));
    // another version
    let other = text.replacen("\"format_version\": 1", "\"format_version\": 2", 1);
    assert!(matches!(
        RbfModel::from_reader(other.as_bytes()),
        Err(PersistError::Version {
            found: Some(2),
            expected: 1
        })
    ));
    // no version
    let none = text.replacen("\"format_version\": 1,", "", 1);
    assert!(matches!(
        RbfModel::from_reader(none.as_bytes()),
        Err(PersistError::Version { found: None, .. })
    ));
    // a shape that does not fit: one width too many
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["model"]["widths"] = serde_json::json!({"per_centre": vec![1.0; m.n_centres() + 1]});
    assert!(matches!(
        RbfModel::from_reader(v.to_string().as_bytes()),
        Err(PersistError::Inconsistent(_))
    ));
    // an unknown kernel
    let bad = text.replacen("\"gaussian\"", "\"sinc\"", 1);
    assert!(matches!(
        RbfModel::from_reader(bad.as_bytes()),
        Err(PersistError::Corrupt(_))
    ));
    // not a file
    assert!(matches!(
        RbfModel::load_json("/nonexistent/dir/m.json"),
        Err(PersistError::Io { path: Some(_), .. })
    ));
}

/// y = g(x) + zᵀθ: the semi-parametric fit recovers θ (noise-free data; tolerance 1e-3
/// leaves room for the RBF part's approximation error leaking into θ) and predicts
/// from both inputs.
#[test]
fn linear_regressors_are_recovered() {
    let (x, y) = data(300, 2, 3);
    let mut rng = Xoshiro256Plus::seed_from_u64(4);
    let z = Mat::from_fn(300, 2, |_, _| rng.gen_range(-2.0..2.0));
    let theta = [0.7, -1.3];
    let yz = Mat::from_fn(300, 1, |i, _| {
        y[(i, 0)] + theta[0] * z[(i, 0)] + theta[1] * z[(i, 1)]
    });
    for sel in [
        CentreSelection::ols(40),
        CentreSelection::kmeans(40),
        CentreSelection::random(40),
    ] {
        let name = format!("{:?}", sel.strategy());
        let m = params()
            .centres(sel)
            .ridge(1e-10)
            .check()
            .unwrap()
            .fit_with_linear(x.as_ref(), z.as_ref(), yz.as_ref())
            .unwrap();
        assert_eq!(m.n_linear(), 2);
        for (k, t) in theta.iter().enumerate() {
            assert!(
                (m.linear_coefficients()[(k, 0)] - t).abs() < 1e-3,
                "{name}: θ = {:?}",
                m.linear_coefficients()
            );
        }
        let (xt, yt) = data(50, 2, 5);
        let zt = Mat::from_fn(50, 2, |i, k| (i as f64 * 0.1 + k as f64).sin());
        let want = Mat::from_fn(50, 1, |i, _| {
            yt[(i, 0)] + theta[0] * zt[(i, 0)] + theta[1] * zt[(i, 1)]
        });
        let got = m.predict_with_linear(xt.as_ref(), zt.as_ref());
        assert!((&got - &want).norm_max() < 0.05, "{name}");
    }
}

/// The QR re-solve of the output weights and the OLS path's triangular solve agree
/// (both are least squares on the same columns), which is why re-solving costs nothing
/// in accuracy and adds the ridge and the rank/condition checks.
#[test]
fn ols_model_weights_equal_the_path_weights() {
    let (x, y) = data(150, 2, 6);
    let p = params().centres(CentreSelection::ols(20)).check().unwrap();
    let m = p.fit(x.as_ref(), y.as_ref()).unwrap();
    let phi = kernel_matrix(
        x.as_ref(),
        x.as_ref(),
        Kernel::Gaussian,
        &Widths::Uniform(0.8),
        Par::Seq,
    );
    let path = forward_select(
        phi.as_ref(),
        Mat::<f64>::ones(150, 1).as_ref(),
        y.as_ref(),
        &OlsOptions::new(20),
    )
    .unwrap();
    let sel: Vec<usize> = m
        .selection()
        .unwrap()
        .picks
        .iter()
        .map(|p| p.index)
        .collect();
    assert_eq!(sel, path.selected());
    let w = path.weights(20);
    assert!((w[(0, 0)] - m.bias().unwrap()[0]).abs() < 1e-9);
    for k in 0..20 {
        assert!((w[(k + 1, 0)] - m.weights()[(k, 0)]).abs() < 1e-9 * w.norm_max());
    }
}

#[test]
fn rank_deficiency_is_reported_not_hidden() {
    let (x, y) = data(60, 2, 7);
    // duplicated given centre → two identical kernel columns
    let c = faer::mat![[0.0, 0.0], [0.5, 0.5], [0.0, 0.0]];
    let e = params()
        .centres(CentreSelection::Given(c))
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap_err();
    match e {
        RbfError::Solve(SolveError::RankDeficient {
            rank,
            columns,
            dependent,
        }) => {
            assert_eq!((rank, columns), (3, 4));
            assert!(
                dependent == vec![1] || dependent == vec![3],
                "{dependent:?}"
            );
        }
        other => panic!("{other}"),
    }
    // a constant linear regressor duplicates the bias
    let z = Mat::<f64>::ones(60, 1);
    let e = params()
        .centres(CentreSelection::ols(5))
        .check()
        .unwrap()
        .fit_with_linear(x.as_ref(), z.as_ref(), y.as_ref())
        .unwrap_err();
    assert!(
        matches!(
            e,
            RbfError::Ols(rbf::OlsError::ForcedCollinear { column: 1 })
        ),
        "{e}"
    );
    let e = params()
        .centres(CentreSelection::random(5))
        .check()
        .unwrap()
        .fit_with_linear(x.as_ref(), z.as_ref(), y.as_ref())
        .unwrap_err();
    assert!(
        matches!(e, RbfError::Solve(SolveError::RankDeficient { .. })),
        "{e}"
    );
}

/// Nearly dependent kernel columns are refused — as rank deficiency when some |R_kk|
/// falls below max(n, c)·ε·|R_11|, as ill-conditioning when the estimated condition
/// number exceeds the limit — and a ridge cures both.
#[test]
fn ill_conditioning_is_refused_and_a_ridge_cures_it() {
    let (x, y) = data(200, 1, 8);
    let p = |beta: f64, k: usize| {
        params()
            .kernel(Kernel::Gaussian)
            .width(WidthRule::Fixed(beta))
            .centres(CentreSelection::random(k))
    };
    // wide Gaussians on a line: numerically rank-deficient
    let e = p(3.0, 30)
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap_err();
    assert!(
        matches!(e, RbfError::Solve(SolveError::RankDeficient { .. })),
        "{e}"
    );
    assert!(e.to_string().contains("ridge"));
    assert!(
        p(3.0, 30)
            .ridge(1e-6)
            .check()
            .unwrap()
            .fit(x.as_ref(), y.as_ref())
            .is_ok()
    );
    // a full-rank but ill-conditioned case, refused under a tighter limit
    let m = p(0.5, 12)
        .max_condition(f64::INFINITY)
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap();
    let limit = m.condition() / 10.0;
    let e = p(0.5, 12)
        .max_condition(limit)
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap_err();
    match e {
        RbfError::Solve(SolveError::IllConditioned {
            condition,
            limit: l,
        }) => {
            assert_eq!(l, limit);
            assert!((condition / m.condition() - 1.0).abs() < 1e-6);
        }
        other => panic!("{other}"),
    }
    let r = p(0.5, 12)
        .ridge(1e-4)
        .max_condition(limit)
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap();
    assert!(r.condition() < limit);
}

#[test]
fn bad_data_are_typed_errors() {
    let (mut x, y) = data(30, 2, 9);
    let p = params().centres(CentreSelection::ols(5)).check().unwrap();
    x[(4, 1)] = f64::NAN;
    assert!(matches!(
        p.fit(x.as_ref(), y.as_ref()),
        Err(RbfError::NonFinite {
            matrix: "x",
            row: 4,
            col: 1
        })
    ));
    let (x, mut y) = data(30, 2, 9);
    y[(7, 0)] = f64::INFINITY;
    assert!(matches!(
        p.fit(x.as_ref(), y.as_ref()),
        Err(RbfError::NonFinite {
            matrix: "y",
            row: 7,
            col: 0
        })
    ));
    let (x, y) = data(30, 2, 9);
    let mut z = Mat::<f64>::zeros(30, 1);
    z[(0, 0)] = f64::NAN;
    assert!(matches!(
        p.fit_with_linear(x.as_ref(), z.as_ref(), y.as_ref()),
        Err(RbfError::NonFinite { matrix: "z", .. })
    ));
    for sel in [
        CentreSelection::random(31),
        CentreSelection::kmeans(40),
        CentreSelection::Given(Mat::zeros(35, 2)),
    ] {
        let e = params()
            .centres(sel)
            .check()
            .unwrap()
            .fit(x.as_ref(), y.as_ref())
            .unwrap_err();
        assert!(
            matches!(e, RbfError::FewerRowsThanCentres { rows: 30, .. }),
            "{e}"
        );
    }
    let one = Mat::<f64>::zeros(1, 2);
    let e = params()
        .linear_tail(true)
        .check()
        .unwrap()
        .fit(one.as_ref(), Mat::<f64>::ones(1, 1).as_ref())
        .unwrap_err();
    assert!(
        matches!(
            e,
            RbfError::TooFewSamples {
                samples: 1,
                needed: 4
            }
        ),
        "{e}"
    );
    let e = params()
        .centres(CentreSelection::Given(Mat::zeros(3, 5)))
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap_err();
    assert!(
        matches!(
            e,
            RbfError::Dimension {
                expected: 2,
                found: 5,
                ..
            }
        ),
        "{e}"
    );
}

/// With standardisation on, rescaling and shifting an input changes nothing
/// (relative 1e-9: the standardised inputs agree to rounding).
#[test]
fn standardisation_makes_the_fit_unit_free() {
    let (x, y) = data(100, 2, 10);
    let scaled = Mat::from_fn(100, 2, |i, k| {
        if k == 0 {
            1000.0 * x[(i, 0)] + 5e4
        } else {
            x[(i, 1)]
        }
    });
    let p = params()
        .centres(CentreSelection::ols(12))
        .standardise(true)
        .check()
        .unwrap();
    let a = p.fit(x.as_ref(), y.as_ref()).unwrap();
    let b = p.fit(scaled.as_ref(), y.as_ref()).unwrap();
    let (pa, pb) = (a.predict(x.as_ref()), b.predict(scaled.as_ref()));
    assert!((&pa - &pb).norm_max() < 1e-9 * pa.norm_max());
    assert!((b.centres()[(0, 0)] - (1000.0 * a.centres()[(0, 0)] + 5e4)).abs() < 1e-6);
}

/// Several outputs at once equal separate fits when the centres are the same.
#[test]
fn outputs_are_fitted_jointly_and_exactly() {
    let (x, y) = data(80, 2, 11);
    let y2 = Mat::from_fn(80, 2, |i, k| {
        if k == 0 {
            y[(i, 0)]
        } else {
            x[(i, 0)] * x[(i, 1)]
        }
    });
    let p = params()
        .centres(CentreSelection::random(12))
        .check()
        .unwrap();
    let both = p.fit(x.as_ref(), y2.as_ref()).unwrap();
    assert_eq!(both.n_outputs(), 2);
    for k in 0..2 {
        let one = p.fit(x.as_ref(), y2.as_ref().subcols(k, 1)).unwrap();
        let (a, b) = (both.predict(x.as_ref()), one.predict(x.as_ref()));
        for i in 0..80 {
            assert!((a[(i, k)] - b[(i, 0)]).abs() < 1e-12);
        }
    }
}

/// Predicting in row blocks (large n × K) equals the direct product.
#[test]
fn blocked_prediction_equals_the_direct_product() {
    let mut rng = Xoshiro256Plus::seed_from_u64(12);
    let c = Mat::from_fn(600, 1, |_, _| rng.gen_range(-1.0..1.0));
    let (x, y) = data(800, 1, 13);
    let m = params()
        .kernel(Kernel::InverseMultiquadric)
        .centres(CentreSelection::Given(c.clone()))
        .ridge(1e-3)
        .max_condition(f64::INFINITY)
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap();
    let xq = Mat::from_fn(15000, 1, |i, _| i as f64 / 7500.0 - 1.0); // 15000 rows: three 6990-row blocks
    let phi = kernel_matrix(
        xq.as_ref(),
        c.as_ref(),
        Kernel::InverseMultiquadric,
        &Widths::Uniform(0.8),
        Par::Seq,
    );
    let direct = &phi * m.weights() + Mat::from_fn(15000, 1, |_, _| m.bias().unwrap()[0]);
    let got = m.predict(xq.as_ref());
    assert!((&got - &direct).norm_max() < 1e-9 * direct.norm_max());
}

/// All-points fits interpolate; conditionally definite kernels get the tail they need
/// even with the bias switched off.
#[test]
fn all_points_interpolates_and_adds_the_needed_tail() {
    let (x, y) = data(60, 2, 14);
    for kernel in [Kernel::ThinPlateSpline, Kernel::Cubic, Kernel::Multiquadric] {
        let m = params()
            .kernel(kernel)
            .width(WidthRule::Fixed(1.0))
            .centres(CentreSelection::AllPoints)
            .bias(false)
            .check()
            .unwrap()
            .fit(x.as_ref(), y.as_ref())
            .unwrap();
        assert!(m.bias().is_some(), "{kernel}");
        assert_eq!(
            m.tail().is_some(),
            kernel.polynomial_order() == 2,
            "{kernel}"
        );
        assert!((&m.predict(x.as_ref()) - &y).norm_max() < 1e-9, "{kernel}");
    }
}

#[test]
fn linfa_traits_agree_with_the_faer_api() {
    use linfa::prelude::*;
    let (x, y) = data(70, 2, 15);
    let xa = ndarray::Array2::from_shape_fn((70, 2), |(i, k)| x[(i, k)]);
    let ya = ndarray::Array1::from_shape_fn(70, |i| y[(i, 0)]);
    let p = params().centres(CentreSelection::ols(10));
    let via_linfa = p.clone().fit(&Dataset::new(xa.clone(), ya)).unwrap();
    let via_faer = p.check().unwrap().fit(x.as_ref(), y.as_ref()).unwrap();
    assert_eq!(via_linfa, via_faer);
    let pa: ndarray::Array1<f64> = linfa::traits::Predict::predict(&via_linfa, &xa);
    let pf = via_faer.predict(x.as_ref());
    for i in 0..70 {
        assert_eq!(pa[i], pf[(i, 0)]);
    }
}

#[test]
fn progress_reports_every_stage_in_order() {
    let (x, y) = data(50, 1, 16);
    let seen = std::sync::Mutex::new(Vec::new());
    let obs = |p: rbf::Progress| seen.lock().unwrap().push(p);
    params()
        .centres(CentreSelection::ols(4))
        .check()
        .unwrap()
        .fit_with_progress(
            x.as_ref(),
            Mat::<f64>::zeros(50, 0).as_ref(),
            y.as_ref(),
            &obs,
        )
        .unwrap();
    let stages: Vec<Stage> = seen.into_inner().unwrap().iter().map(|p| p.stage).collect();
    assert_eq!(
        stages,
        vec![
            Stage::Widths,
            Stage::KernelMatrix,
            Stage::Selection,
            Stage::Selection,
            Stage::Selection,
            Stage::Selection,
            Stage::Weights
        ]
    );
}

/// Errors and models cross threads (the application wraps errors in anyhow and fits
/// channels in parallel).
#[test]
fn errors_and_models_are_send_and_sync() {
    fn check<T: Send + Sync + 'static>() {}
    check::<RbfError>();
    check::<RbfModel>();
    check::<rbf::RbfValidParams>();
    check::<rbf::OlsPath>();
    check::<PersistError>();
    check::<SolveError>();
}
