//! Options of the OLS engine.

use std::fmt;
use std::str::FromStr;

use faer::Par;

/// Progress of a forward selection, reported after each pick.
///
/// ```
/// let p = rbf::OlsProgress { picks: 3, max_terms: 10, cumulative_err: 0.9 };
/// assert!(p.picks <= p.max_terms);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OlsProgress {
    /// Candidates picked so far.
    pub picks: usize,
    /// The most that may be picked (`min(max_terms, candidates)`).
    pub max_terms: usize,
    /// ΣERR so far, forced columns included.
    pub cumulative_err: f64,
}

/// How the engine streams the candidate matrix once per pick.
///
/// ```
/// assert_eq!(rbf::StreamPrecision::default(), rbf::StreamPrecision::F32);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum StreamPrecision {
    /// The f64 columns themselves: 8 bytes a candidate entry and pick.
    F64,
    /// A copy of the columns in f32 (each scaled by a power of two), products
    /// accumulated in f64: half the bytes a pick. Every candidate's ERR then carries a
    /// rigorous error interval, and every candidate whose interval reaches the best one's
    /// is re-evaluated exactly in f64 before a pick is committed, so the picks are those
    /// of [`StreamPrecision::F64`]. Costs a further 4 bytes per candidate entry of memory.
    #[default]
    F32,
}

impl StreamPrecision {
    /// Every precision, in the order of [`StreamPrecision::NAMES`].
    pub const ALL: [StreamPrecision; 2] = [StreamPrecision::F32, StreamPrecision::F64];
    /// The names [`FromStr`] accepts.
    pub const NAMES: [&'static str; 2] = ["f32", "f64"];

    /// Bytes a pass reads per candidate entry.
    ///
    /// ```
    /// assert_eq!(rbf::StreamPrecision::F32.bytes(), 4);
    /// ```
    pub fn bytes(self) -> usize {
        match self {
            StreamPrecision::F32 => 4,
            StreamPrecision::F64 => 8,
        }
    }

    /// Its name (`f32`, `f64`).
    ///
    /// ```
    /// assert_eq!(rbf::StreamPrecision::F64.name(), "f64");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            StreamPrecision::F32 => "f32",
            StreamPrecision::F64 => "f64",
        }
    }
}

/// A precision name that [`StreamPrecision::from_str`] does not know.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown streaming precision {name:?}; valid names: {}", StreamPrecision::NAMES.join(", "))]
pub struct UnknownStreamPrecision {
    /// The name given.
    pub name: String,
}

impl FromStr for StreamPrecision {
    type Err = UnknownStreamPrecision;

    /// ```
    /// assert_eq!("f32".parse::<rbf::StreamPrecision>().unwrap(), rbf::StreamPrecision::F32);
    /// assert!("f16".parse::<rbf::StreamPrecision>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| UnknownStreamPrecision {
                name: s.to_string(),
            })
    }
}

/// Options of [`crate::forward_select`].
///
/// ```
/// use rbf::OlsOptions;
/// let calls = std::sync::atomic::AtomicUsize::new(0);
/// let count = |_: rbf::OlsProgress| { calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed); };
/// let o = OlsOptions::new(30).tol(0.01).regularisation(1e-4).progress(&count);
/// assert_eq!(o.max_terms, 30);
/// ```
#[derive(Clone, Copy)]
pub struct OlsOptions<'a> {
    /// Maximum number of candidates to pick (forced columns not counted).
    pub max_terms: usize,
    /// ρ ∈ [0, 1]: stop once 1 − ΣERR < ρ. 0 runs to `max_terms`.
    pub tol: f64,
    /// λ ≥ 0 of regularised OLS (Chen, Chng & Alkadhimi 1996); 0 is plain OLS.
    pub regularisation: f64,
    /// A candidate stays eligible while its remaining energy exceeds this fraction of its
    /// own energy ‖p‖². Default 10⁻¹²: the orthogonal part keeps ≥ 10⁻⁶ of the column's
    /// norm, so it is still known to ~10 digits, and the selected columns' condition
    /// number stays far below the least-squares refusal limit.
    pub collinearity_tol: f64,
    /// Parallelism of the streaming passes.
    pub par: Par,
    /// Precision of the streaming passes (the picks do not depend on it).
    pub stream: StreamPrecision,
    /// Called after every pick.
    pub progress: Option<&'a (dyn Fn(OlsProgress) + Sync)>,
}

impl Default for OlsOptions<'_> {
    fn default() -> Self {
        Self {
            max_terms: usize::MAX,
            tol: 0.0,
            regularisation: 0.0,
            collinearity_tol: 1e-12,
            par: faer::get_global_parallelism(),
            stream: StreamPrecision::default(),
            progress: None,
        }
    }
}

impl<'a> OlsOptions<'a> {
    /// Defaults with at most `max_terms` picks.
    ///
    /// ```
    /// assert_eq!(rbf::OlsOptions::new(5).tol, 0.0);
    /// ```
    pub fn new(max_terms: usize) -> Self {
        Self {
            max_terms,
            ..Self::default()
        }
    }

    /// Sets ρ.
    ///
    /// ```
    /// assert_eq!(rbf::OlsOptions::new(5).tol(0.01).tol, 0.01);
    /// ```
    pub fn tol(mut self, rho: f64) -> Self {
        self.tol = rho;
        self
    }

    /// Sets the regularisation λ.
    ///
    /// ```
    /// assert_eq!(rbf::OlsOptions::new(5).regularisation(0.1).regularisation, 0.1);
    /// ```
    pub fn regularisation(mut self, lambda: f64) -> Self {
        self.regularisation = lambda;
        self
    }

    /// Sets the collinearity tolerance.
    ///
    /// ```
    /// assert_eq!(rbf::OlsOptions::new(5).collinearity_tol(1e-10).collinearity_tol, 1e-10);
    /// ```
    pub fn collinearity_tol(mut self, tol: f64) -> Self {
        self.collinearity_tol = tol;
        self
    }

    /// Sets the parallelism.
    ///
    /// ```
    /// assert_eq!(rbf::OlsOptions::new(5).par(faer::Par::Seq).par, faer::Par::Seq);
    /// ```
    pub fn par(mut self, par: Par) -> Self {
        self.par = par;
        self
    }

    /// Sets the precision of the streaming passes.
    ///
    /// ```
    /// use rbf::{OlsOptions, StreamPrecision};
    /// assert_eq!(OlsOptions::new(5).stream(StreamPrecision::F64).stream, StreamPrecision::F64);
    /// ```
    pub fn stream(mut self, precision: StreamPrecision) -> Self {
        self.stream = precision;
        self
    }

    /// Sets the progress callback.
    ///
    /// ```
    /// let f = |p: rbf::OlsProgress| eprintln!("{} picks", p.picks);
    /// assert!(rbf::OlsOptions::new(5).progress(&f).progress.is_some());
    /// ```
    pub fn progress(mut self, f: &'a (dyn Fn(OlsProgress) + Sync)) -> Self {
        self.progress = Some(f);
        self
    }
}

impl fmt::Debug for OlsOptions<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("OlsOptions")
            .field("max_terms", &self.max_terms)
            .field("tol", &self.tol)
            .field("regularisation", &self.regularisation)
            .field("collinearity_tol", &self.collinearity_tol)
            .field("par", &self.par)
            .field("stream", &self.stream)
            .field("progress", &self.progress.map(|_| "callback"))
            .finish()
    }
}
