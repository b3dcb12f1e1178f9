//! `rbf fit`: read, split, fit (timed), score, save, report.

use std::time::Instant;

use anyhow::Result;
use rbf::faer::Mat;
use rbf::metrics::Scores;
use rbf_cli::data::{self, TrainVal};
use rbf_cli::progress::{self, FitProgress};
use rbf_cli::report::{FitContext, FitReport, WidthTrial};
use rbf_cli::saved::SavedModel;
use rbf_cli::settings::WIDTH_GRID;
use rbf_cli::{hint, settings::FitSettings};
use tabular::{Table, TableError};

use super::args::FitArgs;

pub fn run(a: FitArgs) -> Result<()> {
    outfile::guard_file("--out", &a.out, &[("--data", Some(&a.data.data))])?;
    let table = Table::read(&a.data.data)?;
    let target = a.data.target.clone();
    let y_all = data::numeric_matrix(&table, std::slice::from_ref(&target))?;
    let rows = match &a.split_column {
        Some(col) => data::split_by_column(&table, col)?,
        None => data::interleaved(table.len()),
    };
    let exclude: Vec<&str> = a.split_column.iter().map(String::as_str).collect();
    let inputs = data::input_columns(&table, &target, a.data.inputs.as_deref(), &exclude)?;
    let x_all = data::numeric_matrix(&table, &inputs)
        .map_err(|e| with_inputs_hint(e, a.data.inputs.is_none()))?;
    if rows.train.is_empty() {
        anyhow::bail!("{}: no data rows to train on", table.file());
    }
    let settings = a.model.settings();
    let params = settings.params(rows.train.len(), inputs.len())?;

    let TrainVal { train, val } = rows;
    let (xt, yt) = (
        data::take_rows(x_all.as_ref(), &train),
        data::take_rows(y_all.as_ref(), &train),
    );
    let (xv, yv) = (
        data::take_rows(x_all.as_ref(), &val),
        data::take_rows(y_all.as_ref(), &val),
    );
    let no_linear = Mat::<f64>::zeros(train.len(), 0);

    let bar = FitProgress::new(progress::visible(a.quiet));
    let observe = |p: rbf::Progress| bar.observe(p);
    let start = Instant::now();
    let mut width_search = Vec::new();
    let fitted = if settings.searches_width() {
        search_width(
            &settings,
            xt.as_ref(),
            yt.as_ref(),
            &observe,
            &mut width_search,
        )?
    } else {
        params.fit_with_progress(xt.as_ref(), no_linear.as_ref(), yt.as_ref(), &observe)
    };
    let fit_seconds = start.elapsed().as_secs_f64();
    let times = bar.finish();
    let model = fitted.map_err(|e| fit_failed(e, &settings))?;

    let train_scores = Scores::of(yt.as_ref(), model.predict(xt.as_ref()).as_ref());
    let start = Instant::now();
    let yv_hat = model.predict(xv.as_ref());
    let predict_seconds = start.elapsed().as_secs_f64();
    let val_scores = (!val.is_empty()).then(|| Scores::of(yv.as_ref(), yv_hat.as_ref()));

    let saved = SavedModel {
        target: target.clone(),
        inputs: inputs.clone(),
        data: table.file().to_string(),
        model,
    };
    saved.save(&a.out)?;

    let ctx = FitContext {
        data: table.file().to_string(),
        target,
        inputs,
        train_lines: train.iter().map(|&r| table.line_of_row(r)).collect(),
        train_rows: train,
        n_val: val.len(),
        settings,
        fit_seconds,
        predict_seconds,
        train: train_scores,
        val: val_scores,
        times,
        out: a.out.display().to_string(),
        threads: params.parallelism().degree(),
        width_search,
    };
    let report = FitReport::new(&saved.model, ctx);
    if a.json {
        println!("{}", serde_json::to_string(&report.json())?);
    } else if !a.quiet {
        println!("{}", report.summary());
    }
    Ok(())
}

/// `--width auto` with `--stop press|gcv`: one OLS run per width of
/// [`WIDTH_GRID`] × the median pairwise distance, each keeping the size `--stop`
/// chooses; the model with the least PRESS at that size wins, the first on ties. Widths whose fit fails
/// (e.g. too ill-conditioned) are skipped; if every one fails, the last error is
/// returned.
fn search_width(
    settings: &FitSettings,
    x: rbf::faer::MatRef<'_, f64>,
    y: rbf::faer::MatRef<'_, f64>,
    observe: &(dyn Fn(rbf::Progress) + Sync),
    trials: &mut Vec<WidthTrial>,
) -> Result<Result<rbf::RbfModel, rbf::RbfError>> {
    let no_linear = Mat::<f64>::zeros(x.nrows(), 0);
    let mut best: Option<(f64, rbf::RbfModel)> = None;
    let mut last_err = None;
    for scale in WIDTH_GRID {
        let p = settings.params_with_width(
            x.nrows(),
            x.ncols(),
            rbf::WidthRule::MedianPairwise { scale },
        )?;
        let m = match p.fit_with_progress(x, no_linear.as_ref(), y, observe) {
            Ok(m) => m,
            Err(e) => {
                last_err = Some(e);
                continue;
            }
        };
        let k = m.n_centres();
        let Some(c) = m
            .selection()
            .and_then(|s| s.criterion.iter().find(|c| c.k == k))
        else {
            continue;
        };
        // Widths are compared by PRESS even under --stop gcv: GCV counts parameters,
        // not leverage, and rewards near-interpolating narrow kernels (sunspots:
        // GCV 92 at k = 99 with β/4, validation rms 52 against 24).
        let value = c.press;
        trials.push(WidthTrial {
            scale,
            width: m.widths().get(0),
            k,
            criterion: value,
        });
        if best.as_ref().is_none_or(|(b, _)| value < *b) {
            best = Some((value, m));
        }
    }
    Ok(match (best, last_err) {
        (Some((_, m)), _) => Ok(m),
        (None, Some(e)) => Err(e),
        (None, None) => anyhow::bail!("--width auto: no width of the grid gave a model"),
    })
}

/// A bad cell in a column that was only *guessed* to be an input says how to choose
/// the inputs instead.
fn with_inputs_hint(e: TableError, defaulted: bool) -> anyhow::Error {
    let guessed = defaulted && matches!(e, TableError::NotANumber { .. });
    let e = anyhow::Error::from(e);
    if guessed {
        anyhow::anyhow!("{e}; choose the input columns with --inputs")
    } else {
        e
    }
}

/// The library's error with the flag that fixes it, if any.
pub fn fit_failed(e: rbf::RbfError, settings: &FitSettings) -> anyhow::Error {
    match hint::fix_for(&e, settings.ridge) {
        Some(fix) => anyhow::anyhow!("fit failed: {e}; {fix}"),
        None => anyhow::Error::from(e).context("fit failed"),
    }
}
