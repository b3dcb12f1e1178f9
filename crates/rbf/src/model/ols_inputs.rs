//! What an OLS centre selection reads besides its targets: the design, the
//! candidate centres and their widths, the selection rows, and optionally
//! the candidates' kernel columns computed once.
//!
//! Split from the selection so that several selections on the same inputs
//! and different targets (a sensor's channels, which share their input
//! windows: [`crate::grid_search_each_with_linear`]) work them out once.
//! Each selection still picks exactly what it picks alone: the stored
//! columns are the generated ones bit for bit, in any batch
//! (`tests/kernel_columns_batches.rs`).

use faer::{Mat, MatRef};

use super::algorithm::{Design, SELECTION_ROWS_SEED, rows};
use super::error::RbfError;
use super::hyperparams::{Candidates, CentreSelection, RbfValidParams};
use super::progress::{Progress, Stage};
use crate::design::{Widths, kernel_matrix};
use crate::select::ols::StreamPrecision;
use crate::select::random::random_subset;

/// Largest candidate kernel matrix (f64 bytes) held to be shared by several
/// selections: the demo's folds need about 5 MB; a large record's selection
/// rows (25,000 × 400 candidates, 80 MB per width) keep generating their
/// columns, so a fit's memory does not grow with its channels.
pub(crate) const MAX_SHARED_BYTES: usize = 32 << 20;

/// The inputs of an OLS selection that do not depend on its targets.
pub(crate) struct OlsInputs {
    pub(crate) design: Design,
    /// Candidate centres (standardised coordinates).
    pub(crate) cands: Mat<f64>,
    /// What a candidate's index means to the user (training row or given row).
    pub(crate) labels: Vec<usize>,
    /// The selection rows' subsample, if any.
    pub(crate) sub: Option<Vec<usize>>,
    /// The design's rows of the subsample.
    pub(crate) xs_sel: Option<Mat<f64>>,
    pub(crate) forced_sel: Option<Mat<f64>>,
    pub(crate) widths: Widths,
}

impl OlsInputs {
    /// The inputs of a selection on `x` (and forced linear columns `z`),
    /// already checked finite.
    pub(crate) fn new(
        params: &RbfValidParams,
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        progress: Option<&(dyn Fn(Progress) + Sync)>,
    ) -> Result<Self, RbfError> {
        let CentreSelection::Ols { candidates, .. } = &params.centres else {
            unreachable!("OlsInputs::new needs OLS centre selection")
        };
        let design = Design::new(params, x, z);
        let (n, d, p) = (design.n(), x.ncols(), design.forced.ncols());
        if n < p + 1 {
            return Err(RbfError::TooFewSamples {
                samples: n,
                needed: p + 1,
            });
        }
        // Selection rows: every row, or a seeded subsample (sorted, so the selection
        // sees the rows in their order). Candidates are drawn from every row.
        let sub: Option<Vec<usize>> = match params.selection_rows {
            Some(s) if s.max(p + 1) < n => Some(random_subset(
                n,
                s.max(p + 1),
                params.seed ^ SELECTION_ROWS_SEED,
            )),
            _ => None,
        };
        let (cands, labels) = match candidates {
            Candidates::TrainingVectors => match &sub {
                None => (design.xs.clone(), (0..n).collect::<Vec<_>>()),
                Some(idx) => (rows(design.xs.as_ref(), idx), idx.clone()),
            },
            Candidates::Subsample { size } => {
                let idx = random_subset(n, (*size).min(n), params.seed);
                (rows(design.xs.as_ref(), &idx), idx)
            }
            Candidates::Given(c) => {
                super::algorithm::check_dim("candidate centres", c.as_ref(), d)?;
                (design.standardised(c.as_ref()), (0..c.nrows()).collect())
            }
        };
        let (xs_sel, forced_sel) = match &sub {
            None => (None, None),
            Some(idx) => (
                Some(rows(design.xs.as_ref(), idx)),
                Some(rows(design.forced.as_ref(), idx)),
            ),
        };
        let n_sel = xs_sel.as_ref().map_or(n, Mat::nrows);
        let (entry_bytes, what) = match params.ols_stream {
            StreamPrecision::F32 => (4, "f32 copy of the OLS candidate kernel columns"),
            StreamPrecision::F64 => (8, "OLS candidate kernel matrix"),
        };
        crate::memory::check_entries(
            n_sel,
            cands.nrows(),
            entry_bytes,
            crate::memory::available_bytes(),
            what,
        )?;
        if let Some(f) = progress {
            f(Progress {
                stage: Stage::Widths,
                done: 0,
                total: 1,
            });
        }
        let widths = params.width.widths(cands.as_ref(), params.par)?;
        Ok(Self {
            design,
            cands,
            labels,
            sub,
            xs_sel,
            forced_sel,
            widths,
        })
    }

    /// The candidates' kernel columns on the selection rows, computed once
    /// for several selections to read; `None` when they would take more
    /// than [`MAX_SHARED_BYTES`] (each selection then generates its own).
    pub(crate) fn shared_columns(&self, params: &RbfValidParams) -> Option<Mat<f64>> {
        let xs_sel = self
            .xs_sel
            .as_ref()
            .map_or(self.design.xs.as_ref(), |m| m.as_ref());
        (xs_sel.nrows() * self.cands.nrows() * 8 <= MAX_SHARED_BYTES).then(|| {
            kernel_matrix(
                xs_sel,
                self.cands.as_ref(),
                params.kernel,
                &self.widths,
                params.par,
            )
        })
    }

    /// A copy for one more selection on the same inputs.
    pub(crate) fn for_one(&self) -> Self {
        Self {
            design: self.design.clone(),
            cands: self.cands.clone(),
            labels: self.labels.clone(),
            sub: self.sub.clone(),
            xs_sel: self.xs_sel.clone(),
            forced_sel: self.forced_sel.clone(),
            widths: self.widths.clone(),
        }
    }
}
