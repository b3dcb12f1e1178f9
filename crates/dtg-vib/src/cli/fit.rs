//! `dtg-vib fit`: the six channel models fitted on the records, saved, and
//! their scores printed (or written as JSON; `explain` prints its final fit
//! the same way).

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::fit::{FitStage, fit_records};
use dtg_vib::model::CompensationModel;
use nav_sensors::calibration::Calibration;
use nav_sensors::record::Record;

use super::fit_args::{FitArgs, fit_inputs, fit_options, read_records, window_signals};
use dtg_vib::fit::choose_window_signals;

/// The paper unit's model with the choice of its window's signals in its
/// report, when the records chose them.
pub fn with_window_signals(
    model: CompensationModel,
    window: Option<sysid::window::signal_choice::WindowSignalsChoice>,
) -> CompensationModel {
    match window {
        Some(w) => CompensationModel::of(model.inner().clone().with_window_signals(w)),
        None => model,
    }
}

/// Fits, saves the model and prints its scores.
pub fn run(a: FitArgs, progress: Progress) -> Result<()> {
    if let Some(unit) = super::unit::chosen(a.unit.as_deref())? {
        return super::unit::fit::fit(&a, unit, progress);
    }
    outfile::guard_file("--out", &a.out, &fit_inputs(&a))?;
    let mut options = fit_options(&a)?;
    let records = read_records(&a)?;
    let calibration = a.calib.as_ref().map(Calibration::load).transpose()?;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let start = std::time::Instant::now();
    let named: Vec<(String, &Record)> = records.iter().map(|(n, r)| (n.clone(), r)).collect();
    let window = window_signals(&a, &mut options.preprocess.window, || {
        Ok(choose_window_signals(&named, calibration.as_ref())?)
    })?;
    let (model, prepared) = fit_records(
        &named,
        calibration.as_ref(),
        &options,
        &|stage| match stage {
            FitStage::Preparing => progress.say("preparing the record"),
            FitStage::ChannelDone(ch) => {
                let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress.say(format!("fitted {n}/6 channels (last {ch})"));
            }
        },
    )?;
    let model = with_window_signals(model, window);
    let per_record = match a.cv.is_some() {
        true => {
            progress.say("leaving one record out");
            Some(dtg_vib::fit::leave_one_record_out(&prepared, &options)?)
        }
        false if records.len() > 1 => Some(dtg_vib::fit::record_scores(&model, &prepared)?),
        false => None,
    };
    let fit_seconds = start.elapsed().as_secs_f64();
    model.save(&a.out)?;
    progress.clear();
    let n_train = model.channels()[0].scores().n_train;
    let stride = dtg_vib::fit::selection_stride(n_train);
    if stride > 1 {
        eprintln!(
            "note: {n_train} training windows: cross-validation and centre selection used every {stride}th of them ({}); the weights were solved on all",
            n_train.div_ceil(stride)
        );
    }
    if a.json {
        let mut report = FitReport::new(&model, fit_seconds);
        if let Some(per) = &per_record {
            report.set_records(per, a.cv.clone());
        }
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print_fit(&model);
        if let Some(c) = model.inner().choice() {
            print_choice(c);
        }
        if let Some(per) = &per_record {
            let names = nav_sensors::geometry::Channel::ALL.map(|c| c.name().to_string());
            print_record_scores(&names, per, a.cv.is_some());
        }
        println!("model: {} ({:.2} s)", a.out.display(), fit_seconds);
    }
    Ok(())
}

/// What the choice of input and smoother weighed: each candidate's mean
/// validation rms and worst ADEV after/before, the chosen one marked, and
/// what it cost and gained against the paper's model (raw, no smoother).
pub fn print_choice(c: &dtg_vib::fit::ChoiceReport) {
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
pub fn print_record_scores(
    channels: &[String],
    per: &[Vec<dtg_vib::fit::RecordScore>],
    loro: bool,
) {
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

/// Each channel's centres, scores and effect coefficients (the fit's
/// estimates, from the training rows), each with its standard error and 95%
/// interval.
pub fn print_fit(model: &CompensationModel) {
    print_fit_channels(model.channels());
}

/// [`print_fit`] of any sensor's channel models.
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

/// `fit --json`.
#[derive(serde::Serialize)]
pub struct FitReport {
    channels: Vec<ChannelReport>,
    split: String,
    fit_seconds: f64,
    /// `records` with `--cv records`.
    #[serde(skip_serializing_if = "Option::is_none")]
    cv: Option<String>,
    /// The networks' input (`raw`, `statistics`).
    input: sysid::ModelInput,
    /// The prediction smoother's cut-off, Hz (null: none).
    smoother_hz: Option<f64>,
    /// What `--input auto` / `--smoother auto` chose among, with every
    /// candidate's validation rms and worst Allan-deviation ratio.
    #[serde(skip_serializing_if = "Option::is_none")]
    choice: Option<dtg_vib::fit::ChoiceReport>,
}

/// One channel of [`FitReport`].
#[derive(serde::Serialize)]
struct ChannelReport {
    channel: String,
    effects: Vec<String>,
    // The key is a contract (issue 24 §5: code says centre, JSON keys stay).
    #[serde(rename = "n_centers")]
    n_centres: usize,
    train_rms: f64,
    val_rms: f64,
    val_rms_bias_only: f64,
    val_fit_percent: f64,
    width: f64,
    bias: f64,
    effect_coefficients: std::collections::BTreeMap<String, CoefficientReport>,
    /// Validation rms per record, with several records.
    #[serde(skip_serializing_if = "Option::is_none")]
    records: Option<Vec<dtg_vib::fit::RecordScore>>,
}

/// One effect coefficient of [`ChannelReport`].
#[derive(serde::Serialize)]
struct CoefficientReport {
    value: f64,
    unit: String,
    /// Absent for a model file that predates standard errors.
    #[serde(skip_serializing_if = "Option::is_none")]
    se: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ci95: Option<[f64; 2]>,
}

impl FitReport {
    pub fn new(model: &CompensationModel, fit_seconds: f64) -> Self {
        let split = match model.validated_on() {
            Some(name) => format!("by record (validated on {name})"),
            None => model.split().to_string(),
        };
        Self::of_channels(model.channels(), split, fit_seconds).with_choice(model.inner())
    }

    /// The model's input, smoother and the fit's choice among candidates.
    pub fn with_choice<S: sysid::Sensor>(mut self, model: &sysid::Model<S>) -> Self {
        self.input = model.preprocess().input;
        self.smoother_hz = model.preprocess().smoother.map(|s| s.cutoff_hz);
        self.choice = model.choice().cloned();
        self
    }

    /// Each channel's validation rms per record (`per`, in channel order),
    /// and `records` for `--cv records`.
    pub fn set_records(&mut self, per: &[Vec<dtg_vib::fit::RecordScore>], cv: Option<String>) {
        for (c, r) in self.channels.iter_mut().zip(per) {
            c.records = Some(r.clone());
        }
        self.cv = cv;
    }

    /// The report of any sensor's channel models.
    pub fn of_channels<C: Clone + std::fmt::Display, E: sysid::Effect>(
        channels: &[sysid::ChannelModel<C, E>],
        split: String,
        fit_seconds: f64,
    ) -> Self {
        let channels = channels
            .iter()
            .map(|c| {
                let s = c.scores();
                let effect_coefficients = c
                    .effects()
                    .iter()
                    .zip(c.effect_coefficients())
                    .enumerate()
                    .map(|(j, (e, v))| {
                        let k = c.coefficients().map(|k| &k[j]);
                        (
                            e.id(),
                            CoefficientReport {
                                value: v,
                                unit: e.unit(),
                                se: k.map(|k| k.se),
                                ci95: k.map(|k| k.ci95),
                            },
                        )
                    })
                    .collect();
                ChannelReport {
                    channel: c.channel().to_string(),
                    effects: c.effects().iter().map(|e| e.id()).collect(),
                    n_centres: c.n_centres(),
                    train_rms: s.train_rms,
                    val_rms: s.val_rms,
                    val_rms_bias_only: s.val_rms_bias_only,
                    val_fit_percent: s.val_fit_percent,
                    width: c.width(),
                    bias: c.bias(),
                    effect_coefficients,
                    records: None,
                }
            })
            .collect();
        Self {
            channels,
            split,
            fit_seconds,
            cv: None,
            input: sysid::ModelInput::default(),
            smoother_hz: None,
            choice: None,
        }
    }
}
