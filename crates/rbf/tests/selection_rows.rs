//! OLS selection on a row subsample with the weights solved on every row by the
//! streaming row-block QR.

use faer::{Mat, Par};
use linfa::ParamGuard;
use rbf::{Candidates, CentreSelection, RbfParams, WidthRule};

fn data(n: usize) -> (Mat<f64>, Mat<f64>) {
    let x = Mat::from_fn(n, 2, |i, j| {
        (((i * 7919 + j * 104_729) % 10_007) as f64 / 10_007.0) * 4.0 - 2.0
    });
    let y = Mat::from_fn(n, 1, |i, _| {
        (2.0 * x[(i, 0)]).sin() * x[(i, 1)].cos()
            + 0.1 * x[(i, 0)] * x[(i, 1)]
            + 0.05 * ((i as f64 * 12.9898).sin() * 43_758.545).fract()
    });
    (x, y)
}

fn ols(rows: Option<usize>) -> rbf::RbfValidParams {
    RbfParams::new()
        .centres(CentreSelection::Ols {
            max_centres: 25,
            tol: 0.0,
            regularisation: 0.0,
            candidates: Candidates::Subsample { size: 400 },
        })
        .width(WidthRule::Fixed(1.5))
        .selection_rows(rows)
        .parallelism(Par::Seq)
        .check()
        .unwrap()
}

#[test]
fn weights_on_every_row_equal_a_whole_matrix_solve_with_the_same_centres() {
    let (x, y) = data(12_000);
    let sub = ols(Some(1500)).fit(x.as_ref(), y.as_ref()).unwrap();
    assert!(sub.n_centres() >= 10, "{} centres", sub.n_centres());
    // The same centres, weights by the in-memory QR on every row.
    let given = RbfParams::new()
        .centres(CentreSelection::Given(sub.centres()))
        .width(WidthRule::Fixed(1.5))
        .parallelism(Par::Seq)
        .check()
        .unwrap()
        .fit(x.as_ref(), y.as_ref())
        .unwrap();
    // Same least-squares problem, two QR orderings: the weights agree to κ·ε (the
    // kernel columns are ill-conditioned), the fitted values to far better.
    let d = (&sub.predict(x.as_ref()) - &given.predict(x.as_ref())).norm_max();
    assert!(d < 1e-8, "predictions differ by {d}");
    let w = (&sub.weights().to_owned() - &given.weights().to_owned()).norm_max();
    let bound = given.condition() * 1e-13 * given.weights().norm_max();
    assert!(w <= bound, "weights differ by {w}, bound {bound}");
    // and the subsample loses little against selecting on every row
    let all = ols(None).fit(x.as_ref(), y.as_ref()).unwrap();
    let rms = |m: &rbf::RbfModel| {
        let e = &m.predict(x.as_ref()) - &y;
        (e.squared_norm_l2() / 12_000.0).sqrt()
    };
    assert!(
        rms(&sub) < 1.5 * rms(&all) + 1e-6,
        "{} vs {}",
        rms(&sub),
        rms(&all)
    );
}

#[test]
fn a_subsample_larger_than_the_data_selects_on_every_row() {
    let (x, y) = data(800);
    let a = ols(Some(5000)).fit(x.as_ref(), y.as_ref()).unwrap();
    let b = ols(None).fit(x.as_ref(), y.as_ref()).unwrap();
    assert_eq!(a.weights().to_owned(), b.weights().to_owned());
}

/// Given centres fitted over row blocks handed over by the caller equal the
/// whole-matrix fit (bias, linear tail, linear regressors, ridge), and refuse
/// what they cannot stream with a typed error.
#[test]
fn given_centres_over_caller_row_blocks_equal_the_whole_matrix_fit() {
    let (x, y) = data(9_000);
    let z = Mat::from_fn(x.nrows(), 2, |i, j| ((i * (j + 2)) as f64 * 0.001).cos());
    let y = Mat::from_fn(x.nrows(), 1, |i, _| {
        y[(i, 0)] + 0.3 * z[(i, 0)] - 0.2 * z[(i, 1)]
    });
    let centres = Mat::from_fn(20, 2, |k, j| x[(k * 449, j)]);
    for (tail, ridge) in [(false, 0.0), (true, 1e-6)] {
        let p = RbfParams::new()
            .centres(CentreSelection::Given(centres.clone()))
            .width(WidthRule::Fixed(1.5))
            .linear_tail(tail)
            .ridge(ridge)
            .parallelism(Par::Seq)
            .check()
            .unwrap();
        let whole = p
            .fit_with_linear(x.as_ref(), z.as_ref(), y.as_ref())
            .unwrap();
        let blocks = p
            .fit_given_streaming(x.nrows(), 2, 2, 1, |start, mut xb, mut zb, mut yb| {
                let b = xb.nrows();
                xb.copy_from(x.as_ref().subrows(start, b));
                zb.copy_from(z.as_ref().subrows(start, b));
                yb.copy_from(y.as_ref().subrows(start, b));
            })
            .unwrap();
        // Equal up to rounding amplified by the conditioning of the design.
        let scale = whole.weights().norm_max();
        let tol = 1e3 * f64::EPSILON * whole.condition();
        let dw = (whole.weights() - blocks.weights()).norm_max() / scale;
        assert!(
            dw < tol,
            "weights differ by {dw:e} (relative), condition {:e}",
            whole.condition()
        );
        let dl = (whole.linear_coefficients() - blocks.linear_coefficients()).norm_max();
        assert!(
            dl < tol * whole.linear_coefficients().norm_max().max(1.0),
            "{dl:e}"
        );
        let db = (whole.bias().unwrap()[0] - blocks.bias().unwrap()[0]).abs();
        assert!(db < tol * whole.bias().unwrap()[0].abs().max(1.0), "{db:e}");
        assert_eq!(whole.tail().is_some(), blocks.tail().is_some());
        let (a, b) = (
            whole.predict_with_linear(x.as_ref(), z.as_ref()),
            blocks.predict_with_linear(x.as_ref(), z.as_ref()),
        );
        // |Δf| ≤ Σ|Δλ|·|φ| with φ ≤ 1: at most (K + 3) weights' differences.
        let dp = (&a - &b).norm_max();
        assert!(
            dp < 23.0 * tol * scale.max(1.0),
            "predictions differ by {dp:e}"
        );
    }
    // A non-finite input is reported at its row of the whole data.
    let p = RbfParams::new()
        .centres(CentreSelection::Given(centres.clone()))
        .width(WidthRule::Fixed(1.5))
        .parallelism(Par::Seq)
        .check()
        .unwrap();
    let err = p
        .fit_given_streaming(9_000, 2, 0, 1, |start, mut xb, _, mut yb| {
            let b = xb.nrows();
            xb.copy_from(x.as_ref().subrows(start, b));
            yb.copy_from(y.as_ref().subrows(start, b));
            if (start..start + b).contains(&5_000) {
                xb[(5_000 - start, 1)] = f64::NAN;
            }
        })
        .unwrap_err();
    assert!(
        matches!(
            err,
            rbf::RbfError::NonFinite {
                matrix: "x",
                row: 5_000,
                col: 1
            }
        ),
        "{err}"
    );
    // Selection and data-dependent transforms need every row at once.
    let unused =
        |_: usize, _: faer::MatMut<'_, f64>, _: faer::MatMut<'_, f64>, _: faer::MatMut<'_, f64>| {};
    for p in [
        ols(None),
        RbfParams::new()
            .centres(CentreSelection::Given(centres.clone()))
            .width(WidthRule::Fixed(1.5))
            .standardise(true)
            .check()
            .unwrap(),
    ] {
        let err = p.fit_given_streaming(100, 2, 0, 1, unused).unwrap_err();
        assert!(matches!(err, rbf::RbfError::NotStreamable { .. }), "{err}");
    }
    let err = p.fit_given_streaming(10, 2, 0, 1, unused).unwrap_err();
    assert!(
        matches!(
            err,
            rbf::RbfError::FewerRowsThanCentres {
                rows: 10,
                centres: 20,
                most: 9
            }
        ),
        "{err}"
    );
}
