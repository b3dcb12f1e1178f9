//! The forward-selection engine (see the module documentation for the numerics).

use faer::linalg::matmul::matmul;
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};

use super::error::OlsError;
use super::options::{OlsOptions, OlsProgress, StreamPrecision};
use super::path::{OlsPath, Pick, StopReason};
use super::store::{CandidateColumns, Store};
use super::stream::{Columns, Compact, fill_slice, products};
use super::threads::Schedule;
use crate::check::first_non_finite;
use crate::parallel::{axpy, dot};

/// A candidate is refreshed (deflated in place) once its running energy estimate falls
/// to this fraction of its stored column's energy: at most 3 of 16 digits are lost to
/// the cancellation in ‖p̃‖² − Σ(qᵢᵀp̃)² before the estimate is made exact again.
const REFRESH: f64 = 1e-3;
/// Candidates whose estimated ERR is within this relative distance of the best one are
/// re-evaluated exactly before a pick is committed. The estimates' relative error is
/// below ~10⁻¹⁰ (k·ε/REFRESH), so the true best is always among them.
const TIE: f64 = 1e-8;
/// With f32 streaming, a candidate is also refreshed once the error bound of its energy
/// estimate reaches this fraction of the estimate: its ERR interval stays narrow, so few
/// candidates need an exact evaluation before a pick.
const F32_ENERGY_REL: f64 = 0.5;
/// With f32 streaming, contenders are evaluated exactly in batches of this many, best
/// upper bound first, until no remaining upper bound can beat the best exact ERR.
const EXACT_BATCH: usize = 8;
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

/// [`forward_select`] on candidate columns generated on demand ([`CandidateColumns`]),
/// e.g. kernel columns of candidate centres: with [`StreamPrecision::F32`] (the default)
/// no f64 candidate matrix is ever held, only the f32 copy the passes stream (4 bytes an
/// entry) and the few columns evaluated exactly at each pick, generated again. With
/// [`StreamPrecision::F64`] the columns are generated once into a matrix.
///
/// # Errors
/// As [`forward_select`]; a non-finite generated entry is [`OlsError::NonFinite`].
///
/// # Panics
/// As [`forward_select`].
///
/// ```
/// use faer::{Mat, MatMut};
/// // The columns of a stored matrix, generated: the same picks as `forward_select`.
/// struct Cols(Mat<f64>);
/// impl rbf::CandidateColumns for Cols {
///     fn nrows(&self) -> usize { self.0.nrows() }
///     fn ncols(&self) -> usize { self.0.ncols() }
///     fn columns_into(&self, cols: &[usize], mut out: MatMut<'_, f64>) {
///         for (k, &j) in cols.iter().enumerate() {
///             out.rb_mut().col_mut(k).copy_from(self.0.col(j));
///         }
///     }
/// }
/// use faer::prelude::ReborrowMut;
/// let x = Mat::from_fn(60, 8, |i, j| ((i * (j + 3)) as f64 * 0.29).cos());
/// let y = Mat::from_fn(60, 1, |i, _| x[(i, 5)] - 2.0 * x[(i, 1)]);
/// let none = Mat::<f64>::zeros(60, 0);
/// let opts = rbf::OlsOptions::new(2);
/// let a = rbf::forward_select_columns(&Cols(x.clone()), none.as_ref(), y.as_ref(), &opts).unwrap();
/// let b = rbf::forward_select(x.as_ref(), none.as_ref(), y.as_ref(), &opts).unwrap();
/// assert_eq!(a.selected(), b.selected());
/// ```
#[track_caller]
pub fn forward_select_columns(
    candidates: &dyn CandidateColumns,
    forced: MatRef<'_, f64>,
    targets: MatRef<'_, f64>,
    options: &OlsOptions<'_>,
) -> Result<OlsPath, OlsError> {
    let (n, m) = (candidates.nrows(), candidates.ncols());
    check_shapes(n, forced, targets);
    match options.stream {
        StreamPrecision::F32 => run(Store::Generated(candidates), m, forced, targets, options),
        StreamPrecision::F64 => {
            let all: Vec<usize> = (0..m).collect();
            let mat = Store::Generated(candidates).gather(n, &all);
            forward_select_owned(mat, forced, targets, options)
        }
    }
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
    /// Σ |qᵢᵀp̃_j| over the same basis columns as `proj2` (for the f32 error bound).
    abs_proj: f64,
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
    /// wᵀr_o per output.
    cd: Vec<f64>,
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
    /// With f32 streaming: the f32 copy of the stored columns, and every live
    /// candidate's ERR interval [lo, hi] (the true ERR lies within it).
    compact: Option<Compact>,
    err_lo: Vec<f64>,
    err_hi: Vec<f64>,
    /// Whether refreshed columns are written to the f64 store (then a column read back
    /// is the refreshed one), or only to the f32 copy (a column read back is the
    /// original candidate): with f32 streaming a borrowed matrix is never copied and a
    /// generated one never stored.
    keeps_refreshed: bool,
    q: usize,
    target_energy: f64,
    options: &'o OlsOptions<'o>,
    /// Leverages hᵢᵢ = Σ_k q_ik² of the basis so far (for PRESS).
    lev: Vec<f64>,
    /// The threads of the streaming passes.
    schedule: Schedule,
}

/// Candidates per block of the initial scan: a block of f64 columns stays in cache
/// while its energies, f32 copy and first products are taken.
const SCAN_BLOCK: usize = 32;

/// What the initial scan learns of one block of candidates.
struct ScanBlock {
    energies: Vec<f64>,
    /// Products with the forced basis columns and the residuals, `s` per candidate.
    products: Vec<f64>,
    non_finite: Option<(usize, usize)>,
}

impl Engine<'_, '_> {
    /// Reads every candidate once, block by block and in parallel where allowed: its
    /// energy ‖p‖², its f32 copy (f32 streaming), and its products with the `p` forced
    /// basis columns and the residuals (in f64). Sets up the candidates' state.
    fn scan(&mut self, p: usize) -> Result<(), OlsError> {
        let (n, q, m) = (self.resid.nrows(), self.q, self.cdot.len() / self.q);
        let s = p + q;
        let mut vecs: Vec<&[f64]> = (0..p).map(|k| self.basis.q.col_as_slice(k)).collect();
        vecs.extend((0..q).map(|o| self.resid.col_as_slice(o)));
        let store = &self.store;
        let read = |j0: usize, cols: usize, dst: Option<(&mut [f32], &mut [f64])>| {
            let idx: Vec<usize> = (j0..j0 + cols).collect();
            let block = match store.mat() {
                Some(mat) => BlockCols::View(mat.subcols(j0, cols)),
                None => BlockCols::Owned(store.gather(n, &idx)),
            };
            let b = block.as_ref();
            let non_finite = if store.mat().is_some() {
                None // checked before the run
            } else {
                first_non_finite(b).map(|(i, k)| (i, j0 + k))
            };
            let energies: Vec<f64> = (0..cols).map(|k| b.col(k).squared_norm_l2()).collect();
            if let Some((data, scale)) = dst {
                for k in 0..cols {
                    let col = b.col(k);
                    scale[k] = match col.try_as_col_major() {
                        Some(c) => fill_slice(c.as_slice(), &mut data[k * n..(k + 1) * n]),
                        None => {
                            let v: Vec<f64> = (0..n).map(|i| col[i]).collect();
                            fill_slice(&v, &mut data[k * n..(k + 1) * n])
                        }
                    };
                }
            }
            let local: Vec<usize> = (0..cols).collect();
            let mut products_out = vec![0.0; cols * s];
            products(&Columns::F64(b), &local, &vecs, &mut products_out, Par::Seq);
            ScanBlock {
                energies,
                products: products_out,
                non_finite,
            }
        };
        let parallel = self.options.par.degree() > 1 && m > SCAN_BLOCK;
        let mut compact =
            (self.options.stream == StreamPrecision::F32).then(|| Compact::zeroed(n, m));
        let blocks: Vec<ScanBlock> = match compact.as_mut() {
            Some(c) => {
                let per = SCAN_BLOCK * n.max(1);
                let work = |(b, (data, scale)): (usize, (&mut [f32], &mut [f64]))| {
                    read(b * SCAN_BLOCK, scale.len(), Some((data, scale)))
                };
                let (data, scale) = (&mut c.data, &mut c.scale);
                if parallel {
                    use rayon::prelude::*;
                    data.par_chunks_mut(per)
                        .zip(scale.par_chunks_mut(SCAN_BLOCK))
                        .enumerate()
                        .map(work)
                        .collect()
                } else {
                    data.chunks_mut(per)
                        .zip(scale.chunks_mut(SCAN_BLOCK))
                        .enumerate()
                        .map(work)
                        .collect()
                }
            }
            None => {
                let starts: Vec<usize> = (0..m).step_by(SCAN_BLOCK).collect();
                let work = |&j0: &usize| read(j0, SCAN_BLOCK.min(m - j0), None);
                if parallel {
                    use rayon::prelude::*;
                    starts.par_iter().map(work).collect()
                } else {
                    starts.iter().map(work).collect()
                }
            }
        };
        let mut cands = Vec::with_capacity(m);
        for (b, blk) in blocks.iter().enumerate() {
            if let Some((row, col)) = blk.non_finite {
                return Err(OlsError::NonFinite {
                    matrix: "candidates",
                    row,
                    col,
                });
            }
            for (k, &e) in blk.energies.iter().enumerate() {
                if !e.is_finite() {
                    return Err(OlsError::Overflow {
                        what: "candidates",
                        value: e,
                    });
                }
                let j = b * SCAN_BLOCK + k;
                let o = &blk.products[k * s..(k + 1) * s];
                self.cdot[j * q..(j + 1) * q].copy_from_slice(&o[p..]);
                cands.push(Cand {
                    orig2: e,
                    base2: e,
                    proj2: o[..p].iter().map(|v| v * v).sum(),
                    since: 0,
                    coef: Vec::new(),
                    abs_proj: o[..p].iter().map(|v| v.abs()).sum(),
                    status: if e > 0.0 {
                        Status::Live
                    } else {
                        Status::Collinear
                    },
                });
            }
        }
        self.cands = cands;
        self.compact = compact;
        Ok(())
    }

    /// The live candidates, once every one has a finite score (a non-finite one is an
    /// error, never compared).
    fn live_scored(&self) -> Result<Vec<usize>, OlsError> {
        let live = self.live();
        match live.iter().find(|&&j| !self.err[j].is_finite()) {
            Some(&j) => Err(OlsError::Overflow {
                what: "candidates",
                value: self.err[j],
            }),
            None => Ok(live),
        }
    }

    fn live(&self) -> Vec<usize> {
        (0..self.cands.len())
            .filter(|&j| self.cands[j].status == Status::Live)
            .collect()
    }

    /// One streaming pass over the live candidates: their products with basis columns
    /// `from..to` (accumulated into the energy estimates) and with the residuals, read
    /// from the f64 columns, or from their f32 copy where there is one (`stream.rs`).
    fn pass(&mut self, from: usize, to: usize) {
        let (q, nb) = (self.q, to - from);
        let s = nb + q;
        let live = self.live();
        let mut vecs: Vec<&[f64]> = (from..to).map(|k| self.basis.q.col_as_slice(k)).collect();
        vecs.extend((0..q).map(|o| self.resid.col_as_slice(o)));
        let mut out = vec![0.0; live.len() * s];
        let columns = match (&self.compact, self.store.mat()) {
            (Some(c), _) => Columns::F32(c),
            (None, Some(p)) => Columns::F64(p),
            (None, None) => unreachable!("generated columns always stream their f32 copy"),
        };
        let (par, start) = (self.schedule.par(), std::time::Instant::now());
        products(&columns, &live, &vecs, &mut out, par);
        let entries = live.len() * self.resid.nrows();
        self.schedule
            .record(par, start.elapsed().as_secs_f64(), entries);
        for (t, &j) in live.iter().enumerate() {
            let o = &out[t * s..(t + 1) * s];
            let c = &mut self.cands[j];
            c.proj2 += o[..nb].iter().map(|v| v * v).sum::<f64>();
            c.abs_proj += o[..nb].iter().map(|v| v.abs()).sum::<f64>();
            self.cdot[j * q..(j + 1) * q].copy_from_slice(&o[nb..]);
        }
    }

    /// A bound on the error of candidate `j`'s energy estimate base2 − proj2 when the
    /// passes read the f32 copy: each projection ĉᵢ is within e of the exact one, so
    /// |Σĉᵢ² − Σcᵢ²| ≤ 2e·Σ|ĉᵢ| + k·e², plus the f64 rounding of the sums.
    fn energy_error(&self, j: usize, compact: &Compact) -> f64 {
        let c = &self.cands[j];
        let k = (self.basis.len - c.since) as f64;
        if k == 0.0 {
            return 0.0;
        }
        let e = compact.error_bound(j, c.base2.sqrt(), 1.0 + 1e-12);
        2.0 * e * c.abs_proj + k * e * e + 4.0 * (k + 2.0) * f64::EPSILON * c.base2
    }

    /// Refreshes candidates whose estimate lost too many digits, then updates
    /// eligibility and the ERR estimates.
    fn settle(&mut self) {
        let live = self.live();
        let nb = self.basis.len;
        let (n, q, par) = (self.resid.nrows(), self.q, self.options.par);
        let ctol = self.options.collinearity_tol;
        let mut need: Vec<usize> = live
            .iter()
            .copied()
            .filter(|&j| {
                let c = &self.cands[j];
                let energy = c.base2 - c.proj2;
                if c.since >= nb {
                    return false;
                }
                // With f32 streaming the ERR intervals carry the cancellation's error
                // too; a candidate is refreshed when it contends for a pick
                // (`write_back`), or when its interval has grown useless.
                match &self.compact {
                    None => energy <= REFRESH * c.base2,
                    Some(cm) => self.energy_error(j, cm) > F32_ENERGY_REL * energy,
                }
            })
            .collect();
        // Batches of similar `since` deflate against (almost) only the columns they need.
        need.sort_by_key(|&j| self.cands[j].since);
        let batch = REFRESH_BATCH.min((1usize << 21) / n.max(1)).max(1);
        let keeps = self.keeps_refreshed;
        for chunk in need.chunks(batch) {
            // A stored column is already deflated up to its `since`; a generated one is
            // the original and is deflated against the whole basis.
            let from = if keeps { self.cands[chunk[0]].since } else { 0 };
            let mut w = self.store.gather(n, chunk);
            let c = self.basis.project_out(w.as_mut(), from, par);
            let cd = self.resid.transpose() * &w;
            for (k, &j) in chunk.iter().enumerate() {
                if keeps {
                    self.store.replace(j, w.col_as_slice(k));
                }
                let cand = &mut self.cands[j];
                // Coefficients on columns before the candidate's own `since` are ~ε
                // (those directions were already removed) and are added all the same.
                if !keeps {
                    cand.coef.clear();
                }
                cand.coef.resize(nb, 0.0);
                for i in from..nb {
                    cand.coef[i] += c[(i - from, k)];
                }
                cand.since = nb;
                cand.base2 = w.col_as_slice(k).iter().map(|v| v * v).sum();
                cand.proj2 = 0.0;
                cand.abs_proj = 0.0;
                for o in 0..q {
                    self.cdot[j * q + o] = cd[(o, k)];
                }
                if let Some(cm) = self.compact.as_mut() {
                    cm.set(j, w.col_as_slice(k));
                }
            }
        }
        let (lam, d) = (self.options.regularisation, self.target_energy);
        let resid_norms: Vec<f64> = (0..q).map(|o| self.resid.col(o).norm_l2()).collect();
        for &j in &live {
            let de = match &self.compact {
                Some(cm) => self.energy_error(j, cm),
                None => 0.0,
            };
            let c = &self.cands[j];
            let energy = c.base2 - c.proj2;
            let collinear = match self.compact {
                // f32: only when certainly at or below the limit (else refreshed above)
                Some(_) => !(energy + de > ctol * c.orig2 && energy + de > 0.0),
                None => !(energy > ctol * c.orig2 && energy > 0.0),
            };
            if collinear {
                self.cands[j].status = Status::Collinear;
                self.err[j] = 0.0;
                continue;
            }
            let cd = &self.cdot[j * q..(j + 1) * q];
            let num: f64 = cd.iter().map(|v| v * v).sum();
            self.err[j] = num / ((energy + lam) * d);
            if let Some(cm) = &self.compact {
                let pn = c.base2.sqrt();
                let (mut lo, mut hi) = (0.0, 0.0);
                for (v, rn) in cd.iter().zip(&resid_norms) {
                    let f = cm.error_bound(j, pn, rn * (1.0 + 1e-12));
                    lo += (v.abs() - f).max(0.0).powi(2);
                    hi += (v.abs() + f).powi(2);
                }
                let (e_lo, e_hi) = (energy - de, energy + de);
                self.err_lo[j] = lo / ((e_hi + lam) * d);
                self.err_hi[j] = if e_lo + lam > 0.0 {
                    hi / ((e_lo + lam) * d)
                } else {
                    f64::INFINITY
                };
            }
        }
    }

    /// Explicit orthogonalisation of candidates `js` against the whole basis (CGS2).
    fn exact(&self, js: &[usize]) -> Vec<Exact> {
        let nb = self.basis.len;
        let n = self.resid.nrows();
        let mut w = self.store.gather(n, js);
        let c = self.basis.project_out(w.as_mut(), 0, self.options.par);
        let cd = self.resid.transpose() * &w;
        let keeps = self.keeps_refreshed;
        js.iter()
            .enumerate()
            .map(|(k, &j)| {
                let mut coefs = vec![0.0; nb];
                if keeps {
                    coefs[..self.cands[j].coef.len()].copy_from_slice(&self.cands[j].coef);
                }
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
                    cd: (0..self.q).map(|o| cd[(o, k)]).collect(),
                }
            })
            .collect()
    }

    /// The next pick: best estimate, confirmed on exact ERRs among near-ties.
    /// Every turn of the loop either returns or retires at least one live
    /// candidate (the best one is always a contender), so it ends; a
    /// non-finite score is an error, never compared.
    fn choose(&mut self) -> Result<Option<Exact>, OlsError> {
        if self.compact.is_some() {
            return self.choose_bounded();
        }
        loop {
            let live = self.live_scored()?;
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
                if !self.eligible(&e)? {
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

    /// Whether an exactly evaluated contender may be picked: a non-finite score is an
    /// error, never compared; one with no energy left beyond the collinearity limit is
    /// retired.
    fn eligible(&mut self, e: &Exact) -> Result<bool, OlsError> {
        if !(e.err.is_finite() && e.norm2.is_finite()) {
            return Err(OlsError::Overflow {
                what: "candidates",
                value: if e.err.is_finite() { e.norm2 } else { e.err },
            });
        }
        if !(e.norm2 > self.options.collinearity_tol * self.cands[e.j].orig2 && e.norm2 > 0.0) {
            self.cands[e.j].status = Status::Collinear;
            self.err[e.j] = 0.0;
            return Ok(false);
        }
        Ok(true)
    }

    /// [`Self::choose`] with f32 streaming: every candidate whose ERR interval reaches
    /// the best lower bound is a contender; contenders are evaluated exactly, highest
    /// upper bound first, until no upper bound left can beat the best exact ERR. The
    /// result is the candidate of largest exact ERR, as with f64 streaming.
    fn choose_bounded(&mut self) -> Result<Option<Exact>, OlsError> {
        // Every turn either returns or retires at least one live candidate.
        loop {
            let live = self.live_scored()?;
            let Some(best_lo) = live.iter().map(|&j| self.err_lo[j]).reduce(f64::max) else {
                return Ok(None);
            };
            let mut order: Vec<usize> = live
                .into_iter()
                .filter(|&j| self.err_hi[j] >= best_lo * (1.0 - TIE))
                .collect();
            // highest upper bound first; equal bounds in ascending index order
            order.sort_by(|&a, &b| self.err_hi[b].total_cmp(&self.err_hi[a]).then(a.cmp(&b)));
            let mut chosen: Option<Exact> = None;
            for batch in order.chunks(EXACT_BATCH) {
                if let Some(c) = &chosen
                    && self.err_hi[batch[0]] < c.err * (1.0 - TIE)
                {
                    break;
                }
                for e in self.exact(batch) {
                    if !self.eligible(&e)? {
                        continue;
                    }
                    self.write_back(&e);
                    // ties keep the lowest index, as with f64 streaming
                    if chosen
                        .as_ref()
                        .is_none_or(|c| e.err > c.err || (e.err == c.err && e.j < c.j))
                    {
                        chosen = Some(e);
                    }
                }
            }
            if chosen.is_some() {
                return Ok(chosen);
            }
        }
    }

    /// Stores a candidate's exact orthogonalisation as its column (a refresh): its
    /// estimates restart exact, so its ERR interval is narrow again at the next picks.
    fn write_back(&mut self, e: &Exact) {
        let nb = self.basis.len;
        if self.keeps_refreshed {
            self.store.replace(e.j, &e.w);
        }
        if let Some(cm) = self.compact.as_mut() {
            cm.set(e.j, &e.w);
        }
        let c = &mut self.cands[e.j];
        c.coef.clone_from(&e.coefs);
        c.since = nb;
        c.base2 = e.norm2;
        c.proj2 = 0.0;
        c.abs_proj = 0.0;
        let q = self.q;
        self.cdot[e.j * q..(e.j + 1) * q].copy_from_slice(&e.cd);
        self.err[e.j] = e.err;
        self.err_lo[e.j] = e.err * (1.0 - TIE);
        self.err_hi[e.j] = e.err * (1.0 + TIE);
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
    let (resid, target_energy) = checked_targets(forced, targets)?;
    let mut eng = Engine::new(store, m, resid, target_energy, options);
    let forced_errs = eng.force(forced)?;
    // Candidates: their energies, their f32 copy, and the first pass against the forced
    // basis and the residuals, all from one read of the candidates block by block. The
    // first pass is in f64: it makes the first-step ERRs (each candidate's own ERR after
    // the forced columns) exact.
    eng.scan(forced.ncols())?;
    eng.settle();
    let first_step_errs = eng.err.clone();
    let mut press = vec![eng.press()];
    let (picks, stop) = eng.pick_all(forced_errs.iter().sum(), &mut press)?;
    let t = eng.basis.len;
    let q = eng.q;
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
        n_samples: targets.nrows(),
        pass_threads: eng.schedule.summary(),
    })
}

/// The residuals to start from (the targets) and their energy Σ‖d_o‖², once the
/// forced columns and the targets are known finite and the targets not all zero.
fn checked_targets(
    forced: MatRef<'_, f64>,
    targets: MatRef<'_, f64>,
) -> Result<(Mat<f64>, f64), OlsError> {
    if targets.nrows() == 0 {
        return Err(OlsError::NoSamples);
    }
    for (matrix, m) in [("forced", forced), ("targets", targets)] {
        if let Some((row, col)) = first_non_finite(m) {
            return Err(OlsError::NonFinite { matrix, row, col });
        }
    }
    let resid = targets.to_owned();
    let target_energy: f64 = (0..resid.ncols())
        .map(|o| resid.col(o).squared_norm_l2())
        .sum();
    if !target_energy.is_finite() {
        return Err(OlsError::Overflow {
            what: "targets",
            value: target_energy,
        });
    }
    if target_energy == 0.0 {
        return Err(OlsError::ZeroTarget);
    }
    Ok((resid, target_energy))
}

impl<'s, 'o> Engine<'s, 'o> {
    /// An engine over `m` candidates with an empty basis and residuals `resid`.
    fn new(
        store: Store<'s>,
        m: usize,
        resid: Mat<f64>,
        target_energy: f64,
        options: &'o OlsOptions<'o>,
    ) -> Self {
        let (n, q) = (resid.nrows(), resid.ncols());
        let keeps_refreshed = match &store {
            Store::Owned(_) => true,
            Store::Borrowed(_) => options.stream == StreamPrecision::F64,
            Store::Generated(_) => false,
        };
        Engine {
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
            compact: None,
            err_lo: vec![0.0; m],
            err_hi: vec![0.0; m],
            keeps_refreshed,
            q,
            target_energy,
            options,
            lev: vec![0.0; n],
            schedule: Schedule::new(options.par, m * n * options.stream.bytes()),
        }
    }

    /// Commits the forced columns, in order; their ERRs.
    fn force(&mut self, forced: MatRef<'_, f64>) -> Result<Vec<f64>, OlsError> {
        let ctol = self.options.collinearity_tol;
        let mut forced_errs = Vec::with_capacity(forced.ncols());
        for k in 0..forced.ncols() {
            let mut w = forced.subcols(k, 1).to_owned();
            let orig2 = dot(w.col_as_slice(0), w.col_as_slice(0));
            if !orig2.is_finite() {
                return Err(OlsError::Overflow {
                    what: "forced columns",
                    value: orig2,
                });
            }
            let c = self.basis.project_out(w.as_mut(), 0, self.options.par);
            let coefs: Vec<f64> = (0..c.nrows()).map(|i| c[(i, 0)]).collect();
            let w = w.col_as_slice(0).to_vec();
            let norm2 = dot(&w, &w);
            if !(norm2 > ctol * orig2 && norm2 > 0.0) {
                return Err(OlsError::ForcedCollinear { column: k });
            }
            forced_errs.push(self.commit(w, coefs, norm2));
        }
        Ok(forced_errs)
    }

    /// Picks until the tolerance, `max_terms` or the candidates run out, from the
    /// cumulative ERR `cum` of the forced columns; PRESS after each pick goes to
    /// `press`.
    fn pick_all(
        &mut self,
        mut cum: f64,
        press: &mut Vec<f64>,
    ) -> Result<(Vec<Pick>, StopReason), OlsError> {
        let options = self.options;
        let max_picks = options.max_terms.min(self.err.len());
        let mut picks: Vec<Pick> = Vec::new();
        let stop = loop {
            if 1.0 - cum < options.tol {
                break StopReason::Tolerance;
            }
            if picks.len() >= max_picks {
                break StopReason::MaxTerms;
            }
            let Some(e) = self.choose()? else {
                break StopReason::Exhausted;
            };
            let j = e.j;
            let err = self.commit(e.w, e.coefs, e.norm2);
            self.cands[j].status = Status::Selected;
            self.err[j] = 0.0;
            cum += err;
            press.push(self.press());
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
                let nb = self.basis.len;
                self.pass(nb - 1, nb);
                self.settle();
            }
        };
        Ok((picks, stop))
    }
}

/// A block of candidate columns: a view of a stored matrix, or generated columns.
enum BlockCols<'a> {
    View(MatRef<'a, f64>),
    Owned(Mat<f64>),
}

impl BlockCols<'_> {
    fn as_ref(&self) -> MatRef<'_, f64> {
        match self {
            BlockCols::View(m) => *m,
            BlockCols::Owned(m) => m.as_ref(),
        }
    }
}
