//! Grid search for several targets on the same inputs, each its own.
//!
//! A sensor's channels read the same input windows: their cross-validations
//! differ only in the targets, and an OLS selection's candidate kernel
//! columns (distances from every training row of a fold to every candidate
//! centre, through the width) depend on the inputs alone. Here each (width,
//! fold) works out the candidates, their widths and their kernel columns
//! once, and every target's selection reads them; each target's report is
//! what [`grid_search_with_linear`] gives on that target alone, bit for bit
//! (the stored columns are the generated ones in any batch), not a
//! selection shared by the targets (whose summed ERR would pick other
//! centres).

use faer::MatRef;
use rayon::prelude::*;

use super::grid::{
    Axes, Grid, GridPoint, GridReport, Results, best_point, grid_search_with_linear, ols_fold,
};
use super::validate::{Part, take_rows};
use crate::check::first_non_finite;
use crate::model::{CentreSelection, OlsInputs, RbfError, RbfValidParams};
use crate::split::Split;

/// [`grid_search_with_linear`] of each column of `y` on its own, the
/// candidates' kernel columns of each width and fold computed once for all
/// of them (with OLS centre selection; other strategies run one grid per
/// target). The targets' selections of a fold run in parallel on the rayon
/// pool.
///
/// # Errors
/// As [`grid_search_with_linear`].
///
/// # Panics
/// If the row counts differ.
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// use rbf::{CentreSelection, Grid, RbfParams, Sizes, Split, WidthRule};
/// let x = Mat::from_fn(120, 1, |i, _| i as f64 / 20.0);
/// let y = Mat::from_fn(120, 2, |i, t| if t == 0 { x[(i, 0)].sin() } else { x[(i, 0)].cos() });
/// let z = Mat::<f64>::zeros(120, 0);
/// let p = RbfParams::new().centres(CentreSelection::ols(10)).parallelism(Par::Seq).check().unwrap();
/// let grid = Grid { widths: vec![WidthRule::Fixed(0.5), WidthRule::Fixed(1.0)], sizes: Sizes::Centres(vec![3, 8]), ridges: vec![] };
/// let split = Split::Blocked { k: 3, gap: 2 };
/// let each = rbf::grid_search_each_with_linear(&p, x.as_ref(), z.as_ref(), y.as_ref(), &split, &grid).unwrap();
/// let alone = rbf::grid_search_with_linear(&p, x.as_ref(), z.as_ref(), y.as_ref().subcols(1, 1), &split, &grid).unwrap();
/// assert_eq!(format!("{:?}", each[1].points), format!("{:?}", alone.points));
/// ```
#[track_caller]
pub fn grid_search_each_with_linear(
    params: &RbfValidParams,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    split: &Split,
    grid: &Grid,
) -> Result<Vec<GridReport>, RbfError> {
    assert_eq!(x.nrows(), y.nrows(), "x and y row counts differ");
    assert_eq!(x.nrows(), z.nrows(), "x and z row counts differ");
    let q = y.ncols();
    if !matches!(params.centres(), CentreSelection::Ols { .. }) || q < 2 {
        return (0..q)
            .map(|t| grid_search_with_linear(params, x, z, y.subcols(t, 1), split, grid))
            .collect();
    }
    let folds = split.folds(x.nrows())?;
    let axes = Axes::of(params, grid)?;
    let mut points: Vec<Vec<GridPoint>> = (0..q).map(|_| Vec::new()).collect();
    for width in &axes.widths {
        let pw = params.with_width(width.clone());
        let mut results: Vec<Results> = (0..q)
            .map(|_| Results::new(axes.sizes.len(), axes.ridges.len()))
            .collect();
        for fold in &folds {
            let (tx, tz) = (take_rows(x, &fold.train), take_rows(z, &fold.train));
            // Inputs a selection would refuse, or cannot work out, are left
            // to each target's own run, which says why as it does alone.
            let finite =
                first_non_finite(tx.as_ref()).is_none() && first_non_finite(tz.as_ref()).is_none();
            let inputs = finite
                .then(|| OlsInputs::new(&pw, tx.as_ref(), tz.as_ref(), None).ok())
                .flatten();
            drop((tx, tz));
            let columns = inputs.as_ref().and_then(|s| s.shared_columns(&pw));
            let shared = inputs
                .as_ref()
                .map(|s| (s, columns.as_ref().map(|m| m.as_ref())));
            // Each target's rows of the fold are gathered while its selection
            // runs, not held for every target at once (a large record's
            // selection rows are 30 MB a copy).
            results.par_iter_mut().enumerate().for_each(|(t, res)| {
                let yt = y.subcols(t, 1);
                let train = Part::new(x, z, yt, &fold.train);
                let val = Part::new(x, z, yt, &fold.validation);
                ols_fold(&pw, &axes, &train, &val, res, shared);
            });
        }
        for (t, r) in results.into_iter().enumerate() {
            r.into_points(width, &axes, &mut points[t]);
        }
    }
    Ok(points
        .into_iter()
        .map(|points| {
            let best = best_point(&points);
            GridReport { points, best }
        })
        .collect())
}
