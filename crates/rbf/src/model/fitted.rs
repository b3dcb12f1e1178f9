//! The fitted network and its predictions.

use faer::linalg::matmul::matmul;
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};
use serde::{Deserialize, Serialize};

use super::algorithm::Design;
use super::hyperparams::{CentreSelection, RbfParams, RbfValidParams, Strategy};
use super::matser;
use super::poly::{PolyFit, PolyTail, kernel_coordinates, monomials, monomials_into};
use super::scaling::Scaling;
use crate::design::{Widths, kernel_matrix_into};
use crate::kernel::Kernel;
use crate::select::ols::{Pick, StopReason};
use crate::width::WidthRule;

/// The OLS selection record of a model.
///
/// ```
/// let s = rbf::Selection { n_candidates: 10, forced_errs: vec![0.5], picks: vec![], stop: rbf::StopReason::Tolerance, criterion: vec![] };
/// assert!(s.picks.is_empty());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Selection {
    /// Size of the candidate set.
    pub n_candidates: usize,
    /// ERR of each fixed column (bias, tail, linear regressors), in that order.
    pub forced_errs: Vec<f64>,
    /// The picks in order; `index` is the training row of the centre (candidates drawn
    /// from the training vectors, also when subsampled) or the row of the given
    /// candidate matrix.
    pub picks: Vec<Pick>,
    /// Why the selection stopped.
    pub stop: StopReason,
    /// PRESS and GCV at every size of the selection run (k = 0 … its picks, while
    /// finite); empty in models saved before it was recorded.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub criterion: Vec<crate::select::ols::Criterion>,
}

/// A fitted RBF network f(x, z) = λ0 + aᵀx + zᵀθ + Σᵢ λᵢ φ(‖x − cᵢ‖; βᵢ).
///
/// Output weights were solved by faer column-pivoted QR on the selected columns (for
/// OLS too: the path's triangular system gives the same coefficients in exact
/// arithmetic, but the QR solve also applies the ridge and the rank/condition checks).
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// let x = Mat::from_fn(30, 1, |i, _| i as f64 / 10.0);
/// let y = Mat::from_fn(30, 1, |i, _| x[(i, 0)].powi(2));
/// let m = rbf::RbfParams::new().centres(rbf::CentreSelection::random(6))
///     .width(rbf::WidthRule::Fixed(1.0)).parallelism(Par::Seq).check().unwrap()
///     .fit(x.as_ref(), y.as_ref()).unwrap();
/// assert_eq!(m.n_centres(), 6);
/// assert_eq!(m.weights().nrows(), 6);
/// assert!(m.bias().is_some());
/// assert!(m.selection().is_none());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RbfModel {
    kernel: Kernel,
    strategy: Strategy,
    dim: usize,
    n_outputs: usize,
    /// Centres in the kernel's coordinates (standardised if `scaling` is set).
    #[serde(with = "matser")]
    centres: Mat<f64>,
    widths: Widths,
    /// K × q.
    #[serde(with = "matser")]
    weights: Mat<f64>,
    bias: Option<Vec<f64>>,
    /// d × q, on the kernel's coordinates.
    #[serde(with = "matser::option")]
    tail: Option<Mat<f64>>,
    /// r × q.
    #[serde(with = "matser")]
    linear: Mat<f64>,
    scaling: Option<Scaling>,
    selection: Option<Selection>,
    condition: f64,
    /// The polynomial tail on unit-box inputs ([`crate::RbfParams::degree`]); absent
    /// from files written without one, which load as before.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    poly: Option<PolyFit>,
    /// How the fit ran: not part of the model, never saved, never compared.
    #[serde(skip)]
    run: RunRecord,
}

/// How a fit ran (today: the threads of the OLS passes). Not part of what the model
/// is: two models that predict alike are equal whatever their fits ran on, and a
/// loaded model has none.
#[derive(Clone, Debug, Default)]
struct RunRecord {
    pass_threads: Option<crate::select::ols::PassThreads>,
}

impl PartialEq for RunRecord {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl RbfModel {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn assemble(
        params: &RbfValidParams,
        design: &Design,
        centres: Mat<f64>,
        widths: Widths,
        kernel_weights: MatRef<'_, f64>,
        fixed: MatRef<'_, f64>,
        condition: f64,
        selection: Option<Selection>,
    ) -> Self {
        let (d, q) = (design.xs.ncols(), kernel_weights.ncols());
        let mut row = 0;
        let bias = design.bias.then(|| {
            row = 1;
            (0..q).map(|o| fixed[(0, o)]).collect()
        });
        let tail = design.tail.then(|| {
            let t = fixed.subrows(row, d).to_owned();
            row += d;
            t
        });
        let poly = design.poly.as_ref().map(|(degree, shift, scale)| {
            let m = degree.n_terms(d);
            row += m;
            PolyFit {
                degree: *degree,
                shift: shift.clone(),
                scale: scale.clone(),
                coefficients: fixed.subrows(0, m).to_owned(),
            }
        });
        let linear = fixed.subrows(row, design.n_linear).to_owned();
        RbfModel {
            kernel: params.kernel,
            strategy: params.centres.strategy(),
            dim: d,
            n_outputs: q,
            centres,
            widths,
            weights: kernel_weights.to_owned(),
            bias,
            tail,
            linear,
            scaling: design.scaling.clone(),
            selection,
            condition,
            poly,
            run: RunRecord::default(),
        }
    }

    /// The threads the streaming passes of the OLS selection ran on, and why; `None` for
    /// other centres and for a loaded model (see [`crate::select::ols::PassThreads`]).
    ///
    /// ```
    /// let m = rbf::doc_model();
    /// let t = m.pass_threads().expect("an OLS fit");
    /// assert!(t.threads >= 1);
    /// let back = rbf::RbfModel::from_reader({ let mut v = Vec::new(); m.to_writer(&mut v).unwrap(); v }.as_slice()).unwrap();
    /// assert!(back.pass_threads().is_none() && back == m);
    /// ```
    pub fn pass_threads(&self) -> Option<&crate::select::ols::PassThreads> {
        self.run.pass_threads.as_ref()
    }

    /// Records the threads of the OLS passes that chose this model's centres.
    pub(crate) fn with_pass_threads(mut self, threads: crate::select::ols::PassThreads) -> Self {
        self.run.pass_threads = Some(threads);
        self
    }

    /// The assembled model, or [`RbfError::UnusableModel`] if it holds a
    /// number no model may hold: a fit never returns what could not be saved
    /// and loaded back.
    pub(crate) fn usable(self) -> Result<Self, super::error::RbfError> {
        self.validate()
            .map_err(super::error::RbfError::UnusableModel)
            .map(|()| self)
    }

    /// The kernel.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.kernel(), rbf::Kernel::Gaussian);
    /// ```
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }

    /// How the centres were chosen.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.strategy(), rbf::Strategy::Ols);
    /// ```
    pub fn strategy(&self) -> Strategy {
        self.strategy
    }

    /// The centres (K × d) in data units.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.centres().nrows(), m.n_centres());
    /// ```
    pub fn centres(&self) -> Mat<f64> {
        match (&self.scaling, &self.poly) {
            (Some(s), _) => Mat::from_fn(self.centres.nrows(), self.dim, |i, k| {
                self.centres[(i, k)] * s.scale[k] + s.mean[k]
            }),
            (None, Some(p)) => Mat::from_fn(self.centres.nrows(), self.dim, |i, k| {
                self.centres[(i, k)] + p.shift[k]
            }),
            (None, None) => self.centres.clone(),
        }
    }

    /// The centres in the coordinates the kernel sees (standardised when the model
    /// standardises, shifted by the unit-box shift with a [`RbfModel::degree`] tail;
    /// equal to [`RbfModel::centres`] otherwise).
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.kernel_centres(), m.centres().as_ref());
    /// ```
    pub fn kernel_centres(&self) -> MatRef<'_, f64> {
        self.centres.as_ref()
    }

    /// The widths β (in the kernel's coordinates).
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.widths(), &rbf::Widths::Uniform(1.0));
    /// ```
    pub fn widths(&self) -> &Widths {
        &self.widths
    }

    /// Output weights λᵢ (K × q).
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.weights().ncols(), 1);
    /// ```
    pub fn weights(&self) -> MatRef<'_, f64> {
        self.weights.as_ref()
    }

    /// The bias λ0 per output, if fitted.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.bias().unwrap().len(), 1);
    /// ```
    pub fn bias(&self) -> Option<&[f64]> {
        self.bias.as_deref()
    }

    /// Coefficients a of the linear tail (d × q, on the kernel's coordinates), if fitted.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert!(m.tail().is_none());
    /// ```
    pub fn tail(&self) -> Option<MatRef<'_, f64>> {
        self.tail.as_ref().map(Mat::as_ref)
    }

    /// θ, the coefficients of the exogenous linear regressors z (r × q; r = 0 without).
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.linear_coefficients().nrows(), 0);
    /// ```
    pub fn linear_coefficients(&self) -> MatRef<'_, f64> {
        self.linear.as_ref()
    }

    /// Input dimension d.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.dim(), 1);
    /// ```
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of centres K.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert!(m.n_centres() <= 8);
    /// ```
    pub fn n_centres(&self) -> usize {
        self.centres.nrows()
    }

    /// Number of outputs q.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.n_outputs(), 1);
    /// ```
    pub fn n_outputs(&self) -> usize {
        self.n_outputs
    }

    /// Number of exogenous linear regressors r.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.n_linear(), 0);
    /// ```
    pub fn n_linear(&self) -> usize {
        self.linear.nrows()
    }

    /// The OLS selection record (picks and their ERRs), for OLS models.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let s = m.selection().unwrap();
    /// assert_eq!(s.picks.len(), m.n_centres());
    /// ```
    pub fn selection(&self) -> Option<&Selection> {
        self.selection.as_ref()
    }

    /// 1-norm condition estimate of the weight solve.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert!(m.condition() >= 1.0);
    /// ```
    pub fn condition(&self) -> f64 {
        self.condition
    }

    /// The hyperparameters that refit this model's structure: its kernel, bias, tail and
    /// standardisation, its centres as [`CentreSelection::Given`] (data units), and its
    /// width as [`WidthRule::Fixed`] when it is one β for all centres. A model does not
    /// record the rule that chose per-centre widths, nor the ridge, seed, parallelism or
    /// condition limit of its fit: those keep [`RbfParams::new`]'s defaults and can be
    /// set on the returned builder.
    ///
    /// ```
    /// use rbf::ParamGuard;
    /// let m = rbf::doc_model(); // OLS centres of sin on [0, 3], β = 1
    /// let p = m.params().parallelism(faer::Par::Seq).check().unwrap();
    /// assert_eq!(p.kernel(), m.kernel());
    /// assert_eq!(p.width(), &rbf::WidthRule::Fixed(1.0));
    /// // refitted on the same data, the given centres give the same network
    /// let x = faer::Mat::from_fn(40, 1, |i, _| i as f64 * 3.0 / 39.0);
    /// let y = faer::Mat::from_fn(40, 1, |i, _| x[(i, 0)].sin());
    /// let again = p.fit(x.as_ref(), y.as_ref()).unwrap();
    /// assert!((again.predict(x.as_ref()) - m.predict(x.as_ref())).norm_max() < 1e-9);
    /// ```
    pub fn params(&self) -> RbfParams {
        let mut p = RbfParams::new()
            .kernel(self.kernel)
            .centres(CentreSelection::Given(self.centres()))
            .bias(self.bias.is_some())
            .linear_tail(self.tail.is_some())
            .standardise(self.scaling.is_some());
        if let Some(tail) = &self.poly {
            p = p.degree(tail.degree);
        }
        if let Widths::Uniform(b) = self.widths {
            p = p.width(WidthRule::Fixed(b));
        }
        p
    }

    /// The degree of the polynomial tail on unit-box inputs, if the model was fitted
    /// with [`crate::RbfParams::degree`] (`None`: [`RbfModel::bias`] and
    /// [`RbfModel::tail`] are the polynomial, on unscaled inputs).
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert_eq!(m.degree(), None);
    /// ```
    pub fn degree(&self) -> Option<PolyTail> {
        self.poly.as_ref().map(|p| p.degree)
    }

    /// The tail's monomial coefficients (n_terms × q, scipy's order: constant, inputs,
    /// products x_i·x_j for i ≤ j) and its unit-box map (shift, scale per input), with a
    /// [`RbfModel::degree`] tail.
    pub fn poly_tail(&self) -> Option<(MatRef<'_, f64>, &[f64], &[f64])> {
        self.poly.as_ref().map(|p| {
            (
                p.coefficients.as_ref(),
                p.shift.as_slice(),
                p.scale.as_slice(),
            )
        })
    }

    /// The input standardisation, if any.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// assert!(m.scaling().is_none());
    /// ```
    pub fn scaling(&self) -> Option<&Scaling> {
        self.scaling.as_ref()
    }

    /// The standardised copy of `x` if the model standardises (`None`: the
    /// kernel sees `x` as it is, and nothing is copied).
    ///
    /// # Panics
    /// If `x` does not have d columns.
    #[track_caller]
    fn standardised(&self, x: MatRef<'_, f64>) -> Option<Mat<f64>> {
        assert_eq!(
            x.ncols(),
            self.dim,
            "x has {} columns but the model has {} inputs",
            x.ncols(),
            self.dim
        );
        match (&self.scaling, &self.poly) {
            (None, None) => None,
            (scaling, poly) => Some(kernel_coordinates(
                scaling.as_ref(),
                poly.as_ref().map(|p| p.shift.as_slice()),
                x,
            )),
        }
    }

    /// The model's basis evaluated at `x` (n × d): a column of ones if the model
    /// has a bias, the tail's d inputs if it has one, then one column per centre.
    /// Every network this model can be (with these centres and widths) is a
    /// linear combination of these columns, which is what a semi-parametric
    /// fit needs to project other series on the same function space.
    ///
    /// # Panics
    /// If `x` does not have d columns.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let x = faer::mat![[0.5], [1.5]];
    /// let f = m.features(x.as_ref());
    /// assert_eq!(f.ncols(), 1 + m.n_centres());
    /// // The prediction is the features times [bias; weights].
    /// let mut w = faer::Mat::zeros(f.ncols(), 1);
    /// w[(0, 0)] = m.bias().unwrap()[0];
    /// for k in 0..m.n_centres() { w[(k + 1, 0)] = m.weights()[(k, 0)]; }
    /// assert!((&f * &w - m.predict(x.as_ref())).norm_max() < 1e-12);
    /// ```
    #[track_caller]
    pub fn features(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        let standardised = self.standardised(x);
        let xs = standardised.as_ref().map_or(x, Mat::as_ref);
        let n_poly = self.poly.as_ref().map_or(0, |p| p.degree.n_terms(self.dim));
        let lead =
            n_poly + usize::from(self.bias.is_some()) + self.tail.as_ref().map_or(0, |_| self.dim);
        let k = self.n_centres();
        let mut out = Mat::zeros(x.nrows(), lead + k);
        if let Some(p) = &self.poly {
            monomials_into(
                p.degree,
                x,
                &p.shift,
                &p.scale,
                out.as_mut().subcols_mut(0, n_poly),
            );
        }
        let mut col = n_poly;
        if self.bias.is_some() {
            out.as_mut().col_mut(col).fill(1.0);
            col += 1;
        }
        if self.tail.is_some() {
            out.as_mut().subcols_mut(col, self.dim).copy_from(xs);
        }
        kernel_matrix_into(
            xs,
            self.centres.as_ref(),
            self.kernel,
            &self.widths,
            out.as_mut().subcols_mut(lead, k),
            Par::Seq,
        );
        out
    }

    /// This model with exogenous linear regressors of fixed coefficients θ
    /// (r × q) added to its output: a network fitted to y − zθ becomes the
    /// model of y. The network's own part is unchanged.
    ///
    /// # Panics
    /// If the model already has linear regressors, or θ does not have q columns.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let theta = faer::mat![[2.0]];
    /// let with = m.clone().with_linear(theta.as_ref());
    /// let x = faer::mat![[0.5]];
    /// let z = faer::mat![[3.0]];
    /// let y = with.predict_with_linear(x.as_ref(), z.as_ref());
    /// assert!((y[(0, 0)] - m.predict(x.as_ref())[(0, 0)] - 6.0).abs() < 1e-12);
    /// ```
    #[track_caller]
    pub fn with_linear(mut self, theta: MatRef<'_, f64>) -> Self {
        assert_eq!(
            self.n_linear(),
            0,
            "the model already has linear regressors"
        );
        assert_eq!(
            theta.ncols(),
            self.n_outputs,
            "θ has {} columns for {} outputs",
            theta.ncols(),
            self.n_outputs
        );
        self.linear = theta.to_owned();
        self
    }

    /// Output `j` of a model of several outputs as a model of its own: the
    /// same centres, widths and input scaling, and that output's column of
    /// the weights, bias, tail and linear coefficients. Each output of a
    /// multi-output fit was solved by its own least squares on the shared
    /// columns, so the model is the one a fit of that target alone on these
    /// centres gives. Its [`RbfModel::selection`], if any, is the shared
    /// one (ERRs summed over every output).
    ///
    /// # Panics
    /// If `j` is not below [`RbfModel::n_outputs`].
    ///
    /// ```
    /// use faer::{Mat, Par};
    /// use linfa::ParamGuard;
    /// let x = Mat::from_fn(60, 1, |i, _| i as f64 / 10.0);
    /// let y = Mat::from_fn(60, 2, |i, j| (x[(i, 0)] * (j + 1) as f64).sin());
    /// let p = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(8))
    ///     .width(rbf::WidthRule::Fixed(1.0)).parallelism(Par::Seq).check().unwrap();
    /// let both = p.fit(x.as_ref(), y.as_ref()).unwrap();
    /// let second = both.output(1);
    /// assert_eq!((second.n_outputs(), second.centres()), (1, both.centres()));
    /// let (a, b) = (both.predict(x.as_ref()), second.predict(x.as_ref()));
    /// // The same numbers, up to the rounding of a one-column product.
    /// assert!((0..60).all(|i| (a[(i, 1)] - b[(i, 0)]).abs() < 1e-12));
    /// ```
    #[track_caller]
    pub fn output(&self, j: usize) -> Self {
        assert!(
            j < self.n_outputs,
            "output {j} of a model of {} outputs",
            self.n_outputs
        );
        let column = |m: &Mat<f64>| m.as_ref().subcols(j, 1).to_owned();
        RbfModel {
            n_outputs: 1,
            weights: column(&self.weights),
            bias: self.bias.as_ref().map(|b| vec![b[j]]),
            tail: self.tail.as_ref().map(column),
            linear: column(&self.linear),
            poly: self.poly.as_ref().map(|p| PolyFit {
                coefficients: column(&p.coefficients),
                ..p.clone()
            }),
            ..self.clone()
        }
    }

    /// The networks of several models as one model of all their outputs, when
    /// they share kernel, centres, widths, input scaling and polynomial
    /// degree (as the outputs of one [`RbfModel::output`] split do): its
    /// prediction computes the kernel columns once for every output. Their
    /// linear regressors are left out (add each model's zθ yourself);
    /// `None` when the models do not share their centres or one has several
    /// outputs.
    ///
    /// ```
    /// use faer::{Mat, Par};
    /// use linfa::ParamGuard;
    /// let x = Mat::from_fn(60, 1, |i, _| i as f64 / 10.0);
    /// let y = Mat::from_fn(60, 2, |i, j| (x[(i, 0)] * (j + 1) as f64).sin());
    /// let p = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(8))
    ///     .width(rbf::WidthRule::Fixed(1.0)).parallelism(Par::Seq).check().unwrap();
    /// let both = p.fit(x.as_ref(), y.as_ref()).unwrap();
    /// let (a, b) = (both.output(0), both.output(1));
    /// let again = rbf::RbfModel::stacked(&[&a, &b]).unwrap();
    /// assert_eq!(again.predict(x.as_ref()), both.predict(x.as_ref()));
    /// assert!(rbf::RbfModel::stacked(&[&both]).is_none(), "a model of two outputs");
    /// ```
    pub fn stacked(models: &[&RbfModel]) -> Option<RbfModel> {
        let first = *models.first()?;
        let same = |m: &RbfModel| {
            m.n_outputs == 1
                && m.kernel == first.kernel
                && m.dim == first.dim
                && m.centres == first.centres
                && m.widths == first.widths
                && m.scaling == first.scaling
                && m.tail.is_some() == first.tail.is_some()
                && m.bias.is_some() == first.bias.is_some()
                && match (&m.poly, &first.poly) {
                    (None, None) => true,
                    (Some(a), Some(b)) => {
                        a.degree == b.degree && a.shift == b.shift && a.scale == b.scale
                    }
                    _ => false,
                }
        };
        if !models.iter().all(|m| same(m)) {
            return None;
        }
        let q = models.len();
        let join = |col: &dyn Fn(&RbfModel) -> MatRef<'_, f64>| {
            let rows = col(first).nrows();
            Mat::from_fn(rows, q, |i, o| col(models[o])[(i, 0)])
        };
        Some(RbfModel {
            n_outputs: q,
            weights: join(&|m| m.weights.as_ref()),
            bias: first.bias.as_ref().map(|_| {
                models
                    .iter()
                    .map(|m| m.bias.as_ref().map_or(0.0, |b| b[0]))
                    .collect()
            }),
            tail: first.tail.as_ref().map(|_| {
                join(&|m| {
                    m.tail
                        .as_ref()
                        .expect("checked: every model has a tail")
                        .as_ref()
                })
            }),
            linear: Mat::zeros(0, q),
            poly: first.poly.as_ref().map(|p| PolyFit {
                coefficients: join(&|m| {
                    m.poly
                        .as_ref()
                        .expect("checked: every model has the tail")
                        .coefficients
                        .as_ref()
                }),
                ..p.clone()
            }),
            selection: None,
            ..first.clone()
        })
    }

    /// Predictions (n × q) for inputs `x` (n × d), with faer's global parallelism.
    /// Non-finite inputs give non-finite predictions.
    ///
    /// # Panics
    /// If `x` does not have d columns, or the model has linear regressors (use
    /// [`RbfModel::predict_with_linear`]).
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let y = m.predict(faer::mat![[0.5], [1.5]].as_ref());
    /// assert_eq!((y.nrows(), y.ncols()), (2, 1));
    /// ```
    #[track_caller]
    pub fn predict(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        let mut out = Mat::zeros(x.nrows(), self.n_outputs);
        self.predict_into(x, out.as_mut(), faer::get_global_parallelism());
        out
    }

    /// [`RbfModel::predict`] into `out` (n × q) with parallelism `par`.
    ///
    /// # Panics
    /// As [`RbfModel::predict`], or if `out` is not n × q.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let mut out = faer::Mat::zeros(1, 1);
    /// m.predict_into(faer::mat![[0.5]].as_ref(), out.as_mut(), faer::Par::Seq);
    /// assert_eq!(out, m.predict(faer::mat![[0.5]].as_ref()));
    /// ```
    #[track_caller]
    pub fn predict_into(&self, x: MatRef<'_, f64>, out: MatMut<'_, f64>, par: Par) {
        assert_eq!(
            self.n_linear(),
            0,
            "the model has {} linear regressors: use predict_with_linear",
            self.n_linear()
        );
        let z = Mat::<f64>::zeros(x.nrows(), 0);
        self.predict_impl(x, z.as_ref(), out, par);
    }

    /// Predictions for inputs `x` (n × d) and linear regressors `z` (n × r).
    ///
    /// # Panics
    /// If `x` does not have d columns, `z` does not have r columns, or their rows differ.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let x = faer::mat![[0.5]];
    /// let z = faer::Mat::<f64>::zeros(1, 0);
    /// assert_eq!(m.predict_with_linear(x.as_ref(), z.as_ref()), m.predict(x.as_ref()));
    /// ```
    #[track_caller]
    pub fn predict_with_linear(&self, x: MatRef<'_, f64>, z: MatRef<'_, f64>) -> Mat<f64> {
        let mut out = Mat::zeros(x.nrows(), self.n_outputs);
        self.predict_impl(x, z, out.as_mut(), faer::get_global_parallelism());
        out
    }

    /// [`RbfModel::predict_with_linear`] into `out` with parallelism `par`.
    ///
    /// # Panics
    /// As [`RbfModel::predict_with_linear`], or if `out` is not n × q.
    ///
    /// ```
    /// # let m = rbf::doc_model();
    /// let mut out = faer::Mat::zeros(1, 1);
    /// m.predict_with_linear_into(faer::mat![[0.5]].as_ref(), faer::Mat::<f64>::zeros(1, 0).as_ref(), out.as_mut(), faer::Par::Seq);
    /// ```
    #[track_caller]
    pub fn predict_with_linear_into(
        &self,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        out: MatMut<'_, f64>,
        par: Par,
    ) {
        self.predict_impl(x, z, out, par);
    }

    #[track_caller]
    fn predict_impl(&self, x: MatRef<'_, f64>, z: MatRef<'_, f64>, out: MatMut<'_, f64>, par: Par) {
        let (n, q) = (x.nrows(), self.n_outputs);
        assert_eq!(
            z.ncols(),
            self.n_linear(),
            "z has {} columns but the model has {} linear regressors",
            z.ncols(),
            self.n_linear()
        );
        assert_eq!(z.nrows(), n, "z has {} rows but x has {}", z.nrows(), n);
        assert_eq!((out.nrows(), out.ncols()), (n, q), "output must be n × q");
        let mut out = out;
        let standardised = self.standardised(x);
        let xs = standardised.as_ref().map_or(x, Mat::as_ref);
        for o in 0..q {
            let b = self.bias.as_ref().map_or(0.0, |b| b[o]);
            out.as_mut().col_mut(o).fill(b);
        }
        if let Some(t) = &self.tail {
            matmul(out.rb_mut(), Accum::Add, xs, t.as_ref(), 1.0, par);
        }
        if let Some(p) = &self.poly {
            let m = monomials(p.degree, x, &p.shift, &p.scale);
            matmul(
                out.rb_mut(),
                Accum::Add,
                m.as_ref(),
                p.coefficients.as_ref(),
                1.0,
                par,
            );
        }
        if self.n_linear() > 0 {
            matmul(out.rb_mut(), Accum::Add, z, self.linear.as_ref(), 1.0, par);
        }
        let k = self.n_centres();
        if k == 0 || n == 0 {
            return;
        }
        // Row blocks bound the kernel scratch to ~4M doubles (32 MB) whatever n is.
        let block = (4_194_304 / k).clamp(1, n);
        let mut phi = Mat::<f64>::zeros(block, k);
        for start in (0..n).step_by(block) {
            let b = block.min(n - start);
            let mut pb = phi.as_mut().subrows_mut(0, b);
            kernel_matrix_into(
                xs.subrows(start, b),
                self.centres.as_ref(),
                self.kernel,
                &self.widths,
                pb.rb_mut(),
                par,
            );
            matmul(
                out.rb_mut().subrows_mut(start, b),
                Accum::Add,
                pb.rb(),
                self.weights.as_ref(),
                1.0,
                par,
            );
        }
    }

    /// Checks the internal consistency of a deserialised model.
    pub(crate) fn validate(&self) -> Result<(), String> {
        let (k, d, q) = (self.centres.nrows(), self.dim, self.n_outputs);
        if self.centres.ncols() != d {
            return Err(format!(
                "centres have {} columns, dim is {d}",
                self.centres.ncols()
            ));
        }
        if (self.weights.nrows(), self.weights.ncols()) != (k, q) {
            return Err(format!(
                "weights are {}×{}, expected {k}×{q}",
                self.weights.nrows(),
                self.weights.ncols()
            ));
        }
        if let Widths::PerCentre(w) = &self.widths
            && w.len() != k
        {
            return Err(format!("{} widths for {k} centres", w.len()));
        }
        if !self.widths.all_positive() {
            return Err("non-positive width".into());
        }
        if let Some(b) = &self.bias
            && b.len() != q
        {
            return Err(format!("{} bias values for {q} outputs", b.len()));
        }
        if let Some(t) = &self.tail
            && (t.nrows(), t.ncols()) != (d, q)
        {
            return Err(format!(
                "tail is {}×{}, expected {d}×{q}",
                t.nrows(),
                t.ncols()
            ));
        }
        if self.linear.ncols() != q {
            return Err(format!(
                "linear coefficients have {} columns for {q} outputs",
                self.linear.ncols()
            ));
        }
        if let Some(s) = &self.scaling
            && (s.mean.len() != d || s.scale.len() != d)
        {
            return Err("scaling length differs from dim".into());
        }
        if let Some(p) = &self.poly {
            let m = p.degree.n_terms(d);
            if (p.coefficients.nrows(), p.coefficients.ncols()) != (m, q) {
                return Err(format!(
                    "polynomial coefficients are {}×{}, expected {m}×{q}",
                    p.coefficients.nrows(),
                    p.coefficients.ncols()
                ));
            }
            if p.shift.len() != d || p.scale.len() != d {
                return Err("polynomial shift or scale length differs from dim".into());
            }
            if let Some(k) = p.scale.iter().position(|&v| v.is_nan() || v <= 0.0) {
                return Err(format!("poly.scale[{k}] must be > 0"));
            }
        }
        // Every number, named with its field and place: a hand-edited weight
        // of 1e155 used to give NaN predictions, and a selection over NaN
        // scores that never ended.
        let mut fields: Vec<(&str, MatRef<'_, f64>)> = vec![
            ("centres", self.centres.as_ref()),
            ("weights", self.weights.as_ref()),
            ("linear", self.linear.as_ref()),
        ];
        if let Some(t) = &self.tail {
            fields.push(("tail", t.as_ref()));
        }
        if let Some(p) = &self.poly {
            fields.push(("poly.coefficients", p.coefficients.as_ref()));
        }
        for (name, m) in fields {
            for i in 0..m.nrows() {
                for j in 0..m.ncols() {
                    check_coefficient(&format!("{name}[{i}][{j}]"), m[(i, j)])?;
                }
            }
        }
        let vectors = [
            ("bias", self.bias.as_deref()),
            (
                "scaling.mean",
                self.scaling.as_ref().map(|s| s.mean.as_slice()),
            ),
            (
                "scaling.scale",
                self.scaling.as_ref().map(|s| s.scale.as_slice()),
            ),
            ("poly.shift", self.poly.as_ref().map(|p| p.shift.as_slice())),
            ("poly.scale", self.poly.as_ref().map(|p| p.scale.as_slice())),
        ];
        for (name, v) in vectors {
            for (i, &x) in v.unwrap_or_default().iter().enumerate() {
                check_coefficient(&format!("{name}[{i}]"), x)?;
            }
        }
        match &self.widths {
            Widths::Uniform(b) => check_width("widths.uniform", *b),
            Widths::PerCentre(w) => w
                .iter()
                .enumerate()
                .try_for_each(|(i, &b)| check_width(&format!("widths[{i}]"), b)),
        }
    }
}

/// The largest magnitude of any number in a model: beyond it a kernel
/// argument, a weighted sum or its square overflows `f64` (the readers of
/// data refuse cells beyond the same bound).
pub const MAX_COEFFICIENT: f64 = 1e150;

/// A width β: distances over β (inputs are within ±1e150) and their squares
/// stay finite from 1/[`MAX_COEFFICIENT`] up; a width edited to 1e-308 made
/// every Gaussian value 0/0.
fn check_width(field: &str, b: f64) -> Result<(), String> {
    if (1.0 / MAX_COEFFICIENT..=MAX_COEFFICIENT).contains(&b) {
        Ok(())
    } else {
        Err(format!(
            "{field} = {b:e}: a width must be from {:e} to {MAX_COEFFICIENT:e}",
            1.0 / MAX_COEFFICIENT
        ))
    }
}

fn check_coefficient(field: &str, v: f64) -> Result<(), String> {
    if v.is_finite() && v.abs() <= MAX_COEFFICIENT {
        Ok(())
    } else {
        Err(format!(
            "{field} = {v:e}: every number in a model must be finite and within ±{MAX_COEFFICIENT:e}"
        ))
    }
}
