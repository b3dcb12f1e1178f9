//! One test per hyperparameter validation rule (linfa's ParamGuard).

use faer::Mat;
use linfa::ParamGuard;
use rbf::{Candidates, CentreSelection, KMeansSettings, RbfParams, RbfParamsError as E, WidthRule};

fn err(p: RbfParams) -> E {
    p.check().unwrap_err()
}

fn ols(
    max_centres: usize,
    tol: f64,
    regularisation: f64,
    candidates: Candidates,
) -> CentreSelection {
    CentreSelection::Ols {
        max_centres,
        tol,
        regularisation,
        candidates,
    }
}

#[test]
fn defaults_are_valid() {
    assert!(RbfParams::new().check().is_ok());
    for s in [
        CentreSelection::kmeans(3),
        CentreSelection::random(3),
        CentreSelection::AllPoints,
    ] {
        assert!(RbfParams::new().centres(s).check().is_ok());
    }
}

#[test]
fn fixed_width_must_be_positive_and_finite() {
    assert_eq!(
        err(RbfParams::new().width(WidthRule::Fixed(0.0))),
        E::Width { value: 0.0 }
    );
    assert!(matches!(
        err(RbfParams::new().width(WidthRule::Fixed(f64::NAN))),
        E::Width { .. }
    ));
}

#[test]
fn width_scale_must_be_positive_and_finite() {
    assert_eq!(
        err(RbfParams::new().width(WidthRule::MedianPairwise { scale: -1.0 })),
        E::WidthScale { value: -1.0 }
    );
    assert!(matches!(
        err(RbfParams::new().width(WidthRule::MeanNearestNeighbour {
            scale: f64::INFINITY
        })),
        E::WidthScale { .. }
    ));
}

#[test]
fn cluster_spread_needs_kmeans() {
    let p = RbfParams::new().width(WidthRule::ClusterSpread { scale: 1.0 });
    assert_eq!(err(p.clone()), E::ClusterSpreadNeedsKMeans);
    assert!(p.centres(CentreSelection::kmeans(4)).check().is_ok());
}

#[test]
fn ridge_must_be_non_negative_and_finite() {
    assert_eq!(
        err(RbfParams::new().ridge(-1e-9)),
        E::Ridge { value: -1e-9 }
    );
    assert!(matches!(
        err(RbfParams::new().ridge(f64::NAN)),
        E::Ridge { .. }
    ));
    assert!(RbfParams::new().ridge(0.0).check().is_ok());
}

#[test]
fn max_condition_must_be_at_least_one() {
    assert_eq!(
        err(RbfParams::new().max_condition(0.5)),
        E::MaxCondition { value: 0.5 }
    );
    assert!(
        RbfParams::new()
            .max_condition(f64::INFINITY)
            .check()
            .is_ok()
    );
}

#[test]
fn ols_needs_a_centre() {
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::ols(0))),
        E::OlsMaxCentres
    );
}

#[test]
fn ols_tolerance_lies_in_zero_one() {
    let p = |t| RbfParams::new().centres(ols(5, t, 0.0, Candidates::TrainingVectors));
    assert_eq!(err(p(1.0)), E::OlsTolerance { value: 1.0 });
    assert_eq!(err(p(-0.1)), E::OlsTolerance { value: -0.1 });
    assert!(p(0.0).check().is_ok() && p(0.99).check().is_ok());
}

#[test]
fn ols_regularisation_is_non_negative() {
    let p = RbfParams::new().centres(ols(5, 0.0, -1.0, Candidates::TrainingVectors));
    assert_eq!(err(p), E::OlsRegularisation { value: -1.0 });
}

#[test]
fn subsample_needs_a_candidate() {
    let p = RbfParams::new().centres(ols(5, 0.0, 0.0, Candidates::Subsample { size: 0 }));
    assert_eq!(err(p), E::SubsampleSize);
}

#[test]
fn given_candidates_are_not_empty() {
    let p = RbfParams::new().centres(ols(5, 0.0, 0.0, Candidates::Given(Mat::zeros(0, 2))));
    assert_eq!(err(p), E::EmptyCandidates);
}

#[test]
fn given_candidates_are_finite() {
    let mut c = Mat::<f64>::zeros(3, 2);
    c[(2, 1)] = f64::NAN;
    let p = RbfParams::new().centres(ols(5, 0.0, 0.0, Candidates::Given(c)));
    assert_eq!(err(p), E::NonFiniteCandidates { row: 2, col: 1 });
}

#[test]
fn kmeans_needs_a_centre() {
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::kmeans(0))),
        E::KMeansCentres
    );
}

#[test]
fn kmeans_needs_a_run() {
    let s = KMeansSettings {
        n_runs: 0,
        ..KMeansSettings::new(3)
    };
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::KMeans(s))),
        E::KMeansRuns
    );
}

#[test]
fn kmeans_needs_an_iteration() {
    let s = KMeansSettings {
        max_iterations: 0,
        ..KMeansSettings::new(3)
    };
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::KMeans(s))),
        E::KMeansIterations
    );
}

#[test]
fn kmeans_tolerance_is_positive() {
    let s = KMeansSettings {
        tolerance: 0.0,
        ..KMeansSettings::new(3)
    };
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::KMeans(s))),
        E::KMeansTolerance { value: 0.0 }
    );
}

#[test]
fn random_needs_a_centre() {
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::random(0))),
        E::RandomCentres
    );
}

#[test]
fn given_centres_are_not_empty() {
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::Given(Mat::zeros(0, 1)))),
        E::EmptyCentres
    );
}

#[test]
fn given_centres_are_finite() {
    let mut c = Mat::<f64>::zeros(2, 1);
    c[(0, 0)] = f64::INFINITY;
    assert_eq!(
        err(RbfParams::new().centres(CentreSelection::Given(c))),
        E::NonFiniteCentres { row: 0, col: 0 }
    );
}

/// linfa's blanket `Fit` for unchecked params checks them first.
#[test]
fn linfa_fit_on_unchecked_params_reports_the_rule() {
    use linfa::prelude::*;
    let x = ndarray::Array2::<f64>::zeros((4, 1));
    let y = ndarray::Array1::<f64>::zeros(4);
    let ds = Dataset::new(x, y);
    let e = RbfParams::new().ridge(-1.0).fit(&ds).unwrap_err();
    assert!(
        matches!(e, rbf::RbfError::InvalidParams(E::Ridge { .. })),
        "{e}"
    );
}
