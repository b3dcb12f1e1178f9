//! Fitting: inputs → design (standardisation, fixed columns) → centres and widths →
//! output weights.

use faer::prelude::ReborrowMut;
use faer::{Mat, MatRef};

use super::error::RbfError;
use super::fitted::{RbfModel, Selection};
use super::hyperparams::{CentreSelection, RbfValidParams};
use super::ols_inputs::OlsInputs;
use super::poly::{PolyTail, kernel_coordinates, monomials, unit_box};
use super::progress::{Progress, Stage};
use super::scaling::Scaling;
use crate::check::first_non_finite;
use crate::design::{KernelColumns, Widths, kernel_matrix, kernel_matrix_into};
use crate::estimate::{InterpolationOptions, LstsqOptions, StreamingLstsq, interpolate, lstsq};
use crate::select::kmeans::kmeans_centres;
use crate::select::ols::{
    OlsOptions, OlsPath, OlsProgress, SizeRule, StopReason, StreamPrecision, forward_select,
    forward_select_columns, forward_select_owned,
};
use crate::select::random::random_subset;

type Observer<'a> = Option<&'a (dyn Fn(Progress) + Sync)>;

fn report(progress: Observer<'_>, stage: Stage, done: usize, total: usize) {
    if let Some(f) = progress {
        f(Progress { stage, done, total });
    }
}

/// Standardised inputs and the fixed columns [1 | x | z] (or [monomials | z] with a
/// polynomial tail) of a fit.
#[derive(Clone)]
pub(crate) struct Design {
    pub(crate) scaling: Option<Scaling>,
    pub(crate) xs: Mat<f64>,
    pub(crate) forced: Mat<f64>,
    pub(crate) bias: bool,
    pub(crate) tail: bool,
    pub(crate) n_linear: usize,
    /// The polynomial tail's degree and unit-box map (shift, scale), when set.
    pub(crate) poly: Option<(PolyTail, Vec<f64>, Vec<f64>)>,
}

impl Design {
    pub(crate) fn new(params: &RbfValidParams, x: MatRef<'_, f64>, z: MatRef<'_, f64>) -> Self {
        if let Some(degree) = params.degree {
            return Self::with_poly(params, degree, x, z);
        }
        let (n, d) = (x.nrows(), x.ncols());
        let scaling = params.standardise.then(|| Scaling::from_data(x));
        let xs = match &scaling {
            Some(s) => s.apply(x),
            None => x.to_owned(),
        };
        let (bias, tail) = params.bias_and_tail();
        let p = params.fixed_columns(d, z.ncols());
        let mut forced = Mat::<f64>::zeros(n, p);
        let mut c = 0;
        if bias {
            forced.as_mut().col_mut(0).fill(1.0);
            c = 1;
        }
        if tail {
            forced.as_mut().subcols_mut(c, d).copy_from(xs.as_ref());
            c += d;
        }
        forced.as_mut().subcols_mut(c, z.ncols()).copy_from(z);
        Self {
            scaling,
            xs,
            forced,
            bias,
            tail,
            n_linear: z.ncols(),
            poly: None,
        }
    }

    /// The design of a polynomial tail of `degree` on unit-box inputs; the kernel sees
    /// the inputs standardised (if asked) or shifted by the unit box's shift.
    fn with_poly(
        params: &RbfValidParams,
        degree: PolyTail,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
    ) -> Self {
        let (shift, scale) = unit_box(x);
        let scaling = params.standardise.then(|| Scaling::from_data(x));
        let xs = kernel_coordinates(scaling.as_ref(), Some(&shift), x);
        let m = monomials(degree, x, &shift, &scale);
        let mut forced = Mat::<f64>::zeros(x.nrows(), m.ncols() + z.ncols());
        forced
            .as_mut()
            .subcols_mut(0, m.ncols())
            .copy_from(m.as_ref());
        forced
            .as_mut()
            .subcols_mut(m.ncols(), z.ncols())
            .copy_from(z);
        Self {
            scaling,
            xs,
            forced,
            bias: false,
            tail: false,
            n_linear: z.ncols(),
            poly: Some((degree, shift, scale)),
        }
    }

    pub(crate) fn standardised(&self, points: MatRef<'_, f64>) -> Mat<f64> {
        kernel_coordinates(
            self.scaling.as_ref(),
            self.poly.as_ref().map(|(_, shift, _)| shift.as_slice()),
            points,
        )
    }

    pub(crate) fn n(&self) -> usize {
        self.xs.nrows()
    }
}

#[track_caller]
pub(crate) fn check_inputs(
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
) -> Result<(), RbfError> {
    assert_eq!(
        x.nrows(),
        y.nrows(),
        "x has {} rows but y has {}",
        x.nrows(),
        y.nrows()
    );
    assert_eq!(
        z.nrows(),
        x.nrows(),
        "z has {} rows but x has {}",
        z.nrows(),
        x.nrows()
    );
    assert!(y.ncols() >= 1, "y needs at least one column");
    for (matrix, m) in [("x", x), ("z", z), ("y", y)] {
        if let Some((row, col)) = first_non_finite(m) {
            return Err(RbfError::NonFinite { matrix, row, col });
        }
    }
    if x.nrows() == 0 {
        return Err(RbfError::TooFewSamples {
            samples: 0,
            needed: 1,
        });
    }
    Ok(())
}

pub(crate) fn check_dim(
    what: &'static str,
    points: MatRef<'_, f64>,
    d: usize,
) -> Result<(), RbfError> {
    if points.ncols() != d {
        return Err(RbfError::Dimension {
            what,
            expected: d,
            found: points.ncols(),
        });
    }
    Ok(())
}

pub(crate) fn rows(m: MatRef<'_, f64>, idx: &[usize]) -> Mat<f64> {
    Mat::from_fn(idx.len(), m.ncols(), |i, k| m[(idx[i], k)])
}

/// Solves the output weights on [fixed columns | kernel columns] by faer QR and
/// assembles the model.
#[allow(clippy::too_many_arguments)] // internal: every argument is a distinct piece of the model
fn solve_model(
    params: &RbfValidParams,
    design: &Design,
    centres: Mat<f64>,
    widths: Widths,
    phi: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    ridge: f64,
    selection: Option<Selection>,
) -> Result<RbfModel, RbfError> {
    let (n, p, k) = (design.n(), design.forced.ncols(), phi.ncols());
    let mut a = Mat::<f64>::zeros(n, p + k);
    a.as_mut()
        .subcols_mut(0, p)
        .copy_from(design.forced.as_ref());
    a.as_mut().subcols_mut(p, k).copy_from(phi);
    let sol = lstsq(a.as_ref(), y, &weight_options(params, p, ridge))?;
    model_from(params, design, centres, widths, sol, selection)
}

/// Options of the weight solve: the `p` fixed columns unpenalised.
fn weight_options(params: &RbfValidParams, p: usize, ridge: f64) -> LstsqOptions {
    LstsqOptions {
        ridge,
        unpenalised: p,
        rank_tol: None,
        max_condition: params.max_condition,
        par: params.par,
    }
}

/// The model from a weight solve on [fixed columns | kernel columns].
fn model_from(
    params: &RbfValidParams,
    design: &Design,
    centres: Mat<f64>,
    widths: Widths,
    sol: crate::estimate::Solution,
    selection: Option<Selection>,
) -> Result<RbfModel, RbfError> {
    let (p, k) = (design.forced.ncols(), centres.nrows());
    let c = sol.coefficients;
    RbfModel::assemble(
        params,
        design,
        centres,
        widths,
        c.as_ref().subrows(p, k),
        c.as_ref().subrows(0, p),
        sol.condition,
        selection,
    )
    .usable()
}

/// OLS centre selection, kept so that every model size (and ridge) can be built from
/// one forward-selection run.
pub(crate) struct OlsStage {
    design: Design,
    /// Candidate centres (standardised coordinates).
    candidates: Mat<f64>,
    widths: Widths,
    /// What a candidate's index means to the user (training row or given row).
    labels: Vec<usize>,
    path: OlsPath,
    /// Kernel columns of the picks, in pick order (n × K); `None` when selection ran on
    /// a row subsample: the weights are then solved over row blocks (memory
    /// independent of n).
    phi: Option<Mat<f64>>,
}

impl OlsStage {
    pub(crate) fn run(
        params: &RbfValidParams,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        y: MatRef<'_, f64>,
        max_terms: usize,
        tol: f64,
        progress: Observer<'_>,
    ) -> Result<Self, RbfError> {
        check_inputs(x, z, y)?;
        let inputs = OlsInputs::new(params, x, z, progress)?;
        Self::select(params, inputs, None, y, max_terms, tol, progress)
    }

    /// [`Self::run`] on inputs worked out once for several selections
    /// (`inputs`, and the candidates' kernel columns when shared): the same
    /// checks of `x`, `z` and `y`, the same selection.
    #[allow(clippy::too_many_arguments)] // internal: run's arguments and what is shared
    pub(crate) fn run_on(
        params: &RbfValidParams,
        (inputs, columns): (&OlsInputs, Option<MatRef<'_, f64>>),
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        y: MatRef<'_, f64>,
        max_terms: usize,
        tol: f64,
    ) -> Result<Self, RbfError> {
        check_inputs(x, z, y)?;
        Self::select(params, inputs.for_one(), columns, y, max_terms, tol, None)
    }

    /// The forward selection on `inputs` (the part of a run that reads the
    /// targets `y`, already checked), its candidate columns generated on
    /// demand or read from `columns` ([`OlsInputs::shared_columns`]).
    #[allow(clippy::too_many_arguments)] // internal: run's arguments, split at the targets
    pub(crate) fn select(
        params: &RbfValidParams,
        inputs: OlsInputs,
        columns: Option<MatRef<'_, f64>>,
        y: MatRef<'_, f64>,
        max_terms: usize,
        tol: f64,
        progress: Observer<'_>,
    ) -> Result<Self, RbfError> {
        let CentreSelection::Ols { regularisation, .. } = &params.centres else {
            unreachable!("OlsStage::select needs OLS centre selection")
        };
        let OlsInputs {
            design,
            cands,
            labels,
            sub,
            xs_sel,
            forced_sel,
            widths,
        } = inputs;
        let y_sel = sub.as_ref().map(|idx| rows(y, idx));
        let xs_sel = xs_sel.as_ref().map_or(design.xs.as_ref(), |m| m.as_ref());
        let forced_sel = forced_sel
            .as_ref()
            .map_or(design.forced.as_ref(), |m| m.as_ref());
        let y_sel = y_sel.as_ref().map_or(y, |m| m.as_ref());
        report(progress, Stage::KernelMatrix, 0, 1);
        let forward = |pr: OlsProgress| report(progress, Stage::Selection, pr.picks, pr.max_terms);
        let mut opts = OlsOptions::new(max_terms)
            .tol(tol)
            .regularisation(*regularisation)
            .par(params.par)
            .stream(params.ols_stream);
        if progress.is_some() {
            opts = opts.progress(&forward);
        }
        // f32 streaming generates the kernel columns block by block into their f32 copy
        // and again for the few evaluated exactly: no f64 candidate matrix is held,
        // unless a store of them is shared by several selections (its columns are
        // the generated ones bit for bit, whatever the batch: tests/kernel_columns_batches.rs).
        let path = match (params.ols_stream, columns) {
            (StreamPrecision::F32, Some(store)) => forward_select(store, forced_sel, y_sel, &opts)?,
            (StreamPrecision::F32, None) => {
                let columns =
                    KernelColumns::new(xs_sel, cands.as_ref(), params.kernel, &widths, params.par);
                forward_select_columns(&columns, forced_sel, y_sel, &opts)?
            }
            (StreamPrecision::F64, Some(store)) => {
                forward_select_owned(store.to_owned(), forced_sel, y_sel, &opts)?
            }
            (StreamPrecision::F64, None) => {
                let phi_all =
                    kernel_matrix(xs_sel, cands.as_ref(), params.kernel, &widths, params.par);
                forward_select_owned(phi_all, forced_sel, y_sel, &opts)?
            }
        };
        let sel = path.selected();
        let phi = sub.is_none().then(|| {
            kernel_matrix(
                design.xs.as_ref(),
                rows(cands.as_ref(), &sel).as_ref(),
                params.kernel,
                &widths.select(&sel),
                params.par,
            )
        });
        Ok(Self {
            design,
            candidates: cands,
            widths,
            labels,
            path,
            phi,
        })
    }

    pub(crate) fn path(&self) -> &OlsPath {
        &self.path
    }

    /// The model with the forced columns and the first `k` picks, weights re-solved by
    /// QR with ridge `ridge`.
    pub(crate) fn model(
        &self,
        params: &RbfValidParams,
        k: usize,
        ridge: f64,
        y: MatRef<'_, f64>,
    ) -> Result<RbfModel, RbfError> {
        let sel: Vec<usize> = self.path.selected()[..k].to_vec();
        let centres = rows(self.candidates.as_ref(), &sel);
        let selection = Selection {
            n_candidates: self.candidates.nrows(),
            forced_errs: self.path.forced_errs().to_vec(),
            picks: self.path.picks()[..k]
                .iter()
                .map(|p| crate::select::ols::Pick {
                    index: self.labels[p.index],
                    ..*p
                })
                .collect(),
            stop: match params.size_rule {
                SizeRule::Press if k == self.path.best_by_press() => StopReason::Press,
                SizeRule::Gcv if k == self.path.best_by_gcv() => StopReason::Gcv,
                _ if k == self.path.len() => self.path.stop_reason(),
                _ => StopReason::MaxTerms,
            },
            criterion: self.path.criterion(),
        };
        let model = match &self.phi {
            Some(phi) => solve_model(
                params,
                &self.design,
                centres,
                self.widths.select(&sel),
                phi.as_ref().subcols(0, k),
                y,
                ridge,
                Some(selection),
            ),
            None => solve_model_streaming(
                params,
                &self.design,
                centres,
                self.widths.select(&sel),
                y,
                ridge,
                selection,
            ),
        };
        model.map(|m| m.with_pass_threads(self.path.pass_threads().clone()))
    }
}

/// Seed offset of the selection-row subsample (distinct from the candidate subsample's
/// draw with the same seed).
pub(crate) const SELECTION_ROWS_SEED: u64 = 0x5e1e_c7ed_0000_0001;

/// Rows per block of the streaming weight solve: the block's kernel columns and design
/// rows stay within a few MB whatever n is.
const WEIGHT_BLOCK_ROWS: usize = 4096;

/// [`solve_model`] over row blocks: [fixed columns | kernel columns] of each block of
/// rows is computed, reduced into a running triangular factor (Householder QR, never
/// the normal equations) and dropped, so memory does not grow with n.
fn solve_model_streaming(
    params: &RbfValidParams,
    design: &Design,
    centres: Mat<f64>,
    widths: Widths,
    y: MatRef<'_, f64>,
    ridge: f64,
    selection: Selection,
) -> Result<RbfModel, RbfError> {
    let (n, p, k, q) = (
        design.n(),
        design.forced.ncols(),
        centres.nrows(),
        y.ncols(),
    );
    let mut acc = StreamingLstsq::new(p + k, q);
    let block = WEIGHT_BLOCK_ROWS.max(p + k + q);
    let mut a = Mat::<f64>::zeros(block, p + k);
    for start in (0..n).step_by(block) {
        let b = block.min(n - start);
        let mut ab = a.as_mut().subrows_mut(0, b);
        ab.rb_mut()
            .subcols_mut(0, p)
            .copy_from(design.forced.as_ref().subrows(start, b));
        kernel_matrix_into(
            design.xs.as_ref().subrows(start, b),
            centres.as_ref(),
            params.kernel,
            &widths,
            ab.subcols_mut(p, k),
            params.par,
        );
        acc.push(a.as_ref().subrows(0, b), y.subrows(start, b))?;
    }
    let sol = acc.finish(&weight_options(params, p, ridge))?;
    model_from(params, design, centres, widths, sol, Some(selection))
}

impl RbfValidParams {
    /// Fits the weights of [`CentreSelection::Given`] centres (and the
    /// coefficients of `r` linear regressors) on `n` rows handed over in
    /// blocks, with memory independent of `n`: `fill(start, x, z, y)` copies
    /// rows `start .. start + x.nrows()` of the inputs (d columns), the linear
    /// regressors (r) and the targets (q) into the blocks. Each block's
    /// [fixed columns | kernel columns] is reduced into a running triangular
    /// factor by Householder QR ([`StreamingLstsq`], never the normal
    /// equations), so the model equals
    /// [`RbfValidParams::fit_with_linear`] on the whole matrices up to
    /// rounding, with the same errors.
    ///
    /// # Errors
    /// [`RbfError::NotStreamable`] for centres other than given ones, or
    /// settings whose input transform depends on all rows (standardised
    /// inputs, a polynomial tail); otherwise as
    /// [`RbfValidParams::fit_with_linear`].
    ///
    /// ```
    /// use faer::{Mat, Par};
    /// use linfa::ParamGuard;
    /// use rbf::{CentreSelection, RbfParams, WidthRule};
    /// let x = Mat::from_fn(500, 1, |i, _| i as f64 / 50.0);
    /// let y = Mat::from_fn(500, 1, |i, _| x[(i, 0)].sin());
    /// let c = Mat::from_fn(8, 1, |k, _| k as f64 * 10.0 / 7.0);
    /// let p = RbfParams::new().centres(CentreSelection::Given(c)).width(WidthRule::Fixed(1.5))
    ///     .parallelism(Par::Seq).check().unwrap();
    /// let whole = p.fit(x.as_ref(), y.as_ref()).unwrap();
    /// let blocks = p.fit_given_streaming(500, 1, 0, 1, |start, mut xb, _, mut yb| {
    ///     xb.copy_from(x.as_ref().subrows(start, xb.nrows()));
    ///     yb.copy_from(y.as_ref().subrows(start, yb.nrows()));
    /// }).unwrap();
    /// assert!((&whole.weights() - &blocks.weights()).norm_max() < 1e-8);
    /// ```
    pub fn fit_given_streaming(
        &self,
        n: usize,
        d: usize,
        r: usize,
        q: usize,
        mut fill: impl FnMut(usize, faer::MatMut<'_, f64>, faer::MatMut<'_, f64>, faer::MatMut<'_, f64>),
    ) -> Result<RbfModel, RbfError> {
        let CentreSelection::Given(given) = &self.centres else {
            return Err(RbfError::NotStreamable {
                needs: "given centres",
            });
        };
        if self.standardise || self.degree.is_some() {
            return Err(RbfError::NotStreamable {
                needs: "inputs used as they are (no standardisation, no polynomial tail)",
            });
        }
        if n == 0 {
            return Err(RbfError::TooFewSamples {
                samples: 0,
                needed: 1,
            });
        }
        assert!(q >= 1, "y needs at least one column");
        check_dim("centres", given.as_ref(), d)?;
        let most = self.most_centres(n, d, r);
        if given.nrows() > most {
            return Err(RbfError::FewerRowsThanCentres {
                rows: n,
                centres: given.nrows(),
                most,
            });
        }
        // The design of Design::new without its n-row matrices: [1 | x | z].
        let (bias, tail) = (self.bias, self.linear_tail);
        let p = usize::from(bias) + if tail { d } else { 0 } + r;
        let design = Design {
            scaling: None,
            xs: Mat::zeros(0, d),
            forced: Mat::zeros(0, p),
            bias,
            tail,
            n_linear: r,
            poly: None,
        };
        let centres = design.standardised(given.as_ref());
        let widths = self.width.widths(centres.as_ref(), self.par)?;
        let k = centres.nrows();
        let mut acc = StreamingLstsq::new(p + k, q);
        let block = WEIGHT_BLOCK_ROWS.max(p + k + q);
        let (mut xb, mut zb, mut yb) = (
            Mat::<f64>::zeros(block, d),
            Mat::<f64>::zeros(block, r),
            Mat::<f64>::zeros(block, q),
        );
        let mut a = Mat::<f64>::zeros(block, p + k);
        for start in (0..n).step_by(block) {
            let b = block.min(n - start);
            fill(
                start,
                xb.as_mut().subrows_mut(0, b),
                zb.as_mut().subrows_mut(0, b),
                yb.as_mut().subrows_mut(0, b),
            );
            let (x, z, y) = (
                xb.as_ref().subrows(0, b),
                zb.as_ref().subrows(0, b),
                yb.as_ref().subrows(0, b),
            );
            for (matrix, m) in [("x", x), ("z", z), ("y", y)] {
                if let Some((row, col)) = first_non_finite(m) {
                    return Err(RbfError::NonFinite {
                        matrix,
                        row: start + row,
                        col,
                    });
                }
            }
            let mut ab = a.as_mut().subrows_mut(0, b);
            let mut c = 0;
            if bias {
                ab.rb_mut().col_mut(0).fill(1.0);
                c = 1;
            }
            if tail {
                ab.rb_mut().subcols_mut(c, d).copy_from(x);
                c += d;
            }
            ab.rb_mut().subcols_mut(c, r).copy_from(z);
            kernel_matrix_into(
                x,
                centres.as_ref(),
                self.kernel,
                &widths,
                ab.subcols_mut(p, k),
                self.par,
            );
            acc.push(a.as_ref().subrows(0, b), y)?;
        }
        let sol = acc.finish(&weight_options(self, p, self.ridge))?;
        model_from(self, &design, centres, widths, sol, None)
    }
}

/// Centres and widths for k-means, random and given centres.
fn fixed_centres(
    params: &RbfValidParams,
    design: &Design,
    progress: Observer<'_>,
) -> Result<(Mat<f64>, Widths), RbfError> {
    let (n, d) = (design.n(), design.xs.ncols());
    // Refused before any clustering, by the rule callers ask for their hints.
    let most = params.most_centres(n, d, design.n_linear);
    let need = |k: usize| {
        if k > most {
            Err(RbfError::FewerRowsThanCentres {
                rows: n,
                centres: k,
                most,
            })
        } else {
            Ok(())
        }
    };
    match &params.centres {
        CentreSelection::KMeans(s) => {
            need(s.n_centres)?;
            report(progress, Stage::Clustering, 0, 1);
            let km = kmeans_centres(design.xs.as_ref(), s, params.seed, params.par)?;
            report(progress, Stage::Widths, 0, 1);
            let w = params.width.cluster_widths(
                design.xs.as_ref(),
                km.centres.as_ref(),
                &km.memberships,
                params.par,
            )?;
            Ok((km.centres, w))
        }
        CentreSelection::Random { n_centres } => {
            need(*n_centres)?;
            let idx = random_subset(n, *n_centres, params.seed);
            let c = rows(design.xs.as_ref(), &idx);
            report(progress, Stage::Widths, 0, 1);
            let w = params.width.widths(c.as_ref(), params.par)?;
            Ok((c, w))
        }
        CentreSelection::Given(c) => {
            check_dim("centres", c.as_ref(), d)?;
            need(c.nrows())?;
            let c = design.standardised(c.as_ref());
            report(progress, Stage::Widths, 0, 1);
            let w = params.width.widths(c.as_ref(), params.par)?;
            Ok((c, w))
        }
        CentreSelection::Ols { .. } | CentreSelection::AllPoints => {
            unreachable!("not a fixed-centre strategy")
        }
    }
}

impl RbfValidParams {
    /// Fits f(x) = λ0 + Σ λᵢ φ(‖x − cᵢ‖) (plus the optional tail) to targets `y`
    /// (n × q, several outputs at once); rows of `x` (n × d) are samples.
    ///
    /// This inherent method takes faer views; linfa's `Fit` (on datasets) is available
    /// through `RbfParams::fit` or `linfa::traits::Fit::fit(&valid, &dataset)`.
    ///
    /// # Errors
    /// [`RbfError`]: non-finite inputs, too few samples, fewer rows than centres,
    /// rank deficiency or ill-conditioning of the weight solve (never silently wrong),
    /// width, k-means or OLS failures.
    ///
    /// # Panics
    /// If `x` and `y` have different numbers of rows or `y` has no column.
    ///
    /// ```
    /// use faer::{Mat, Par};
    /// use linfa::ParamGuard;
    /// use rbf::{CentreSelection, RbfParams, WidthRule};
    /// let x = Mat::from_fn(100, 2, |i, j| ((i * (j + 3)) as f64 * 0.13).sin());
    /// let y = Mat::from_fn(100, 1, |i, _| x[(i, 0)] * x[(i, 1)]);
    /// let p = RbfParams::new().centres(CentreSelection::kmeans(12)).width(WidthRule::Fixed(0.8))
    ///     .ridge(1e-10).parallelism(Par::Seq).check().unwrap();
    /// let m = p.fit(x.as_ref(), y.as_ref()).unwrap();
    /// assert_eq!((m.n_centres(), m.dim(), m.n_outputs()), (12, 2, 1));
    /// ```
    #[track_caller]
    pub fn fit(&self, x: MatRef<'_, f64>, y: MatRef<'_, f64>) -> Result<RbfModel, RbfError> {
        let z = Mat::<f64>::zeros(x.nrows(), 0);
        self.fit_impl(x, z.as_ref(), y, None)
    }

    /// Fits the semi-parametric network f(x, z) = λ0 + zᵀθ + Σ λᵢ φ(‖x − cᵢ‖): the
    /// exogenous regressors `z` (n × r) enter linearly — as forced columns of the OLS
    /// selection, as unpenalised columns of the QR weight solve, and in the polynomial
    /// block of the all-points system. θ is [`RbfModel::linear_coefficients`].
    ///
    /// # Errors
    /// As [`RbfValidParams::fit`]; also `Ols(ForcedCollinear)` / `Solve(RankDeficient)`
    /// when columns of `z` are dependent.
    ///
    /// # Panics
    /// As [`RbfValidParams::fit`], or if `z` has a different number of rows.
    ///
    /// ```
    /// use faer::{Mat, Par};
    /// use linfa::ParamGuard;
    /// use rbf::{CentreSelection, RbfParams, WidthRule};
    /// let n = 300;
    /// let x = Mat::from_fn(n, 1, |i, _| (i as f64 * 0.05).sin());
    /// let z = Mat::from_fn(n, 1, |i, _| ((i * 7 % 13) as f64) - 6.0);
    /// let y = Mat::from_fn(n, 1, |i, _| (3.0 * x[(i, 0)]).cos() + 0.25 * z[(i, 0)]);
    /// let p = RbfParams::new().centres(CentreSelection::ols(20)).width(WidthRule::Fixed(0.5))
    ///     .parallelism(Par::Seq).check().unwrap();
    /// let m = p.fit_with_linear(x.as_ref(), z.as_ref(), y.as_ref()).unwrap();
    /// assert!((m.linear_coefficients()[(0, 0)] - 0.25).abs() < 1e-4);
    /// let yhat = m.predict_with_linear(x.as_ref(), z.as_ref());
    /// assert!((&yhat - &y).norm_max() < 1e-3);
    /// ```
    #[track_caller]
    pub fn fit_with_linear(
        &self,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        y: MatRef<'_, f64>,
    ) -> Result<RbfModel, RbfError> {
        self.fit_impl(x, z, y, None)
    }

    /// [`RbfValidParams::fit_with_linear`] reporting [`Progress`] to `observer` (stages,
    /// and each OLS pick); `z` may have zero columns.
    ///
    /// # Errors
    /// As [`RbfValidParams::fit_with_linear`].
    ///
    /// ```
    /// use std::sync::Mutex;
    /// use faer::{Mat, Par};
    /// use linfa::ParamGuard;
    /// let x = Mat::from_fn(50, 1, |i, _| i as f64 / 10.0);
    /// let y = Mat::from_fn(50, 1, |i, _| x[(i, 0)].sin());
    /// let p = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(5)).parallelism(Par::Seq).check().unwrap();
    /// let seen = Mutex::new(Vec::new());
    /// let obs = |pr: rbf::Progress| seen.lock().unwrap().push(pr);
    /// p.fit_with_progress(x.as_ref(), Mat::<f64>::zeros(50, 0).as_ref(), y.as_ref(), &obs).unwrap();
    /// let seen = seen.into_inner().unwrap();
    /// assert_eq!(seen.iter().filter(|p| p.stage == rbf::Stage::Selection).count(), 5);
    /// ```
    #[track_caller]
    pub fn fit_with_progress(
        &self,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        y: MatRef<'_, f64>,
        observer: &(dyn Fn(Progress) + Sync),
    ) -> Result<RbfModel, RbfError> {
        self.fit_impl(x, z, y, Some(observer))
    }

    #[track_caller]
    fn fit_impl(
        &self,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        y: MatRef<'_, f64>,
        progress: Observer<'_>,
    ) -> Result<RbfModel, RbfError> {
        match &self.centres {
            CentreSelection::Ols {
                max_centres, tol, ..
            } => {
                let stage = OlsStage::run(self, x, z, y, *max_centres, *tol, progress)?;
                report(progress, Stage::Weights, 0, 1);
                let k = stage.path.size_for(self.size_rule);
                stage.model(self, k, self.ridge, y)
            }
            CentreSelection::AllPoints => {
                check_inputs(x, z, y)?;
                let design = Design::new(self, x, z);
                fit_all_points(self, design, y, progress)
            }
            _ => {
                check_inputs(x, z, y)?;
                let design = Design::new(self, x, z);
                let (centres, widths) = fixed_centres(self, &design, progress)?;
                report(progress, Stage::KernelMatrix, 0, 1);
                let phi = kernel_matrix(
                    design.xs.as_ref(),
                    centres.as_ref(),
                    self.kernel,
                    &widths,
                    self.par,
                );
                report(progress, Stage::Weights, 0, 1);
                solve_model(
                    self,
                    &design,
                    centres,
                    widths,
                    phi.as_ref(),
                    y,
                    self.ridge,
                    None,
                )
            }
        }
    }

    /// Fits with centres computed once and reused for several ridges (k-means, random,
    /// given): returns one model per ridge value.
    pub(crate) fn fit_ridges(
        &self,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        y: MatRef<'_, f64>,
        ridges: &[f64],
    ) -> Result<Vec<Result<RbfModel, RbfError>>, RbfError> {
        check_inputs(x, z, y)?;
        let design = Design::new(self, x, z);
        match &self.centres {
            CentreSelection::AllPoints => {
                // One kernel matrix for all ridges; each solve consumes a copy.
                let (widths, phi) = all_points_matrix(self, &design, None)?;
                Ok(ridges
                    .iter()
                    .map(|&r| {
                        solve_all_points(
                            &self.with_ridge(r),
                            &design,
                            widths.clone(),
                            phi.clone(),
                            y,
                        )
                    })
                    .collect())
            }
            CentreSelection::Ols { .. } => unreachable!("OLS grids go through OlsStage"),
            _ => {
                let (centres, widths) = fixed_centres(self, &design, None)?;
                let phi = kernel_matrix(
                    design.xs.as_ref(),
                    centres.as_ref(),
                    self.kernel,
                    &widths,
                    self.par,
                );
                Ok(ridges
                    .iter()
                    .map(|&r| {
                        solve_model(
                            self,
                            &design,
                            centres.clone(),
                            widths.clone(),
                            phi.as_ref(),
                            y,
                            r,
                            None,
                        )
                    })
                    .collect())
            }
        }
    }
}

fn fit_all_points(
    params: &RbfValidParams,
    design: Design,
    y: MatRef<'_, f64>,
    progress: Observer<'_>,
) -> Result<RbfModel, RbfError> {
    let (widths, phi) = all_points_matrix(params, &design, progress)?;
    report(progress, Stage::Weights, 0, 1);
    solve_all_points(params, &design, widths, phi, y)
}

/// Widths and the N × N kernel matrix of an all-points fit.
fn all_points_matrix(
    params: &RbfValidParams,
    design: &Design,
    progress: Observer<'_>,
) -> Result<(Widths, Mat<f64>), RbfError> {
    let (n, p) = (design.n(), design.forced.ncols());
    if n < p + 1 {
        return Err(RbfError::TooFewSamples {
            samples: n,
            needed: p + 1,
        });
    }
    report(progress, Stage::Widths, 0, 1);
    let widths = params.width.widths(design.xs.as_ref(), params.par)?;
    report(progress, Stage::KernelMatrix, 0, 1);
    let phi = kernel_matrix(
        design.xs.as_ref(),
        design.xs.as_ref(),
        params.kernel,
        &widths,
        params.par,
    );
    Ok((widths, phi))
}

/// The interpolation (smoothing = the params' ridge) solve and the model.
fn solve_all_points(
    params: &RbfValidParams,
    design: &Design,
    widths: Widths,
    phi: Mat<f64>,
    y: MatRef<'_, f64>,
) -> Result<RbfModel, RbfError> {
    let opts = InterpolationOptions {
        smoothing: params.ridge,
        sign: params.kernel.definiteness_sign(),
        max_condition: params.max_condition,
        par: params.par,
    };
    let sol = interpolate(phi, design.forced.as_ref(), y, &opts)?;
    RbfModel::assemble(
        params,
        design,
        design.xs.clone(),
        widths,
        sol.weights.as_ref(),
        sol.tail.as_ref(),
        sol.condition,
        None,
    )
    .usable()
}
