//! The assignment step of Lloyd's iterations: every sample's nearest centroid from one
//! f32 product per iteration, checked in f64 where f32 cannot tell.
//!
//! The nearest centroid of x minimises ‖c‖² − 2·x̃·c̃ (x̃, c̃ shifted by the samples'
//! mean μ; ‖x̃‖² is the same for every centroid). The products x̃·c̃ come from one faer
//! product in f32, twice the vector lanes of f64 (on the peer data the product was
//! most of an iteration). Its error, with the rounding of x̃ and c̃ to f32, is at most
//! about 2(d + 4)·u·‖x̃‖·‖c̃‖ ≤ (d + 4)·u·(‖x̃‖² + ‖c̃‖²), u = 2⁻²⁴; every sample
//! whose nearest and second-nearest centroid are closer than twice four times that
//! bound has all its distances recomputed directly in f64 (Σ (x_t − c_t)², no
//! cancellation). So every assignment is the nearest centroid by f64 distances, the
//! lowest index on a tie, as a full f64 computation gives, whatever the f32 rounding.

use faer::linalg::matmul::matmul;
use faer::prelude::ReborrowMut;
use faer::{Accum, Mat, MatRef, Par};

use crate::widest::widest;

/// The samples shifted by their mean, in f32, and what the f64 check needs.
pub(super) struct Assigner {
    mean: Vec<f64>,
    /// n × d, x − μ in f32.
    xs: Mat<f32>,
    /// ‖x − μ‖² in f64.
    xn: Vec<f64>,
    /// The centroids shifted by μ, in f32 (k × d), and their squared norms in f64.
    cs: Mat<f32>,
    cn: Vec<f64>,
    /// n × k products.
    products: Mat<f32>,
    second: Vec<f64>,
}

impl Assigner {
    pub(super) fn new(x: MatRef<'_, f64>) -> Self {
        let (n, d) = (x.nrows(), x.ncols());
        let mean: Vec<f64> = (0..d)
            .map(|t| (0..n).map(|i| x[(i, t)]).sum::<f64>() / n.max(1) as f64)
            .collect();
        let mut xs = Mat::<f32>::zeros(n, d);
        let mut xn = vec![0.0; n];
        for (t, &m) in mean.iter().enumerate() {
            let col = x.col(t);
            let dst = xs.col_as_slice_mut(t);
            for (i, (v, norm)) in dst.iter_mut().zip(xn.iter_mut()).enumerate() {
                let s = col[i] - m;
                *v = s as f32;
                *norm += s * s;
            }
        }
        Self {
            mean,
            xs,
            xn,
            cs: Mat::zeros(0, 0),
            cn: Vec::new(),
            products: Mat::zeros(0, 0),
            second: Vec::new(),
        }
    }

    /// Every sample's nearest centroid of `centres` (k × d) into `labels` (the lowest
    /// index on a tie); the same result for any `par` (the product is cut into the
    /// same column blocks whatever the threads).
    pub(super) fn assign(
        &mut self,
        x: MatRef<'_, f64>,
        centres: MatRef<'_, f64>,
        labels: &mut [usize],
        par: Par,
    ) {
        let (n, d, k) = (x.nrows(), x.ncols(), centres.nrows());
        self.cs.resize_with(k, d, |_, _| 0.0);
        self.cn.clear();
        for j in 0..k {
            let mut norm = 0.0;
            for t in 0..d {
                let s = centres[(j, t)] - self.mean[t];
                self.cs[(j, t)] = s as f32;
                norm += s * s;
            }
            self.cn.push(norm);
        }
        self.products.resize_with(n, k, |_, _| 0.0);
        let (xs, cs) = (self.xs.as_ref(), self.cs.as_ref());
        const COLS: usize = 32;
        let tile = |c0: usize, mut block: faer::MatMut<'_, f32>| {
            let cols = block.ncols();
            matmul(
                block.rb_mut(),
                Accum::Replace,
                xs,
                cs.subrows(c0, cols).transpose(),
                1.0f32,
                Par::Seq,
            );
        };
        if par.degree() > 1 && k > COLS {
            use rayon::prelude::*;
            self.products
                .as_mut()
                .par_col_chunks_mut(COLS)
                .enumerate()
                .for_each(|(c, block)| tile(c * COLS, block));
        } else {
            for c0 in (0..k).step_by(COLS) {
                let cols = COLS.min(k - c0);
                tile(c0, self.products.as_mut().subcols_mut(c0, cols));
            }
        }
        // nearest and second nearest of ‖c‖² − 2·x̃·c̃, column by column
        let column = |j: usize| {
            self.products
                .col(j)
                .try_as_col_major()
                .expect("an owned matrix has contiguous columns")
                .as_slice()
        };
        let mut best = vec![0.0; n];
        first_column(&mut best, column(0), self.cn[0]);
        self.second.clear();
        self.second.resize(n, f64::INFINITY);
        labels.fill(0);
        for j in 1..k {
            nearer_two(
                labels,
                &mut best,
                &mut self.second,
                column(j),
                self.cn[j],
                j,
            );
        }
        let most = self.cn.iter().copied().fold(0.0, f64::max);
        let scale = 4.0 * (d as f64 + 4.0) * f64::from(f32::EPSILON);
        for i in 0..n {
            let margin = scale * (self.xn[i] + most);
            if self.second[i] - best[i] <= 2.0 * margin {
                labels[i] = exact_nearest(x, centres, i);
            }
        }
    }
}

/// The nearest centroid of sample `i` by f64 distances computed directly, the lowest
/// index on a tie.
fn exact_nearest(x: MatRef<'_, f64>, centres: MatRef<'_, f64>, i: usize) -> usize {
    let mut best = (f64::INFINITY, 0);
    for j in 0..centres.nrows() {
        let v: f64 = (0..x.ncols())
            .map(|t| (x[(i, t)] - centres[(j, t)]).powi(2))
            .sum();
        if v < best.0 {
            best = (v, j);
        }
    }
    best.1
}

widest! {
    /// best ← ‖c₀‖² − 2·p.
    fn first_column(best: &mut [f64], products: &[f32], cn: f64) {
        for (b, &p) in best.iter_mut().zip(products) {
            *b = cn - 2.0 * f64::from(p);
        }
    }
}

widest! {
    /// Samples nearer to centroid `j` (‖c_j‖² − 2·p) than to the nearest so far take
    /// it, the old nearest becoming the second; otherwise `j` may be the second.
    /// Branch-free selects, the earlier centroid kept on a tie.
    fn nearer_two(
        labels: &mut [usize],
        best: &mut [f64],
        second: &mut [f64],
        products: &[f32],
        cn: f64,
        j: usize,
    ) {
        for (((l, b), s), &p) in labels
            .iter_mut()
            .zip(best.iter_mut())
            .zip(second.iter_mut())
            .zip(products)
        {
            let v = cn - 2.0 * f64::from(p);
            let closer = v < *b;
            *s = if closer { *b } else { s.min(v) };
            *b = if closer { v } else { *b };
            *l = if closer { j } else { *l };
        }
    }
}
