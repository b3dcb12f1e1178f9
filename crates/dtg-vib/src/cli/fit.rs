//! `dtg-vib fit`: every channel model of the unit fitted on the records,
//! saved with the unit, and their scores printed (or written as JSON;
//! `explain` prints its final fit the same way).

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::commands::fit::{Fitted, fit};
use dtg_vib::unit_sensor::UnitSensor;
use std::sync::atomic::{AtomicUsize, Ordering};
use sysid::Sensor;

pub use dtg_vib::commands::fit_report::FitReport;

use dtg_vib::commands::fit_args::{FitArgs, FitRecipe, fit_inputs};

/// Fits, saves the model and prints its scores.
pub fn run(a: FitArgs, progress: Progress) -> Result<()> {
    outfile::guard_file("--out", &a.out, &fit_inputs(&a))?;
    let recipe = FitRecipe::resolve(&a)?;
    let sensor = &recipe.sensor;
    let n = sensor.unit.gyros().len();
    let done = AtomicUsize::new(0);
    let Fitted {
        model,
        per_record,
        seconds,
    } = fit(
        &recipe,
        a.cv.is_some(),
        &|stage| match stage {
            sysid::FitStage::Preparing => progress.say("preparing the records"),
            sysid::FitStage::ChannelDone(ch) => {
                let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress.say(format!("fitted {k}/{n} channels (last {ch})"));
            }
        },
        &|what| progress.say(what),
    )?;
    model.save(&a.out)?;
    progress.clear();
    recipe.read.say_notes();
    let m = model.inner();
    stride_note(m);
    if a.json {
        let mut report = FitReport::of_model(m, seconds);
        if let Some(per) = &per_record {
            report.set_records(per, a.cv.clone());
        }
        println!("{}", serde_json::to_string(&report)?);
        return Ok(());
    }
    println!("unit: {} ({})", sensor.unit.name(), sensor.unit.file());
    print_fit_channels(m.channels());
    print_frequency_responses(m);
    if let Some(c) = m.choice() {
        print_choice(c);
    }
    if let Some(per) = &per_record {
        print_record_scores(&sensor.channels(), per, a.cv.is_some());
    }
    println!("model: {} ({:.2} s)", a.out.display(), seconds);
    Ok(())
}

/// On stderr, where cross-validation and centre selection ran on every
/// k-th training window only.
pub fn stride_note(m: &sysid::Model<UnitSensor>) {
    let n_train = m.channels()[0].scores().n_train;
    let stride = sysid::fit::selection_stride(n_train);
    if stride > 1 {
        eprintln!(
            "note: {n_train} training windows: cross-validation and centre selection used every {stride}th of them ({}); the weights were solved on all",
            n_train.div_ceil(stride)
        );
    }
}

/// What the choice of input and smoother weighed: each candidate's mean
/// validation rms and worst ADEV after/before, the chosen one marked, and
/// what it cost and gained against the paper's model (raw, no smoother).
pub fn print_choice(c: &sysid::fit::ChoiceReport) {
    if let Some(w) = &c.window_signals {
        println!("{}", w.line());
    }
    if c.adev_runs == 0
        && c.candidates.len() == 1
        && c.networks_shrunk.is_empty()
        && c.bias_instability_raised.is_empty()
        && c.input_sample.is_none()
    {
        // Only the window was chosen: no input or smoother to tell of.
        return;
    }
    let label = sysid::Smoother::label;
    println!(
        "input and smoother: chosen {} / {} among {} candidates (lowest mean validation rms whose compensation keeps ADEV ≤ before × (1 + hw68) at every τ; {} validation run(s) checked):",
        c.chosen().input,
        label(c.chosen().smoother),
        c.candidates.len(),
        c.adev_runs
    );
    println!(
        "  input       smoother  val rms (deg/h)  worst ADEV after/before (channel, τ s)  passes"
    );
    for (i, k) in c.candidates.iter().enumerate() {
        println!(
            "{} {:<10}  {:<8}  {:>15.4}  {:>6.3} ({}, {:.2}){:>14}",
            if i == c.chosen { "*" } else { " " },
            k.input.to_string(),
            label(k.smoother),
            k.mean_val_rms,
            k.worst_adev_ratio,
            k.worst_channel,
            k.worst_tau_s,
            if k.passes { "yes" } else { "no" }
        );
    }
    if let Some(s) = &c.input_sample {
        let best = |input| {
            s.candidates
                .iter()
                .filter(|k| k.input == input)
                .map(|k| k.mean_val_rms)
                .fold(f64::INFINITY, f64::min)
        };
        let inputs: Vec<String> = sysid::ModelInput::ALL
            .iter()
            .filter(|&&i| best(i).is_finite())
            .map(|&i| format!("{i} {:.4}", best(i)))
            .collect();
        println!(
            "  the input was chosen on a sample of {} rows ({} chunks spread over the record; best validation rms there: {} deg/h), and only it was fitted on the whole record",
            s.rows,
            s.chunks,
            inputs.join(", ")
        );
        if let Some(t) = &s.shared_centres {
            println!(
                "  one centre selection for all channels on that sample: mean validation rms {:.4} against {:.4} deg/h with one per channel; {}",
                t.shared_mean_val_rms,
                t.per_channel_mean_val_rms,
                match t.taken {
                    true => "the record was fitted with one (within 1%)",
                    false => "the record was fitted with one per channel",
                }
            );
        }
    }
    if let Some(b) = c.baseline() {
        let w = c.chosen();
        println!(
            "  against raw/none: validation rms {:.4} → {:.4} deg/h, worst ADEV ratio {:.3} → {:.3}",
            b.mean_val_rms, w.mean_val_rms, b.worst_adev_ratio, w.worst_adev_ratio
        );
    }
    for s in &c.networks_shrunk {
        println!("  network shrunk (bias and effects kept): {s}");
    }
    for s in &c.bias_instability_raised {
        println!("  bias instability raised: {s}");
    }
}

/// Validation rms of each channel on each record.
pub fn print_record_scores(channels: &[String], per: &[Vec<sysid::fit::RecordScore>], loro: bool) {
    println!(
        "validation rms per record, deg/h ({}):",
        if loro {
            "each record validated by a model fitted on the others"
        } else {
            "each record's validation rows"
        }
    );
    for (k, scores) in per.iter().enumerate() {
        let cells: Vec<String> = scores
            .iter()
            .map(|s| format!("{} {:.4}", s.file, s.val_rms))
            .collect();
        println!("{:>7}  {}", channels[k], cells.join(", "));
    }
}

/// Each channel's FIR tap families read as filters, one line each (none
/// when no channel has a family of two or more taps).
pub fn print_frequency_responses(m: &sysid::Model<UnitSensor>) {
    use dtg_vib::unit_sensor::frequency_response::{BANDS, lines, responses};
    let all: Vec<String> = m
        .channels()
        .iter()
        .flat_map(|c| {
            lines(
                &c.channel().to_string(),
                &responses(c.effects(), c.coefficients(), m.dt_s()),
            )
        })
        .collect();
    if all.is_empty() {
        return;
    }
    println!(
        "frequency response of each tap family (mean response over {BANDS} bands to {} Hz; 95% intervals from the taps' joint covariance):",
        dtg_vib::numfmt::short((5.0 / m.dt_s()).round() / 10.0)
    );
    all.iter().for_each(|l| println!("{l}"));
}

/// Each channel's centres, scores and effect coefficients (the fit's
/// estimates, from the training rows), each with its standard error and 95%
/// interval.
pub fn print_fit_channels<C: Clone + std::fmt::Display, E: sysid::Effect>(
    channels: &[sysid::ChannelModel<C, E>],
) {
    println!(
        "channel  centres  train rms  val rms  (deg/h)  effects (coefficient ± standard error, 95% CI)"
    );
    for c in channels {
        let s = c.scores();
        let e: Vec<String> = c
            .effects()
            .iter()
            .enumerate()
            .map(|(j, e)| match c.coefficients() {
                Some(k) => format!(
                    "{} {:.4} ± {:.4} {} ({:.4} to {:.4})",
                    e.id(),
                    k[j].value,
                    k[j].se,
                    k[j].unit,
                    k[j].ci95[0],
                    k[j].ci95[1]
                ),
                None => e.id(),
            })
            .collect();
        println!(
            "{:>7}  {:>7}  {:>9.4}  {:>7.4}           {}",
            c.channel().to_string(),
            c.n_centres(),
            s.train_rms,
            s.val_rms,
            if e.is_empty() {
                "—".into()
            } else {
                e.join(", ")
            }
        );
    }
}
