//! Cross-validation and grid search.

mod common;

use faer::{Mat, Par};
use linfa::ParamGuard;
use rbf::{
    CentreSelection, Grid, KMeansSettings, RbfError, RbfParams, Sizes, Split, WidthRule,
    cross_validate, grid_search,
};

fn chen() -> (Mat<f64>, Mat<f64>) {
    let s = common::chen_series(402, 0.2, 3);
    common::lagged(&s)
}

fn params(sel: CentreSelection) -> rbf::RbfValidParams {
    RbfParams::new()
        .width(WidthRule::Fixed(1.0))
        .centres(sel)
        .parallelism(Par::Seq)
        .check()
        .unwrap()
}

/// The OLS grid reads every K off one forward selection per fold; its scores equal
/// cross-validating a separately fitted ols(K) model (the first K picks do not depend
/// on how many more are made), for every K and ridge.
#[test]
fn ols_grid_from_one_path_equals_refitting_each_k() {
    let (x, y) = chen();
    let split = Split::KFold { k: 4, seed: 5 };
    let ks = vec![2, 5, 9, 14];
    let ridges = vec![0.0, 1e-3];
    let grid = Grid {
        widths: vec![WidthRule::Fixed(0.7), WidthRule::Fixed(1.2)],
        sizes: Sizes::Centres(ks.clone()),
        ridges: ridges.clone(),
    };
    let rep = grid_search(
        &params(CentreSelection::ols(30)),
        x.as_ref(),
        y.as_ref(),
        &split,
        &grid,
    )
    .unwrap();
    assert_eq!(rep.points.len(), 2 * ks.len() * ridges.len());
    for point in &rep.points {
        let direct = RbfParams::new()
            .width(point.width.clone())
            .centres(CentreSelection::ols(point.n_centres.unwrap()))
            .ridge(point.ridge)
            .parallelism(Par::Seq)
            .check()
            .unwrap();
        let want = cross_validate(&direct, x.as_ref(), y.as_ref(), &split).unwrap();
        let got = point.result.as_ref().unwrap();
        for (a, b) in got.folds.iter().zip(&want.folds) {
            assert_eq!(a.n_centres, b.n_centres);
            assert!(
                (a.validation.rmse - b.validation.rmse).abs() < 1e-12,
                "{:?}",
                point
            );
        }
    }
    let best = rep.best().unwrap();
    let best_nmse = best.result.as_ref().unwrap().mean.nmse;
    assert!(
        rep.points
            .iter()
            .all(|p| p.result.as_ref().unwrap().mean.nmse >= best_nmse)
    );
}

/// A tolerance grid picks, per fold, the first K with 1 − ΣERR < ρ; smaller ρ never
/// gives fewer centres.
#[test]
fn tolerance_grid_orders_model_sizes() {
    let (x, y) = chen();
    let grid = Grid {
        widths: vec![],
        sizes: Sizes::Tolerances(vec![0.2, 0.08, 0.06]),
        ridges: vec![],
    };
    let rep = grid_search(
        &params(CentreSelection::ols(40)),
        x.as_ref(),
        y.as_ref(),
        &Split::Blocked { k: 3, gap: 2 },
        &grid,
    )
    .unwrap();
    let sizes: Vec<Vec<usize>> = rep
        .points
        .iter()
        .map(|p| {
            p.result
                .as_ref()
                .unwrap()
                .folds
                .iter()
                .map(|f| f.n_centres)
                .collect()
        })
        .collect();
    for f in 0..3 {
        assert!(
            sizes[0][f] <= sizes[1][f] && sizes[1][f] <= sizes[2][f],
            "{sizes:?}"
        );
    }
    assert!(sizes[0][0] >= 1);
}

/// Other strategies refit per size and re-solve per ridge; failures are recorded per
/// point and never chosen as best.
#[test]
fn grid_records_failures_per_point() {
    let (x, y) = chen();
    let km = CentreSelection::KMeans(KMeansSettings::new(5));
    let grid = Grid {
        widths: vec![WidthRule::Fixed(0.5), WidthRule::Fixed(1000.0)],
        sizes: Sizes::Centres(vec![4, 12]),
        ridges: vec![0.0, 1e-4],
    };
    let rep = grid_search(
        &params(km),
        x.as_ref(),
        y.as_ref(),
        &Split::Interleaved { k: 2 },
        &grid,
    )
    .unwrap();
    assert_eq!(rep.points.len(), 8);
    // β = 1000 on data of range ±1.5 makes 12 Gaussian columns numerically dependent without a ridge
    let failed: Vec<&rbf::GridPoint> = rep.points.iter().filter(|p| p.result.is_err()).collect();
    assert!(!failed.is_empty());
    assert!(
        failed
            .iter()
            .all(|p| p.ridge == 0.0 && p.width == WidthRule::Fixed(1000.0)),
        "{failed:?}"
    );
    let best = rep.best().unwrap();
    assert!(best.result.is_ok());
    // tolerance grids are for OLS only
    let bad = Grid {
        widths: vec![],
        sizes: Sizes::Tolerances(vec![0.1]),
        ridges: vec![],
    };
    let e = grid_search(
        &params(CentreSelection::random(5)),
        x.as_ref(),
        y.as_ref(),
        &Split::Interleaved { k: 2 },
        &bad,
    )
    .unwrap_err();
    assert!(matches!(e, RbfError::GridMismatch { .. }));
}

/// Fold bookkeeping: sizes add up, the mean and sample standard deviation are those of
/// the fold scores, and the paper's split trains on even rows.
#[test]
fn reports_are_consistent_with_their_folds() {
    let (x, y) = chen();
    let n = x.nrows();
    let rep = cross_validate(
        &params(CentreSelection::ols(10)),
        x.as_ref(),
        y.as_ref(),
        &Split::Interleaved { k: 2 },
    )
    .unwrap();
    assert_eq!(rep.folds[0].train_size, n.div_ceil(2));
    assert_eq!(rep.folds[0].train_size + rep.folds[0].validation_size, n);
    let v: Vec<f64> = rep.folds.iter().map(|f| f.validation.rmse).collect();
    let mean = v.iter().sum::<f64>() / 2.0;
    assert!((rep.mean.rmse - mean).abs() < 1e-15);
    assert!((rep.std.rmse - ((v[0] - mean).powi(2) + (v[1] - mean).powi(2)).sqrt()).abs() < 1e-15);
    // scores are mutually consistent: nmse = 1 − r², fit% = 100(1 − √nmse)
    for f in &rep.folds {
        assert!((f.validation.nmse - (1.0 - f.validation.r2)).abs() < 1e-12);
        assert!((f.validation.fit_percent - 100.0 * (1.0 - f.validation.nmse.sqrt())).abs() < 1e-9);
    }
    let e = cross_validate(
        &params(CentreSelection::ols(10)),
        x.as_ref(),
        y.as_ref(),
        &Split::Blocked { k: 2, gap: n },
    )
    .unwrap_err();
    assert!(matches!(
        e,
        RbfError::Split(rbf::SplitError::EmptyFold { .. })
    ));
}

/// All-points grids share one kernel matrix across ridges; each point equals
/// cross-validating that smoothing directly.
#[test]
fn all_points_grid_over_smoothing_equals_direct_cross_validation() {
    let (x, y) = chen();
    let (x, y) = (
        x.as_ref().subrows(0, 150).to_owned(),
        y.as_ref().subrows(0, 150).to_owned(),
    );
    let split = Split::Blocked { k: 3, gap: 2 };
    let p = RbfParams::new()
        .kernel(rbf::Kernel::ThinPlateSpline)
        .centres(CentreSelection::AllPoints)
        .width(WidthRule::Fixed(1.0))
        .parallelism(Par::Seq);
    let grid = Grid {
        widths: vec![],
        sizes: Sizes::Default,
        ridges: vec![1e-6, 1e-2, 1.0],
    };
    let rep = grid_search(
        &p.clone().check().unwrap(),
        x.as_ref(),
        y.as_ref(),
        &split,
        &grid,
    )
    .unwrap();
    for point in &rep.points {
        let direct = cross_validate(
            &p.clone().ridge(point.ridge).check().unwrap(),
            x.as_ref(),
            y.as_ref(),
            &split,
        )
        .unwrap();
        let got = point.result.as_ref().unwrap();
        assert!((got.mean.rmse - direct.mean.rmse).abs() < 1e-12);
    }
    // interpolating noise (tiny smoothing) validates worse than smoothing it
    let nmse: Vec<f64> = rep
        .points
        .iter()
        .map(|p| p.result.as_ref().unwrap().mean.nmse)
        .collect();
    assert!(nmse[0] > nmse[1].min(nmse[2]), "{nmse:?}");
}
