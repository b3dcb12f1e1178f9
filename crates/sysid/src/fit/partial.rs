//! The effects' coefficients by cross-fitted partialling out (Chernozhukov
//! et al. 2018): a network alone on one block of the rows, the residuals
//! of the target and of every effect column on the other, θ from their
//! regression with Newey–West errors; then the network on what θ leaves,
//! on the training rows.

use super::channel::gather;
use super::network::fit_network;
use crate::error::SysidError;
use crate::inference::{Blocks, Coefficient, HacFit, hac_regression, residualise};
use crate::input::ModelInput;
use crate::prepared::Prepared;
use crate::recipe::FitSettings;
use crate::sensor::Sensor;
use faer::{Mat, MatRef};
use rayon::prelude::*;
use rbf::Split;

/// The rows of a partially linear fit.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rows<'a> {
    /// Where the network is fitted (to what the effects leave).
    pub(super) train: &'a [usize],
    /// Where the effects' coefficients are estimated by cross-fitting: the
    /// training and validation rows of every record, as the diagnosis
    /// estimates them, or the training rows alone.
    pub(super) theta: &'a [usize],
    /// The coefficients already estimated on those rows (a model's, for its
    /// mirror): taken as they are instead of cross-fitted again.
    pub(super) known: Option<&'a [Coefficient]>,
}

/// How the training rows are cut for cross-fitting: into this many spans of
/// time, alternately assigned to the two blocks, so that both blocks see the
/// whole test (every level step, the whole temperature range). Each count
/// gives an estimate; their spread is part of the uncertainty, because the
/// networks that partial the effects out are themselves estimates and shift
/// with the rows they were fitted on.
const CROSS_FIT_CHUNKS: [usize; 3] = [4, 6, 8];

/// Several cross-fits' estimates as one (Chernozhukov et al. 2018, §3.4):
/// θ the mean, σ² the mean of σ_s² + (θ_s − θ)², the fewest degrees of
/// freedom; the joint covariance likewise, the mean of Σ_s + (θ_s − θ)(θ_s − θ)ᵀ.
fn combine_splits(fits: &[HacFit]) -> Option<HacFit> {
    let first = fits.first()?;
    let s = fits.len() as f64;
    let p = first.coef.len();
    let mut out = first.clone();
    let means: Vec<f64> = (0..p)
        .map(|j| fits.iter().map(|f| f.coef[j]).sum::<f64>() / s)
        .collect();
    for a in 0..p {
        for b in 0..p {
            out.cov[a][b] = fits
                .iter()
                .map(|f| f.cov[a][b] + (f.coef[a] - means[a]) * (f.coef[b] - means[b]))
                .sum::<f64>()
                / s;
        }
    }
    for j in 0..p {
        let mean = fits.iter().map(|f| f.coef[j]).sum::<f64>() / s;
        let var = fits
            .iter()
            .map(|f| f.se[j].powi(2) + (f.coef[j] - mean).powi(2))
            .sum::<f64>()
            / s;
        out.coef[j] = mean;
        out.se[j] = var.sqrt();
    }
    out.dof = fits.iter().map(|f| f.dof).fold(f64::INFINITY, f64::min);
    Some(out)
}

/// The rows the effects' coefficients are estimated on when every row
/// counts (the fit's default, and the diagnosis's statement of a
/// suggestion): the training and validation rows in time order, at the
/// stride the network's selection uses ([`super::network::selection_stride`]).
pub(crate) fn theta_rows(train: &[usize], val: &[usize]) -> Vec<usize> {
    let stride = super::network::selection_stride(train.len());
    let mut all: Vec<usize> = train.iter().chain(val).copied().collect();
    all.sort_unstable();
    all.dedup();
    all.into_iter().step_by(stride).collect()
}

/// The raw windows of `prepared` when its input is not the raw window
/// (`None` when it is: its own windows are the ones).
pub(crate) fn raw_windows<S: Sensor>(
    prepared: &Prepared<S>,
) -> Result<Option<Prepared<S>>, SysidError> {
    match prepared.preprocess().input {
        ModelInput::Raw => Ok(None),
        _ => prepared.with_input(ModelInput::Raw).map(Some),
    }
}

/// Fewest rows in each cross-fitting block: each block's network is chosen
/// by its own cross-validation, which needs a few hundred windows.
pub const MIN_BLOCK_ROWS: usize = 200;

/// The effects' coefficients (each in its unit of `units`) by cross-fitted partialling out, then the network
/// on what the effects leave.
///
/// The rows `rows.theta` are cut in two blocks (with the leakage gap between).
/// On each block a network alone (no effects) is fitted to y by
/// cross-validation; its basis (bias and kernel columns) is fitted by least
/// squares to y and to every effect column on that block, and the residuals
/// are taken on the other block. θ is the regression of y's residual on the
/// effects' residuals over both blocks, with Newey–West standard errors.
/// The final network is fitted to y − Zθ on all training rows.
///
/// The networks that partial the effects out read `x_theta`, the raw
/// windows ([`cross_fitted_theta`]); the final network (and the joint fit
/// of the fallback) reads `x`, the model's input.
///
/// A cut is used only if each block is long enough for its own blocked
/// cross-validation with the leakage gap: a long window's gap (250 samples)
/// leaves the middle fold of a 772-row block no training rows, and such a
/// cut is skipped rather than failing the fit.
///
/// With blocks too short for their own cross-validation the fit is joint (θ
/// and the network in one solve) and θ's standard errors come from the same
/// regression in-sample (Frisch–Waugh–Lovell), which is optimistic.
pub(super) fn fit_partially_linear(
    (x, x_theta): (MatRef<'_, f64>, MatRef<'_, f64>),
    z: &Mat<f64>,
    y: &[f64],
    rows: Rows<'_>,
    units: &[String],
    settings: &FitSettings,
    gap: usize,
) -> Result<(rbf::RbfModel, Vec<Coefficient>), rbf::RbfError> {
    let p = units.len();
    let train = rows.train;
    let theta = theta_of(x_theta, z, y, rows, p, settings, gap)?;
    let Some(t) = theta.values() else {
        let (model, fit) = joint_fit(x, z, y, train, settings, gap)?;
        let theta = model.linear_coefficients();
        let values: Vec<f64> = (0..p).map(|j| theta[(j, 0)]).collect();
        return Ok((model, coefficients(units, fit.as_ref(), &values)));
    };
    let x_train = gather(x, train);
    let z_train = gather(z.as_ref(), train);
    let y_train = Mat::from_fn(train.len(), 1, |i, _| y[train[i]]);
    let y_adj = adjusted(&y_train, &z_train, t);
    let net = fit_network(
        settings,
        x_train.as_ref(),
        Mat::<f64>::zeros(train.len(), 0).as_ref(),
        y_adj.as_ref(),
        gap,
    )?;
    Ok(theta.with_network(net, units))
}

/// The effects' coefficients of a partially linear fit, before its network.
pub(super) enum Theta {
    /// Given (a model's own, for its mirror): taken as they are.
    Given(Mat<f64>, Vec<Coefficient>),
    /// Cross-fitted ([`cross_fitted_theta`]).
    CrossFitted(Mat<f64>, HacFit),
    /// Blocks too short to cross-fit: θ and the network in one solve.
    Joint,
}

impl Theta {
    /// θ as a column, none for a joint fit.
    pub(super) fn values(&self) -> Option<&Mat<f64>> {
        match self {
            Theta::Given(t, _) | Theta::CrossFitted(t, _) => Some(t),
            Theta::Joint => None,
        }
    }

    /// The model of a network fitted to [`adjusted`] with these
    /// coefficients, and the coefficients it stores.
    ///
    /// # Panics
    /// For [`Theta::Joint`], which has no network of its own.
    pub(super) fn with_network(
        self,
        net: rbf::RbfModel,
        units: &[String],
    ) -> (rbf::RbfModel, Vec<Coefficient>) {
        match self {
            Theta::Given(t, known) => (net.with_linear(t.as_ref()), known),
            Theta::CrossFitted(t, f) => {
                let model = net.with_linear(t.as_ref());
                let theta = model.linear_coefficients();
                let values: Vec<f64> = (0..units.len()).map(|j| theta[(j, 0)]).collect();
                let coefficients = coefficients(units, Some(&f), &values);
                (model, coefficients)
            }
            Theta::Joint => unreachable!("a joint fit has no network of its own"),
        }
    }
}

/// The `p` effects' coefficients of a partially linear fit: the given ones,
/// or cross-fitted on `rows.theta` of `x_theta`, or none (a joint fit).
pub(super) fn theta_of(
    x_theta: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    rows: Rows<'_>,
    p: usize,
    settings: &FitSettings,
    gap: usize,
) -> Result<Theta, rbf::RbfError> {
    if let Some(known) = rows.known.filter(|c| c.len() == p) {
        let theta = Mat::from_fn(p, 1, |j, _| known[j].value);
        return Ok(Theta::Given(theta, known.to_vec()));
    }
    Ok(
        match cross_fitted_theta(x_theta, z, y, rows.theta, settings, gap)? {
            Some(f) => Theta::CrossFitted(Mat::from_fn(p, 1, |j, _| f.coef[j]), f),
            None => Theta::Joint,
        },
    )
}

/// What a partially linear fit's network is fitted to: y − Zθ on the
/// training rows.
pub(super) fn adjusted(y_train: &Mat<f64>, z_train: &Mat<f64>, theta: &Mat<f64>) -> Mat<f64> {
    y_train - z_train * theta
}

/// θ (with its HAC errors) by cross-fitted partialling out on `theta_rows`
/// of the windows `x_theta` (the first half of [`fit_partially_linear`]:
/// every cut of [`CROSS_FIT_CHUNKS`] whose blocks can choose their own
/// network, the cuts' spread in the errors), or `None` when no cut leaves
/// both blocks long enough for their own cross-validation or the regression
/// of the residuals fails.
///
/// This is the one estimator of a coefficient: the fit stores it (one
/// channel at a time or with a shared selection), and the diagnosis states
/// a suggested effect's coefficient with it, on the rows and settings the
/// refit will use, so the two say the same. `x_theta` is the raw window
/// whatever input the network reads ([`raw_windows`]): the estimate must not
/// depend on which input the model choice then takes (on the demo the
/// statistics input's networks put `col:temp` at 0.47, 0.48 and 2.13 over
/// the three cuts, the raw window's at 0.78, 0.36 and 0.65).
pub(crate) fn cross_fitted_theta(
    x_theta: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    theta_rows: &[usize],
    settings: &FitSettings,
    gap: usize,
) -> Result<Option<HacFit>, rbf::RbfError> {
    // Asked again with the same rows (the refit of a suggestion the
    // diagnosis stated, once per input tried): the estimate made before.
    super::memo::estimates::remembered((x_theta, z, y), theta_rows, settings, gap, || {
        estimate_theta(x_theta, z, y, theta_rows, settings, gap)
    })
}

/// [`cross_fitted_theta`], computed.
fn estimate_theta(
    x_theta: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    theta_rows: &[usize],
    settings: &FitSettings,
    gap: usize,
) -> Result<Option<HacFit>, rbf::RbfError> {
    let cuts: Vec<Blocks> = CROSS_FIT_CHUNKS
        .iter()
        .filter_map(|&k| Blocks::alternating(theta_rows, gap, k))
        .filter(|b| {
            block_fits(b.first.len(), settings, gap) && block_fits(b.second.len(), settings, gap)
        })
        .collect();
    // The cuts are independent fits: in parallel, combined in their order.
    let fits: Vec<Option<HacFit>> = cuts
        .par_iter()
        .map(|b| cross_fit(x_theta, z, y, b, settings, gap))
        .collect::<Result<_, _>>()?;
    let fits: Vec<HacFit> = fits.into_iter().flatten().collect();
    Ok(combine_splits(&fits))
}

/// The stored coefficients (values `theta`, each in its unit of `units`)
/// with the intervals of the regression `fit`: none rather than a made-up
/// one when the regression of the residuals failed (the model file then
/// carries none).
pub(super) fn coefficients(
    units: &[String],
    fit: Option<&HacFit>,
    theta: &[f64],
) -> Vec<Coefficient> {
    match fit {
        Some(f) => units
            .iter()
            .enumerate()
            .map(|(j, unit)| {
                // Centred on the stored value (θ itself, or the joint fit's in the fallback).
                let half = f.interval(j, 0.95).map(|b| b - f.coef[j]);
                let v = theta[j];
                Coefficient::new(v, f.se[j], [v + half[0], v + half[1]], unit.as_str())
                    .with_covariance(f.cov[j].clone())
            })
            .collect(),
        None => Vec::new(),
    }
}

/// Whether a block of `n` rows can choose its own network: at least
/// [`MIN_BLOCK_ROWS`], and every fold of its blocked cross-validation keeps
/// training rows beyond the leakage gap.
fn block_fits(n: usize, settings: &FitSettings, gap: usize) -> bool {
    n >= MIN_BLOCK_ROWS
        && (Split::Blocked {
            k: settings.inner_folds,
            gap,
        })
        .folds(n)
        .is_ok()
}

/// `[y, Z]` on `rows`: the targets whose residuals on a network's basis
/// the partialling out regresses.
fn y_and_z(y: &[f64], z: &Mat<f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), 1 + z.ncols(), |i, j| {
        if j == 0 {
            y[rows[i]]
        } else {
            z[(rows[i], j - 1)]
        }
    })
}

/// One cross-fit: residuals of `[y, Z]` on each block from the other
/// block's basis (a network alone fitted there), put back in time order,
/// and θ with its HAC errors.
fn cross_fit(
    x: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    b: &Blocks,
    settings: &FitSettings,
    gap: usize,
) -> Result<Option<HacFit>, rbf::RbfError> {
    let p = z.ncols();
    let mut by_row: Vec<(usize, Vec<f64>)> = Vec::with_capacity(b.first.len() + b.second.len());
    for (fit_rows, test_rows) in [(&b.second, &b.first), (&b.first, &b.second)] {
        let xf = gather(x, fit_rows);
        let yf = Mat::from_fn(fit_rows.len(), 1, |i, _| y[fit_rows[i]]);
        let no_z = Mat::<f64>::zeros(fit_rows.len(), 0);
        let net = fit_network(settings, xf.as_ref(), no_z.as_ref(), yf.as_ref(), gap)?;
        let xt = gather(x, test_rows);
        let r = residualise(
            net.features(xf.as_ref()).as_ref(),
            y_and_z(y, z, fit_rows).as_ref(),
            net.features(xt.as_ref()).as_ref(),
            y_and_z(y, z, test_rows).as_ref(),
            1,
            settings.ridge,
        )
        .map_err(rbf::RbfError::from)?;
        by_row.extend(
            test_rows
                .iter()
                .enumerate()
                .map(|(i, &row)| (row, (0..=p).map(|j| r[(i, j)]).collect())),
        );
    }
    by_row.sort_by_key(|(row, _)| *row);
    let column = |j: usize| -> Vec<f64> { by_row.iter().map(|(_, v)| v[j]).collect() };
    let rz: Vec<Vec<f64>> = (1..=p).map(column).collect();
    let cols: Vec<&[f64]> = rz.iter().map(Vec::as_slice).collect();
    Ok(hac_regression(&column(0), &cols).ok())
}

/// The joint fit of blocks too short to cross-fit: θ and the network in one
/// solve, θ's uncertainty from the same projection in-sample.
fn joint_fit(
    x: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    train: &[usize],
    settings: &FitSettings,
    gap: usize,
) -> Result<(rbf::RbfModel, Option<HacFit>), rbf::RbfError> {
    let p = z.ncols();
    let x_train = gather(x, train);
    let z_train = gather(z.as_ref(), train);
    let y_train = Mat::from_fn(train.len(), 1, |i, _| y[train[i]]);
    let joint = fit_network(
        settings,
        x_train.as_ref(),
        z_train.as_ref(),
        y_train.as_ref(),
        gap,
    )?;
    let phi = joint.features(x_train.as_ref());
    let targets = y_and_z(y, z, train);
    let r = residualise(
        phi.as_ref(),
        targets.as_ref(),
        phi.as_ref(),
        targets.as_ref(),
        1,
        settings.ridge,
    )
    .map_err(rbf::RbfError::from)?;
    let ry: Vec<f64> = (0..r.nrows()).map(|i| r[(i, 0)]).collect();
    let rz: Vec<Vec<f64>> = (1..=p)
        .map(|j| (0..r.nrows()).map(|i| r[(i, j)]).collect())
        .collect();
    let cols: Vec<&[f64]> = rz.iter().map(Vec::as_slice).collect();
    let f = hac_regression(&ry, &cols).ok();
    Ok((joint, f))
}

#[cfg(test)]
mod tests {
    use crate::example::{Line, Slope, line_record};
    use crate::{FitOptions, Model, WindowSpec};

    fn fit_line(n: usize, window: usize) -> (Model<Line>, crate::Prepared<Line>) {
        let rec = line_record(n, 2.0, 11);
        let mut options = FitOptions::new(1);
        options.recipe.preprocess = Line::preprocess();
        options.recipe.preprocess.window = WindowSpec::new(vec!["u".into()], window).unwrap();
        options.recipe.effects[0] = vec![Slope];
        options.recipe.settings.max_centres = 5;
        crate::fit_records(&Line, &[("r".into(), &rec)], &options, &|_| {}).unwrap()
    }

    /// One estimate of each coefficient: the model and its mirror (trained
    /// on the other rows) store the same θ and interval, cross-fitted on the
    /// rows both were given.
    #[test]
    fn the_model_and_its_mirror_store_one_estimate() {
        let (model, prepared) = fit_line(3000, 5);
        let mirror = crate::fit::mirror(&model, &prepared).unwrap();
        let (a, b) = (
            &model.channel(0).coefficients().unwrap()[0],
            &mirror.channel(0).coefficients().unwrap()[0],
        );
        assert_eq!(a, b);
        assert!(a.se > 0.0 && (a.value - 2.0).abs() < 0.3, "{a:?}");
    }

    /// A window of 250 samples leaves a leakage gap that a cross-fitting
    /// block of a few hundred rows cannot hold three blocked folds around
    /// (the demo's "fold 1 of 772 samples has 0 training rows"): such cuts
    /// are skipped, the fit goes through.
    #[test]
    fn a_long_window_cross_fits() {
        let (model, _) = fit_line(3000, 250);
        let c = &model.channel(0).coefficients().unwrap()[0];
        assert!(c.se > 0.0 && (c.value - 2.0).abs() < 0.3, "{c:?}");
    }

    /// A short record with a long window (issue 22's 40-s record with
    /// `--window 250`): the model fits, but the diagnosis's mirror, trained
    /// on the validation rows, has too few for its folds; the refusal says
    /// so and what helps (more validation rows), not "training windows".
    #[test]
    fn a_mirror_too_short_for_its_folds_is_named_as_the_mirror() {
        let (model, prepared) = fit_line(1500, 200);
        let e = crate::fit::mirror(&model, &prepared).unwrap_err();
        assert!(
            matches!(e, crate::SysidError::MirrorFoldsEmpty { .. }),
            "{e:?}"
        );
        let text = e.to_string();
        assert!(
            text.starts_with("the diagnosis fits the model's mirror on its ")
                && text.contains("a smaller --train-fraction"),
            "{text}"
        );
    }
}
