//! The forward-selection engine (see the module documentation for the numerics).

use faer::linalg::matmul::matmul;
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};

use super::errors::OlsError;
use super::options::{OlsOptions, OlsProgress};
use super::path::{OlsPath, Pick, StopReason};
use super::store::Store;
use crate::check::first_non_finite;
use crate::parallel::{axpy, dot, for_each_chunk_mut};

/// A candidate is refreshed (deflated in place) once its running energy estimate falls
/// to this fraction of its stored column's energy: at most 3 of 16 digits are lost to
/// the cancellation in ‖p̃‖² − Σ(qᵢᵀp̃)² before the estimate is made exact again.
const REFRESH: f64 = 1e-3;
/// Candidates whose estimated ERR is within this relative distance of the best one are
/// re-evaluated exactly before a pick is committed. The estimates' relative error is
/// below ~10⁻¹⁰ (k·ε/REFRESH), so the true best is always among them.
const TIE: f64 = 1e-8;
/// Refreshed columns are deflated in blocks (matrix products) of at most this many
/// columns, or fewer so that a block stays below 2²¹ doubles (16 MB).
const REFRESH_BATCH: usize = 256;

/// Runs forward selection on borrowed candidate columns.
///
/// - `candidates`: n × m, one candidate per column (kernel columns of candidate centres,
///   or any regressors);
/// - `forced`: n × p, always included first and in order (may have 0 columns);
/// - `targets`: n × q, q ≥ 1; with several outputs the ERRs are summed over them.
///
/// The candidate matrix is read, never written (columns that need refreshing are
/// copied); see [`forward_select_owned`] to let the engine overwrite it instead.
///
/// # Errors
/// [`OlsError::NonFinite`], [`OlsError::NoSamples`], [`OlsError::ZeroTarget`],
/// [`OlsError::ForcedCollinear`], [`OlsError::InvalidOption`].
///
/// # Panics
/// If the three matrices do not have the same number of rows, or `targets` has no column.
///
/// ```
/// use faer::{Mat, Par};
/// use rbf::{forward_select, OlsOptions};
/// // y = 3·x₂ − x₀ with five candidate regressors; a bias column is forced in.
/// let n = 50;
/// let x = Mat::from_fn(n, 5, |i, j| ((i * (j + 2)) as f64 * 0.37).sin());
/// let y = Mat::from_fn(n, 1, |i, _| 3.0 * x[(i, 2)] - x[(i, 0)] + 0.5);
/// let ones = Mat::<f64>::ones(n, 1);
/// let path = forward_select(x.as_ref(), ones.as_ref(), y.as_ref(), &OlsOptions::new(2).par(Par::Seq)).unwrap();
/// assert_eq!(path.selected(), vec![2, 0]);
/// let w = path.weights(2); // bias, x₂, x₀
/// assert!((w[(0, 0)] - 0.5).abs() < 1e-12 && (w[(1, 0)] - 3.0).abs() < 1e-12 && (w[(2, 0)] + 1.0).abs() < 1e-12);
/// assert!((path.cumulative_err() - 1.0).abs() < 1e-12);
/// ```
#[track_caller]
pub fn forward_select(
    candidates: MatRef<'_, f64>,
    forced: MatRef<'_, f64>,
    targets: MatRef<'_, f64>,
    options: &OlsOptions<'_>,
) -> Result<OlsPath, OlsError> {
    check_shapes(candidates.nrows(), forced, targets);
    if let Some((row, col)) = first_non_finite(candidates) {
        return Err(OlsError::NonFinite {
            matrix: "candidates",
            row,
            col,
        });
    }
    run(
        Store::Borrowed(candidates),
        candidates.ncols(),
        forced,
        targets,
        options,
    )
}

/// [`forward_select`] on an owned candidate matrix, which the engine may overwrite with
/// deflated columns: the peak memory stays at one candidate matrix (for large N).
///
/// # Errors
/// As [`forward_select`].
///
/// # Panics
/// As [`forward_select`].
///
/// ```
/// use faer::{mat, Mat};
/// let cand = mat![[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]];
/// let y = mat![[0.0], [2.0], [0.0]];
/// let path = rbf::forward_select_owned(cand, Mat::<f64>::zeros(3, 0).as_ref(), y.as_ref(), &rbf::OlsOptions::new(1)).unwrap();
/// assert_eq!(path.selected(), vec![1]);
/// ```
#[track_caller]
pub fn forward_select_owned(
    candidates: Mat<f64>,
    forced: MatRef<'_, f64>,
    targets: MatRef<'_, f64>,
    options: &OlsOptions<'_>,
) -> Result<OlsPath, OlsError> {
    check_shapes(candidates.nrows(), forced, targets);
    if let Some((row, col)) = first_non_finite(candidates.as_ref()) {
        return Err(OlsError::NonFinite {
            matrix: "candidates",
            row,
            col,
        });
    }
    let m = candidates.ncols();
    run(Store::Owned(candidates), m, forced, targets, options)
}

#[track_caller]
fn check_shapes(n: usize, forced: MatRef<'_, f64>, targets: MatRef<'_, f64>) {
    assert_eq!(
        forced.nrows(),
        n,
        "forced columns have {} rows, candidates {}",
        forced.nrows(),
        n
    );
    assert_eq!(
        targets.nrows(),
        n,
        "targets have {} rows, candidates {}",
        targets.nrows(),
        n
    );
    assert!(targets.ncols() >= 1, "targets need at least one column");
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Status {
    Live,
    Selected,
    Collinear,
}

struct Cand {
    /// ‖p_j‖² of the original column.
    orig2: f64,
    /// ‖p̃_j‖² of the stored (possibly refreshed) column.
    base2: f64,
    /// Σ (qᵢᵀp̃_j)² over the basis columns i ≥ `since`.
    proj2: f64,
    /// Basis columns < `since` are already removed from the stored column.
    since: usize,
    /// p_j = p̃_j + Σ_{i<since} coef[i] qᵢ (`coef.len() == since`).
    coef: Vec<f64>,
    status: Status,
}

/// The growing orthonormal basis (n × capacity, `len` columns used) and the factors.
struct Basis {
    q: Mat<f64>,
    len: usize,
    /// Column k of R: k + 1 entries.
    r: Vec<Vec<f64>>,
    /// gₖ = qₖᵀd per output.
    g: Vec<Vec<f64>>,
    energies: Vec<f64>,
}

impl Basis {
    fn cols(&self, from: usize) -> MatRef<'_, f64> {
        self.q.as_ref().subcols(from, self.len - from)
    }

    /// Block classical Gram–Schmidt applied twice (CGS2, "twice is enough": Giraud,
    /// Langou & Rozložník 2005) of the columns of `w` against basis columns `from..len`:
    /// as accurate as modified Gram–Schmidt with re-orthogonalisation, and it runs as
    /// matrix products. Returns the (len − from) × b coefficients removed.
    fn project_out(&self, mut w: MatMut<'_, f64>, from: usize, par: Par) -> Mat<f64> {
        let qs = self.cols(from);
        let mut total = Mat::<f64>::zeros(qs.ncols(), w.ncols());
        if qs.ncols() == 0 {
            return total;
        }
        for _ in 0..2 {
            let c = qs.transpose() * w.rb();
            matmul(w.rb_mut(), Accum::Add, qs, c.as_ref(), -1.0, par);
            total += &c;
        }
        total
    }

    fn push(&mut self, q: &[f64], coefs: Vec<f64>, g: Vec<f64>, energy: f64) {
        let n = self.q.nrows();
        if self.len == self.q.ncols() {
            let cap = (2 * self.len).max(8);
            let mut grown = Mat::<f64>::zeros(n, cap);
            grown
                .as_mut()
                .subcols_mut(0, self.len)
                .copy_from(self.cols(0));
            self.q = grown;
        }
        self.q.col_as_slice_mut(self.len).copy_from_slice(q);
        self.len += 1;
        self.r.push(coefs);
        self.g.push(g);
        self.energies.push(energy);
    }
}

struct Exact {
    j: usize,
    w: Vec<f64>,
    coefs: Vec<f64>,
    norm2: f64,
    err: f64,
}

struct Engine<'s, 'o> {
    store: Store<'s>,
    basis: Basis,
    /// Residuals r_o = d_o minus their projections on the basis (n × q).
    resid: Mat<f64>,
    cands: Vec<Cand>,
    /// p̃_jᵀr_o, m × q.
    cdot: Vec<f64>,
    err: Vec<f64>,
    q: usize,
    target_energy: f64,
    options: &'o OlsOptions<'o>,
    /// Leverages hᵢᵢ = Σ_k q_ik² of the basis so far (for PRESS).
    lev: Vec<f64>,
}

impl Engine<'_, '_> {
    fn live(&self) -> Vec<usize> {
        (0..self.cands.len())
            .filter(|&j| self.cands[j].status == Status::Live)
            .collect()
    }

    /// One streaming pass over the candidate matrix: its products with basis columns
    /// `from..to` (accumulated into the energy estimates) and with the residuals, as one
    /// faer product [q_from … q_to, r]ᵀP (s × m). Written with the small factor on the
    /// left: faer then streams P without repacking it, which measured 2.5 ms per pass
    /// for a 2500 × 2500 P against 3–4 ms for PᵀV and 4.5–6 ms for hand-written
    /// column-dot loops (AVX2) on one core.
    fn pass(&mut self, from: usize, to: usize) {
        let (q, nb) = (self.q, to - from);
        let n = self.resid.nrows();
        let mut vt = Mat::<f64>::zeros(nb + q, n);
        vt.as_mut()
            .subrows_mut(0, nb)
            .copy_from(self.basis.q.as_ref().subcols(from, nb).transpose());
        vt.as_mut()
            .subrows_mut(nb, q)
            .copy_from(self.resid.transpose());
        let p = self.store.mat();
        let mut out = Mat::<f64>::zeros(nb + q, p.ncols());
        matmul(
            out.as_mut(),
            Accum::Replace,
            vt.as_ref(),
            p,
            1.0,
            self.options.par,
        );
        for (j, c) in self.cands.iter_mut().enumerate() {
            if c.status != Status::Live {
                continue;
            }
            c.proj2 += (0..nb).map(|k| out[(k, j)].powi(2)).sum::<f64>();
            for o in 0..q {
                self.cdot[j * q + o] = out[(nb + o, j)];
            }
        }
    }

    /// Refreshes candidates whose estimate lost too many digits, then updates
    /// eligibility and the ERR estimates.
    fn settle(&mut self) {
        let live = self.live();
        let nb = self.basis.len;
        let (n, q, par) = (self.resid.nrows(), self.q, self.options.par);
        let mut need: Vec<usize> = live
            .iter()
            .copied()
            .filter(|&j| {
                let c = &self.cands[j];
                c.since < nb && c.base2 - c.proj2 <= REFRESH * c.base2
            })
            .collect();
        // Batches of similar `since` deflate against (almost) only the columns they need.
        need.sort_by_key(|&j| self.cands[j].since);
        let batch = REFRESH_BATCH.min((1usize << 21) / n.max(1)).max(1);
        for chunk in need.chunks(batch) {
            let from = self.cands[chunk[0]].since;
            let p = self.store.mat();
            let mut w = Mat::from_fn(n, chunk.len(), |i, k| p[(i, chunk[k])]);
            let c = self.basis.project_out(w.as_mut(), from, par);
            let cd = self.resid.transpose() * &w;
            for (k, &j) in chunk.iter().enumerate() {
                self.store.replace(j, w.col_as_slice(k));
                let cand = &mut self.cands[j];
                // Coefficients on columns before the candidate's own `since` are ~ε
                // (those directions were already removed) and are added all the same.
                cand.coef.resize(nb, 0.0);
                for i in from..nb {
                    cand.coef[i] += c[(i - from, k)];
                }
                cand.since = nb;
                cand.base2 = w.col_as_slice(k).iter().map(|v| v * v).sum();
                cand.proj2 = 0.0;
                for o in 0..q {
                    self.cdot[j * q + o] = cd[(o, k)];
                }
            }
        }
        let (lam, ctol, d) = (
            self.options.regularisation,
            self.options.collinearity_tol,
            self.target_energy,
        );
        for &j in &live {
            let c = &mut self.cands[j];
            let energy = c.base2 - c.proj2;
            if !(energy > ctol * c.orig2 && energy > 0.0) {
                c.status = Status::Collinear;
                self.err[j] = 0.0;
                continue;
            }
            let num: f64 = self.cdot[j * q..(j + 1) * q].iter().map(|v| v * v).sum();
            self.err[j] = num / ((energy + lam) * d);
        }
    }

    /// Explicit orthogonalisation of candidates `js` against the whole basis (CGS2).
    fn exact(&self, js: &[usize]) -> Vec<Exact> {
        let nb = self.basis.len;
        let n = self.resid.nrows();
        let p = self.store.mat();
        let mut w = Mat::from_fn(n, js.len(), |i, k| p[(i, js[k])]);
        let c = self.basis.project_out(w.as_mut(), 0, self.options.par);
        let cd = self.resid.transpose() * &w;
        js.iter()
            .enumerate()
            .map(|(k, &j)| {
                let mut coefs = vec![0.0; nb];
                coefs[..self.cands[j].coef.len()].copy_from_slice(&self.cands[j].coef);
                for (i, v) in coefs.iter_mut().enumerate() {
                    *v += c[(i, k)];
                }
                let w: Vec<f64> = w.col_as_slice(k).to_vec();
                let norm2: f64 = w.iter().map(|v| v * v).sum();
                let num: f64 = (0..self.q).map(|o| cd[(o, k)].powi(2)).sum();
                let err = num / ((norm2 + self.options.regularisation) * self.target_energy);
                Exact {
                    j,
                    w,
                    coefs,
                    norm2,
                    err,
                }
            })
            .collect()
    }

    /// The next pick: best estimate, confirmed on exact ERRs among near-ties.
    /// Every turn of the loop either returns or retires at least one live
    /// candidate (the best one is always a contender), so it ends; a
    /// non-finite score is an error, never compared.
    fn choose(&mut self) -> Result<Option<Exact>, OlsError> {
        loop {
            let live = self.live();
            if let Some(&j) = live.iter().find(|&&j| !self.err[j].is_finite()) {
                return Err(OlsError::Overflow {
                    what: "candidates",
                    value: self.err[j],
                });
            }
            let mut best: Option<usize> = None;
            for &j in &live {
                if best.is_none_or(|b| self.err[j] > self.err[b]) {
                    best = Some(j);
                }
            }
            let Some(best) = best else {
                return Ok(None);
            };
            let threshold = self.err[best] * (1.0 - TIE);
            let contenders: Vec<usize> = live
                .into_iter()
                .filter(|&j| self.err[j] >= threshold)
                .collect();
            let mut chosen: Option<Exact> = None;
            for e in self.exact(&contenders) {
                if !(e.err.is_finite() && e.norm2.is_finite()) {
                    return Err(OlsError::Overflow {
                        what: "candidates",
                        value: if e.err.is_finite() { e.norm2 } else { e.err },
                    });
                }
                if !(e.norm2 > self.options.collinearity_tol * self.cands[e.j].orig2
                    && e.norm2 > 0.0)
                {
                    self.cands[e.j].status = Status::Collinear;
                    self.err[e.j] = 0.0;
                    continue;
                }
                // contenders are in ascending index order: ties keep the lowest index
                if chosen.as_ref().is_none_or(|c| e.err > c.err) {
                    chosen = Some(e);
                }
            }
            if chosen.is_some() {
                return Ok(chosen);
            }
        }
    }

    /// Appends the orthogonal column `w` (with R-column `coefs`), deflates the residuals
    /// and returns its ERR.
    fn commit(&mut self, mut w: Vec<f64>, mut coefs: Vec<f64>, norm2: f64) -> f64 {
        let norm = norm2.sqrt();
        for v in &mut w {
            *v /= norm;
        }
        coefs.push(norm);
        for (h, v) in self.lev.iter_mut().zip(&w) {
            *h += v * v;
        }
        let mut gk = Vec::with_capacity(self.q);
        for o in 0..self.q {
            let r = self.resid.col_as_slice_mut(o);
            let g = dot(&w, r);
            axpy(-g, &w, r);
            gk.push(g);
        }
        let lam = self.options.regularisation;
        let explained: f64 = gk.iter().map(|g| g * g).sum();
        self.basis.push(&w, coefs, gk, norm2);
        explained * (norm2 / (norm2 + lam)) / self.target_energy
    }

    /// PRESS of the current basis: Σ (rᵢ/(1 − hᵢᵢ))² over samples and outputs, from the
    /// residuals and leverages already at hand (O(nq), no pass over the candidates).
    /// +∞ once a leverage reaches 1 (to rounding): that sample is interpolated.
    fn press(&self) -> f64 {
        let mut total = 0.0;
        for (i, &h) in self.lev.iter().enumerate() {
            let m = 1.0 - h;
            if m <= 1e-10 {
                return f64::INFINITY;
            }
            for o in 0..self.q {
                total += (self.resid[(i, o)] / m).powi(2);
            }
        }
        total
    }
}

fn validate(options: &OlsOptions<'_>) -> Result<(), OlsError> {
    if !(options.tol >= 0.0 && options.tol <= 1.0) {
        return Err(OlsError::InvalidOption {
            option: "tol",
            value: options.tol,
        });
    }
    if !crate::check::non_negative(options.regularisation) {
        return Err(OlsError::InvalidOption {
            option: "regularisation",
            value: options.regularisation,
        });
    }
    if !(options.collinearity_tol >= 0.0 && options.collinearity_tol < 1.0) {
        return Err(OlsError::InvalidOption {
            option: "collinearity_tol",
            value: options.collinearity_tol,
        });
    }
    Ok(())
}

fn run(
    store: Store<'_>,
    m: usize,
    forced: MatRef<'_, f64>,
    targets: MatRef<'_, f64>,
    options: &OlsOptions<'_>,
) -> Result<OlsPath, OlsError> {
    validate(options)?;
    let (n, q, p) = (targets.nrows(), targets.ncols(), forced.ncols());
    if n == 0 {
        return Err(OlsError::NoSamples);
    }
    if let Some((row, col)) = first_non_finite(forced) {
        return Err(OlsError::NonFinite {
            matrix: "forced",
            row,
            col,
        });
    }
    if let Some((row, col)) = first_non_finite(targets) {
        return Err(OlsError::NonFinite {
            matrix: "targets",
            row,
            col,
        });
    }
    let resid = targets.to_owned();
    let target_energy: f64 = (0..q).map(|o| resid.col(o).squared_norm_l2()).sum();
    if !target_energy.is_finite() {
        return Err(OlsError::Overflow {
            what: "targets",
            value: target_energy,
        });
    }
    if target_energy == 0.0 {
        return Err(OlsError::ZeroTarget);
    }

    let mut eng = Engine {
        store,
        basis: Basis {
            q: Mat::zeros(n, 0),
            len: 0,
            r: Vec::new(),
            g: Vec::new(),
            energies: Vec::new(),
        },
        resid,
        cands: Vec::new(),
        cdot: vec![0.0; m * q],
        err: vec![0.0; m],
        q,
        target_energy,
        options,
        lev: vec![0.0; n],
    };

    // Forced columns, in order.
    let mut forced_errs = Vec::with_capacity(p);
    for k in 0..p {
        let mut w = forced.subcols(k, 1).to_owned();
        let orig2 = dot(w.col_as_slice(0), w.col_as_slice(0));
        if !orig2.is_finite() {
            return Err(OlsError::Overflow {
                what: "forced columns",
                value: orig2,
            });
        }
        let c = eng.basis.project_out(w.as_mut(), 0, options.par);
        let coefs: Vec<f64> = (0..c.nrows()).map(|i| c[(i, 0)]).collect();
        let w = w.col_as_slice(0).to_vec();
        let norm2 = dot(&w, &w);
        if !(norm2 > options.collinearity_tol * orig2 && norm2 > 0.0) {
            return Err(OlsError::ForcedCollinear { column: k });
        }
        forced_errs.push(eng.commit(w, coefs, norm2));
    }

    // Candidates: energies, then one pass against the forced basis and the residuals.
    let mut norms = vec![0.0; m];
    {
        let p = eng.store.mat();
        for_each_chunk_mut(&mut norms, options.par, 64, |start, chunk| {
            for (k, v) in chunk.iter_mut().enumerate() {
                *v = p.col(start + k).squared_norm_l2();
            }
        });
    }
    if let Some(&e) = norms.iter().find(|e| !e.is_finite()) {
        return Err(OlsError::Overflow {
            what: "candidates",
            value: e,
        });
    }
    eng.cands = norms
        .iter()
        .map(|&e| Cand {
            orig2: e,
            base2: e,
            proj2: 0.0,
            since: 0,
            coef: Vec::new(),
            status: if e > 0.0 {
                Status::Live
            } else {
                Status::Collinear
            },
        })
        .collect();
    eng.pass(0, p);
    eng.settle();
    let first_step_errs = eng.err.clone();
    let mut press = vec![eng.press()];

    let max_picks = options.max_terms.min(m);
    let mut cum: f64 = forced_errs.iter().sum();
    let mut picks: Vec<Pick> = Vec::new();
    let stop = loop {
        if 1.0 - cum < options.tol {
            break StopReason::Tolerance;
        }
        if picks.len() >= max_picks {
            break StopReason::MaxTerms;
        }
        let Some(e) = eng.choose()? else {
            break StopReason::Exhausted;
        };
        let j = e.j;
        let err = eng.commit(e.w, e.coefs, e.norm2);
        eng.cands[j].status = Status::Selected;
        eng.err[j] = 0.0;
        cum += err;
        press.push(eng.press());
        picks.push(Pick {
            index: j,
            err,
            cumulative_err: cum,
        });
        if let Some(f) = options.progress {
            f(OlsProgress {
                picks: picks.len(),
                max_terms: max_picks,
                cumulative_err: cum,
            });
        }
        if picks.len() < max_picks && 1.0 - cum >= options.tol {
            let nb = eng.basis.len;
            eng.pass(nb - 1, nb);
            eng.settle();
        }
    };

    let t = eng.basis.len;
    let r = Mat::from_fn(t, t, |i, k| if i <= k { eng.basis.r[k][i] } else { 0.0 });
    let g = Mat::from_fn(t, q, |i, o| eng.basis.g[i][o]);
    Ok(OlsPath {
        n_outputs: q,
        forced_errs,
        picks,
        first_step_errs,
        r,
        g,
        energies: eng.basis.energies,
        regularisation: options.regularisation,
        target_energy,
        stop,
        press,
        n_samples: n,
    })
}
