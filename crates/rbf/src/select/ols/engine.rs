//! The forward-selection engine (see the module documentation for the numerics).

use faer::{Mat, MatRef, Par};
use rayon::prelude::*;

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
/// Refreshed columns are computed in batches to bound the scratch memory.
const REFRESH_BATCH: usize = 64;

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
        Store::borrowed(candidates),
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
    /// p_j = p̃_j + Σ_{i<since} coef[i] qᵢ.
    coef: Vec<f64>,
    status: Status,
}

/// The growing orthonormal basis and the triangular factors.
struct Basis {
    q: Vec<Vec<f64>>,
    /// Column k of R: k + 1 entries.
    r: Vec<Vec<f64>>,
    /// gₖ = qₖᵀd per output.
    g: Vec<Vec<f64>>,
    energies: Vec<f64>,
}

impl Basis {
    fn len(&self) -> usize {
        self.q.len()
    }

    /// Modified Gram–Schmidt of `v` against basis columns `from..to`, twice
    /// ("twice is enough"), adding the coefficients to `coef[i - from]`.
    fn orthogonalise(&self, v: &mut [f64], from: usize, to: usize, coef: &mut [f64]) {
        for _ in 0..2 {
            for i in from..to {
                let a = dot(&self.q[i], v);
                axpy(-a, &self.q[i], v);
                coef[i - from] += a;
            }
        }
    }
}

struct Exact {
    j: usize,
    w: Vec<f64>,
    coefs: Vec<f64>,
    norm2: f64,
    err: f64,
}

fn maybe_par_map<T: Sync, U: Send>(
    items: &[T],
    par: Par,
    f: impl Fn(&T) -> U + Sync + Send,
) -> Vec<U> {
    if par.degree() > 1 && items.len() > 1 {
        items.par_iter().map(f).collect()
    } else {
        items.iter().map(f).collect()
    }
}

/// Dots of column `p` with every vector of `vs`, in row blocks that keep `p` in L1.
#[inline]
fn dots_into(p: &[f64], vs: &[&[f64]], out: &mut [f64]) {
    const BLOCK: usize = 1024;
    out.fill(0.0);
    let n = p.len();
    let mut start = 0;
    while start < n {
        let end = (start + BLOCK).min(n);
        let pb = &p[start..end];
        for (o, v) in out.iter_mut().zip(vs) {
            *o += dot(pb, &v[start..end]);
        }
        start = end;
    }
}

struct Engine<'s, 'o> {
    store: Store<'s>,
    basis: Basis,
    resid: Vec<Vec<f64>>,
    cands: Vec<Cand>,
    /// p̃_jᵀr_o, m × q.
    cdot: Vec<f64>,
    err: Vec<f64>,
    q: usize,
    target_energy: f64,
    options: &'o OlsOptions<'o>,
}

impl Engine<'_, '_> {
    fn live(&self) -> Vec<usize> {
        (0..self.cands.len())
            .filter(|&j| self.cands[j].status == Status::Live)
            .collect()
    }

    /// One streaming pass over the live candidates: projections on basis columns
    /// `from..to` (accumulated into the energy estimates) and on the residuals.
    fn pass(&mut self, from: usize, to: usize) {
        let live = self.live();
        let q = self.q;
        let nb = to - from;
        let s = nb + q;
        let mut out = vec![0.0; live.len() * s];
        {
            let vs: Vec<&[f64]> = self.basis.q[from..to]
                .iter()
                .map(Vec::as_slice)
                .chain(self.resid.iter().map(Vec::as_slice))
                .collect();
            let store = &self.store;
            let mut rows: Vec<&mut [f64]> = out.chunks_mut(s).collect();
            for_each_chunk_mut(&mut rows, self.options.par, 8, |start, chunk| {
                for (k, row) in chunk.iter_mut().enumerate() {
                    dots_into(store.col(live[start + k]), &vs, row);
                }
            });
        }
        for (k, &j) in live.iter().enumerate() {
            let row = &out[k * s..(k + 1) * s];
            self.cands[j].proj2 += row[..nb].iter().map(|a| a * a).sum::<f64>();
            self.cdot[j * q..(j + 1) * q].copy_from_slice(&row[nb..]);
        }
    }

    /// Refreshes candidates whose estimate lost too many digits, then updates
    /// eligibility and the ERR estimates.
    fn settle(&mut self) {
        let live = self.live();
        let nb = self.basis.len();
        let q = self.q;
        let need: Vec<usize> = live
            .iter()
            .copied()
            .filter(|&j| {
                let c = &self.cands[j];
                c.since < nb && c.base2 - c.proj2 <= REFRESH * c.base2
            })
            .collect();
        for batch in need.chunks(REFRESH_BATCH) {
            let results = {
                let (store, basis, resid, cands) =
                    (&self.store, &self.basis, &self.resid, &self.cands);
                maybe_par_map(batch, self.options.par, |&j| {
                    let since = cands[j].since;
                    let mut w = store.col(j).to_vec();
                    let mut ext = vec![0.0; nb - since];
                    basis.orthogonalise(&mut w, since, nb, &mut ext);
                    let norm2 = dot(&w, &w);
                    let cd: Vec<f64> = resid.iter().map(|r| dot(&w, r)).collect();
                    (w, ext, norm2, cd)
                })
            };
            for (&j, (w, ext, norm2, cd)) in batch.iter().zip(results) {
                self.store.replace(j, &w);
                let c = &mut self.cands[j];
                c.coef.extend_from_slice(&ext);
                c.since = nb;
                c.base2 = norm2;
                c.proj2 = 0.0;
                self.cdot[j * q..(j + 1) * q].copy_from_slice(&cd);
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

    /// Explicit orthogonalisation of candidate `j` against the whole basis (twice).
    fn exact(&self, j: usize) -> Exact {
        let nb = self.basis.len();
        let c = &self.cands[j];
        let mut w = self.store.col(j).to_vec();
        let mut coefs = vec![0.0; nb];
        coefs[..c.coef.len()].copy_from_slice(&c.coef);
        let mut add = vec![0.0; nb];
        self.basis.orthogonalise(&mut w, 0, nb, &mut add);
        for (a, b) in coefs.iter_mut().zip(&add) {
            *a += b;
        }
        let norm2 = dot(&w, &w);
        let num: f64 = self.resid.iter().map(|r| dot(&w, r).powi(2)).sum();
        let err = num / ((norm2 + self.options.regularisation) * self.target_energy);
        Exact {
            j,
            w,
            coefs,
            norm2,
            err,
        }
    }

    /// The next pick: best estimate, confirmed on exact ERRs among near-ties.
    fn choose(&mut self) -> Option<Exact> {
        loop {
            let live = self.live();
            let mut best: Option<usize> = None;
            for &j in &live {
                if best.is_none_or(|b| self.err[j] > self.err[b]) {
                    best = Some(j);
                }
            }
            let best = best?;
            let threshold = self.err[best] * (1.0 - TIE);
            let contenders: Vec<usize> = live
                .into_iter()
                .filter(|&j| self.err[j] >= threshold)
                .collect();
            let exact = maybe_par_map(&contenders, self.options.par, |&j| self.exact(j));
            let mut chosen: Option<Exact> = None;
            for e in exact {
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
                return chosen;
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
        let mut gk = Vec::with_capacity(self.q);
        for r in &mut self.resid {
            let g = dot(&w, r);
            axpy(-g, &w, r);
            gk.push(g);
        }
        let lam = self.options.regularisation;
        let explained: f64 = gk.iter().map(|g| g * g).sum();
        self.basis.q.push(w);
        self.basis.r.push(coefs);
        self.basis.g.push(gk);
        self.basis.energies.push(norm2);
        explained * (norm2 / (norm2 + lam)) / self.target_energy
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
    let resid: Vec<Vec<f64>> = (0..q)
        .map(|o| (0..n).map(|i| targets[(i, o)]).collect())
        .collect();
    let target_energy: f64 = resid.iter().map(|r| dot(r, r)).sum();
    if target_energy == 0.0 {
        return Err(OlsError::ZeroTarget);
    }

    let mut eng = Engine {
        store,
        basis: Basis {
            q: Vec::new(),
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
    };

    // Forced columns, in order.
    let mut forced_errs = Vec::with_capacity(p);
    for k in 0..p {
        let mut w: Vec<f64> = (0..n).map(|i| forced[(i, k)]).collect();
        let orig2 = dot(&w, &w);
        let nb = eng.basis.len();
        let mut coefs = vec![0.0; nb];
        eng.basis.orthogonalise(&mut w, 0, nb, &mut coefs);
        let norm2 = dot(&w, &w);
        if !(norm2 > options.collinearity_tol * orig2 && norm2 > 0.0) {
            return Err(OlsError::ForcedCollinear { column: k });
        }
        forced_errs.push(eng.commit(w, coefs, norm2));
    }

    // Candidates: energies, then one pass against the forced basis and the residuals.
    let mut norms = vec![0.0; m];
    {
        let store = &eng.store;
        for_each_chunk_mut(&mut norms, options.par, 64, |start, chunk| {
            for (k, v) in chunk.iter_mut().enumerate() {
                let c = store.col(start + k);
                *v = dot(c, c);
            }
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
        let Some(e) = eng.choose() else {
            break StopReason::Exhausted;
        };
        let j = e.j;
        let err = eng.commit(e.w, e.coefs, e.norm2);
        eng.cands[j].status = Status::Selected;
        eng.err[j] = 0.0;
        cum += err;
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
            let nb = eng.basis.len();
            eng.pass(nb - 1, nb);
            eng.settle();
        }
    };

    let t = eng.basis.len();
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
    })
}
