//! `rbf fit`: read, split, fit (timed), score, save, report.

use std::time::Instant;

use anyhow::Result;
use rbf::metrics::Scores;
use rbf_cli::data::{self, TrainVal};
use rbf_cli::progress::{self, FitProgress};
use rbf_cli::report::{FitContext, FitReport};
use rbf_cli::saved::SavedModel;
use rbf_cli::train::{self, Fitted};
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

    let bar = FitProgress::new(progress::visible(a.quiet));
    let observe = |p: rbf::Progress| bar.observe(p);
    let start = Instant::now();
    let fitted = train::fit(&settings, &params, xt.as_ref(), yt.as_ref(), &observe);
    let fit_seconds = start.elapsed().as_secs_f64();
    let times = bar.finish();
    let Fitted {
        model,
        width_search,
    } = fitted?;

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
