//! Hyperparameters: the [`RbfParams`] builder and its checked form [`RbfValidParams`].

use faer::{Mat, Par};
use linfa::ParamGuard;
use serde::{Deserialize, Serialize};

use super::error::RbfParamsError;
use super::poly::PolyTail;
use crate::check::{first_non_finite, non_negative, positive};
use crate::estimate::DEFAULT_MAX_CONDITION;
use crate::kernel::Kernel;
use crate::select::kmeans::{KMeansError, KMeansSettings};
use crate::width::WidthRule;

/// The candidate centres OLS chooses from.
///
/// ```
/// let c = rbf::Candidates::Subsample { size: 500 };
/// assert_ne!(c, rbf::Candidates::TrainingVectors);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Candidates {
    /// Every training vector (Chen, Cowan & Grant 1991). The candidate matrix is n × n.
    TrainingVectors,
    /// A seeded random subsample of this many training vectors (all of them if fewer):
    /// the candidate matrix is n × size, the way to large N.
    Subsample {
        /// Number of candidates.
        size: usize,
    },
    /// User-given candidate centres (rows, in data units).
    Given(Mat<f64>),
}

/// How the centres are chosen.
///
/// ```
/// use rbf::CentreSelection;
/// assert!(matches!(CentreSelection::ols(30), CentreSelection::Ols { max_centres: 30, .. }));
/// assert!(matches!(CentreSelection::kmeans(10), CentreSelection::KMeans(_)));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum CentreSelection {
    /// OLS forward selection by error-reduction ratio.
    Ols {
        /// At most this many centres.
        max_centres: usize,
        /// Stop once 1 − ΣERR < ρ (0: run to `max_centres`).
        tol: f64,
        /// Regularised-OLS λ (Chen, Chng & Alkadhimi 1996); 0 for plain OLS.
        regularisation: f64,
        /// Candidate set.
        candidates: Candidates,
    },
    /// k-means centroids (seeded k-means++ start; the library's Lloyd iterations or
    /// linfa-clustering's: the `algorithm` field of [`KMeansSettings`]).
    KMeans(KMeansSettings),
    /// A seeded random subset of the training vectors.
    Random {
        /// Number of centres.
        n_centres: usize,
    },
    /// Every training vector is a centre: exact interpolation (ridge 0) or smoothing
    /// (ridge λ added to the kernel matrix's diagonal, as scipy's `smoothing`).
    /// Conditionally definite kernels (multiquadric, thin-plate, cubic) always get the
    /// polynomial tail their order needs (a constant, or a linear polynomial).
    AllPoints,
    /// User-given centres (rows, in data units).
    Given(Mat<f64>),
}

impl CentreSelection {
    /// OLS over all training vectors, at most `max_centres`, ρ = 0, no regularisation.
    ///
    /// ```
    /// let s = rbf::CentreSelection::ols(5);
    /// assert_eq!(s.strategy(), rbf::Strategy::Ols);
    /// ```
    pub fn ols(max_centres: usize) -> Self {
        CentreSelection::Ols {
            max_centres,
            tol: 0.0,
            regularisation: 0.0,
            candidates: Candidates::TrainingVectors,
        }
    }

    /// k-means with `n_centres` clusters and the defaults of [`KMeansSettings::new`].
    ///
    /// ```
    /// assert_eq!(rbf::CentreSelection::kmeans(4).strategy(), rbf::Strategy::KMeans);
    /// ```
    pub fn kmeans(n_centres: usize) -> Self {
        CentreSelection::KMeans(KMeansSettings::new(n_centres))
    }

    /// `n_centres` random training vectors.
    ///
    /// ```
    /// assert_eq!(rbf::CentreSelection::random(4).strategy(), rbf::Strategy::Random);
    /// ```
    pub fn random(n_centres: usize) -> Self {
        CentreSelection::Random { n_centres }
    }

    /// Which strategy this is.
    ///
    /// ```
    /// assert_eq!(rbf::CentreSelection::AllPoints.strategy(), rbf::Strategy::AllPoints);
    /// ```
    pub fn strategy(&self) -> Strategy {
        match self {
            CentreSelection::Ols { .. } => Strategy::Ols,
            CentreSelection::KMeans(_) => Strategy::KMeans,
            CentreSelection::Random { .. } => Strategy::Random,
            CentreSelection::AllPoints => Strategy::AllPoints,
            CentreSelection::Given(_) => Strategy::Given,
        }
    }
}

/// The kind of centre selection a model was fitted with (stored in saved models).
///
/// ```
/// assert_eq!(serde_json::to_string(&rbf::Strategy::KMeans).unwrap(), "\"kmeans\"");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Strategy {
    /// OLS forward selection.
    Ols,
    /// k-means.
    #[serde(rename = "kmeans")]
    KMeans,
    /// Random subset.
    Random,
    /// All training points.
    AllPoints,
    /// User-given centres.
    Given,
}

/// Checked hyperparameters; obtain them with `ParamGuard::check` on [`RbfParams`].
///
/// ```
/// use linfa::ParamGuard;
/// let p = rbf::RbfParams::new().ridge(1e-6).check().unwrap();
/// assert_eq!(p.ridge(), 1e-6);
/// assert!(p.bias());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RbfValidParams {
    pub(crate) kernel: Kernel,
    pub(crate) centres: CentreSelection,
    pub(crate) width: WidthRule,
    pub(crate) ridge: f64,
    pub(crate) bias: bool,
    pub(crate) linear_tail: bool,
    pub(crate) standardise: bool,
    pub(crate) seed: u64,
    pub(crate) par: Par,
    pub(crate) max_condition: f64,
    /// The polynomial tail on unit-box inputs (`None`: `bias` and `linear_tail` decide,
    /// on unscaled inputs, as before this option existed).
    pub(crate) degree: Option<PolyTail>,
    /// OLS: select on a seeded subsample of this many rows, weights on all (None: all).
    pub(crate) selection_rows: Option<usize>,
    /// OLS: how many of the path's picks the model keeps.
    pub(crate) size_rule: crate::select::ols::SizeRule,
    /// OLS: precision of the streaming passes (the picks do not depend on it).
    pub(crate) ols_stream: crate::select::ols::StreamPrecision,
}

impl RbfValidParams {
    /// The kernel.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().kernel(), rbf::Kernel::Gaussian);
    /// ```
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }

    /// The centre selection.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// let p = rbf::RbfParams::new().check().unwrap();
    /// assert_eq!(p.centres().strategy(), rbf::Strategy::Ols);
    /// ```
    pub fn centres(&self) -> &CentreSelection {
        &self.centres
    }

    /// The width rule.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().width(), &rbf::WidthRule::default());
    /// ```
    pub fn width(&self) -> &WidthRule {
        &self.width
    }

    /// The ridge λ on the output weights.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().ridge(), 0.0);
    /// ```
    pub fn ridge(&self) -> f64 {
        self.ridge
    }

    /// Whether the bias λ0 is fitted.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert!(!rbf::RbfParams::new().bias(false).check().unwrap().bias());
    /// ```
    pub fn bias(&self) -> bool {
        self.bias
    }

    /// Whether a linear polynomial tail is fitted.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert!(rbf::RbfParams::new().linear_tail(true).check().unwrap().linear_tail());
    /// ```
    pub fn linear_tail(&self) -> bool {
        self.linear_tail
    }

    /// Whether the inputs are standardised.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert!(!rbf::RbfParams::new().check().unwrap().standardise());
    /// ```
    pub fn standardise(&self) -> bool {
        self.standardise
    }

    /// The seed of every random draw.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().seed(3).check().unwrap().seed(), 3);
    /// ```
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The parallelism.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// let p = rbf::RbfParams::new().parallelism(faer::Par::Seq).check().unwrap();
    /// assert_eq!(p.parallelism(), faer::Par::Seq);
    /// ```
    pub fn parallelism(&self) -> Par {
        self.par
    }

    /// The condition-number limit of the weight solve.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().max_condition(), rbf::DEFAULT_MAX_CONDITION);
    /// ```
    pub fn max_condition(&self) -> f64 {
        self.max_condition
    }

    /// The polynomial tail set by [`RbfParams::degree`] (`None`: the bias and linear-tail
    /// switches decide).
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// let p = rbf::RbfParams::new().degree(rbf::PolyTail::Linear).check().unwrap();
    /// assert_eq!(p.degree(), Some(rbf::PolyTail::Linear));
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().degree(), None);
    /// ```
    pub fn degree(&self) -> Option<PolyTail> {
        self.degree
    }

    /// OLS: the rows centre selection runs on (`None`: every training row).
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().selection_rows(), None);
    /// ```
    pub fn selection_rows(&self) -> Option<usize> {
        self.selection_rows
    }

    /// OLS: how many of the path's picks the model keeps.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().size_rule(), rbf::ols::SizeRule::All);
    /// ```
    pub fn size_rule(&self) -> crate::select::ols::SizeRule {
        self.size_rule
    }

    /// OLS: the precision of the streaming passes.
    ///
    /// ```
    /// # use rbf::ParamGuard;
    /// assert_eq!(rbf::RbfParams::new().check().unwrap().ols_stream(), rbf::StreamPrecision::F32);
    /// ```
    pub fn ols_stream(&self) -> crate::select::ols::StreamPrecision {
        self.ols_stream
    }

    pub(crate) fn with_width(&self, width: WidthRule) -> Self {
        Self {
            width,
            ..self.clone()
        }
    }

    pub(crate) fn with_ridge(&self, ridge: f64) -> Self {
        Self {
            ridge,
            ..self.clone()
        }
    }

    pub(crate) fn with_centres(&self, centres: CentreSelection) -> Self {
        Self {
            centres,
            ..self.clone()
        }
    }

    fn validate(&self) -> Result<(), RbfParamsError> {
        if let Some(degree) = self.degree {
            let minimum = PolyTail::minimum_for(self.kernel);
            if matches!(self.centres, CentreSelection::AllPoints) && degree < minimum {
                return Err(RbfParamsError::DegreeTooLow {
                    kernel: self.kernel,
                    degree: degree.degree(),
                    minimum: minimum.degree(),
                });
            }
        }
        match self.width {
            WidthRule::Fixed(b) if !positive(b) => return Err(RbfParamsError::Width { value: b }),
            WidthRule::Fixed(_) => {}
            ref rule => {
                if !positive(rule.value()) {
                    return Err(RbfParamsError::WidthScale {
                        value: rule.value(),
                    });
                }
            }
        }
        if matches!(self.width, WidthRule::ClusterSpread { .. })
            && !matches!(self.centres, CentreSelection::KMeans(_))
        {
            return Err(RbfParamsError::ClusterSpreadNeedsKMeans);
        }
        if !non_negative(self.ridge) {
            return Err(RbfParamsError::Ridge { value: self.ridge });
        }
        if self.max_condition.is_nan() || self.max_condition < 1.0 {
            return Err(RbfParamsError::MaxCondition {
                value: self.max_condition,
            });
        }
        match &self.centres {
            CentreSelection::Ols {
                max_centres,
                tol,
                regularisation,
                candidates,
            } => {
                if *max_centres == 0 {
                    return Err(RbfParamsError::OlsMaxCentres);
                }
                if !(*tol >= 0.0 && *tol < 1.0) {
                    return Err(RbfParamsError::OlsTolerance { value: *tol });
                }
                if !non_negative(*regularisation) {
                    return Err(RbfParamsError::OlsRegularisation {
                        value: *regularisation,
                    });
                }
                match candidates {
                    Candidates::TrainingVectors => {}
                    Candidates::Subsample { size } => {
                        if *size == 0 {
                            return Err(RbfParamsError::SubsampleSize);
                        }
                    }
                    Candidates::Given(c) => {
                        if c.nrows() == 0 {
                            return Err(RbfParamsError::EmptyCandidates);
                        }
                        if let Some((row, col)) = first_non_finite(c.as_ref()) {
                            return Err(RbfParamsError::NonFiniteCandidates { row, col });
                        }
                    }
                }
            }
            CentreSelection::KMeans(s) => {
                // the k-means rules, each broken rule as this type's own variant
                s.check().map_err(|e| match e {
                    KMeansError::NoClusters => RbfParamsError::KMeansCentres,
                    KMeansError::NoRuns => RbfParamsError::KMeansRuns,
                    KMeansError::NoIterations => RbfParamsError::KMeansIterations,
                    KMeansError::Tolerance { .. } | KMeansError::Linfa(_) => {
                        RbfParamsError::KMeansTolerance { value: s.tolerance }
                    }
                })?;
            }
            CentreSelection::Random { n_centres } => {
                if *n_centres == 0 {
                    return Err(RbfParamsError::RandomCentres);
                }
            }
            CentreSelection::AllPoints => {}
            CentreSelection::Given(c) => {
                if c.nrows() == 0 {
                    return Err(RbfParamsError::EmptyCentres);
                }
                if let Some((row, col)) = first_non_finite(c.as_ref()) {
                    return Err(RbfParamsError::NonFiniteCentres { row, col });
                }
            }
        }
        Ok(())
    }
}

/// The hyperparameter builder.
///
/// Defaults: Gaussian kernel, OLS over all training vectors with at most 50 centres
/// (ρ = 0), width = median pairwise distance between candidates, no ridge, bias on
/// (λ0 of eq. 7), no linear tail, no standardisation (β in data units, as in the paper),
/// seed 42, parallelism from faer's global setting, condition limit
/// [`DEFAULT_MAX_CONDITION`].
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// use rbf::{CentreSelection, Kernel, RbfParams, WidthRule};
/// let x = Mat::from_fn(200, 1, |i, _| i as f64 / 200.0 * 6.0);
/// let y = Mat::from_fn(200, 1, |i, _| x[(i, 0)].sin());
/// let model = RbfParams::new()
///     .kernel(Kernel::Gaussian)
///     .centres(CentreSelection::ols(15))
///     .width(WidthRule::Fixed(1.0))
///     .parallelism(Par::Seq)
///     .check()
///     .unwrap()
///     .fit(x.as_ref(), y.as_ref())
///     .unwrap();
/// let yhat = model.predict(x.as_ref());
/// assert!(rbf::metrics::rmse(y.col(0).try_as_col_major().unwrap().as_slice(),
///                            yhat.col(0).try_as_col_major().unwrap().as_slice()) < 1e-4);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RbfParams(RbfValidParams);

impl Default for RbfParams {
    fn default() -> Self {
        Self::new()
    }
}

impl RbfParams {
    /// The defaults listed on the type.
    ///
    /// ```
    /// let p = rbf::RbfParams::new();
    /// # let _ = p;
    /// ```
    pub fn new() -> Self {
        Self(RbfValidParams {
            kernel: Kernel::Gaussian,
            centres: CentreSelection::ols(50),
            width: WidthRule::default(),
            ridge: 0.0,
            bias: true,
            linear_tail: false,
            standardise: false,
            seed: 42,
            par: faer::get_global_parallelism(),
            max_condition: DEFAULT_MAX_CONDITION,
            degree: None,
            selection_rows: None,
            size_rule: crate::select::ols::SizeRule::All,
            ols_stream: crate::select::ols::StreamPrecision::default(),
        })
    }

    /// OLS only: run centre selection on a seeded subsample of `rows` training rows
    /// (the candidate kernel matrix is then `rows` × candidates, whatever N is), and
    /// solve the weights of the chosen centres on every row by a streaming row-block QR
    /// ([`crate::estimate::StreamingLstsq`]). `None` (the default) selects on every row.
    /// At least the forced columns plus one row are used.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// let p = rbf::RbfParams::new().selection_rows(Some(20_000)).check().unwrap();
    /// assert_eq!(p.selection_rows(), Some(20_000));
    /// ```
    pub fn selection_rows(mut self, rows: Option<usize>) -> Self {
        self.0.selection_rows = rows;
        self
    }

    /// OLS only: keep every pick ([`crate::select::ols::SizeRule::All`], the default: the run
    /// stops at the most centres or by ρ), or the size with the least leave-one-out
    /// error (PRESS) or GCV along the path, computed from the selection's orthogonal
    /// basis at no extra pass over the candidates.
    ///
    /// ```
    /// # use linfa::ParamGuard;
    /// let p = rbf::RbfParams::new().size_rule(rbf::ols::SizeRule::Press).check().unwrap();
    /// assert_eq!(p.size_rule(), rbf::ols::SizeRule::Press);
    /// ```
    pub fn size_rule(mut self, rule: crate::select::ols::SizeRule) -> Self {
        self.0.size_rule = rule;
        self
    }

    /// OLS only: stream the candidates as an f32 copy with f64 accumulation
    /// ([`crate::select::ols::StreamPrecision::F32`], the default: half the bytes a pick, no f64
    /// candidate matrix held, the same picks) or as f64 columns.
    ///
    /// ```
    /// # use rbf::ParamGuard;
    /// let p = rbf::RbfParams::new().ols_stream(rbf::StreamPrecision::F64).check().unwrap();
    /// assert_eq!(p.ols_stream(), rbf::StreamPrecision::F64);
    /// ```
    pub fn ols_stream(mut self, precision: crate::select::ols::StreamPrecision) -> Self {
        self.0.ols_stream = precision;
        self
    }

    /// Sets the kernel.
    ///
    /// ```
    /// let p = rbf::RbfParams::new().kernel(rbf::Kernel::ThinPlateSpline);
    /// # let _ = p;
    /// ```
    pub fn kernel(mut self, kernel: Kernel) -> Self {
        self.0.kernel = kernel;
        self
    }

    /// Sets the centre selection.
    ///
    /// ```
    /// let p = rbf::RbfParams::new().centres(rbf::CentreSelection::kmeans(20));
    /// # let _ = p;
    /// ```
    pub fn centres(mut self, centres: CentreSelection) -> Self {
        self.0.centres = centres;
        self
    }

    /// Sets the width rule.
    ///
    /// ```
    /// let p = rbf::RbfParams::new().width(rbf::WidthRule::Fixed(0.8));
    /// # let _ = p;
    /// ```
    pub fn width(mut self, width: WidthRule) -> Self {
        self.0.width = width;
        self
    }

    /// Sets the ridge λ ≥ 0 on the output weights (bias, tail and linear regressors are
    /// not shrunk); with [`CentreSelection::AllPoints`] it is the smoothing.
    ///
    /// ```
    /// let p = rbf::RbfParams::new().ridge(1e-8);
    /// # let _ = p;
    /// ```
    pub fn ridge(mut self, ridge: f64) -> Self {
        self.0.ridge = ridge;
        self
    }

    /// Fits the bias λ0 (default on).
    ///
    /// ```
    /// let p = rbf::RbfParams::new().bias(false);
    /// # let _ = p;
    /// ```
    pub fn bias(mut self, on: bool) -> Self {
        self.0.bias = on;
        self
    }

    /// Adds a linear polynomial tail aᵀx (default off).
    ///
    /// ```
    /// let p = rbf::RbfParams::new().linear_tail(true);
    /// # let _ = p;
    /// ```
    pub fn linear_tail(mut self, on: bool) -> Self {
        self.0.linear_tail = on;
        self
    }

    /// Sets the polynomial tail, scipy `RBFInterpolator`'s `degree`: every monomial of
    /// degree ≤ D of the inputs mapped to the unit box (shift = middle of the training
    /// range, scale = half-range), for every centre selection — forced columns of OLS,
    /// unpenalised columns of the QR solve, the polynomial block of all-points
    /// interpolation. The kernel then sees the inputs shifted by the same amount (not
    /// scaled: β stays in data units). It replaces the [`RbfParams::bias`] and
    /// [`RbfParams::linear_tail`] switches; with [`CentreSelection::AllPoints`] a degree
    /// below [`PolyTail::minimum_for`] the kernel is refused. Unset (the default), those
    /// switches decide as before, and all-points fits get the kernel's minimum degree.
    ///
    /// ```
    /// let p = rbf::RbfParams::new().degree(rbf::PolyTail::Quadratic);
    /// # let _ = p;
    /// ```
    pub fn degree(mut self, degree: PolyTail) -> Self {
        self.0.degree = Some(degree);
        self
    }

    /// Standardises each input to zero mean and unit variance before anything else
    /// (default off, so β is in data units as in the paper; when on, widths are in
    /// standardised units).
    ///
    /// ```
    /// let p = rbf::RbfParams::new().standardise(true);
    /// # let _ = p;
    /// ```
    pub fn standardise(mut self, on: bool) -> Self {
        self.0.standardise = on;
        self
    }

    /// Seeds every random draw (subsampling, random centres, k-means).
    ///
    /// ```
    /// let p = rbf::RbfParams::new().seed(7);
    /// # let _ = p;
    /// ```
    pub fn seed(mut self, seed: u64) -> Self {
        self.0.seed = seed;
        self
    }

    /// Sets the parallelism of every kernel.
    ///
    /// ```
    /// let p = rbf::RbfParams::new().parallelism(faer::Par::rayon(2));
    /// # let _ = p;
    /// ```
    pub fn parallelism(mut self, par: Par) -> Self {
        self.0.par = par;
        self
    }

    /// Sets the condition-number limit of the weight solve (`f64::INFINITY` disables it).
    ///
    /// ```
    /// let p = rbf::RbfParams::new().max_condition(1e10);
    /// # let _ = p;
    /// ```
    pub fn max_condition(mut self, limit: f64) -> Self {
        self.0.max_condition = limit;
        self
    }
}

impl From<RbfValidParams> for RbfParams {
    /// Back to a builder, e.g. to change one setting of checked params.
    ///
    /// ```
    /// use linfa::ParamGuard;
    /// let p = rbf::RbfParams::new().ridge(0.5).check().unwrap();
    /// let q = rbf::RbfParams::from(p).seed(9).check().unwrap();
    /// assert_eq!((q.ridge(), q.seed()), (0.5, 9));
    /// ```
    fn from(p: RbfValidParams) -> Self {
        Self(p)
    }
}

impl ParamGuard for RbfParams {
    type Checked = RbfValidParams;
    type Error = RbfParamsError;

    fn check_ref(&self) -> Result<&Self::Checked, Self::Error> {
        self.0.validate()?;
        Ok(&self.0)
    }

    fn check(self) -> Result<Self::Checked, Self::Error> {
        self.0.validate()?;
        Ok(self.0)
    }
}
