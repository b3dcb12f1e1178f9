//! The network chosen by blocked cross-validation over widths and numbers
//! of centres, refitted on all the rows it was chosen on.

use crate::recipe::{CentreMethod, FitSettings};
use faer::{MatRef, Par};
use rbf::{
    Candidates, CentreSelection, Grid, KMeansSettings, ParamGuard, RbfParams, Sizes, Split,
    WidthRule,
};

/// Numbers of centres tried: a roughly geometric ladder up to `max`.
fn size_ladder(max: usize) -> Vec<usize> {
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
    let params = |k: usize, width: WidthRule| {
        RbfParams::new()
            .kernel(settings.kernel)
            .centres(selection(k))
            .width(width)
            .ridge(settings.ridge)
            .seed(settings.seed)
            .parallelism(Par::Seq)
            .check()
            .map_err(rbf::RbfError::from)
    };
    let widths: Vec<WidthRule> = settings
        .width_scales
        .iter()
        .map(|&s| WidthRule::MedianPairwise { scale: s })
        .collect();
    let max_k = settings.max_centres.min(x.nrows() / 2).max(1);
    let grid = Grid {
        widths: widths.clone(),
        sizes: Sizes::Centres(size_ladder(max_k)),
        ridges: vec![],
    };
    let report = rbf::grid_search_with_linear(
        &params(max_k, widths[0].clone())?,
        x,
        z,
        y,
        &Split::Blocked {
            k: settings.inner_folds,
            gap,
        },
        &grid,
    )?;
    let best = match report.best() {
        Some(b) => b,
        None => {
            let first_error = report.points.into_iter().find_map(|p| p.result.err());
            return Err(first_error.unwrap_or(rbf::RbfError::FoldFailed {
                reason: "no grid point".into(),
            }));
        }
    };
    let k = best.n_centres.unwrap_or(max_k);
    params(k, best.width.clone())?.fit_with_linear(x, z, y)
}
