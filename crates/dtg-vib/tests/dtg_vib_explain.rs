//! The loop to the noise floor (`dtg-vib explain`): two effects on one
//! channel are both found, a clean record gets nothing, and the coefficients'
//! 95% intervals cover the simulated truth.
//!
//! The statistical claims over many seeds (false-alarm rate per record over
//! 50 clean records, power on the two-effect record, interval coverage over
//! 100 seeds) are the `#[ignore]`d tests at the end:
//! `cargo test --release -p dtg-vib --test dtg_vib_explain -- --ignored --nocapture`
//! prints what docs/dtg-vib.md quotes.
//!
//! The paper's unit runs the one plug-in ([`paper_fit`]).

mod paper_fit;

use dtg_vib::diagnose::DiagnoseOptions;
use dtg_vib::unit_sensor::{UnitModel, UnitSensor, to_signals};
use nav_sensors::dtg::DtgTerm;
use nav_sensors::geometry::Channel;
use nav_sensors::sim::{HiddenEffect, Scenario};
use nav_sensors::vibration::{Drive, PsdTable};
use paper_fit::{diagnose_records, fit, options, simulate};

/// The tri-axial record with two effects hidden on Y1: an anisoelastic term
/// (gg_IS, 0.4 deg/h/g²) and a drift temperature sensitivity of
/// `temp_deg_h_per_c` (the unit's temperature ramps by 8 °C over the record).
/// At 0.06 deg/h/°C the temperature term explains about half of what gg_IS
/// leaves.
fn two_effects(temp_deg_h_per_c: f64) -> Scenario {
    let mut s = Scenario::triaxial_hidden();
    s.name = "two_effects".into();
    s.gyros
        .channels
        .entry(Channel::Z)
        .or_default()
        .set(DtgTerm::Temp, 0.0);
    s.gyros
        .channels
        .entry(Channel::Y1)
        .or_default()
        .set(DtgTerm::Temp, temp_deg_h_per_c);
    s.hidden = vec![
        HiddenEffect {
            channel: Channel::Y1,
            term: DtgTerm::GgIS,
        },
        HiddenEffect {
            channel: Channel::Y1,
            term: DtgTerm::Temp,
        },
    ];
    s
}

/// The same record with the hidden terms set to zero (same seed, same noise).
fn without_hidden(s: &Scenario) -> Scenario {
    let mut clean = s.clone();
    for h in &s.hidden {
        clean
            .gyros
            .channels
            .entry(h.channel)
            .or_default()
            .set(h.term, 0.0);
    }
    clean.hidden.clear();
    clean
}

/// Tri-axial random vibration at 1–8 Hz, well below the 50-Hz output rate,
/// so the record resolves the within-interval power that a g² regressor
/// needs (at 3–20 Hz the neighbouring-sample estimate misses about 9% of it,
/// and the coefficient comes out that much high: docs/dtg-vib.md, limits).
fn resolved_vibration(mut s: Scenario) -> Scenario {
    for d in &mut s.vibration.drives {
        if let Drive::Random { psd, .. } = d {
            *psd = PsdTable::new(vec![[1.0, 0.05], [2.0, 0.2], [6.0, 0.2], [8.0, 0.05]])
                .expect("valid table");
        }
    }
    s
}

/// The default fit of `s`'s clean twin (the same record without its
/// hidden terms): what a refit with the hidden effects should come near.
fn clean_twin_fit(s: &Scenario) -> UnitModel {
    let clean = simulate(&without_hidden(s));
    fit(&clean.record, Some(&clean.calibration), &options())
}

fn id_of(term: DtgTerm) -> String {
    if term == DtgTerm::Temp {
        "col:temp".into()
    } else {
        term.id().into()
    }
}

/// Simulates `scenario` and runs the loop with default settings; returns
/// the loop and the `CHANNEL=ID` it added, sorted.
fn explain_with_defaults(
    scenario: &Scenario,
) -> (sysid::explain::Explanation<UnitSensor>, Vec<String>) {
    let sim = simulate(scenario);
    let sensor = paper_fit::sensor(Some(&sim.calibration));
    let signals = to_signals(&sim.record).unwrap();
    let e = sysid::explain::explain(
        &sensor,
        &[("r".to_string(), &signals)],
        &options(),
        &DiagnoseOptions::default(),
        5,
        &|_| {},
    )
    .unwrap();
    let mut added: Vec<String> = e
        .rounds
        .iter()
        .flat_map(|r| {
            r.added
                .iter()
                .map(|a| format!("{}={}", a.channel, a.effect))
        })
        .collect();
    added.sort();
    (e, added)
}

#[test]
fn explain_finds_both_effects_on_one_channel_and_reaches_the_clean_records_error() {
    let scenario = two_effects(0.06);
    let (e, added) = explain_with_defaults(&scenario);
    assert!(
        e.converged,
        "still suggesting after {} rounds",
        e.rounds.len()
    );
    assert_eq!(added, ["Y1=col:temp", "Y1=gg_IS"]);

    // The final model's Y1 against a fit of the same record without the hidden terms.
    let reference = clean_twin_fit(&scenario);
    for (k, c) in e.model.channels().iter().enumerate() {
        let r = c.scores().val_rms / reference.inner().channel(k).scores().val_rms;
        eprintln!(
            "{}: val rms {:.4} deg/h, {r:.3}× the clean record's",
            c.channel(),
            c.scores().val_rms
        );
        assert!(r <= 1.10, "{}: {r:.3}× the clean record's rms", c.channel());
    }
    // The coefficients stored in the final model, with their intervals, against the truth.
    let y1 = e.model.channel(Channel::Y1.index());
    let k = y1.coefficients().expect("intervals");
    for (effect, coef) in y1.effects().iter().zip(k) {
        eprintln!(
            "Y1 {effect}: {:.4} ± {:.4} {} [{:.4}, {:.4}]",
            coef.value, coef.se, coef.unit, coef.ci95[0], coef.ci95[1]
        );
        assert!(coef.se > 0.0 && coef.ci95[0] < coef.value && coef.value < coef.ci95[1]);
    }
}

/// Per effect, its id, how many seeds' stored 95% intervals covered the
/// truth and the number of seeds; and the largest ratio of a refit
/// channel's validation rms to its clean twin's (the same seed without the
/// hidden terms, fitted without them).
struct Coverage {
    tally: Vec<(String, usize, usize)>,
    worst_twin_ratio: f64,
}

/// One fit per seed with both effects named (issue 10's records: the
/// tri-axial record with gg_IS on Y1 and a temperature term on Z, on 1–8 Hz
/// drives), and one of its clean twin; the stored coefficients (cross-fitted
/// on every row, issue 23 §3) against the truth.
fn coverage(seeds: std::ops::Range<u64>) -> Coverage {
    let base = resolved_vibration(Scenario::triaxial_hidden());
    let add: Vec<String> = base
        .hidden
        .iter()
        .map(|h| format!("{}={}", h.channel, id_of(h.term)))
        .collect();
    let mut tally: Vec<(String, usize, usize)> = base
        .hidden
        .iter()
        .map(|h| (format!("{}={}", h.channel, id_of(h.term)), 0, 0))
        .collect();
    let mut worst_twin_ratio = 0.0f64;
    for seed in seeds {
        let mut s = base.clone();
        s.seed = 1_000_003 * (seed + 1);
        let sim = simulate(&s);
        let mut options = options();
        paper_fit::add(
            &mut options,
            &add.iter().map(String::as_str).collect::<Vec<_>>(),
        );
        let m = fit(&sim.record, Some(&sim.calibration), &options);
        let twin = clean_twin_fit(&s);
        for (h, t) in base.hidden.iter().zip(&mut tally) {
            let c = m.inner().channel(h.channel.index());
            let j = c
                .effects()
                .iter()
                .position(|e| e.id() == id_of(h.term))
                .unwrap();
            let k = &c.coefficients().expect("intervals")[j];
            let truth = s.gyro(h.channel).get(h.term);
            t.1 += usize::from(k.covers(truth));
            t.2 += 1;
            let twin_rms = twin.inner().channel(h.channel.index()).scores().val_rms;
            let ratio = c.scores().val_rms / twin_rms;
            worst_twin_ratio = worst_twin_ratio.max(ratio);
            eprintln!(
                "seed {seed} {}: {:.4} ± {:.4} (truth {truth}){}; val rms {ratio:.3}× the clean twin's",
                t.0,
                k.value,
                k.se,
                if k.covers(truth) { "" } else { "  MISSED" }
            );
        }
    }
    Coverage {
        tally,
        worst_twin_ratio,
    }
}

/// The short coverage check CI runs: over 8 seeds each 95% interval covers
/// the truth at least 6 times (P(≤ 5 of 8 | 95%) = 0.6%), and every refit
/// channel stays within 1.1× its clean twin's validation rms.
#[test]
fn intervals_cover_the_true_coefficients_on_a_few_seeds() {
    let c = coverage(0..8);
    for (effect, covered, n) in c.tally {
        assert!(covered >= 6, "{effect}: covered {covered} of {n}");
    }
    assert!(
        c.worst_twin_ratio <= 1.1,
        "a refit is {:.3}× its clean twin",
        c.worst_twin_ratio
    );
}

/// Coverage over 100 seeds: must lie in 90–99% for the temperature and the
/// g² term (issue 23's acceptance), every refit within 1.1× its clean twin.
///
/// Measured with the coefficients cross-fitted on every row (4, 6 and 8
/// alternating spans, their spread in the interval, partialled with the
/// raw window whatever the network's input): Y1=gg_IS 94/100,
/// Z=col:temp 98/100; worst refit channel 1.007× its clean twin's
/// validation rms (1.016× partialled with the chosen input). With the record cut in two halves only (the
/// diagnosis's cut) the intervals were too narrow: Y1=gg_IS 85%,
/// Z=col:temp 73% over 78 seeds.
#[test]
#[ignore = "statistical claim over 100 seeds, ~30 min: run with --ignored"]
fn interval_coverage_over_100_seeds() {
    let c = coverage(0..100);
    for (effect, covered, n) in &c.tally {
        println!("coverage {effect}: {covered}/{n}");
    }
    println!("worst refit / clean twin: {:.3}", c.worst_twin_ratio);
    for (effect, covered, n) in c.tally {
        assert!(
            (90..=99).contains(&(100 * covered / n)),
            "{effect}: {covered}/{n}"
        );
    }
    assert!(c.worst_twin_ratio <= 1.1, "{:.3}", c.worst_twin_ratio);
}

/// False alarms per record over 50 clean records: how many records get any
/// suggestion on any channel.
#[test]
#[ignore = "statistical claim over 50 seeds, ~10 min: run with --ignored"]
fn false_alarm_rate_per_record_over_50_clean_records() {
    let options = DiagnoseOptions::default();
    let mut alarms = 0;
    // Correlation tests failing per kind, over every channel of every record.
    let mut failing: std::collections::BTreeMap<String, usize> = Default::default();
    let mut tests: std::collections::BTreeMap<String, usize> = Default::default();
    let mut slow_claims = 0;
    for seed in 0..50u64 {
        let mut s = Scenario::triaxial_clean();
        s.seed = 2_000_003 * (seed + 1);
        let sim = simulate(&s);
        let m = fit(&sim.record, Some(&sim.calibration), &paper_fit::options());
        let d = diagnose_records(m.inner(), &[(String::new(), &sim.record)], &options);
        let found: Vec<String> = d
            .channels
            .iter()
            .flat_map(|c| {
                c.suggested
                    .iter()
                    .map(move |id| format!("{}={id}", c.channel))
            })
            .collect();
        if !found.is_empty() {
            alarms += 1;
            eprintln!("seed {seed}: {found:?}");
        }
        for c in &d.channels {
            for k in &c.checks {
                let kind = k.name.split(':').next().unwrap_or_default().to_string();
                *tests.entry(kind.clone()).or_default() += 1;
                *failing.entry(kind).or_default() += usize::from(!k.check.passed);
            }
            slow_claims += c
                .findings
                .iter()
                .filter(|f| f.contains("something slow"))
                .count();
        }
    }
    for (kind, n) in &tests {
        println!(
            "correlation test {kind}: failed {} of {n} (nominal 1%)",
            failing[kind]
        );
    }
    println!("'something slow' findings: {slow_claims} of 300 channels");
    println!(
        "false alarms: {alarms} of 50 clean records (design level {:.2})",
        options.rank.alpha
    );
    assert!(alarms <= 3, "{alarms} of 50");
}

/// Power on the two-effect record: the second effect is found in at least
/// 90% of seeds.
#[test]
#[ignore = "statistical claim over 20 seeds, ~15 min: run with --ignored"]
fn power_on_the_two_effect_record() {
    let mut found = 0;
    let n = 20;
    for seed in 0..n {
        let mut s = two_effects(0.06);
        s.seed = 3_000_017 * (seed + 1);
        let (_, added) = explain_with_defaults(&s);
        let both =
            added.contains(&"Y1=gg_IS".to_string()) && added.contains(&"Y1=col:temp".to_string());
        found += usize::from(both);
        eprintln!("seed {seed}: {added:?}");
    }
    println!("power: both effects found in {found} of {n} seeds");
    assert!(found * 10 >= n as usize * 9, "{found} of {n}");
}

/// The command line's contract: `explain --json` and `diagnose --json` keys,
/// and `fit --json`'s coefficients with their standard errors and intervals.
/// `dtg-vib` run in a temporary directory that holds a 60-s tri-axial
/// record with hidden effects (`sim/record.csv`, `sim/calibration.json`),
/// simulated through the command line.
struct ShortRecord {
    dir: tempfile::TempDir,
}

impl ShortRecord {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let mut s = Scenario::triaxial_hidden();
        s.duration_s = 60.0;
        s.save(dir.path().join("short.toml")).unwrap();
        let r = ShortRecord { dir };
        r.run(&["simulate", "--scenario", "short.toml", "--out", "sim"]);
        r
    }

    fn output(&self, args: &[&str]) -> std::process::Output {
        std::process::Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
            .args(args)
            .current_dir(self.dir.path())
            .output()
            .unwrap()
    }

    /// Runs a command that must succeed; its stdout as JSON, if it is.
    fn run(&self, args: &[&str]) -> Option<serde_json::Value> {
        let out = self.output(args);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice::<serde_json::Value>(&out.stdout).ok()
    }

    /// `explain` on the record with its calibration, at most two rounds,
    /// writing `out`, with `extra` flags.
    fn explain_args<'a>(out: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
        let mut args = vec![
            "explain",
            "--data",
            "sim/record.csv",
            "--calib",
            "sim/calibration.json",
            "--out",
            out,
            "--max-rounds",
            "2",
        ];
        args.extend_from_slice(extra);
        args
    }
}

#[test]
fn explain_and_diagnose_json_keep_their_keys() {
    let r = ShortRecord::new();
    let run = |args: &[&str]| r.run(args);
    let e = run(&ShortRecord::explain_args(
        "final.json",
        &["--json", "--alpha", "0.01", "--min-gain", "0.1"],
    ))
    .expect("one JSON object");
    let rounds = e["rounds"].as_array().unwrap();
    assert_eq!(rounds.len(), 2, "{e}");
    let added = rounds[1]["added"].as_array().unwrap();
    assert!(!added.is_empty(), "{e}");
    for a in added {
        for key in ["channel", "effect", "coef", "p"] {
            assert!(!a[key].is_null(), "{key} in {a}");
        }
        let ci = a["ci95"].as_array().unwrap();
        assert!(ci[0].as_f64().unwrap() < a["coef"].as_f64().unwrap());
        assert!(a["coef"].as_f64().unwrap() < ci[1].as_f64().unwrap());
    }
    for c in rounds[0]["channels"].as_array().unwrap() {
        assert!(
            c["channel"].is_string() && c["val_rms"].as_f64().unwrap() > 0.0,
            "{c}"
        );
    }
    let channels = e["final"]["channels"].as_array().unwrap();
    let with_effects: Vec<&serde_json::Value> = channels
        .iter()
        .filter(|c| !c["effects"].as_array().unwrap().is_empty())
        .collect();
    assert!(!with_effects.is_empty());
    for c in with_effects {
        for (_, k) in c["effect_coefficients"].as_object().unwrap() {
            assert!(k["value"].is_number() && k["unit"].is_string(), "{k}");
            assert!(k["se"].as_f64().unwrap() > 0.0, "{k}");
            assert_eq!(k["ci95"].as_array().unwrap().len(), 2, "{k}");
        }
    }
    let d = run(&[
        "diagnose",
        "--model",
        "final.json",
        "--data",
        "sim/record.csv",
        "--json",
    ])
    .expect("one JSON object");
    let k = &d["channels"][0]["candidates"][0];
    for key in [
        "effect",
        "err",
        "coef",
        "coef_se",
        "coef_ci95",
        "unit",
        "alternatives",
    ] {
        assert!(!k[key].is_null(), "{key} in {k}");
    }
    // Thresholds out of range are usage errors naming the range.
    let out = r.output(&[
        "diagnose",
        "--model",
        "final.json",
        "--data",
        "sim/record.csv",
        "--alpha",
        "1.5",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("between 0 and 1"));
}

/// `explain`'s text: when a round added an effect, a line says which of
/// its two coefficients is which (the round's is the diagnosis's, the
/// final table's the fit's, and they differ), and the final table gives
/// each stored coefficient with its 95% interval.
#[test]
fn explain_says_which_coefficient_is_which() {
    let r = ShortRecord::new();
    let out = r.output(&ShortRecord::explain_args("text.json", &[]));
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let round = |l: &&str| l.starts_with("  added ");
    let which = lines
        .iter()
        .position(|l| l.starts_with("coefficients: a round's is the diagnosis's estimate"))
        .unwrap_or_else(|| panic!("no which-is-which line:\n{text}"));
    assert!(lines[..which].iter().any(round), "{text}");
    assert!(
        lines[which].contains("the model below stores and compensates with the fit's"),
        "{text}"
    );
    assert!(
        lines[which + 1].ends_with("effects (coefficient ± standard error, 95% CI)"),
        "{text}"
    );
    let model: serde_json::Value =
        serde_json::from_slice(&std::fs::read(r.dir.path().join("text.json")).unwrap()).unwrap();
    // Each stored interval, on its channel's line.
    for (c, line) in model["model"]["channels"]
        .as_array()
        .unwrap()
        .iter()
        .zip(&lines[which + 2..which + 8])
    {
        for k in c["coefficients"].as_array().into_iter().flatten() {
            let ci = &k["ci95"];
            let (lo, hi) = (ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap());
            assert!(line.contains(&format!("({lo:.4} to {hi:.4})")), "{line}");
        }
    }
}

/// A pair one record cannot tell apart: channel X's g_O and g_S are both
/// ∝ a_z under Z-only vibration. The diagnosis names one, lists the other,
/// says which combination the record measures (c(g_S) + c(g_O), the hidden
/// 1.0 deg/h/g) and which run splits them (vibration along y, where they
/// respond with opposite signs).
#[test]
fn a_collinear_pair_is_reported_with_the_run_that_splits_it() {
    let mut s = resolved_vibration(Scenario::triaxial_hidden());
    s.vibration
        .drives
        .retain(|d| d.axis() == nav_sensors::geometry::Axis::Z);
    let x = s.gyros.channels.entry(Channel::X).or_default();
    x.set(DtgTerm::GO, 1.0);
    s.hidden = vec![HiddenEffect {
        channel: Channel::X,
        term: DtgTerm::GO,
    }];
    let sim = simulate(&s);
    let m = fit(&sim.record, Some(&sim.calibration), &options());
    let records = [(String::new(), &sim.record)];
    let d = diagnose_records(m.inner(), &records, &DiagnoseOptions::default());
    let x = &d.channels[Channel::X.index()];
    assert_eq!(x.suggested.len(), 1, "{:?}", x.findings);
    let k = x
        .candidates
        .iter()
        .find(|k| k.effect == x.suggested[0])
        .unwrap();
    let pair = ["g_O", "g_S"];
    assert!(pair.contains(&k.effect.as_str()), "{}", k.effect);
    assert!(
        k.alternatives
            .iter()
            .any(|a| pair.contains(&a.as_str()) && *a != k.effect)
    );
    let sep = k.separation.as_ref().expect("separation advice");
    assert_eq!(
        sep.axis,
        Some(nav_sensors::geometry::Axis::Y),
        "{}",
        sep.advice
    );
    // The record measures c_rep + κ·c_other with κ = 1 (both are −a_z/√2 here),
    // which is the hidden 1.0 deg/h/g: the interval covers it.
    assert!(
        (sep.combination[0].1 - 1.0).abs() < 0.05,
        "{:?}",
        sep.combination
    );
    assert!(k.coef_ci95[0] < 1.0 && 1.0 < k.coef_ci95[1], "{k:?}");
}

/// One round of `explain` is `diagnose` and `fit --add-effect` by hand,
/// with the same answer (issue 10 §1). `--max-rounds` counts fits, so the
/// first round that adds anything is the second fit: `--max-rounds 2` is
/// fit → diagnose → refit with the suggestions, and by hand that is
/// `fit`, `diagnose --json`, then `fit --add-effect CHANNEL=ID` for every
/// suggestion. Both paths run the same deterministic code on the same
/// record and options (the model file round-trips its floats exactly), so
/// the effects added must be the same and the final coefficients and
/// validation rms equal; the tolerance is 1e-12 relative, i.e. equal to
/// the last few bits, not a statistical allowance.
#[test]
fn one_explain_round_is_diagnose_and_fit_add_effect_by_hand() {
    let r = ShortRecord::new();
    let run = |args: &[&str]| r.run(args).unwrap_or(serde_json::Value::Null);
    let data = [
        "--data",
        "sim/record.csv",
        "--calib",
        "sim/calibration.json",
    ];
    let with = |rest: &[&'static str]| -> Vec<String> {
        data.iter().chain(rest).map(|s| s.to_string()).collect()
    };
    fn args(v: &[String]) -> Vec<&str> {
        v.iter().map(String::as_str).collect()
    }

    let mut e_args = vec!["explain".to_string()];
    e_args.extend(with(&[
        "--out",
        "explained.json",
        "--json",
        "--max-rounds",
        "2",
    ]));
    let e = run(&args(&e_args));

    // By hand: fit, diagnose, refit with every suggestion.
    let mut f0 = vec!["fit".to_string()];
    f0.extend(with(&["--out", "m0.json"]));
    run(&args(&f0));
    let d = run(&[
        "diagnose",
        "--model",
        "m0.json",
        "--data",
        "sim/record.csv",
        "--json",
    ]);
    let mut suggested: Vec<String> = d["channels"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| {
            let ch = c["channel"].as_str().unwrap().to_string();
            c["suggested"]
                .as_array()
                .unwrap()
                .iter()
                .map(move |id| format!("{ch}={}", id.as_str().unwrap()))
        })
        .collect();
    assert!(!suggested.is_empty(), "the record hides effects: {d}");
    let mut f1 = vec!["fit".to_string()];
    f1.extend(with(&["--out", "m1.json", "--json"]));
    for s in &suggested {
        f1.push("--add-effect".into());
        f1.push(s.clone());
    }
    let by_hand = run(&args(&f1));

    // The same effects added, with the evidence diagnose gave.
    let rounds = e["rounds"].as_array().unwrap();
    assert_eq!(rounds.len(), 2, "{e}");
    let mut added: Vec<String> = rounds[1]["added"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| {
            format!(
                "{}={}",
                a["channel"].as_str().unwrap(),
                a["effect"].as_str().unwrap()
            )
        })
        .collect();
    added.sort();
    suggested.sort();
    assert_eq!(added, suggested);

    // The same final model: coefficients and validation rms.
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
    let (ours, theirs) = (
        e["final"]["channels"].as_array().unwrap(),
        by_hand["channels"].as_array().unwrap(),
    );
    assert_eq!(ours.len(), 6);
    for (a, b) in ours.iter().zip(theirs) {
        assert_eq!(a["channel"], b["channel"]);
        assert_eq!(a["effects"], b["effects"], "{}", a["channel"]);
        let (va, vb) = (
            a["val_rms"].as_f64().unwrap(),
            b["val_rms"].as_f64().unwrap(),
        );
        assert!(close(va, vb), "{}: val rms {va} vs {vb}", a["channel"]);
        let (ka, kb) = (
            a["effect_coefficients"].as_object().unwrap(),
            b["effect_coefficients"].as_object().unwrap(),
        );
        assert_eq!(ka.len(), kb.len());
        for (id, x) in ka {
            let y = &kb[id];
            for key in ["value", "se"] {
                let (p, q) = (x[key].as_f64().unwrap(), y[key].as_f64().unwrap());
                assert!(close(p, q), "{} {id} {key}: {p} vs {q}", a["channel"]);
            }
            assert_eq!(x["unit"], y["unit"]);
        }
    }
    // And the explain round's rms is the by-hand fit's.
    for (c, b) in rounds[1]["channels"].as_array().unwrap().iter().zip(theirs) {
        let (p, q) = (
            c["val_rms"].as_f64().unwrap(),
            b["val_rms"].as_f64().unwrap(),
        );
        assert!(close(p, q), "{}: {p} vs {q}", c["channel"]);
    }
}
