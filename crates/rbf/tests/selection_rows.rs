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
