//! Shared helpers of the integration tests: the Chen, Cowan & Grant (1991) example-1
//! system, and reference forward-selection implementations to compare the engine with.
#![allow(dead_code)]

pub mod blobs;

use faer::{Mat, MatRef};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};
use rand_xoshiro::Xoshiro256Plus;

/// One step of the noise-free map of Chen, Cowan & Grant (1991), example 1.
pub fn chen_map(y1: f64, y2: f64) -> f64 {
    let e = (-y1 * y1).exp();
    (0.8 - 0.5 * e) * y1 - (0.3 + 0.9 * e) * y2 + 0.1 * (std::f64::consts::PI * y1).sin()
}

/// `n` samples of the series with Gaussian *process* noise of standard deviation `sd`
/// (inside the recursion), after a 100-sample burn-in from y = 0.1, 0.
pub fn chen_series(n: usize, sd: f64, seed: u64) -> Vec<f64> {
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    let noise = Normal::new(0.0, sd).unwrap();
    let (mut y2, mut y1) = (0.0, 0.1);
    let mut out = Vec::with_capacity(n);
    for t in 0..n + 100 {
        let e: f64 = if sd > 0.0 {
            noise.sample(&mut rng)
        } else {
            0.0
        };
        let y = chen_map(y1, y2) + e;
        y2 = y1;
        y1 = y;
        if t >= 100 {
            out.push(y);
        }
    }
    out
}

/// Regressors [y(t−1), y(t−2)] (n−2 × 2) and targets y(t) (n−2 × 1).
pub fn lagged(series: &[f64]) -> (Mat<f64>, Mat<f64>) {
    let m = series.len() - 2;
    let x = Mat::from_fn(m, 2, |i, j| series[i + 1 - j]);
    let y = Mat::from_fn(m, 1, |i, _| series[i + 2]);
    (x, y)
}

fn col(m: MatRef<'_, f64>, j: usize) -> Vec<f64> {
    (0..m.nrows()).map(|i| m[(i, j)]).collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Reference greedy selection: at each step an orthonormal basis of the columns in is
/// recomputed by Householder QR (faer), every remaining candidate is projected out of it
/// explicitly (twice), and the candidate with the largest exact ERR is taken. O(m·n·k)
/// per step: slow, obviously right. Returns the picks and their ERRs.
pub fn reference_select(
    cand: MatRef<'_, f64>,
    forced: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    k_max: usize,
    ctol: f64,
) -> (Vec<usize>, Vec<f64>) {
    let (n, m, q) = (cand.nrows(), cand.ncols(), y.ncols());
    let dd: f64 = (0..q).map(|o| dot(&col(y, o), &col(y, o))).sum();
    let mut picks: Vec<usize> = Vec::new();
    let mut errs = Vec::new();
    for _ in 0..k_max {
        let cols: Vec<Vec<f64>> = (0..forced.ncols())
            .map(|j| col(forced, j))
            .chain(picks.iter().map(|&j| col(cand, j)))
            .collect();
        let basis: Vec<Vec<f64>> = if cols.is_empty() {
            Vec::new()
        } else {
            let a = Mat::from_fn(n, cols.len(), |i, j| cols[j][i]);
            let qm = a.qr().compute_thin_Q();
            (0..cols.len()).map(|j| col(qm.as_ref(), j)).collect()
        };
        let mut best: Option<(usize, f64)> = None;
        for j in 0..m {
            if picks.contains(&j) {
                continue;
            }
            let p = col(cand, j);
            let orig = dot(&p, &p);
            let mut w = p.clone();
            for _ in 0..2 {
                for b in &basis {
                    let a = dot(b, &w);
                    for (wi, bi) in w.iter_mut().zip(b) {
                        *wi -= a * bi;
                    }
                }
            }
            let e = dot(&w, &w);
            if !(e > ctol * orig && e > 0.0) {
                continue;
            }
            let num: f64 = (0..q).map(|o| dot(&w, &col(y, o)).powi(2)).sum();
            let err = num / (e * dd);
            if best.is_none_or(|(_, b)| err > b) {
                best = Some((j, err));
            }
        }
        let Some((j, err)) = best else { break };
        picks.push(j);
        errs.push(err);
    }
    (picks, errs)
}

/// Chen's algorithm as a straightforward implementation writes it: classical
/// Gram–Schmidt, α_jk = w_jᵀp_k / w_jᵀw_j computed from the *original* candidate
/// column, no re-orthogonalisation. Returns the picks.
pub fn classical_gram_schmidt_select(
    cand: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    k_max: usize,
) -> Vec<usize> {
    let (m, q) = (cand.ncols(), y.ncols());
    let ys: Vec<Vec<f64>> = (0..q).map(|o| col(y, o)).collect();
    let dd: f64 = ys.iter().map(|v| dot(v, v)).sum();
    let mut ws: Vec<Vec<f64>> = Vec::new();
    let mut picks = Vec::new();
    for _ in 0..k_max {
        let mut best: Option<(usize, f64, Vec<f64>)> = None;
        for j in 0..m {
            if picks.contains(&j) {
                continue;
            }
            let p = col(cand, j);
            let mut w = p.clone();
            for wk in &ws {
                let alpha = dot(wk, &p) / dot(wk, wk);
                for (wi, wki) in w.iter_mut().zip(wk) {
                    *wi -= alpha * wki;
                }
            }
            let e = dot(&w, &w);
            if e <= 0.0 {
                continue;
            }
            let num: f64 = ys.iter().map(|v| dot(&w, v).powi(2)).sum();
            let err = num / (e * dd);
            if best.as_ref().is_none_or(|b| err > b.1) {
                best = Some((j, err, w));
            }
        }
        let Some((j, _, w)) = best else { break };
        picks.push(j);
        ws.push(w);
    }
    picks
}

/// The attractor of an iterated map y(t) = f(y(t−1), y(t−2)) started from (0.1, 0):
/// the phase-plane points (y(t−1), y(t)) of steps 2500..3000, or fewer if the iteration
/// diverges (|y| > 1e3 or non-finite).
pub fn attractor(mut f: impl FnMut(f64, f64) -> f64) -> Vec<[f64; 2]> {
    let (mut y2, mut y1) = (0.0, 0.1);
    let mut pts = Vec::new();
    for t in 0..3000 {
        let y = f(y1, y2);
        if !y.is_finite() || y.abs() > 1e3 {
            break;
        }
        y2 = y1;
        y1 = y;
        if t >= 2500 {
            pts.push([y2, y1]);
        }
    }
    pts
}

/// Symmetric mean nearest-point distance between two attractors (∞ if one is empty):
/// the larger of mean_a min_b ‖a − b‖ and mean_b min_a ‖a − b‖.
pub fn attractor_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return f64::INFINITY;
    }
    let near = |p: &[f64; 2], s: &[[f64; 2]]| {
        s.iter()
            .map(|q| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt())
            .fold(f64::INFINITY, f64::min)
    };
    let ab = a.iter().map(|p| near(p, b)).sum::<f64>() / a.len() as f64;
    let ba = b.iter().map(|p| near(p, a)).sum::<f64>() / b.len() as f64;
    ab.max(ba)
}

/// Largest |y| on an attractor.
pub fn amplitude(a: &[[f64; 2]]) -> f64 {
    a.iter().map(|p| p[1].abs()).fold(0.0, f64::max)
}

/// One-step prediction of a fitted two-input model at (y(t−1), y(t−2)).
pub fn step(model: &rbf::RbfModel, y1: f64, y2: f64) -> f64 {
    let x = faer::mat![[y1, y2]];
    let mut out = Mat::zeros(1, 1);
    model.predict_into(x.as_ref(), out.as_mut(), faer::Par::Seq);
    out[(0, 0)]
}
