//! `dtg-vib fit`: every channel model of the unit fitted on the records,
//! saved with the unit, and their scores printed (or written as JSON;
//! `explain` prints its final fit the same way).

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::commands::fit::{Fitted, fit};
use dtg_vib::unit_sensor::UnitSensor;
use std::sync::atomic::{AtomicUsize, Ordering};
use sysid::Sensor;
use sysid::inference::Coefficient;

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
    for line in choice_lines(c) {
        println!("{line}");
    }
}

/// An ADEV ratio as the table says it: "not judged" when no run was long
/// enough (NaN).
fn adev_ratio(r: f64) -> String {
    if r.is_nan() {
        "not judged".to_string()
    } else {
        format!("{r:.3}")
    }
}

/// The lines [`print_choice`] prints. The candidates' table only when there
/// was a choice (more than one candidate, or an ADEV run or an input
/// sample): with one candidate given (`--input raw --smoother none`) it
/// would compare that candidate with itself.
pub fn choice_lines(c: &sysid::fit::ChoiceReport) -> Vec<String> {
    let mut out: Vec<String> = c.window_signals.iter().map(|w| w.line()).collect();
    let chose = c.candidates.len() > 1 || c.adev_runs > 0 || c.input_sample.is_some();
    if chose {
        out.extend(candidate_lines(c));
    }
    for s in &c.networks_shrunk {
        out.push(format!("  network shrunk (bias and effects kept): {s}"));
    }
    for s in &c.bias_instability_raised {
        out.push(format!("  bias instability raised: {s}"));
    }
    out
}

/// The choice's header, its candidates' table, the input sample and the
/// cost and gain against raw/none.
fn candidate_lines(c: &sysid::fit::ChoiceReport) -> Vec<String> {
    let label = sysid::Smoother::label;
    let mut out = vec![
        format!(
            "input and smoother: chosen {} / {} among {} candidates (lowest mean validation rms whose compensation keeps ADEV ≤ before × (1 + hw68) at every τ; {} validation run(s) checked):",
            c.chosen().input,
            label(c.chosen().smoother),
            c.candidates.len(),
            c.adev_runs
        ),
        "  input       smoother  val rms (deg/h)  worst ADEV after/before (channel, τ s)  passes"
            .to_string(),
    ];
    for (i, k) in c.candidates.iter().enumerate() {
        let worst = match k.worst_adev_ratio.is_nan() {
            true => format!("{:>10}", "not judged"),
            false => format!(
                "{:>6.3} ({}, {:.2})",
                k.worst_adev_ratio, k.worst_channel, k.worst_tau_s
            ),
        };
        out.push(format!(
            "{} {:<10}  {:<8}  {:>15.4}  {worst}{:>14}",
            if i == c.chosen { "*" } else { " " },
            k.input.to_string(),
            label(k.smoother),
            k.mean_val_rms,
            if k.passes { "yes" } else { "no" }
        ));
    }
    if let Some(s) = &c.input_sample {
        out.extend(input_sample_lines(s));
    }
    let w = c.chosen();
    if let Some(b) = c.baseline().filter(|&b| b != w) {
        out.push(format!(
            "  against raw/none: validation rms {:.4} → {:.4} deg/h, worst ADEV ratio {} → {}",
            b.mean_val_rms,
            w.mean_val_rms,
            adev_ratio(b.worst_adev_ratio),
            adev_ratio(w.worst_adev_ratio)
        ));
    }
    out
}

/// How the input was chosen on a sample of the record.
fn input_sample_lines(s: &sysid::fit::InputSample) -> Vec<String> {
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
    let mut out = vec![format!(
        "  the input was chosen on a sample of {} rows ({} chunks spread over the record; best validation rms there: {} deg/h), and only it was fitted on the whole record",
        s.rows,
        s.chunks,
        inputs.join(", ")
    )];
    if let Some(t) = &s.shared_centres {
        out.push(format!(
            "  one centre selection for all channels on that sample: mean validation rms {:.4} against {:.4} deg/h with one per channel; {}",
            t.shared_mean_val_rms,
            t.per_channel_mean_val_rms,
            match t.taken {
                true => "the record was fitted with one (within 1%)",
                false => "the record was fitted with one per channel",
            }
        ));
    }
    out
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
/// when no channel has a family of two or more taps); when the model kept
/// no joint covariance of its coefficients, one line saying so instead.
pub fn print_frequency_responses(m: &sysid::Model<UnitSensor>) {
    use dtg_vib::unit_sensor::frequency_response::{BANDS, lines, responses};
    let mut all = Vec::new();
    // Each reason once, with the channels it holds for: a model without the
    // joint covariance gives every channel the same one.
    let mut missing: Vec<(String, Vec<String>)> = Vec::new();
    for c in m.channels() {
        match responses(c.effects(), c.coefficients(), m.dt_s()) {
            Ok(families) => all.extend(lines(&c.channel().to_string(), &families)),
            Err(e) => {
                let (reason, name) = (e.to_string(), c.channel().to_string());
                match missing.iter_mut().find(|(r, _)| *r == reason) {
                    Some((_, names)) => names.push(name),
                    None => missing.push((reason, vec![name])),
                }
            }
        }
    }
    missing_response_lines(&missing, m.channels().len())
        .iter()
        .for_each(|l| println!("{l}"));
    if all.is_empty() {
        return;
    }
    println!(
        "frequency response of each tap family (mean response over {BANDS} bands to {} Hz; 95% intervals from the taps' joint covariance):",
        dtg_vib::numfmt::short((5.0 / m.dt_s()).round() / 10.0)
    );
    all.iter().for_each(|l| println!("{l}"));
}

/// One line per reason a frequency response is not given, naming its
/// channels unless it holds for all `channels` of the model.
fn missing_response_lines(missing: &[(String, Vec<String>)], channels: usize) -> Vec<String> {
    missing
        .iter()
        .map(|(reason, names)| {
            let of = if names.len() == channels {
                String::new()
            } else {
                format!(" ({})", names.join(", "))
            };
            format!("frequency response of the tap families{of}: not given: {reason}")
        })
        .collect()
}

/// Each channel's centres, scores and effect coefficients (the fit's
/// estimates, from the training rows), each with its standard error and 95%
/// interval. A family of taps (`ID`, `ID@1`, … of a dynamic effect) takes
/// one line below its channel's ([`effect_cells`]); `--json` holds every tap.
pub fn print_fit_channels<C: Clone + std::fmt::Display, E: sysid::Effect>(
    channels: &[sysid::ChannelModel<C, E>],
) {
    println!(
        "channel  centres  train rms  val rms  (deg/h)  effects (coefficient ± standard error, 95% CI)"
    );
    for c in channels {
        let s = c.scores();
        let effects: Vec<(String, Option<Coefficient>)> = c
            .effects()
            .iter()
            .enumerate()
            .map(|(j, e)| (e.id(), c.coefficients().map(|k| k[j].clone())))
            .collect();
        let (singles, families) = effect_cells(&effects);
        println!(
            "{:>7}  {:>7}  {:>9.4}  {:>7.4}           {}",
            c.channel().to_string(),
            c.n_centres(),
            s.train_rms,
            s.val_rms,
            match (singles.is_empty(), families.is_empty()) {
                (true, true) => "—".into(),
                (true, false) => format!("{} effects:", effects.len()),
                _ => singles.join(", "),
            }
        );
        for f in families {
            println!("{:>9}{f}", "");
        }
    }
}

/// An effect with its coefficient as the table prints it.
fn effect_cell(id: &str, k: Option<&Coefficient>) -> String {
    match k {
        Some(k) => format!(
            "{id} {:.4} ± {:.4} {} ({:.4} to {:.4})",
            k.value, k.se, k.unit, k.ci95[0], k.ci95[1]
        ),
        None => id.to_string(),
    }
}

/// A channel's effects in the table: the effects alone, and one line per
/// family of two or more taps (ids `ID` and `ID@LAG` of one `ID`) with its
/// lags, how many taps are significant (95% interval excluding
/// zero) and its largest tap in magnitude, in the order the effects come.
fn effect_cells(effects: &[(String, Option<Coefficient>)]) -> (Vec<String>, Vec<String>) {
    let base = |id: &str| -> (String, usize) {
        match id.rsplit_once('@').map(|(b, l)| (b, l.parse::<usize>())) {
            Some((b, Ok(lag))) => (b.to_string(), lag),
            _ => (id.to_string(), 0),
        }
    };
    let mut order: Vec<String> = Vec::new();
    for (id, _) in effects {
        let b = base(id).0;
        if !order.contains(&b) {
            order.push(b);
        }
    }
    let (mut singles, mut families) = (Vec::new(), Vec::new());
    for b in order {
        let taps: Vec<(usize, &String, Option<&Coefficient>)> = effects
            .iter()
            .filter(|(id, _)| base(id).0 == b)
            .map(|(id, k)| (base(id).1, id, k.as_ref()))
            .collect();
        if let [(_, id, k)] = taps[..] {
            singles.push(effect_cell(id, k));
            continue;
        }
        let lags = taps.iter().map(|t| t.0);
        let (lo, hi) = (lags.clone().min().unwrap_or(0), lags.max().unwrap_or(0));
        let known: Vec<(&String, &Coefficient)> = taps
            .iter()
            .filter_map(|(_, id, k)| k.map(|k| (*id, k)))
            .collect();
        let Some((largest, k)) = known
            .iter()
            .max_by(|a, b| a.1.value.abs().total_cmp(&b.1.value.abs()))
        else {
            families.push(format!("{b}@{lo}..{hi} ({} taps)", taps.len()));
            continue;
        };
        let significant = known
            .iter()
            .filter(|(_, k)| k.ci95[0] > 0.0 || k.ci95[1] < 0.0)
            .count();
        families.push(format!(
            "{b}@{lo}..{hi} ({} taps): {significant} significant; largest {}",
            taps.len(),
            effect_cell(largest, Some(k))
        ));
    }
    (singles, families)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A family of taps takes one line (lags, count, unit, significant
    /// taps, the largest); an effect alone prints as itself.
    #[test]
    fn a_family_of_taps_is_one_line() {
        let k = |v: f64, lo: f64, hi: f64| Some(Coefficient::new(v, 1.0, [lo, hi], "ppm"));
        let effects = vec![
            (
                "g_z".to_string(),
                Some(Coefficient::new(2.0, 0.5, [1.0, 3.0], "deg/h/g")),
            ),
            ("sf".to_string(), k(-3.0, -5.0, -1.0)),
            ("sf@1".to_string(), k(7.0, 5.0, 9.0)),
            ("sf@2".to_string(), k(0.5, -1.5, 2.5)),
        ];
        let (singles, families) = effect_cells(&effects);
        assert_eq!(singles, ["g_z 2.0000 ± 0.5000 deg/h/g (1.0000 to 3.0000)"]);
        assert_eq!(
            families,
            [
                "sf@0..2 (3 taps): 2 significant; largest sf@1 7.0000 ± 1.0000 ppm (5.0000 to 9.0000)"
            ]
        );
    }

    /// A reason that holds for every channel is said once without names;
    /// one that holds for some names them, and no channel's reason hides
    /// another's.
    #[test]
    fn each_missing_response_reason_is_said_with_its_channels() {
        let missing = vec![
            (
                "no covariance".to_string(),
                vec!["g1".to_string(), "g2".to_string()],
            ),
            ("no interval".to_string(), vec!["g3".to_string()]),
        ];
        assert_eq!(
            missing_response_lines(&missing, 3),
            [
                "frequency response of the tap families (g1, g2): not given: no covariance",
                "frequency response of the tap families (g3): not given: no interval",
            ]
        );
        assert_eq!(
            missing_response_lines(&missing[..1], 2),
            ["frequency response of the tap families: not given: no covariance"]
        );
    }
    use sysid::fit::{Candidate, ChoiceReport};

    fn candidate(input: sysid::ModelInput, rms: f64, adev: f64) -> Candidate {
        Candidate {
            input,
            smoother: None,
            val_rms: vec![rms],
            mean_val_rms: rms,
            worst_adev_ratio: adev,
            worst_channel: if adev.is_nan() {
                String::new()
            } else {
                "g1".into()
            },
            worst_tau_s: if adev.is_nan() { f64::NAN } else { 0.5 },
            worst_excess: adev,
            passes: true,
        }
    }

    fn report(candidates: Vec<Candidate>, shrunk: Vec<String>) -> ChoiceReport {
        ChoiceReport {
            candidates,
            chosen: 0,
            adev_runs: 0,
            networks_shrunk: shrunk,
            input_sample: None,
            bias_instability_raised: Vec::new(),
            window_signals: Vec::new(),
        }
    }

    /// One candidate given (`--input raw --smoother none`): no table
    /// comparing it with itself, no NaN; the shrunk networks still said.
    #[test]
    fn one_candidate_prints_no_choice_and_no_nan() {
        let raw = candidate(sysid::ModelInput::Raw, 3878.78, f64::NAN);
        let lines = choice_lines(&report(vec![raw], vec!["g1 to zero".into()]));
        assert_eq!(
            lines,
            ["  network shrunk (bias and effects kept): g1 to zero"],
            "{lines:?}"
        );
    }

    /// Two candidates whose ADEV was not judged: the table and the line
    /// against raw/none say "not judged", never NaN.
    #[test]
    fn an_unjudged_adev_is_said_not_judged() {
        let mut c = report(
            vec![
                candidate(sysid::ModelInput::Raw, 2.0, f64::NAN),
                candidate(sysid::ModelInput::Statistics, 1.0, f64::NAN),
            ],
            Vec::new(),
        );
        c.chosen = 1;
        let text = choice_lines(&c).join("\n");
        assert!(!text.contains("NaN"), "{text}");
        assert!(
            text.contains("against raw/none: validation rms 2.0000 → 1.0000 deg/h, worst ADEV ratio not judged → not judged"),
            "{text}"
        );
        c.candidates[1].worst_adev_ratio = 0.95;
        assert!(choice_lines(&c).join("\n").contains("not judged → 0.950"));
    }
}
