//! `fit` and `explain` on a unit other than the paper's: the unit's
//! effects parsed against its channels, its logs read in segments, the
//! observability refusal, and the model saved with its unit.

use anyhow::{Result, anyhow};
use cli_support::progress::Progress;
use dtg_vib::pipeline::RateReference;
use dtg_vib::unit_sensor::{UnitEffect, UnitEffectError, UnitModel, UnitSensor};
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use std::sync::atomic::{AtomicUsize, Ordering};
use sysid::Sensor;

use super::super::fit::{FitReport, print_fit_channels, print_record_scores};
use super::super::fit_args::{
    FitArgs, check_against_record, fit_inputs, fit_options_with, window_signals,
};
use super::{borrowed, check_observable, read_records, sensor, signals};

/// The line that says which signals the records chose for the window, if they did.
fn print_window_signals(m: &sysid::Model<UnitSensor>) {
    if let Some(w) = m.choice().and_then(|c| c.window_signals.as_ref()) {
        println!("{}", w.line());
    }
}

/// The loop's options for the unit, and the rate reference, from the fit
/// flags: `--effects` must suit every channel, `--add-effect CHANNEL=ID`
/// its channel's model.
pub fn unit_fit_options(
    a: &FitArgs,
    unit: &Unit,
) -> Result<(sysid::FitOptions<UnitEffect>, RateReference)> {
    let (effects, add, o) = fit_options_with(
        a,
        |list| Ok(UnitEffect::parse_list(list)?),
        |s| {
            s.split_once('=')
                .map(|(c, e)| (c.trim().to_string(), e.trim().to_string()))
                .ok_or_else(|| UnitEffectError::NotAPair { given: s.into() }.into())
        },
    )?;
    let plug = UnitSensor::new(unit.clone());
    let mut per: Vec<Vec<UnitEffect>> = Vec::new();
    for k in 0..unit.gyros().len() {
        let mut e = Vec::new();
        for x in &effects {
            e.push(
                plug.parse_effect(k, &x.id())
                    .map_err(|err| anyhow!("--effects {x}: {err}"))?,
            );
        }
        per.push(e);
    }
    for (channel, id) in add {
        let k = unit
            .gyro_index(&channel)
            .ok_or_else(|| UnitEffectError::UnknownChannel {
                given: format!("{channel}={id}"),
                channel: channel.clone(),
                valid: unit.gyro_names().iter().map(|n| n.to_string()).collect(),
            })?;
        let e = plug
            .parse_effect(k, &id)
            .map_err(|err| anyhow!("--add-effect {channel}={id}: {err}"))?;
        if !per[k].contains(&e) {
            per[k].push(e);
        }
    }
    let recipe = sysid::Recipe {
        preprocess: o.preprocess.sysid(),
        split: o.split,
        effects: per,
        settings: o.settings,
    };
    Ok((
        sysid::FitOptions {
            recipe,
            validate_on: o.validate_on,
        },
        o.preprocess.rate_reference,
    ))
}

/// What a fit on a unit starts from: the plug-in, the options, the records.
struct Inputs {
    sensor: UnitSensor,
    options: sysid::FitOptions<UnitEffect>,
    records: Vec<(String, Record)>,
    notes: super::Read,
    /// The window's signals the records chose (`--window-signals auto`).
    window: Option<sysid::window::signal_choice::WindowSignalsChoice>,
}

fn inputs(a: &FitArgs, unit: Unit) -> Result<Inputs> {
    outfile::guard_file("--out", &a.out, &fit_inputs(a))?;
    let (mut options, reference) = unit_fit_options(a, &unit)?;
    let sensor = sensor(unit, a.calib.as_deref(), reference)?;
    let mut read = read_records(&a.data, &sensor.unit, 2 * a.window)?;
    for (_, r) in &read.records {
        check_against_record(a, r)?;
    }
    check_observable(&sensor, &read.records)?;
    let records = std::mem::take(&mut read.records);
    let window = window_signals(a, &mut options.recipe.preprocess.window, || {
        let named = signals(&records)?;
        Ok(sysid::choose_window_signals(&sensor, &borrowed(&named))?)
    })?;
    Ok(Inputs {
        sensor,
        options,
        records,
        notes: read,
        window,
    })
}

/// The split as `fit --json` says it.
fn split_text(m: &sysid::Model<UnitSensor>) -> String {
    match m.validated_on() {
        Some(name) => format!("by record (validated on {name})"),
        None => m.split().to_string(),
    }
}

/// `fit --unit`.
pub fn fit(a: &FitArgs, unit: Unit, progress: Progress) -> Result<()> {
    let Inputs {
        sensor,
        options,
        records,
        notes,
        window,
    } = inputs(a, unit)?;
    let named = signals(&records)?;
    let n = sensor.unit.gyros().len();
    let done = AtomicUsize::new(0);
    let start = std::time::Instant::now();
    let (mut model, prepared) =
        sysid::fit_records(&sensor, &borrowed(&named), &options, &|stage| match stage {
            sysid::FitStage::Preparing => progress.say("preparing the records"),
            sysid::FitStage::ChannelDone(ch) => {
                let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress.say(format!("fitted {k}/{n} channels (last {ch})"));
            }
        })?;
    if records.len() > 1 {
        model = model.with_records(records.iter().map(|(n, _)| n.clone()).collect());
    }
    if let Some(w) = window {
        model = model.with_window_signals(w);
    }
    // Each record's (or log segment's) validation rms; with --cv records,
    // each validated by a model fitted on the others.
    let per_record = match a.cv.is_some() {
        true => {
            progress.say("leaving one record out");
            Some(sysid::fit::leave_one_record_out(&prepared, &options)?)
        }
        false if records.len() > 1 => Some(sysid::fit::record_scores(&model, &prepared)?),
        false => None,
    };
    let seconds = start.elapsed().as_secs_f64();
    let model = UnitModel::of(model);
    model.save(&a.out)?;
    progress.clear();
    notes.say_notes();
    let m = model.inner();
    if a.json {
        let mut report =
            FitReport::of_channels(m.channels(), split_text(m), seconds).with_choice(m);
        if let Some(per) = &per_record {
            report.set_records(per, a.cv.clone());
        }
        let mut v = serde_json::to_value(&report)?;
        v["unit"] = serde_json::Value::String(sensor.unit.name().to_string());
        println!("{v}");
    } else {
        println!("unit: {} ({})", sensor.unit.name(), sensor.unit.file());
        print_fit_channels(m.channels());
        print_window_signals(m);
        if let Some(per) = &per_record {
            print_record_scores(&sensor.channels(), per, a.cv.is_some());
        }
        println!("model: {} ({:.2} s)", a.out.display(), seconds);
    }
    Ok(())
}

/// `explain --unit`.
pub fn explain(
    a: &FitArgs,
    unit: Unit,
    diagnose: &sysid::diagnose::DiagnoseOptions,
    max_rounds: usize,
    report: Option<&std::path::Path>,
    progress: Progress,
) -> Result<()> {
    let Inputs {
        sensor,
        options,
        records,
        notes,
        window,
    } = inputs(a, unit)?;
    let named = signals(&records)?;
    let start = std::time::Instant::now();
    let e = sysid::explain::explain(
        &sensor,
        &borrowed(&named),
        &options,
        diagnose,
        max_rounds,
        &|stage| match stage {
            sysid::explain::ExplainStage::Fitting(n) => progress.say(format!("round {n}: fitting")),
            sysid::explain::ExplainStage::ChannelFitted(n, ch) => {
                progress.say(format!("round {n}: {ch} fitted"))
            }
            sysid::explain::ExplainStage::Diagnosing(n) => {
                progress.say(format!("round {n}: diagnosing"))
            }
        },
    )?;
    let seconds = start.elapsed().as_secs_f64();
    let model = UnitModel::of(match window {
        Some(w) => e.model.with_window_signals(w),
        None => e.model,
    });
    model.save(&a.out)?;
    let page = match report {
        Some(dir) => {
            progress.say("drawing figures");
            let last = &e.rounds.last().expect("at least one round").diagnosis;
            Some(dtg_vib::report::write_diagnosis_report_of(
                last,
                diagnose.rank.min_err(),
                &dtg_vib::report::Wording::of_unit(&sensor.unit),
                dir,
            )?)
        }
        None => None,
    };
    progress.clear();
    notes.say_notes();
    let m = model.inner();
    if a.json {
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        let v = serde_json::json!({
            "unit": sensor.unit.name(),
            "rounds": &e.rounds,
            "converged": e.converged,
            "final": FitReport::of_channels(m.channels(), split_text(m), seconds).with_choice(m),
        });
        println!("{v}");
        return Ok(());
    }
    println!("unit: {} ({})", sensor.unit.name(), sensor.unit.file());
    super::super::findings::print_rounds(&e.rounds, e.converged, max_rounds as u64);
    print_fit_channels(m.channels());
    print_window_signals(m);
    println!("model: {} ({:.1} s)", a.out.display(), seconds);
    if let Some(p) = &page {
        println!("report: {}", p.display());
    }
    Ok(())
}
