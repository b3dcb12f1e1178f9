//! The record of one forward-selection run, from which every model size follows.

use faer::linalg::triangular_solve::solve_upper_triangular_in_place;
use faer::{Mat, Par};
use serde::{Deserialize, Serialize};

/// One selected candidate.
///
/// ```
/// let p = rbf::Pick { index: 4, err: 0.5, cumulative_err: 0.75 };
/// assert!(p.err <= p.cumulative_err);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pick {
    /// Column index in the candidate matrix.
    pub index: usize,
    /// Its error-reduction ratio when it was picked.
    pub err: f64,
    /// ΣERR after this pick, forced columns included.
    pub cumulative_err: f64,
}

/// Why forward selection stopped.
///
/// ```
/// assert_ne!(rbf::StopReason::MaxTerms, rbf::StopReason::Tolerance);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// `max_terms` picks were made.
    MaxTerms,
    /// 1 − ΣERR fell below ρ.
    Tolerance,
    /// No candidate had energy left outside the selected span.
    Exhausted,
    /// The size with the least PRESS on the path was kept ([`SizeRule::Press`]).
    Press,
    /// The size with the least GCV on the path was kept ([`SizeRule::Gcv`]).
    Gcv,
}

/// How many of a path's picks a model keeps.
///
/// ```
/// assert_eq!(rbf::ols::SizeRule::default(), rbf::ols::SizeRule::All);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SizeRule {
    /// Every pick (the run stops at `max_terms` or by ρ).
    #[default]
    All,
    /// The size with the least leave-one-out error sum (PRESS), [`OlsPath::best_by_press`].
    Press,
    /// The size with the least generalised cross-validation score, [`OlsPath::best_by_gcv`].
    Gcv,
}

/// A model-selection criterion at one size of the path.
///
/// ```
/// let c = rbf::ols::Criterion { k: 3, press: 1.5, gcv: 0.01 };
/// assert_eq!(c.k, 3);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Criterion {
    /// Picks (forced columns not counted).
    pub k: usize,
    /// PRESS: Σ over samples and outputs of the leave-one-out residual² (eᵢ/(1 − hᵢᵢ))².
    pub press: f64,
    /// GCV: n·RSS/(n − t)², t = forced columns + k.
    pub gcv: f64,
}

/// The path of a forward selection: forced columns, then picks in order.
///
/// The orthogonal decomposition is kept as [F, P_picked] = Q R (Q orthonormal,
/// R upper triangular with R_ii = ‖wᵢ‖) together with gᵢ = qᵢᵀd, so the least-squares
/// coefficients of the forced columns plus the first k picks are R⁻¹g over the leading
/// block: [`OlsPath::weights`] gives any k ≤ [`OlsPath::len`] without refitting.
///
/// ```
/// use faer::{mat, Mat};
/// use rbf::{forward_select, OlsOptions};
/// let cand = mat![[1.0, 0.0], [1.0, 1.0], [1.0, 2.0], [1.0, 3.0]];
/// let y = mat![[1.0], [3.0], [5.0], [7.0]]; // 1 + 2t
/// let path = forward_select(cand.as_ref(), Mat::<f64>::zeros(4, 0).as_ref(), y.as_ref(), &OlsOptions::new(2)).unwrap();
/// assert_eq!(path.len(), 2);
/// let w = path.weights(2);
/// let (a, b) = if path.picks()[0].index == 0 { (w[(0, 0)], w[(1, 0)]) } else { (w[(1, 0)], w[(0, 0)]) };
/// assert!((a - 1.0).abs() < 1e-12 && (b - 2.0).abs() < 1e-12);
/// assert!((path.cumulative_err() - 1.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct OlsPath {
    pub(crate) n_outputs: usize,
    pub(crate) forced_errs: Vec<f64>,
    pub(crate) picks: Vec<Pick>,
    pub(crate) first_step_errs: Vec<f64>,
    /// R of [F, P_picked] = QR, (p + K) × (p + K).
    pub(crate) r: Mat<f64>,
    /// gᵢ = qᵢᵀd, (p + K) × q.
    pub(crate) g: Mat<f64>,
    /// ‖wᵢ‖² of every basis column.
    pub(crate) energies: Vec<f64>,
    pub(crate) regularisation: f64,
    pub(crate) target_energy: f64,
    pub(crate) stop: StopReason,
    /// PRESS after the forced columns and after each pick (len + 1 entries; +∞ where a
    /// sample's leverage reached 1).
    pub(crate) press: Vec<f64>,
    /// Rows of the candidate matrix.
    pub(crate) n_samples: usize,
    /// The threads the streaming passes ran on.
    pub(crate) pass_threads: super::threads::PassThreads,
}

impl OlsPath {
    /// The threads the streaming passes ran on, and why (the engine keeps the
    /// parallelism asked for only where it makes the passes faster: see
    /// [`PassThreads`](super::threads::PassThreads)). How the selection ran, not what it chose.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0], [2.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [2.0]].as_ref(), &Default::default()).unwrap();
    /// assert!(path.pass_threads().threads >= 1);
    /// ```
    pub fn pass_threads(&self) -> &super::threads::PassThreads {
        &self.pass_threads
    }

    /// Number of picks (forced columns not counted).
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0], [2.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [2.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.len(), 1);
    /// assert!(!path.is_empty());
    /// ```
    pub fn len(&self) -> usize {
        self.picks.len()
    }

    /// Whether nothing was picked.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0], [2.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [2.0]].as_ref(), &rbf::OlsOptions::new(0)).unwrap();
    /// assert!(path.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.picks.is_empty()
    }

    /// Number of forced columns.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0], [2.0]].as_ref(), Mat::<f64>::ones(2, 1).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.n_forced(), 1);
    /// ```
    pub fn n_forced(&self) -> usize {
        self.forced_errs.len()
    }

    /// Number of target columns.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0], [2.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0, 0.0], [2.0, 1.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.n_outputs(), 2);
    /// ```
    pub fn n_outputs(&self) -> usize {
        self.n_outputs
    }

    /// ERR of each forced column, in order.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// let ones = Mat::<f64>::ones(2, 1);
    /// let path = rbf::forward_select(mat![[1.0], [2.0]].as_ref(), ones.as_ref(), mat![[1.0], [1.0]].as_ref(), &Default::default()).unwrap();
    /// assert!((path.forced_errs()[0] - 1.0).abs() < 1e-15); // a constant target is all bias
    /// ```
    pub fn forced_errs(&self) -> &[f64] {
        &self.forced_errs
    }

    /// The picks, in order.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.picks()[0].index, 1); // the column aligned with the larger entry
    /// ```
    pub fn picks(&self) -> &[Pick] {
        &self.picks
    }

    /// Candidate indices of the picks, in order.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.selected(), vec![1, 0]);
    /// ```
    pub fn selected(&self) -> Vec<usize> {
        self.picks.iter().map(|p| p.index).collect()
    }

    /// ERR every candidate had at the first step, after the forced columns and before any
    /// pick (0 for candidates collinear with the forced columns): each candidate's
    /// individual contribution, for ranking effects one by one.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert!((path.first_step_errs()[0] - 0.1).abs() < 1e-15);
    /// assert!((path.first_step_errs()[1] - 0.9).abs() < 1e-15);
    /// ```
    pub fn first_step_errs(&self) -> &[f64] {
        &self.first_step_errs
    }

    /// ΣERR over forced columns and all picks.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &rbf::OlsOptions::new(1)).unwrap();
    /// assert!((path.cumulative_err() - 0.9).abs() < 1e-15);
    /// ```
    pub fn cumulative_err(&self) -> f64 {
        self.cumulative_err_at(self.picks.len())
    }

    /// ΣERR of the forced columns plus the first `k` picks.
    ///
    /// # Panics
    /// If `k > self.len()`.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.cumulative_err_at(0), 0.0);
    /// ```
    #[track_caller]
    pub fn cumulative_err_at(&self, k: usize) -> f64 {
        assert!(
            k <= self.picks.len(),
            "k = {k} exceeds the {} picks",
            self.picks.len()
        );
        if k == 0 {
            self.forced_errs.iter().sum()
        } else {
            self.picks[k - 1].cumulative_err
        }
    }

    /// The smallest number of picks k with 1 − ΣERR(k) < ρ, or [`OlsPath::len`] if none.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.terms_for_tol(0.5), 1);
    /// assert_eq!(path.terms_for_tol(0.05), 2);
    /// ```
    pub fn terms_for_tol(&self, rho: f64) -> usize {
        (0..=self.picks.len())
            .find(|&k| 1.0 - self.cumulative_err_at(k) < rho)
            .unwrap_or(self.picks.len())
    }

    /// Why the run stopped.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &rbf::OlsOptions::new(1)).unwrap();
    /// assert_eq!(path.stop_reason(), rbf::StopReason::MaxTerms);
    /// ```
    pub fn stop_reason(&self) -> StopReason {
        self.stop
    }

    /// Σ_o d_oᵀd_o, the targets' energy that ERRs are fractions of.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.target_energy(), 10.0);
    /// ```
    pub fn target_energy(&self) -> f64 {
        self.target_energy
    }

    /// Residual sum of squares (all outputs) of the unregularised least-squares fit on the
    /// forced columns plus the first `k` picks: Σ‖d‖² − Σᵢ‖gᵢ‖².
    ///
    /// # Panics
    /// If `k > self.len()`.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0]].as_ref(), Mat::<f64>::zeros(2, 0).as_ref(), mat![[1.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// assert!((path.residual_sum_squares(1) - 1.0).abs() < 1e-12);
    /// ```
    #[track_caller]
    pub fn residual_sum_squares(&self, k: usize) -> f64 {
        assert!(
            k <= self.picks.len(),
            "k = {k} exceeds the {} picks",
            self.picks.len()
        );
        let t = self.n_forced() + k;
        let explained: f64 = (0..t)
            .map(|i| {
                (0..self.n_outputs)
                    .map(|o| self.g[(i, o)].powi(2))
                    .sum::<f64>()
            })
            .sum();
        (self.target_energy - explained).max(0.0)
    }

    /// Coefficients ((p + k) × q) of the forced columns (first p rows) and the first `k`
    /// picks (in pick order), in terms of the original columns: R⁻¹g on the leading block.
    ///
    /// With λ = 0 these are the least-squares coefficients on those columns (MGS with
    /// re-orthogonalisation gives a Q orthonormal to working precision, so this is as
    /// accurate as a Householder solve); with λ > 0 each gᵢ is shrunk by
    /// ‖wᵢ‖²/(‖wᵢ‖² + λ), the regularised-OLS estimate of Chen, Chng & Alkadhimi (1996),
    /// which is *not* a ridge on the original coefficients.
    ///
    /// # Panics
    /// If `k > self.len()`.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// let ones = Mat::<f64>::ones(3, 1);
    /// let cand = mat![[0.0], [1.0], [2.0]];
    /// let path = rbf::forward_select(cand.as_ref(), ones.as_ref(), mat![[1.0], [2.0], [3.0]].as_ref(), &Default::default()).unwrap();
    /// let w = path.weights(1);
    /// assert!((w[(0, 0)] - 1.0).abs() < 1e-12 && (w[(1, 0)] - 1.0).abs() < 1e-12);
    /// assert!((path.weights(0)[(0, 0)] - 2.0).abs() < 1e-12); // bias only: the mean
    /// ```
    #[track_caller]
    pub fn weights(&self, k: usize) -> Mat<f64> {
        assert!(
            k <= self.picks.len(),
            "k = {k} exceeds the {} picks",
            self.picks.len()
        );
        let t = self.n_forced() + k;
        let lam = self.regularisation;
        let mut x = Mat::from_fn(t, self.n_outputs, |i, o| {
            let e = self.energies[i];
            self.g[(i, o)] * if lam > 0.0 { e / (e + lam) } else { 1.0 }
        });
        solve_upper_triangular_in_place(
            self.r.as_ref().submatrix(0, 0, t, t),
            x.as_mut(),
            Par::Seq,
        );
        x
    }

    /// PRESS of the forced columns plus the first `k` picks: Σ (eᵢ/(1 − hᵢᵢ))² over
    /// samples and outputs, the leave-one-out residuals of the least-squares fit
    /// (λ = 0), from the orthonormal basis the selection builds anyway (hᵢᵢ = Σⱼ qᵢⱼ²):
    /// O(n) per pick, no pass over the candidates. +∞ once a sample's leverage reaches 1.
    ///
    /// # Panics
    /// If `k > self.len()`.
    ///
    /// ```
    /// use faer::Mat;
    /// let n = 40;
    /// let x = Mat::from_fn(n, 3, |i, j| ((i * (j + 2)) as f64 * 0.37).sin());
    /// let y = Mat::from_fn(n, 1, |i, _| 2.0 * x[(i, 1)] + 0.1 * ((i * 7 % 5) as f64 - 2.0));
    /// let path = rbf::forward_select(x.as_ref(), Mat::<f64>::ones(n, 1).as_ref(), y.as_ref(), &Default::default()).unwrap();
    /// // brute-force leave-one-out of the bias + first pick
    /// let sel = path.selected()[0];
    /// let mut press = 0.0;
    /// for out in 0..n {
    ///     let keep: Vec<usize> = (0..n).filter(|&i| i != out).collect();
    ///     let a = Mat::from_fn(n - 1, 2, |i, j| if j == 0 { 1.0 } else { x[(keep[i], sel)] });
    ///     let b = Mat::from_fn(n - 1, 1, |i, _| y[(keep[i], 0)]);
    ///     let w = rbf::lstsq(a.as_ref(), b.as_ref(), &Default::default()).unwrap().coefficients;
    ///     press += (y[(out, 0)] - w[(0, 0)] - w[(1, 0)] * x[(out, sel)]).powi(2);
    /// }
    /// assert!((path.press(1) - press).abs() < 1e-10 * press);
    /// ```
    #[track_caller]
    pub fn press(&self, k: usize) -> f64 {
        assert!(
            k <= self.picks.len(),
            "k = {k} exceeds the {} picks",
            self.picks.len()
        );
        self.press[k]
    }

    /// Generalised cross-validation n·RSS(k)/(n − t)², t = forced columns + k
    /// (+∞ when t ≥ n).
    ///
    /// # Panics
    /// If `k > self.len()`.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]].as_ref(), Mat::<f64>::zeros(3, 0).as_ref(), mat![[1.0], [3.0], [1.0]].as_ref(), &Default::default()).unwrap();
    /// assert!((path.gcv(1) - 3.0 * 2.0 / 4.0).abs() < 1e-12);
    /// ```
    #[track_caller]
    pub fn gcv(&self, k: usize) -> f64 {
        let rss = self.residual_sum_squares(k);
        let t = self.n_forced() + k;
        if t >= self.n_samples {
            return f64::INFINITY;
        }
        let dof = (self.n_samples - t) as f64;
        self.n_samples as f64 * rss / (dof * dof)
    }

    /// PRESS and GCV at every size 0 ..= len while they are finite.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]].as_ref(), Mat::<f64>::zeros(3, 0).as_ref(), mat![[1.0], [3.0], [1.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.criterion()[0].k, 0);
    /// ```
    pub fn criterion(&self) -> Vec<Criterion> {
        (0..=self.picks.len())
            .map(|k| Criterion {
                k,
                press: self.press(k),
                gcv: self.gcv(k),
            })
            .take_while(|c| c.press.is_finite() && c.gcv.is_finite())
            .collect()
    }

    /// The number of picks with the least PRESS (the smallest such k on ties).
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]].as_ref(), Mat::<f64>::zeros(3, 0).as_ref(), mat![[1.0], [3.0], [1.0]].as_ref(), &Default::default()).unwrap();
    /// assert!(path.best_by_press() <= path.len());
    /// ```
    pub fn best_by_press(&self) -> usize {
        argmin((0..=self.picks.len()).map(|k| self.press(k)))
    }

    /// The number of picks with the least GCV (the smallest such k on ties).
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]].as_ref(), Mat::<f64>::zeros(3, 0).as_ref(), mat![[1.0], [3.0], [1.0]].as_ref(), &Default::default()).unwrap();
    /// assert!(path.best_by_gcv() <= path.len());
    /// ```
    pub fn best_by_gcv(&self) -> usize {
        argmin((0..=self.picks.len()).map(|k| self.gcv(k)))
    }

    /// The number of picks `rule` keeps.
    ///
    /// ```
    /// # use faer::{mat, Mat};
    /// # let path = rbf::forward_select(mat![[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]].as_ref(), Mat::<f64>::zeros(3, 0).as_ref(), mat![[1.0], [3.0], [1.0]].as_ref(), &Default::default()).unwrap();
    /// assert_eq!(path.size_for(rbf::ols::SizeRule::All), path.len());
    /// ```
    pub fn size_for(&self, rule: SizeRule) -> usize {
        match rule {
            SizeRule::All => self.picks.len(),
            SizeRule::Press => self.best_by_press(),
            SizeRule::Gcv => self.best_by_gcv(),
        }
    }
}

/// Index of the least value (first on ties; NaN never wins).
fn argmin(values: impl Iterator<Item = f64>) -> usize {
    let mut best = (0, f64::INFINITY);
    for (k, v) in values.enumerate() {
        if v < best.1 {
            best = (k, v);
        }
    }
    best.0
}
