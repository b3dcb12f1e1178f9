//! Command-line choices and the library parameters they stand for.
//!
//! Flags arrive here already parsed (clap); this module checks the combinations that
//! only make sense together (`--tol` needs OLS, at most as many centres as training
//! rows) and builds the checked [`rbf::RbfValidParams`].

use std::fmt;
use std::str::FromStr;

use rbf::ParamGuard;
use rbf::{
    Candidates, CentreSelection, KMeansAlgorithm, KMeansInit, KMeansSettings, Kernel, PolyTail,
    RbfParams, RbfParamsError, RbfValidParams, Split, WidthRule,
};

/// Centres when `--max-centres` is not given (the library's default OLS size).
///
/// ```
/// assert_eq!(rbf_cli::settings::DEFAULT_MAX_CENTRES, 50);
/// ```
pub const DEFAULT_MAX_CENTRES: usize = 50;

/// OLS on more training rows than this selects its centres on a seeded subsample of
/// this many rows (unless `--selection-rows` says otherwise) and solves the weights on
/// every row by a streaming row-block QR: memory then stops growing with N.
///
/// ```
/// assert_eq!(rbf_cli::settings::AUTO_SELECTION_ROWS, 20_000);
/// ```
pub const AUTO_SELECTION_ROWS: usize = 20_000;

/// OLS candidates when the selection rows are subsampled and `--candidates` is not
/// given: the candidate kernel matrix is then at most 20 000 × 2000 doubles (320 MB).
///
/// ```
/// assert_eq!(rbf_cli::settings::AUTO_CANDIDATES, 2000);
/// ```
pub const AUTO_CANDIDATES: usize = 2000;

/// The largest ridge the flags take. Beyond it the penalty swamps the
/// unpenalised bias column and the least-squares solve reports it rank
/// deficient (measured: 1e18 still fits, 1e30 does not); at 1e12 the kernel
/// weights are already zero for any data whose rows number below a million.
pub const MAX_RIDGE: f64 = 1e12;

/// A count of centres or candidates (`--max-centres`, `--candidates`, …): a whole
/// number ≥ 1 (0 would leave nothing to fit; hints built from it proposed
/// "--max-centers ≤ 0"). The parsers here are clap's value parsers of the flags and
/// the checks of the Python binding's parameters alike.
///
/// ```
/// assert_eq!(rbf_cli::settings::parse_count("7"), Ok(7));
/// assert_eq!(rbf_cli::settings::parse_count("0").unwrap_err(), "must be a whole number ≥ 1");
/// ```
pub fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("must be a whole number ≥ 1".to_string()),
    }
}

/// An OLS tolerance ρ (`--tol`): 1 − ΣERR < ρ stops selection, so ρ lies in [0, 1).
///
/// ```
/// assert!(rbf_cli::settings::parse_tol("1").is_err() && rbf_cli::settings::parse_tol("0").is_ok());
/// ```
pub fn parse_tol(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..1.0).contains(&v) => Ok(v),
        _ => Err("must be a number from 0 up to (not including) 1".to_string()),
    }
}

/// A ridge λ (`--ridge`): finite, from 0 to [`MAX_RIDGE`].
///
/// ```
/// assert_eq!(rbf_cli::settings::parse_ridge("-0"), Ok(0.0));
/// assert_eq!(rbf_cli::settings::parse_ridge("1e13").unwrap_err(), "must be a number from 0 to 1e12");
/// ```
pub fn parse_ridge(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        // −0 is 0: no ridge.
        Ok(v) if (0.0..=MAX_RIDGE).contains(&v) => Ok(v.abs()),
        _ => Err(format!("must be a number from 0 to {MAX_RIDGE:e}")),
    }
}

/// `--centres`: how the centres are chosen.
///
/// ```
/// use rbf_cli::settings::Centres;
/// assert_eq!("kmeans".parse::<Centres>().unwrap(), Centres::Kmeans);
/// assert!("best".parse::<Centres>().unwrap_err().contains("ols, kmeans, random, all"));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Centres {
    /// OLS forward selection by error-reduction ratio (Chen, Cowan & Grant 1991).
    #[default]
    Ols,
    /// k-means centroids (k-means++, seeded) with QR output weights.
    Kmeans,
    /// A seeded random subset of the training rows with QR output weights.
    Random,
    /// Every training row is a centre (interpolation, or smoothing with a ridge).
    All,
}

impl Centres {
    /// The names `--centres` accepts.
    ///
    /// ```
    /// assert_eq!(rbf_cli::settings::Centres::NAMES[0], "ols");
    /// ```
    pub const NAMES: [&'static str; 4] = ["ols", "kmeans", "random", "all"];

    /// The flag value naming this choice.
    ///
    /// ```
    /// assert_eq!(rbf_cli::settings::Centres::All.name(), "all");
    /// ```
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl FromStr for Centres {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "ols" => Ok(Centres::Ols),
            "kmeans" => Ok(Centres::Kmeans),
            "random" => Ok(Centres::Random),
            "all" => Ok(Centres::All),
            _ => Err(format!("valid names: {}", Self::NAMES.join(", "))),
        }
    }
}

impl fmt::Display for Centres {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The width grid of `--width auto` with `--stop press|gcv`: these multiples of the
/// median pairwise distance between the candidates.
///
/// ```
/// assert_eq!(rbf_cli::settings::WIDTH_GRID, [0.25, 0.5, 1.0, 2.0, 4.0]);
/// ```
pub const WIDTH_GRID: [f64; 5] = [0.25, 0.5, 1.0, 2.0, 4.0];

/// `--stop`: how OLS chooses its number of centres.
///
/// ```
/// use rbf_cli::settings::StopArg;
/// assert_eq!("press".parse::<StopArg>().unwrap(), StopArg::Press);
/// assert_eq!("err:0.01".parse::<StopArg>().unwrap(), StopArg::Err(0.01));
/// assert_eq!("k:20".parse::<StopArg>().unwrap(), StopArg::K(20));
/// assert!("k:0".parse::<StopArg>().is_err() && "err:1.5".parse::<StopArg>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StopArg {
    /// The size with the least leave-one-out error (PRESS) along the path.
    Press,
    /// The size with the least generalised cross-validation score.
    Gcv,
    /// Stop once 1 − ΣERR < ρ (`--tol ρ`).
    Err(f64),
    /// Exactly K picks, fewer only if the candidates run out (`--max-centres K`).
    K(usize),
}

impl StopArg {
    /// The flag value.
    ///
    /// ```
    /// assert_eq!(rbf_cli::settings::StopArg::K(5).to_string(), "k:5");
    /// ```
    pub fn name(self) -> String {
        match self {
            StopArg::Press => "press".into(),
            StopArg::Gcv => "gcv".into(),
            StopArg::Err(r) => format!("err:{r}"),
            StopArg::K(k) => format!("k:{k}"),
        }
    }
}

impl fmt::Display for StopArg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

impl FromStr for StopArg {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || "expected press, gcv, err:RHO (0 ≤ RHO < 1) or k:K (K ≥ 1)".to_string();
        match s.trim() {
            "press" => Ok(StopArg::Press),
            "gcv" => Ok(StopArg::Gcv),
            t => {
                if let Some(r) = t.strip_prefix("err:") {
                    match r.parse::<f64>() {
                        Ok(v) if (0.0..1.0).contains(&v) => Ok(StopArg::Err(v)),
                        _ => Err(bad()),
                    }
                } else if let Some(k) = t.strip_prefix("k:") {
                    match k.parse::<usize>() {
                        Ok(v) if v >= 1 => Ok(StopArg::K(v)),
                        _ => Err(bad()),
                    }
                } else {
                    Err(bad())
                }
            }
        }
    }
}

/// The most centres `--stop press|gcv` considers when `--max-centres` is not given:
/// a tenth of the training rows, from 10 to 200 (and at most the candidates).
///
/// ```
/// use rbf_cli::settings::auto_max_centres;
/// assert_eq!((auto_max_centres(50), auto_max_centres(1000), auto_max_centres(1_000_000)), (10, 100, 200));
/// ```
pub fn auto_max_centres(n_train: usize) -> usize {
    (n_train / 10).clamp(10, 200)
}

/// The narrowest fixed width `--width` takes: inputs (at most ±1e150, the
/// readers' limit) divided by β stay finite, so kernel arguments never become
/// NaN (a width of 1e-308 made every candidate non-finite).
pub const MIN_WIDTH: f64 = 1e-100;
/// The widest fixed width `--width` takes (the mirror of [`MIN_WIDTH`]).
pub const MAX_WIDTH: f64 = 1e100;

/// `--width`: a fixed β in input units, or `auto`, the library's default rule (β = the
/// median pairwise distance between the candidate centres, on a seeded subsample of
/// 1000 of them above that count).
///
/// ```
/// use rbf_cli::settings::WidthArg;
/// assert_eq!("auto".parse::<WidthArg>().unwrap(), WidthArg::Auto);
/// assert_eq!("0.5".parse::<WidthArg>().unwrap(), WidthArg::Fixed(0.5));
/// assert!("-1".parse::<WidthArg>().is_err());
/// assert_eq!(WidthArg::Auto.rule(), rbf::WidthRule::default());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum WidthArg {
    /// The library's default width rule.
    #[default]
    Auto,
    /// A fixed β.
    Fixed(f64),
}

impl WidthArg {
    /// The library's width rule.
    ///
    /// ```
    /// assert_eq!(rbf_cli::settings::WidthArg::Fixed(2.0).rule(), rbf::WidthRule::Fixed(2.0));
    /// ```
    pub fn rule(self) -> WidthRule {
        match self {
            WidthArg::Auto => WidthRule::default(),
            WidthArg::Fixed(b) => WidthRule::Fixed(b),
        }
    }
}

impl FromStr for WidthArg {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        if s == "auto" {
            return Ok(WidthArg::Auto);
        }
        match s.parse::<f64>() {
            Ok(b) if (MIN_WIDTH..=MAX_WIDTH).contains(&b) => Ok(WidthArg::Fixed(b)),
            _ => Err(format!(
                "expected 'auto' or a width β from {MIN_WIDTH:e} to {MAX_WIDTH:e}"
            )),
        }
    }
}

impl fmt::Display for WidthArg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WidthArg::Auto => f.write_str("auto"),
            WidthArg::Fixed(b) => write!(f, "{b}"),
        }
    }
}

/// The scheme `rbf cv --split` names; with the fold count and gap it becomes
/// an [`rbf::Split`] (the hold-out of one fit is [`rbf::Holdout`]).
///
/// ```
/// use rbf_cli::settings::CvScheme;
/// assert_eq!(CvScheme::Blocked.split(5, 3, 0), rbf::Split::Blocked { k: 5, gap: 3 });
/// assert_eq!("kfold".parse::<CvScheme>().unwrap(), CvScheme::Kfold);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CvScheme {
    /// Shuffled k-fold (seeded).
    Kfold,
    /// Fold f validates every k-th row (k = 2: the seed paper's alternate rows).
    Interleaved,
    /// Contiguous blocks, `gap` rows dropped from training on each side.
    Blocked,
}

impl CvScheme {
    /// The names `--split` accepts.
    ///
    /// ```
    /// assert_eq!(rbf_cli::settings::CvScheme::NAMES[2], "blocked");
    /// ```
    pub const NAMES: [&'static str; 3] = ["kfold", "interleaved", "blocked"];

    /// The library's split with `folds` folds.
    ///
    /// ```
    /// use rbf_cli::settings::CvScheme;
    /// assert_eq!(CvScheme::Kfold.split(4, 0, 9), rbf::Split::KFold { k: 4, seed: 9 });
    /// ```
    pub fn split(self, folds: usize, gap: usize, seed: u64) -> Split {
        match self {
            CvScheme::Kfold => Split::KFold { k: folds, seed },
            CvScheme::Interleaved => Split::Interleaved { k: folds },
            CvScheme::Blocked => Split::Blocked { k: folds, gap },
        }
    }

    /// The flag value naming this split.
    ///
    /// ```
    /// assert_eq!(rbf_cli::settings::CvScheme::Interleaved.name(), "interleaved");
    /// ```
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl FromStr for CvScheme {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "kfold" => Ok(CvScheme::Kfold),
            "interleaved" => Ok(CvScheme::Interleaved),
            "blocked" => Ok(CvScheme::Blocked),
            _ => Err(format!("valid names: {}", Self::NAMES.join(", "))),
        }
    }
}

/// A combination of flags that cannot be fitted.
///
/// ```
/// use rbf_cli::settings::SettingsError;
/// let e = SettingsError::TooManyCentres { centres: 9, rows: 4, what: "training rows", most: 3, flag: "--max-centers" };
/// assert!(e.to_string().ends_with("use --max-centers ≤ 3"));
/// ```
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum SettingsError {
    /// A flag that only applies to other `--centres`.
    #[error("{flag} applies to --centers {applies} only, not {centres}")]
    NotApplicable {
        /// The flag.
        flag: &'static str,
        /// The strategies it applies to.
        applies: &'static str,
        /// The strategy given.
        centres: Centres,
    },
    /// Two flags that say the same thing differently.
    #[error("{a} and {b} both set the {what}: give one")]
    Conflict {
        /// One flag.
        a: &'static str,
        /// The other.
        b: &'static str,
        /// What both set.
        what: &'static str,
    },
    /// More centres than the rows (or candidates) take, by the library's own rule
    /// ([`rbf::RbfValidParams::most_centres`]): the value proposed then works.
    #[error(
        "{centres} centres asked for but {rows} {what} take at most {most}; use {flag} ≤ {most}"
    )]
    TooManyCentres {
        /// Centres asked for.
        centres: usize,
        /// Rows or candidates available.
        rows: usize,
        /// What `rows` counts.
        what: &'static str,
        /// The most centres that work.
        most: usize,
        /// The flag that sets the number of centres.
        flag: &'static str,
    },
    /// Too few rows for the fixed columns alone (bias, linear or polynomial tail).
    #[error(
        "{rows} {what} are too few for the {fixed} fixed columns of the fit (bias, tails); use more rows or a lower --degree"
    )]
    TooFewRows {
        /// Rows available.
        rows: usize,
        /// What `rows` counts.
        what: &'static str,
        /// Fixed columns of the weights' least squares.
        fixed: usize,
    },
    /// The library rejected the parameters.
    #[error(transparent)]
    Params(#[from] RbfParamsError),
}

/// Refuses `k` centres when `rows` training rows of `dim` inputs take fewer by the
/// library's rule ([`rbf::RbfValidParams::most_centres`], the rule the fit itself
/// refuses by), naming `flag` with the largest value that works; `what` says what
/// `rows` counts.
///
/// # Errors
/// [`SettingsError::TooManyCentres`], or [`SettingsError::TooFewRows`] when the rows do
/// not cover the fixed columns alone.
///
/// ```
/// use rbf_cli::settings::{check_centres, Centres, FitSettings};
/// let p = FitSettings { centres: Centres::Kmeans, ..Default::default() }.build(30, rbf::WidthRule::default()).unwrap();
/// assert!(check_centres(&p, 23, 24, 2, "training rows", "--max-centers").is_ok());
/// let e = check_centres(&p, 24, 24, 2, "training rows", "--max-centers").unwrap_err();
/// assert!(e.to_string().ends_with("use --max-centers ≤ 23"), "{e}");
/// ```
pub fn check_centres(
    params: &RbfValidParams,
    k: usize,
    rows: usize,
    dim: usize,
    what: &'static str,
    flag: &'static str,
) -> Result<(), SettingsError> {
    let most = params.most_centres(rows, dim, 0);
    if k <= most {
        return Ok(());
    }
    if most == 0 {
        return Err(SettingsError::TooFewRows {
            rows,
            what,
            fixed: params.fixed_columns(dim, 0),
        });
    }
    // OLS picks among its candidates: when they are a subsample, say so.
    let (rows, what) = match params.centres() {
        rbf::CentreSelection::Ols { .. } if most < rows => (most, "OLS candidates (--candidates)"),
        _ => (rows, what),
    };
    Err(SettingsError::TooManyCentres {
        centres: k,
        rows,
        what,
        most,
        flag,
    })
}

/// Everything `rbf fit` needs to build the library's parameters.
///
/// ```
/// use rbf_cli::settings::{Centres, FitSettings};
/// let s = FitSettings { centres: Centres::Kmeans, max_centres: Some(8), ..FitSettings::default() };
/// let p = s.params(100, 2).unwrap();
/// assert!(matches!(p.centres(), rbf::CentreSelection::KMeans(k) if k.n_centres == 8));
/// // 5 rows take 4 centres and the bias
/// assert!(s.params(5, 2).unwrap_err().to_string().contains("--max-centers ≤ 4"));
///
/// // --kmeans-algorithm picks whose Lloyd iterations run (the library's default otherwise)
/// use rbf::KMeansAlgorithm::{Linfa, Lloyd};
/// let linfa = FitSettings { kmeans_algorithm: Some(Linfa), ..s.clone() };
/// assert!(matches!(p.centres(), rbf::CentreSelection::KMeans(k) if k.algorithm == Lloyd));
/// assert!(matches!(linfa.params(100, 2).unwrap().centres(),
///     rbf::CentreSelection::KMeans(k) if k.algorithm == Linfa));
/// let ols = FitSettings { centres: Centres::Ols, ..linfa };
/// assert_eq!(ols.params(100, 2).unwrap_err().to_string(),
///     "--kmeans-algorithm applies to --centers kmeans only, not ols");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct FitSettings {
    /// `--centres`.
    pub centres: Centres,
    /// `--max-centres` (OLS: the most; k-means and random: exactly).
    pub max_centres: Option<usize>,
    /// `--candidates` (OLS: a seeded subsample of this many training rows).
    pub candidates: Option<usize>,
    /// `--selection-rows` (OLS: select on a seeded subsample of this many training
    /// rows, weights on all; default [`AUTO_SELECTION_ROWS`] above that many rows).
    pub selection_rows: Option<usize>,
    /// `--ols-stream` (OLS: precision of the streaming passes; the library's default,
    /// f32, if not given).
    pub ols_stream: Option<rbf::StreamPrecision>,
    /// `--kmeans-algorithm` (k-means: whose Lloyd iterations; the library's default if
    /// not given).
    pub kmeans_algorithm: Option<KMeansAlgorithm>,
    /// `--kmeans-init` (k-means: the seeding; the library's default if not given).
    pub kmeans_init: Option<KMeansInit>,
    /// `--n-init` (k-means: seeded starts, the lowest inertia kept).
    pub n_init: Option<usize>,
    /// `--degree` (the polynomial tail on unit-box inputs; unset: the bias).
    pub degree: Option<PolyTail>,
    /// `--tol` (OLS ρ: stop once 1 − ΣERR < ρ).
    pub tol: Option<f64>,
    /// `--stop` (OLS: press, gcv, err:ρ or k:K).
    pub stop: Option<StopArg>,
    /// `--kernel`.
    pub kernel: Kernel,
    /// `--width`.
    pub width: WidthArg,
    /// `--ridge`.
    pub ridge: f64,
    /// `--standardize`.
    pub standardize: bool,
    /// `--seed`.
    pub seed: u64,
}

impl Default for FitSettings {
    fn default() -> Self {
        Self {
            centres: Centres::Ols,
            max_centres: None,
            candidates: None,
            selection_rows: None,
            ols_stream: None,
            kmeans_algorithm: None,
            kmeans_init: None,
            n_init: None,
            degree: None,
            tol: None,
            stop: None,
            kernel: Kernel::Gaussian,
            width: WidthArg::Auto,
            ridge: 0.0,
            standardize: false,
            seed: 42,
        }
    }
}

impl FitSettings {
    /// The number of centres asked for (all: none).
    ///
    /// ```
    /// assert_eq!(rbf_cli::settings::FitSettings::default().n_centres(), Some(50));
    /// ```
    pub fn n_centres(&self) -> Option<usize> {
        match self.centres {
            Centres::All => None,
            _ => Some(self.max_centres.unwrap_or(DEFAULT_MAX_CENTRES)),
        }
    }

    /// The most centres for `n_train` training rows: `--stop k:K`, `--max-centres`, or
    /// with `--stop press|gcv` [`auto_max_centres`] (at most the OLS candidates), else
    /// [`DEFAULT_MAX_CENTRES`].
    ///
    /// ```
    /// use rbf_cli::settings::{FitSettings, StopArg};
    /// let s = FitSettings { stop: Some(StopArg::Press), ..FitSettings::default() };
    /// assert_eq!(s.n_centres_for(2500), Some(200));
    /// assert_eq!(FitSettings::default().n_centres_for(2500), Some(50));
    /// ```
    pub fn n_centres_for(&self, n_train: usize) -> Option<usize> {
        match (self.centres, self.stop, self.max_centres) {
            (Centres::All, ..) => None,
            (_, Some(StopArg::K(k)), _) => Some(k),
            (_, _, Some(k)) => Some(k),
            (Centres::Ols, Some(StopArg::Press | StopArg::Gcv), None) => {
                let (sel, cands) = self.ols_rows(n_train);
                let m = cands.or(sel).unwrap_or(n_train).min(n_train);
                Some(auto_max_centres(n_train).min(m.max(1)))
            }
            _ => Some(DEFAULT_MAX_CENTRES),
        }
    }

    /// The OLS ρ: `--stop err:ρ` or `--tol`.
    fn rho(&self) -> Option<f64> {
        match self.stop {
            Some(StopArg::Err(r)) => Some(r),
            _ => self.tol,
        }
    }

    /// The library's size rule for `--stop`.
    fn size_rule(&self) -> rbf::ols::SizeRule {
        match self.stop {
            Some(StopArg::Press) => rbf::ols::SizeRule::Press,
            Some(StopArg::Gcv) => rbf::ols::SizeRule::Gcv,
            _ => rbf::ols::SizeRule::All,
        }
    }

    /// OLS selection rows and candidates for `n_train` training rows: the flags, or on
    /// more than [`AUTO_SELECTION_ROWS`] rows a subsample of that many rows and
    /// [`AUTO_CANDIDATES`] candidates. `None` = every training row.
    ///
    /// ```
    /// let s = rbf_cli::settings::FitSettings::default();
    /// assert_eq!(s.ols_rows(5000), (None, None));
    /// assert_eq!(s.ols_rows(500_000), (Some(20_000), Some(2000)));
    /// let t = rbf_cli::settings::FitSettings { candidates: Some(300), ..s };
    /// assert_eq!(t.ols_rows(500_000), (Some(20_000), Some(300)));
    /// ```
    pub fn ols_rows(&self, n_train: usize) -> (Option<usize>, Option<usize>) {
        if self.centres != Centres::Ols {
            return (None, None);
        }
        let sel = self
            .selection_rows
            .or((n_train > AUTO_SELECTION_ROWS).then_some(AUTO_SELECTION_ROWS))
            .filter(|&s| s < n_train);
        let cands = self.candidates.or(sel.map(|s| AUTO_CANDIDATES.min(s)));
        (sel, cands)
    }

    /// Checks the flag combination for `n_train` training rows of `dim` inputs and builds
    /// the params.
    ///
    /// # Errors
    /// [`SettingsError`]: a flag for another strategy, more centres than the rows (or OLS
    /// candidates) take, or parameters the library rejects (e.g. a negative ridge).
    ///
    /// ```
    /// use rbf_cli::settings::{Centres, FitSettings};
    /// let s = FitSettings { centres: Centres::All, tol: Some(0.01), ..FitSettings::default() };
    /// assert_eq!(s.params(10, 1).unwrap_err().to_string(), "--tol applies to --centers ols only, not all");
    /// ```
    pub fn params(&self, n_train: usize, dim: usize) -> Result<RbfValidParams, SettingsError> {
        self.params_with_width(n_train, dim, self.width.rule())
    }

    /// Whether `--width auto` is a search: with `--stop press|gcv` (and OLS) the width
    /// is chosen on the grid [`WIDTH_GRID`] × the median pairwise distance by the least
    /// criterion; otherwise `auto` is the median rule alone.
    ///
    /// ```
    /// use rbf_cli::settings::{FitSettings, StopArg};
    /// assert!(!FitSettings::default().searches_width());
    /// assert!(FitSettings { stop: Some(StopArg::Press), ..FitSettings::default() }.searches_width());
    /// ```
    pub fn searches_width(&self) -> bool {
        self.centres == Centres::Ols
            && self.width == WidthArg::Auto
            && matches!(self.stop, Some(StopArg::Press | StopArg::Gcv))
    }

    /// [`FitSettings::params`] with the width rule `width` instead of `--width`'s.
    ///
    /// # Errors
    /// As [`FitSettings::params`].
    ///
    /// ```
    /// let s = rbf_cli::settings::FitSettings::default();
    /// let p = s.params_with_width(100, 3, rbf::WidthRule::MedianPairwise { scale: 2.0 }).unwrap();
    /// assert_eq!(p.width(), &rbf::WidthRule::MedianPairwise { scale: 2.0 });
    /// ```
    pub fn params_with_width(
        &self,
        n_train: usize,
        dim: usize,
        width: WidthRule,
    ) -> Result<RbfValidParams, SettingsError> {
        let params = self.build(n_train, width)?;
        if let Some(k) = self.n_centres_for(n_train) {
            check_centres(&params, k, n_train, dim, "training rows", "--max-centers")?;
        }
        Ok(params)
    }

    /// The params for `n_train` training rows without comparing the number of centres
    /// with any rows: for callers that check it against other rows themselves (`rbf cv`:
    /// the smallest fold's) with [`check_centres`].
    ///
    /// # Errors
    /// As [`FitSettings::params`], but for the number of centres.
    ///
    /// ```
    /// let s = rbf_cli::settings::FitSettings { max_centres: Some(500), ..Default::default() };
    /// assert!(s.build(10, rbf::WidthRule::default()).is_ok());
    /// assert!(s.params(10, 1).is_err());
    /// ```
    pub fn build(&self, n_train: usize, width: WidthRule) -> Result<RbfValidParams, SettingsError> {
        self.check_flags()?;
        let k = self.n_centres_for(n_train).unwrap_or(0);
        let (selection_rows, candidates) = self.ols_rows(n_train);
        let centres = match self.centres {
            Centres::Ols => CentreSelection::Ols {
                max_centres: k,
                tol: self.rho().unwrap_or(0.0),
                regularisation: 0.0,
                candidates: match candidates {
                    Some(size) => Candidates::Subsample { size },
                    None => Candidates::TrainingVectors,
                },
            },
            Centres::Kmeans => {
                let mut s =
                    KMeansSettings::new(k).algorithm(self.kmeans_algorithm.unwrap_or_default());
                if let Some(init) = self.kmeans_init {
                    s = s.init(init);
                }
                if let Some(n) = self.n_init {
                    s = s.n_init(n);
                }
                CentreSelection::KMeans(s)
            }
            Centres::Random => CentreSelection::random(k),
            Centres::All => CentreSelection::AllPoints,
        };
        let mut params = RbfParams::new();
        if let Some(degree) = self.degree {
            params = params.degree(degree);
        }
        Ok(params
            .kernel(self.kernel)
            .centres(centres)
            .width(width)
            .ridge(self.ridge)
            .standardise(self.standardize)
            .seed(self.seed)
            .selection_rows(selection_rows)
            .size_rule(self.size_rule())
            .ols_stream(self.ols_stream.unwrap_or_default())
            .check()?)
    }

    fn check_flags(&self) -> Result<(), SettingsError> {
        let only = |flag, applies, ok: bool| {
            if ok {
                Ok(())
            } else {
                Err(SettingsError::NotApplicable {
                    flag,
                    applies,
                    centres: self.centres,
                })
            }
        };
        let ols = self.centres == Centres::Ols;
        only("--tol", "ols", ols || self.tol.is_none())?;
        only("--stop", "ols", ols || self.stop.is_none())?;
        let conflict = |a, b, what| Err(SettingsError::Conflict { a, b, what });
        match self.stop {
            Some(StopArg::Err(_)) if self.tol.is_some() => {
                return conflict("--stop err:RHO", "--tol", "OLS tolerance");
            }
            Some(StopArg::K(_)) if self.max_centres.is_some() => {
                return conflict("--stop k:K", "--max-centers", "number of centres");
            }
            _ => {}
        }
        only("--candidates", "ols", ols || self.candidates.is_none())?;
        only(
            "--selection-rows",
            "ols",
            ols || self.selection_rows.is_none(),
        )?;
        only("--ols-stream", "ols", ols || self.ols_stream.is_none())?;
        only(
            "--kmeans-algorithm",
            "kmeans",
            self.centres == Centres::Kmeans || self.kmeans_algorithm.is_none(),
        )?;
        let kmeans = self.centres == Centres::Kmeans;
        only(
            "--kmeans-init",
            "kmeans",
            kmeans || self.kmeans_init.is_none(),
        )?;
        only("--n-init", "kmeans", kmeans || self.n_init.is_none())?;
        only(
            "--max-centers",
            "ols, kmeans and random",
            self.centres != Centres::All || self.max_centres.is_none(),
        )
    }
}
