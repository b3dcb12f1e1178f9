//! The polynomial tail on unit-box inputs (`RbfParams::degree`), after scipy's
//! `RBFInterpolator`: results invariant to shifting the inputs by 1e7 and to scaling them
//! (with the width), for every centre selection, and all-points interpolation equal to
//! scipy's on offset data.
//!
//! The scipy reference values (scipy 1.17.1, numpy 2.4.6) were printed by
//!
//! ```sh
//! python3 peers/scripts/rbf_offset.py
//! ```
//!
//! which builds the same data by the same formula.

use faer::{Mat, MatRef, Par};
use rbf::{CentreSelection, Kernel, ParamGuard, PolyTail, RbfModel, RbfParams, WidthRule};

const OFFSET: f64 = 1e7;

/// 50 points of a 2-D low-discrepancy sequence and a smooth target; 7 test points.
fn data(offset: f64) -> (Mat<f64>, Mat<f64>, Mat<f64>) {
    let x = Mat::from_fn(50, 2, |i, k| {
        let a = [0.6180339887498949, 0.7548776662466927][k];
        (a * i as f64) % 1.0
    });
    let y = Mat::from_fn(50, 1, |i, _| {
        (3.0 * x[(i, 0)]).sin() * (2.0 * x[(i, 1)]).cos() + x[(i, 0)]
    });
    let t = Mat::from_fn(7, 2, |j, k| {
        let j = j as f64;
        if k == 0 {
            0.05 + 0.13 * j
        } else {
            0.9 - 0.11 * j
        }
    });
    let shift = |m: &Mat<f64>| Mat::from_fn(m.nrows(), m.ncols(), |i, k| m[(i, k)] + offset);
    (shift(&x), y, shift(&t))
}

fn fit(p: RbfParams, x: MatRef<'_, f64>, y: MatRef<'_, f64>) -> RbfModel {
    p.parallelism(Par::Seq).check().unwrap().fit(x, y).unwrap()
}

/// scipy's predictions at the test points, `RBFInterpolator(x + 1e7, y, kernel, epsilon,
/// degree)`, by case.
const SCIPY: [(&str, Kernel, f64, PolyTail, [f64; 7]); 4] = [
    (
        "thin_plate_deg1",
        Kernel::ThinPlateSpline,
        1.0,
        PolyTail::Linear,
        [
            -0.03367299799300853,
            0.1711997604482523,
            0.4765056036144865,
            0.8434408867761886,
            1.1698321521877475,
            1.3600285217542185,
            1.3661695687773425,
        ],
    ),
    (
        "cubic_deg1",
        Kernel::Cubic,
        1.0,
        PolyTail::Linear,
        [
            -0.00868048009062292,
            0.1700778095779916,
            0.47628478212760267,
            0.8450704109056196,
            1.1699183359548175,
            1.360049824487527,
            1.3670314955742269,
        ],
    ),
    (
        "gaussian_deg2",
        Kernel::Gaussian,
        0.5,
        PolyTail::Quadratic,
        [
            0.014797072596309135,
            0.1749955839006745,
            0.4774651358791573,
            0.8444133490135926,
            1.1699632963657223,
            1.360209138236712,
            1.3676602659612058,
        ],
    ),
    (
        "gaussian_deg0",
        Kernel::Gaussian,
        0.5,
        PolyTail::Constant,
        [
            0.014467753157077823,
            0.1749717640433346,
            0.4772067424339639,
            0.8444207469302683,
            1.169963433407247,
            1.360226536827895,
            1.3677627938109254,
        ],
    ),
];

/// Interpolation on inputs near 1e7 equals scipy's. The bound: scipy's own results with
/// and without the offset differ by up to 5e-9 (Gaussian, degree 2); measured here 2.1e-9
/// at most; 1e-7 leaves that a 20-fold margin and fails on any wrong tail or map (a tail
/// on unscaled 1e7 inputs is rank-deficient or off by O(1)).
#[test]
fn interpolation_on_offset_data_matches_scipy() {
    let (x, y, t) = data(OFFSET);
    let mut largest = 0.0f64;
    for (name, kernel, beta, degree, reference) in SCIPY {
        let m = fit(
            RbfParams::new()
                .kernel(kernel)
                .centres(CentreSelection::AllPoints)
                .width(WidthRule::Fixed(beta))
                .degree(degree),
            x.as_ref(),
            y.as_ref(),
        );
        let p = m.predict(t.as_ref());
        for j in 0..7 {
            largest = largest.max((p[(j, 0)] - reference[j]).abs());
            assert!(
                (p[(j, 0)] - reference[j]).abs() < 1e-7,
                "{name} point {j}: {} against scipy's {}",
                p[(j, 0)],
                reference[j]
            );
        }
    }
    println!("largest difference from scipy: {largest:.1e}");
}

/// scipy's test_translation_invariance: shifting every input by 1e7 changes no
/// prediction, for every centre selection (the tail and the kernel see the inputs
/// relative to the middle of their range). Measured 3.5e-9 at most (all points); the
/// bound 1e-7 on outputs of size 1 fails on a kernel that sees unshifted inputs (squared
/// distances near 1e14 carry errors of ≈ 1e-2).
#[test]
fn predictions_are_invariant_to_an_offset_of_1e7() {
    // the unshifted inputs are the shifted ones minus 1e7 (exact), so both fits see the
    // same numbers up to the offset, as in scipy's test; data(0.0) would differ by the
    // rounding of x + 1e7 (≈ 1e-9), which the all-points system amplifies to ≈ 1e-6
    let (x1, y, t1) = data(OFFSET);
    let back = |m: &Mat<f64>| Mat::from_fn(m.nrows(), m.ncols(), |i, k| m[(i, k)] - OFFSET);
    let (x0, t0) = (back(&x1), back(&t1));
    let selections = [
        CentreSelection::AllPoints,
        CentreSelection::ols(12),
        CentreSelection::kmeans(12),
        CentreSelection::random(12),
    ];
    let mut largest = 0.0f64;
    for centres in selections {
        for degree in [
            PolyTail::None,
            PolyTail::Constant,
            PolyTail::Linear,
            PolyTail::Quadratic,
        ] {
            let p = RbfParams::new()
                .kernel(Kernel::Gaussian)
                .centres(centres.clone())
                .width(WidthRule::Fixed(0.5))
                .degree(degree);
            let a = fit(p.clone(), x0.as_ref(), y.as_ref()).predict(t0.as_ref());
            let b = fit(p, x1.as_ref(), y.as_ref()).predict(t1.as_ref());
            let diff = (&a - &b).norm_max();
            largest = largest.max(diff);
            assert!(diff < 1e-7, "{centres:?} {degree:?}: {diff}");
        }
    }
    println!("largest change under the 1e7 offset: {largest:.1e}");
}

/// scipy's test_scale_invariance: scaling the inputs by 1e-3 and the width with them
/// changes no prediction (the tail's unit box absorbs the scale).
#[test]
fn predictions_are_invariant_to_scaling_inputs_and_width() {
    let (x, y, t) = data(0.0);
    let s = 1e-3;
    let xs = Mat::from_fn(50, 2, |i, k| x[(i, k)] * s);
    let ts = Mat::from_fn(7, 2, |i, k| t[(i, k)] * s);
    for centres in [CentreSelection::AllPoints, CentreSelection::ols(12)] {
        let p = |beta: f64| {
            RbfParams::new()
                .kernel(Kernel::Gaussian)
                .centres(centres.clone())
                .width(WidthRule::Fixed(beta))
                .degree(PolyTail::Linear)
        };
        let a = fit(p(0.5), x.as_ref(), y.as_ref()).predict(t.as_ref());
        let b = fit(p(0.5 * s), xs.as_ref(), y.as_ref()).predict(ts.as_ref());
        assert!((&a - &b).norm_max() < 1e-8, "{centres:?}");
    }
}

/// A degree-2 tail reproduces a quadratic exactly (scipy's test_polynomial_reproduction),
/// here with least-squares centres at an offset of 1e7.
#[test]
fn a_quadratic_tail_reproduces_a_quadratic_at_an_offset() {
    let (x, _, t) = data(OFFSET);
    let q = |a: f64, b: f64| {
        let (a, b) = (a - OFFSET, b - OFFSET);
        1.0 + 2.0 * a - 3.0 * b + a * a - 0.5 * a * b + 2.0 * b * b
    };
    let y = Mat::from_fn(50, 1, |i, _| q(x[(i, 0)], x[(i, 1)]));
    let m = fit(
        RbfParams::new()
            .centres(CentreSelection::kmeans(8))
            .width(WidthRule::Fixed(0.5))
            .degree(PolyTail::Quadratic),
        x.as_ref(),
        y.as_ref(),
    );
    let p = m.predict(t.as_ref());
    for j in 0..7 {
        assert!(
            (p[(j, 0)] - q(t[(j, 0)], t[(j, 1)])).abs() < 1e-6,
            "point {j}"
        );
    }
}

/// Thin-plate and cubic interpolation need a linear tail: a lower degree is refused, and
/// without `degree` they get it as before.
#[test]
fn interpolation_below_the_kernels_minimum_degree_is_refused() {
    for kernel in [Kernel::ThinPlateSpline, Kernel::Cubic] {
        let e = RbfParams::new()
            .kernel(kernel)
            .centres(CentreSelection::AllPoints)
            .degree(PolyTail::Constant)
            .check()
            .unwrap_err();
        assert!(
            matches!(e, rbf::RbfParamsError::DegreeTooLow { minimum: 1, .. }),
            "{e}"
        );
        // least squares needs no minimum
        assert!(
            RbfParams::new()
                .kernel(kernel)
                .centres(CentreSelection::ols(5))
                .degree(PolyTail::None)
                .check()
                .is_ok()
        );
    }
}

/// A saved model keeps its tail and unit-box map and predicts bit-identically after
/// loading; a model without a degree writes no `poly` entry, so older files (which have
/// none) load as before.
#[test]
fn the_tail_and_its_map_persist() {
    let (x, y, t) = data(OFFSET);
    let m = fit(
        RbfParams::new()
            .centres(CentreSelection::ols(10))
            .width(WidthRule::Fixed(0.5))
            .degree(PolyTail::Quadratic),
        x.as_ref(),
        y.as_ref(),
    );
    let mut buf = Vec::new();
    m.to_writer(&mut buf).unwrap();
    let text = String::from_utf8(buf.clone()).unwrap();
    assert!(text.contains("\"poly\"") && text.contains("\"quadratic\""));
    let back = RbfModel::from_reader(buf.as_slice()).unwrap();
    assert_eq!(back, m);
    assert_eq!(back.predict(t.as_ref()), m.predict(t.as_ref()));
    assert_eq!(back.degree(), Some(PolyTail::Quadratic));
    assert_eq!(
        back.params().check().unwrap().degree(),
        Some(PolyTail::Quadratic)
    );

    let plain = fit(
        RbfParams::new()
            .centres(CentreSelection::ols(10))
            .width(WidthRule::Fixed(0.5)),
        x.as_ref(),
        y.as_ref(),
    );
    let mut buf = Vec::new();
    plain.to_writer(&mut buf).unwrap();
    assert!(!String::from_utf8(buf.clone()).unwrap().contains("\"poly\""));
    assert_eq!(
        RbfModel::from_reader(buf.as_slice()).unwrap().degree(),
        None
    );
}

/// The features are [monomials | kernel columns], and the prediction is their product
/// with [tail coefficients; weights].
#[test]
fn features_hold_the_monomials_first() {
    let (x, y, t) = data(OFFSET);
    let m = fit(
        RbfParams::new()
            .centres(CentreSelection::random(6))
            .width(WidthRule::Fixed(0.5))
            .degree(PolyTail::Linear),
        x.as_ref(),
        y.as_ref(),
    );
    let f = m.features(t.as_ref());
    assert_eq!(f.ncols(), 3 + 6);
    let (c, _, _) = m.poly_tail().unwrap();
    let mut w = Mat::zeros(9, 1);
    for r in 0..3 {
        w[(r, 0)] = c[(r, 0)];
    }
    for k in 0..6 {
        w[(3 + k, 0)] = m.weights()[(k, 0)];
    }
    assert!((&f * &w - m.predict(t.as_ref())).norm_max() < 1e-9);
}
