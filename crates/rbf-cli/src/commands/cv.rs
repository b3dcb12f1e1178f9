//! `rbf cv`: cross-validation and grid search through the library's `grid_search`.

use std::time::Instant;

use anyhow::{Result, bail};
use rbf::{Grid, Sizes, grid_search};
use rbf_cli::data;
use rbf_cli::progress;
use rbf_cli::report::{CvContext, CvOut};
use rbf_cli::settings::{Centres, CvScheme, SettingsError, check_centres};
use rbf_cli::train;
use tabular::Table;

use super::args::CvArgs;

pub fn run(a: CvArgs) -> Result<()> {
    let mut settings = a.model.settings();
    if a.gap.is_some() && a.split != CvScheme::Blocked {
        bail!("--gap applies to --split blocked only");
    }
    if !a.sizes.is_empty() && settings.centres == Centres::All {
        bail!("--sizes applies to --centers ols, kmeans and random only, not all");
    }
    if !a.tols.is_empty() && settings.centres != Centres::Ols {
        bail!(
            "--tols applies to --centers ols only, not {}",
            settings.centres
        );
    }
    // The grid's largest size is the one the params must allow.
    if let Some(&k) = a.sizes.iter().max() {
        settings.max_centres = Some(k);
    }

    let table = Table::read(&a.data.data)?;
    let target = a.data.target.clone();
    let y = data::numeric_matrix(&table, std::slice::from_ref(&target))?;
    let inputs = data::input_columns(&table, &target, a.data.inputs.as_deref(), &[])?;
    let x = data::numeric_matrix(&table, &inputs)?;
    // Checked here, with the flag, before k folds of n rows are allocated.
    if a.folds < 2 || a.folds > table.len() {
        anyhow::bail!(
            "--folds {}: {} has {} data rows; use --folds 2 to {}",
            a.folds,
            table.file(),
            table.len(),
            table.len().max(2)
        );
    }
    // The number of centres is checked against the folds' training rows below.
    let params = settings.build(table.len(), settings.width.rule())?;

    let gap = a.gap.unwrap_or(0);
    let split = a.split.split(a.folds, gap, settings.seed);
    let needs = FoldNeeds {
        a: &a,
        centres: settings.n_centres_for(table.len()),
        params: &params,
        n: table.len(),
        dim: inputs.len(),
    };
    needs.check(&split, gap, table.file())?;
    let grid = Grid {
        widths: a.widths.iter().map(|w| w.rule()).collect(),
        sizes: if !a.sizes.is_empty() {
            Sizes::Centres(a.sizes.clone())
        } else if !a.tols.is_empty() {
            Sizes::Tolerances(a.tols.clone())
        } else {
            Sizes::Default
        },
        ridges: a.ridges.clone(),
    };

    let spinner = progress::spinner(progress::visible(a.quiet), "cross-validating");
    let start = Instant::now();
    let result = grid_search(&params, x.as_ref(), y.as_ref(), &split, &grid);
    let seconds = start.elapsed().as_secs_f64();
    spinner.finish_and_clear();
    let report = result.map_err(|e| train::failed(e, &settings))?;

    let ctx = CvContext {
        data: table.file().to_string(),
        target,
        inputs,
        n_rows: table.len(),
        split: a.split.name().to_string(),
        folds: a.folds,
        gap,
        settings: settings.clone(),
        seconds,
    };
    let out = CvOut::new(&report, ctx);
    if a.json {
        println!("{}", serde_json::to_string(&out.json())?);
    } else {
        println!("{}", out.summary());
    }
    if report.best.is_none() {
        // Every point failed: report the first failure as the error, with its remedy.
        if let Some(Err(e)) = report.points.first().map(|p| &p.result) {
            let msg = e.to_string();
            let e = rbf::RbfError::FoldFailed { reason: msg };
            return Err(train::failed(e, &settings).context("no grid point could be fitted"));
        }
        bail!("no grid point could be fitted");
    }
    Ok(())
}

/// What the folds of `rbf cv` must allow, checked once before any fitting so that a
/// refusal names the flags that caused it with values that work: rows on both sides of
/// every fold, and as many centres as the grid asks for in the smallest fold's training
/// rows (every fold fits on its own: the whole file's row count, proposed before,
/// failed in the folds).
struct FoldNeeds<'a> {
    a: &'a CvArgs,
    /// Centres the grid asks for (none with `--centres all`).
    centres: Option<usize>,
    params: &'a rbf::RbfValidParams,
    /// Data rows.
    n: usize,
    /// Inputs.
    dim: usize,
}

impl FoldNeeds<'_> {
    /// The number of centres against the smallest fold's training rows.
    fn centres_fit(&self, folds: &[rbf::Fold]) -> Result<(), SettingsError> {
        let Some(k) = self.centres else {
            return Ok(());
        };
        let fewest = folds.iter().map(|f| f.train.len()).min().unwrap_or(0);
        let flag = if self.a.sizes.is_empty() {
            "--max-centers"
        } else {
            "--sizes"
        };
        let what = "training rows in the smallest fold";
        check_centres(self.params, k, fewest, self.dim, what, flag)
    }

    /// Whether `--gap gap` leaves every fold rows on both sides and enough training
    /// rows for the centres.
    fn works(&self, gap: usize) -> bool {
        let split = self.a.split.split(self.a.folds, gap, 0);
        split
            .folds(self.n)
            .is_ok_and(|folds| self.centres_fit(&folds).is_ok())
    }

    fn check(&self, split: &rbf::Split, gap: usize, file: &str) -> Result<()> {
        match split.folds(self.n) {
            Ok(folds) => Ok(self.centres_fit(&folds)?),
            Err(e) => self.empty_fold(e, gap, file),
        }
    }

    /// A split that leaves a fold without training or validation rows (a `--gap` that
    /// eats them), said with the largest `--gap` that works.
    fn empty_fold(&self, e: rbf::SplitError, gap: usize, file: &str) -> Result<()> {
        let (a, n) = (self.a, self.n);
        let rbf::SplitError::EmptyFold {
            fold,
            train,
            validation,
            ..
        } = e
        else {
            bail!("--split {} --folds {}: {e}", a.split.name(), a.folds);
        };
        let what = if train == 0 { "training" } else { "validation" };
        // The largest gap that works: the folds shrink as the gap grows, so bisect
        // (log n splits of n indices each).
        let fix = if a.split == CvScheme::Blocked && self.works(0) {
            let (mut lo, mut hi) = (0, gap);
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if self.works(mid) { lo = mid } else { hi = mid }
            }
            format!("use --gap {lo} or less (or fewer --folds)")
        } else {
            "use fewer --folds".to_string()
        };
        bail!(
            "--split {} --folds {} --gap {gap}: fold {fold} of {file}'s {n} data rows would have no {what} rows ({train} training, {validation} validation); {fix}",
            a.split.name(),
            a.folds,
        )
    }
}
