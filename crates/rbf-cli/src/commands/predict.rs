//! `rbf predict`: load the model, find its inputs by name, predict, write CSV.

use std::time::Instant;

use anyhow::{Context, Result};
use rbf::metrics::Scores;
use rbf_cli::data;
use rbf_cli::report::{PredictJson, finite};
use rbf_cli::saved::SavedModel;
use tabular::Table;

use super::args::PredictArgs;

pub fn run(a: PredictArgs) -> Result<()> {
    outfile::guard_file(
        "--out",
        &a.out,
        &[("--model", Some(&a.model)), ("--data", Some(&a.data))],
    )?;
    let saved = SavedModel::load(&a.model)?;
    if saved.model.n_linear() > 0 {
        anyhow::bail!(
            "{}: the model has {} linear (forced) regressor columns, which `rbf predict` cannot supply from a CSV; models from `rbf fit` have none: refit with `rbf fit`, or evaluate this model with the library's predict_with_linear",
            a.model.display(),
            saved.model.n_linear()
        );
    }
    let table = Table::read(&a.data)?;
    let x = data::numeric_matrix(&table, &saved.inputs).with_context(|| {
        format!(
            "the model {} needs input columns {}",
            a.model.display(),
            saved.inputs.join(", ")
        )
    })?;
    let start = Instant::now();
    let yhat = saved.model.predict(x.as_ref());
    let predict_seconds = start.elapsed().as_secs_f64();
    let prediction = data::column(yhat.as_ref(), 0);
    // Said per row, before anything is written: which row, and why.
    if let Some(i) = prediction
        .iter()
        .position(|v| !(v.is_finite() && v.abs() <= tabular::MAX_MAGNITUDE))
    {
        anyhow::bail!(
            "{}:{}: the prediction of {} for this row is {:e}: the {} kernel overflows on its inputs (far outside the training data, or a model of extreme numbers); remove or rescale the row, or refit (nothing was written)",
            table.file(),
            table.line_of_row(i),
            a.model.display(),
            prediction[i],
            saved.model.kernel()
        );
    }

    let target = if table.has_column(&saved.target) {
        Some(table.numeric(&saved.target)?)
    } else {
        None
    };
    let out = a.out.display().to_string();
    let scores = match &target {
        Some(y) => {
            let residual: Vec<f64> = y.iter().zip(&prediction).map(|(a, b)| a - b).collect();
            tabular::write_csv(
                &a.out,
                &["prediction", saved.target.as_str(), "residual"],
                &[&prediction, y, &residual],
            )?;
            (!y.is_empty()).then(|| {
                let ym = rbf::faer::Mat::from_fn(y.len(), 1, |i, _| y[i]);
                Scores::of(ym.as_ref(), yhat.as_ref())
            })
        }
        None => {
            tabular::write_csv(&a.out, &["prediction"], &[&prediction])?;
            None
        }
    };
    if a.json {
        let model = a.model.display().to_string();
        let v = PredictJson {
            command: "predict",
            data: table.file(),
            inputs: &saved.inputs,
            model: &model,
            n_rows: table.len(),
            nmse: scores.as_ref().and_then(|s| finite(s.nmse)),
            out: &out,
            predict_seconds,
            rmse: scores.as_ref().and_then(|s| finite(s.rmse)),
            target: &saved.target,
        };
        println!("{}", serde_json::to_string(&v)?);
    } else if !a.quiet {
        match &scores {
            Some(s) => println!(
                "rbf predict: {} rows → {out}; against '{}': RMSE {:.6}, NMSE {:.6}",
                table.len(),
                saved.target,
                s.rmse,
                s.nmse
            ),
            None => println!("rbf predict: {} rows → {out}", table.len()),
        }
    }
    Ok(())
}
