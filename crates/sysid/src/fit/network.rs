//! The network chosen by blocked cross-validation over widths and numbers
//! of centres, refitted on all the rows it was chosen on.

use crate::recipe::{CentreMethod, FitSettings};
use faer::{MatRef, Par};
use rayon::prelude::*;
use rbf::{
    Candidates, CentreSelection, Grid, KMeansSettings, ParamGuard, RbfParams, Sizes, Split,
    WidthRule,
};

/// Numbers of centres tried: a roughly geometric ladder up to `max`.
pub(super) fn size_ladder(max: usize) -> Vec<usize> {
    let mut v: Vec<usize> = [2, 5, 10, 15, 20, 30, 40, 60, 80, 100, 150, 200, 300]
        .into_iter()
        .filter(|&k| k < max)
        .collect();
    v.push(max);
    v
}

/// The network (with `z` as forced linear columns, none if it has no
/// columns) chosen by blocked cross-validation over widths and numbers of
/// centres, refitted on all the given rows.
pub(super) fn fit_network(
    settings: &FitSettings,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    gap: usize,
) -> Result<rbf::RbfModel, rbf::RbfError> {
    let chosen = choose_network(settings, x, z, y, gap)?;
    fit_chosen(settings, &chosen, x, z, y)
}

/// What the cross-validation of [`fit_network`] chose: the number of
/// centres and the width rule (a multiple of the rows' median distance).
#[derive(Debug, Clone)]
pub(super) struct Chosen {
    n_centres: usize,
    width: WidthRule,
}

/// The network's parameters for `settings`, `k` centres and `width`.
pub(super) fn params(
    settings: &FitSettings,
    k: usize,
    width: WidthRule,
) -> Result<rbf::RbfValidParams, rbf::RbfError> {
    let selection = |k: usize| match settings.centres {
        CentreMethod::Ols => CentreSelection::Ols {
            max_centres: k,
            tol: 0.0,
            regularisation: 0.0,
            candidates: Candidates::Subsample {
                size: settings.candidates,
            },
        },
        CentreMethod::KMeans => CentreSelection::KMeans(KMeansSettings::new(k)),
    };
    RbfParams::new()
        .kernel(settings.kernel)
        .centres(selection(k))
        .width(width)
        .ridge(settings.ridge)
        .seed(settings.seed)
        .parallelism(Par::Seq)
        .check()
        .map_err(rbf::RbfError::from)
}

/// The network chosen by [`choose_network`] fitted on the given rows; its
/// number of centres at most half the rows.
pub(super) fn fit_chosen(
    settings: &FitSettings,
    chosen: &Chosen,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
) -> Result<rbf::RbfModel, rbf::RbfError> {
    let k = chosen.n_centres.min(x.nrows() / 2).max(1);
    params(settings, k, chosen.width.clone())?.fit_with_linear(x, z, y)
}

/// The number of centres and width of [`fit_network`], by blocked
/// cross-validation over the settings' widths and a ladder of sizes.
fn choose_network(
    settings: &FitSettings,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    gap: usize,
) -> Result<Chosen, rbf::RbfError> {
    let widths: Vec<WidthRule> = settings
        .width_scales
        .iter()
        .map(|&s| WidthRule::MedianPairwise { scale: s })
        .collect();
    let max_k = settings.max_centres.min(x.nrows() / 2).max(1);
    let split = Split::Blocked {
        k: settings.inner_folds,
        gap,
    };
    // One grid per width, in parallel (a shared selection is one network
    // for every channel, so the channels no longer keep both cores busy);
    // the points come back in the width-major order of one grid, and the
    // first lowest mean validation NMSE wins, as in one grid.
    let reports: Vec<rbf::GridReport> = widths
        .par_iter()
        .map(|w| {
            let grid = Grid {
                widths: vec![w.clone()],
                sizes: Sizes::Centres(size_ladder(max_k)),
                ridges: vec![],
            };
            let p = params(settings, max_k, w.clone())?;
            rbf::grid_search_with_linear(&p, x, z, y, &split, &grid)
        })
        .collect::<Result<_, _>>()?;
    let points: Vec<rbf::GridPoint> = reports.into_iter().flat_map(|r| r.points).collect();
    best_of(points, y.ncols(), max_k)
}

/// The grid point of lowest criterion among `points` (every width's, in the
/// width-major order of one grid) for `n_targets` targets.
pub(super) fn best_of(
    points: Vec<rbf::GridPoint>,
    n_targets: usize,
    max_k: usize,
) -> Result<Chosen, rbf::RbfError> {
    // One target: its validation NMSE, as the library's grid. Several
    // (a shared selection): the mean over channels of the validation rms,
    // in the targets' one unit, as the summed ERR weighs them; the mean
    // NMSE let a channel the network cannot help (NMSE near 1 everywhere,
    // rising a little with every centre) hold every channel at 2 centres on
    // the three-record campaign (X +51%, Z +41%).
    let criterion = |r: &rbf::CvReport| match n_targets {
        1 => r.mean.nmse,
        _ => r.mean.rmse,
    };
    let best = points
        .iter()
        .filter_map(|p| p.result.as_ref().ok().map(|r| (p, criterion(r))))
        .filter(|(_, v)| v.is_finite())
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(p, _)| (p.n_centres, p.width.clone()));
    let Some((n_centres, width)) = best else {
        let first_error = points.into_iter().find_map(|p| p.result.err());
        return Err(first_error.unwrap_or(rbf::RbfError::FoldFailed {
            reason: "no grid point".into(),
        }));
    };
    Ok(Chosen {
        n_centres: n_centres.unwrap_or(max_k),
        width,
    })
}
/// Training windows above which cross-validation and centre selection run on
/// every `selection_stride`-th of them; the weights are still solved on all.
/// Their cost is rows × candidates per fold and channel: 1.6 GB a channel at
/// 500,000 rows, where a 1M-row record needed 6 GB and over 5 minutes. On
/// the 1M-sample record of docs/performance.md, 25,000 selection rows
/// instead of 50,000 took the fit from 52 s to 33 s with every channel's
/// validation rms within 1% (0.6% lower to 0.1% higher); 10,000 took 22 s
/// but raised Z1's by 1.5%.
pub const MAX_SELECTION_ROWS: usize = 25_000;

/// The stride of the training windows that choose centres and width: 1 up to
/// [`MAX_SELECTION_ROWS`]. A stride keeps time order, so the blocked folds'
/// leakage gap of g rows spans g·stride samples, never fewer than needed.
///
/// ```
/// assert_eq!(sysid::fit::selection_stride(25_000), 1);
/// assert_eq!(sysid::fit::selection_stride(500_000), 20);
/// ```
pub fn selection_stride(n_train: usize) -> usize {
    n_train.div_ceil(MAX_SELECTION_ROWS).max(1)
}
