//! Grid search over width, model size (K or ρ) and ridge.
//!
//! With OLS, each fold runs forward selection once per width (up to the largest K, or
//! the smallest ρ) and reads every smaller model off the path; only the cheap QR weight
//! solve is repeated per K and ridge. Other strategies compute their centres once per
//! width, size and fold, and re-solve the weights per ridge.

use faer::{Mat, MatRef};

use super::validate::{CvReport, FoldReport, Part, fold_report};
use crate::model::{CentreSelection, OlsInputs, OlsStage, RbfError, RbfValidParams};
use crate::split::Split;
use crate::width::WidthRule;

/// Model sizes to try.
///
/// ```
/// let s = rbf::Sizes::Centres(vec![10, 20, 40]);
/// assert_ne!(s, rbf::Sizes::Default);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Sizes {
    /// The size in the params.
    Default,
    /// Numbers of centres (OLS: path prefixes; k-means and random: refits).
    Centres(Vec<usize>),
    /// OLS tolerances ρ (OLS only).
    Tolerances(Vec<f64>),
}

/// The grid: every combination of width × size × ridge. Empty `widths` or `ridges`
/// mean the params' own.
///
/// ```
/// let g = rbf::Grid {
///     widths: vec![rbf::WidthRule::Fixed(0.5), rbf::WidthRule::Fixed(1.0)],
///     sizes: rbf::Sizes::Centres(vec![5, 10]),
///     ridges: vec![0.0, 1e-6],
/// };
/// assert_eq!(g.len(), 8);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Width rules to try.
    pub widths: Vec<WidthRule>,
    /// Sizes to try.
    pub sizes: Sizes,
    /// Ridges to try.
    pub ridges: Vec<f64>,
}

impl Grid {
    /// Number of grid points.
    ///
    /// ```
    /// let g = rbf::Grid { widths: vec![], sizes: rbf::Sizes::Default, ridges: vec![] };
    /// assert_eq!(g.len(), 1);
    /// ```
    pub fn len(&self) -> usize {
        let s = match &self.sizes {
            Sizes::Default => 1,
            Sizes::Centres(v) => v.len(),
            Sizes::Tolerances(v) => v.len(),
        };
        self.widths.len().max(1) * s * self.ridges.len().max(1)
    }

    /// Whether the grid has no point (an empty size list).
    ///
    /// ```
    /// let g = rbf::Grid { widths: vec![], sizes: rbf::Sizes::Centres(vec![]), ridges: vec![] };
    /// assert!(g.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One grid point and its cross-validation result.
///
/// ```
/// let p = rbf::GridPoint { width: rbf::WidthRule::Fixed(1.0), n_centres: Some(5), tol: None, ridge: 0.0,
///     result: Err(rbf::RbfError::FoldFailed { reason: "example".into() }) };
/// assert!(p.result.is_err());
/// ```
#[derive(Debug)]
pub struct GridPoint {
    /// Width rule.
    pub width: WidthRule,
    /// Number of centres asked for (`Sizes::Centres`), if any.
    pub n_centres: Option<usize>,
    /// OLS tolerance ρ (`Sizes::Tolerances`), if any.
    pub tol: Option<f64>,
    /// Ridge λ.
    pub ridge: f64,
    /// Its cross-validation, or why a fold failed (e.g. an ill-conditioned solve).
    pub result: Result<CvReport, RbfError>,
}

/// All grid points, in width-major, then size, then ridge order.
///
/// ```
/// let r = rbf::GridReport { points: vec![], best: None };
/// assert!(r.points.is_empty());
/// ```
#[derive(Debug)]
pub struct GridReport {
    /// Every point.
    pub points: Vec<GridPoint>,
    /// Index of the point with the lowest mean validation NMSE among those that succeeded.
    pub best: Option<usize>,
}

impl GridReport {
    /// The best point, if any succeeded.
    ///
    /// ```
    /// let r = rbf::GridReport { points: vec![], best: None };
    /// assert!(r.best().is_none());
    /// ```
    pub fn best(&self) -> Option<&GridPoint> {
        self.best.map(|i| &self.points[i])
    }
}

/// Grid search with cross-validation on inputs `x` and targets `y`.
///
/// # Errors
/// A split that cannot be made, or [`Sizes::Tolerances`] with a strategy other than
/// OLS. A grid point whose fit fails is recorded in its [`GridPoint::result`].
///
/// # Panics
/// If the row counts differ.
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// use rbf::{grid_search, CentreSelection, Grid, RbfParams, Sizes, Split, WidthRule};
/// let x = Mat::from_fn(150, 1, |i, _| i as f64 / 25.0);
/// let y = Mat::from_fn(150, 1, |i, _| (2.0 * x[(i, 0)]).sin());
/// let p = RbfParams::new().centres(CentreSelection::ols(20)).parallelism(Par::Seq).check().unwrap();
/// let grid = Grid {
///     widths: vec![WidthRule::Fixed(0.3), WidthRule::Fixed(1.0)],
///     sizes: Sizes::Centres(vec![2, 12]),
///     ridges: vec![0.0],
/// };
/// let rep = grid_search(&p, x.as_ref(), y.as_ref(), &Split::KFold { k: 3, seed: 1 }, &grid).unwrap();
/// assert_eq!(rep.points.len(), 4);
/// assert_eq!(rep.best().unwrap().n_centres, Some(12));
/// ```
#[track_caller]
pub fn grid_search(
    params: &RbfValidParams,
    x: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    split: &Split,
    grid: &Grid,
) -> Result<GridReport, RbfError> {
    let z = Mat::<f64>::zeros(x.nrows(), 0);
    grid_search_with_linear(params, x, z.as_ref(), y, split, grid)
}

/// [`grid_search`] with exogenous linear regressors `z`.
///
/// # Errors
/// As [`grid_search`].
///
/// # Panics
/// If the row counts differ.
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// let x = Mat::from_fn(90, 1, |i, _| i as f64 / 15.0);
/// let z = Mat::from_fn(90, 1, |i, _| (i % 3) as f64);
/// let y = Mat::from_fn(90, 1, |i, _| x[(i, 0)].sin() + z[(i, 0)]);
/// let p = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(15)).width(rbf::WidthRule::Fixed(1.0))
///     .parallelism(Par::Seq).check().unwrap();
/// let grid = rbf::Grid { widths: vec![], sizes: rbf::Sizes::Tolerances(vec![1e-2, 1e-6]), ridges: vec![0.0, 1e-3] };
/// let rep = rbf::grid_search_with_linear(&p, x.as_ref(), z.as_ref(), y.as_ref(), &rbf::Split::Blocked { k: 3, gap: 0 }, &grid).unwrap();
/// assert_eq!(rep.points.len(), 4);
/// assert!(rep.points.iter().all(|p| p.result.is_ok()));
/// ```
#[track_caller]
pub fn grid_search_with_linear(
    params: &RbfValidParams,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    split: &Split,
    grid: &Grid,
) -> Result<GridReport, RbfError> {
    assert_eq!(x.nrows(), y.nrows(), "x and y row counts differ");
    assert_eq!(x.nrows(), z.nrows(), "x and z row counts differ");
    let folds = split.folds(x.nrows())?;
    let axes = Axes::of(params, grid)?;
    let parts: Vec<(Part, Part)> = folds
        .iter()
        .map(|f| {
            (
                Part::new(x, z, y, &f.train),
                Part::new(x, z, y, &f.validation),
            )
        })
        .collect();

    let mut points = Vec::with_capacity(axes.widths.len() * axes.sizes.len() * axes.ridges.len());
    for width in &axes.widths {
        let pw = params.with_width(width.clone());
        let mut results = Results::new(axes.sizes.len(), axes.ridges.len());
        for (train, val) in &parts {
            if matches!(pw.centres(), CentreSelection::Ols { .. }) {
                ols_fold(&pw, &axes, train, val, &mut results, None);
            } else {
                fixed_fold(&pw, &axes, train, val, &mut results);
            }
        }
        results.into_points(width, &axes, &mut points);
    }
    let best = best_point(&points);
    Ok(GridReport { points, best })
}

/// The grid's axes, with the params' own width and ridge where the grid gives none.
pub(super) struct Axes {
    pub(super) widths: Vec<WidthRule>,
    /// (n_centres, tol) per size.
    pub(super) sizes: Vec<(Option<usize>, Option<f64>)>,
    pub(super) ridges: Vec<f64>,
}

impl Axes {
    pub(super) fn of(params: &RbfValidParams, grid: &Grid) -> Result<Self, RbfError> {
        let is_ols = matches!(params.centres(), CentreSelection::Ols { .. });
        if matches!(grid.sizes, Sizes::Tolerances(_)) && !is_ols {
            return Err(RbfError::GridMismatch {
                reason: "tolerance grids need OLS centre selection",
            });
        }
        let widths = if grid.widths.is_empty() {
            vec![params.width().clone()]
        } else {
            grid.widths.clone()
        };
        let ridges = if grid.ridges.is_empty() {
            vec![params.ridge()]
        } else {
            grid.ridges.clone()
        };
        let sizes = match &grid.sizes {
            Sizes::Default => vec![(None, None)],
            Sizes::Centres(v) => v.iter().map(|&k| (Some(k), None)).collect(),
            Sizes::Tolerances(v) => v.iter().map(|&t| (None, Some(t))).collect(),
        };
        Ok(Self {
            widths,
            sizes,
            ridges,
        })
    }
}

/// The fold reports of one width: `[size][ridge]`, or the first error of that point.
pub(super) struct Results(Vec<Vec<Result<Vec<FoldReport>, RbfError>>>);

impl Results {
    pub(super) fn new(sizes: usize, ridges: usize) -> Self {
        Self(
            (0..sizes)
                .map(|_| (0..ridges).map(|_| Ok(Vec::new())).collect())
                .collect(),
        )
    }

    fn record(&mut self, s: usize, r: usize, rep: Result<FoldReport, RbfError>) {
        let slot = &mut self.0[s][r];
        if let Ok(v) = slot {
            match rep {
                Ok(f) => v.push(f),
                Err(e) => *slot = Err(e),
            }
        }
    }

    /// A fold whose fit failed fails every ridge of the sizes `sizes`.
    fn fail(&mut self, sizes: std::ops::Range<usize>, e: &RbfError) {
        let msg = e.to_string();
        for si in sizes {
            for ri in 0..self.0[si].len() {
                let reason = msg.clone();
                self.record(si, ri, Err(RbfError::FoldFailed { reason }));
            }
        }
    }

    /// The grid points of `width`, in size then ridge order.
    pub(super) fn into_points(self, width: &WidthRule, axes: &Axes, points: &mut Vec<GridPoint>) {
        for (si, row) in self.0.into_iter().enumerate() {
            for (ri, res) in row.into_iter().enumerate() {
                points.push(GridPoint {
                    width: width.clone(),
                    n_centres: axes.sizes[si].0,
                    tol: axes.sizes[si].1,
                    ridge: axes.ridges[ri],
                    result: res.map(CvReport::from_folds),
                });
            }
        }
    }
}

/// One fold with OLS: one forward selection up to the largest size (or smallest ρ),
/// every size read off its path, the weights re-solved per ridge; on the
/// inputs `shared` when several targets share them.
pub(super) fn ols_fold(
    pw: &RbfValidParams,
    axes: &Axes,
    train: &Part,
    val: &Part,
    results: &mut Results,
    shared: Option<(&OlsInputs, Option<MatRef<'_, f64>>)>,
) {
    let CentreSelection::Ols {
        max_centres, tol, ..
    } = pw.centres()
    else {
        unreachable!("called for OLS params only");
    };
    let sizes = &axes.sizes;
    let k_max = sizes
        .iter()
        .filter_map(|s| s.0)
        .max()
        .unwrap_or(*max_centres);
    // The smallest ρ asked for runs longest; every larger ρ is a prefix.
    let rho = sizes
        .iter()
        .filter_map(|s| s.1)
        .reduce(f64::min)
        .unwrap_or(*tol);
    let (tx, tz, ty) = (train.x.as_ref(), train.z.as_ref(), train.y.as_ref());
    let stage = match shared {
        Some(s) => OlsStage::run_on(pw, s, tx, tz, ty, k_max, rho),
        None => OlsStage::run(pw, tx, tz, ty, k_max, rho, None),
    };
    let stage = match stage {
        Ok(stage) => stage,
        Err(e) => return results.fail(0..sizes.len(), &e),
    };
    for (si, &(nc, t)) in sizes.iter().enumerate() {
        let path = stage.path();
        let k = match (nc, t) {
            (Some(k), _) => k.min(path.len()),
            (None, Some(t)) => path.terms_for_tol(t),
            (None, None) => path.len(),
        };
        for (ri, &ridge) in axes.ridges.iter().enumerate() {
            let rep = stage
                .model(pw, k, ridge, ty)
                .map(|m| fold_report(&m, train, val));
            results.record(si, ri, rep);
        }
    }
}

/// One fold with k-means, random or given centres: the centres once per size, the
/// weights per ridge.
fn fixed_fold(pw: &RbfValidParams, axes: &Axes, train: &Part, val: &Part, results: &mut Results) {
    for (si, &(nc, _)) in axes.sizes.iter().enumerate() {
        let ps = match (nc, pw.centres()) {
            (Some(k), CentreSelection::KMeans(s)) => pw.with_centres(CentreSelection::KMeans(
                crate::select::kmeans::KMeansSettings { n_centres: k, ..*s },
            )),
            (Some(k), CentreSelection::Random { .. }) => {
                pw.with_centres(CentreSelection::Random { n_centres: k })
            }
            _ => pw.clone(),
        };
        let (tx, tz, ty) = (train.x.as_ref(), train.z.as_ref(), train.y.as_ref());
        match ps.fit_ridges(tx, tz, ty, &axes.ridges) {
            Ok(models) => {
                for (ri, m) in models.into_iter().enumerate() {
                    results.record(si, ri, m.map(|m| fold_report(&m, train, val)));
                }
            }
            Err(e) => results.fail(si..si + 1, &e),
        }
    }
}

/// The point of lowest finite mean validation NMSE among those that succeeded.
pub(super) fn best_point(points: &[GridPoint]) -> Option<usize> {
    points
        .iter()
        .enumerate()
        .filter_map(|(i, p)| p.result.as_ref().ok().map(|r| (i, r.mean.nmse)))
        .filter(|(_, v)| v.is_finite())
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}
