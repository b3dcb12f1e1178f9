//! A test campaign (issue 12 §5): the same unit run along x, y and z, then
//! flown. Data simulated here from the built-in campaign scenarios' fixed seeds.
//!
//! - An effect that the z run alone cannot tell from another (channel X's
//!   g_O and g_S both follow a_z there) is flagged as a pair on the z record
//!   and named, with its coefficient, when the x, y and z runs are
//!   diagnosed together; the diagnosis says on which record the pair was
//!   collinear.
//! - A model of the z run checked on the flight warns of extrapolation; a
//!   model of the three runs holds better on the flight than the z-only one.

//!
//! The paper's unit runs the one plug-in ([`paper_fit`]).

mod paper_fit;

use dtg_vib::diagnose::DiagnoseOptions;
use dtg_vib::unit_sensor::check::{DEFAULT_OUTSIDE_THRESHOLD, MOVING_RATE_DEG_S, TransferCheck};
use dtg_vib::unit_sensor::{ResidueStats, UnitSensor};
use nav_sensors::dtg::DtgTerm;
use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::record::Record;
use nav_sensors::sim::{HiddenEffect, Scenario, UnitSimulation as Simulation};
use nav_sensors::vibration::{Drive, PsdTable};
use paper_fit::{checked as check, diagnose_records, fit, fit_records, options, simulate};

/// The hidden g-sensitive drift of channel X along its output axis, deg/h/g.
const HIDDEN_G_O: f64 = 1.0;

/// One run of a small campaign on the tri-axial unit (`triaxial_hidden`'s
/// sensor, with its own hidden terms set to zero) shaken along `axis` alone,
/// with channel X's g_O hidden from the calibration. The drive is at 1–8 Hz:
/// a g-sensitive drift follows the vibration itself, which the 50-Hz record
/// resolves only below its Nyquist frequency (the NAVMAT band of the
/// built-in `x-axis`, `y-axis` and `z-axis` runs, 20–2000 Hz, averages out
/// within an output interval). Each run has its own seed, as each run of a
/// campaign has its own noise.
fn run_with_hidden_g_o(axis: Axis) -> Simulation {
    let mut s = Scenario::triaxial_hidden();
    s.seed += 1 + axis.index() as u64;
    for h in std::mem::take(&mut s.hidden) {
        s.gyros
            .channels
            .entry(h.channel)
            .or_default()
            .set(h.term, 0.0);
    }
    s.vibration.drives.retain(|d| d.axis() == axis);
    for d in &mut s.vibration.drives {
        if let Drive::Random { psd, .. } = d {
            *psd = PsdTable::new(vec![[1.0, 0.05], [2.0, 0.2], [6.0, 0.2], [8.0, 0.05]])
                .expect("valid table");
        }
    }
    s.gyros
        .channels
        .entry(Channel::X)
        .or_default()
        .set(DtgTerm::GO, HIDDEN_G_O);
    s.hidden = vec![HiddenEffect {
        channel: Channel::X,
        term: DtgTerm::GO,
    }];
    simulate(&s)
}

#[test]
fn a_pair_collinear_on_the_z_run_is_named_by_the_three_axis_campaign() {
    let runs: Vec<(String, Simulation)> = Axis::ALL
        .into_iter()
        .map(|a| {
            (
                format!("{}-axis.csv", a.column().trim_start_matches('a')),
                run_with_hidden_g_o(a),
            )
        })
        .collect();
    // One unit, one ground calibration: every run hands out the same one.
    let calibration = &runs[0].1.calibration;
    let options = options();
    let opts = DiagnoseOptions::default();

    // The z run alone: a suggestion on X with g_O and g_S as one group.
    let z = &runs[2].1.record;
    let model_z = fit(z, Some(calibration), &options);
    let d = diagnose_records(model_z.inner(), &[(String::new(), z)], &opts);
    let x = &d.channels[Channel::X.index()];
    assert_eq!(x.suggested.len(), 1, "{:?}", x.findings);
    let pair = ["g_O", "g_S"];
    let k = x
        .candidates
        .iter()
        .find(|k| k.effect == x.suggested[0])
        .unwrap();
    assert!(pair.contains(&k.effect.as_str()), "{}", k.effect);
    assert!(
        k.alternatives
            .iter()
            .any(|a| pair.contains(&a.as_str()) && *a != k.effect),
        "{:?}",
        x.findings
    );

    // The three runs together: g_O itself, with no alternative, its interval
    // covering the hidden coefficient, and the record that could not tell.
    let named: Vec<(String, &Record)> = runs.iter().map(|(n, s)| (n.clone(), &s.record)).collect();
    let (model, _) = fit_records(&named, Some(calibration), &options);
    // The library's default window (`--window-signals auto`): every axis
    // the runs vibrate on, which the network could read a g-term through.
    assert_eq!(
        model.inner().preprocess().window.signals(),
        ["ax", "ay", "az"]
    );
    let d = diagnose_records(model.inner(), &named, &opts);
    assert_eq!(d.records.len(), 3);
    let x = &d.channels[Channel::X.index()];
    assert_eq!(x.suggested, ["g_O"], "{:?}", x.findings);
    let k = x.candidates.iter().find(|k| k.effect == "g_O").unwrap();
    eprintln!(
        "three runs: X suggests {:?}, g_O {:.4} ± {:.4} deg/h/g (95% CI {:.4} to {:.4}; hidden {HIDDEN_G_O}); {:?}",
        x.suggested, k.coef, k.coef_se, k.coef_ci95[0], k.coef_ci95[1], k.record_separations
    );
    assert!(k.alternatives.is_empty(), "{:?}", k.alternatives);
    assert!(
        k.coef_ci95[0] < HIDDEN_G_O && HIDDEN_G_O < k.coef_ci95[1],
        "g_O {} ± {} deg/h/g, interval {:?}",
        k.coef,
        k.coef_se,
        k.coef_ci95
    );
    let s = k
        .record_separations
        .iter()
        .find(|s| s.effect == "g_S")
        .unwrap_or_else(|| panic!("{:?}", k.record_separations));
    assert!(s.collinear_on.iter().any(|r| r == "z-axis.csv"), "{s:?}");
    assert!(
        x.findings[0].contains("z-axis.csv"),
        "the finding names the record: {}",
        x.findings[0]
    );
    // Nothing else is suggested on the clean channels.
    for c in d.channels.iter().filter(|c| c.channel != Channel::X.name()) {
        assert!(c.suggested.is_empty(), "{}: {:?}", c.channel, c.findings);
    }
}

#[test]
fn a_z_run_model_warns_on_the_flight_and_its_fade_holds_the_residues() {
    let sim = |n: &str| simulate(&Scenario::builtin(n).unwrap());
    let (x, y, z, flight) = (sim("x-axis"), sim("y-axis"), sim("z-axis"), sim("flight"));
    let calibration = &z.calibration;
    let options = options();
    let model_z = fit(&z.record, Some(calibration), &options);
    let named = [
        ("x-axis.csv".to_string(), &x.record),
        ("y-axis.csv".to_string(), &y.record),
        ("z-axis.csv".to_string(), &z.record),
    ];
    let (model_xyz, _) = fit_records(&named, Some(calibration), &options);

    let on_flight_z = check(&model_z, &flight.record);
    let outside = on_flight_z.outside_fraction.unwrap();
    assert!(outside > DEFAULT_OUTSIDE_THRESHOLD, "{outside}");
    assert!(
        on_flight_z.warning.as_deref().unwrap().contains("outside"),
        "{:?}",
        on_flight_z.warning
    );
    let on_flight_xyz = check(&model_xyz, &flight.record);
    // Less of the flight lies outside what the three runs covered …
    assert!(
        on_flight_xyz.outside_fraction.unwrap() < outside,
        "{:?} vs {outside}",
        on_flight_xyz.outside_fraction
    );
    // … and the flight's parity residues are lower after the three-axis
    // model than after the z-only one. The residues, not the channels: the
    // unit turns, and a channel's rms is mostly that motion, as check says.
    for c in [&on_flight_z, &on_flight_xyz] {
        assert!(c.rate_std_deg_s > MOVING_RATE_DEG_S);
        assert!(c.note.as_deref().unwrap().contains("residues"));
    }
    // As fitted (the network part not faded: `residues_unfaded`), the
    // three-axis model extrapolates less than the z-only one.
    let pooled_of = |r: &[ResidueStats]| {
        (r.iter().map(|r| r.rms_after.powi(2)).sum::<f64>() / r.len() as f64).sqrt()
    };
    let pooled = |c: &TransferCheck| pooled_of(c.residues_unfaded.as_ref().unwrap());
    let (rz, rxyz) = (pooled(&on_flight_z), pooled(&on_flight_xyz));
    let before = (on_flight_z
        .residues
        .iter()
        .map(|r| r.rms_before.powi(2))
        .sum::<f64>()
        / on_flight_z.residues.len() as f64)
        .sqrt();
    // Faded outside its range, the z-only model leaves less than as fitted
    // and less than before: it holds what its network said on the ground
    // (measured: 1.96 → 1.52 deg/h faded, 2.56 as fitted; 12.35 as fitted
    // with the paper's raw window and no smoother, before issue 23; 2.10
    // faded when the hold moved toward the network by the weight each
    // sample).
    let faded_z = pooled_of(&on_flight_z.residues);
    assert!(
        faded_z < rz && faded_z < before,
        "z-only on the flight: faded {faded_z:.4}, as fitted {rz:.4}, before {before:.4}"
    );
    for (name, c) in [("z-only", &on_flight_z), ("x+y+z", &on_flight_xyz)] {
        eprintln!(
            "{name} model on the flight: {:.1}% of windows outside, residue rms after {:.3} deg/h as fitted, {:.3} faded (before {:.3})",
            100.0 * c.outside_fraction.unwrap(),
            pooled(c),
            pooled_of(&c.residues),
            (c.residues.iter().map(|r| r.rms_before.powi(2)).sum::<f64>()
                / c.residues.len() as f64)
                .sqrt()
        );
    }
    // Before the fit chose its input and prediction smoother (issue 23)
    // the z-only model multiplied the flight's residues 6.3× as fitted
    // (pooled 1.96 → 12.35 deg/h) and the three-axis one 4.1× (→ 8.0). With
    // the choice the z-only model holds far better as fitted too (→ 2.56)
    // while the three-axis model stays near 8: neither should fly
    // (docs/campaign.md). What holds as fitted: the z-only model no longer
    // multiplies them by more than 2.
    assert!(
        rz < 2.0 * before,
        "flight residue rms: z-only {rz:.4} (before {before:.4}), x+y+z {rxyz:.4} deg/h"
    );
    // A shaker test does not move: no note there.
    let on_x = check(&model_z, &x.record);
    assert!(on_x.note.is_none(), "{:?}", on_x.note);

    // Issue 23's transfer bound: on every shaker run, each channel's spread
    // after (about its own mean) is at most 1.02× its rms before, for the
    // z-only model (faded on the x and y runs) and the three-run one (whose
    // networks that added spread on a run they were fitted on are shrunk
    // to zero). Measured (docs/campaign.md §6): at most 1.001×; before the
    // fade cross-faded and the networks were judged per record, 1.032× and
    // 1.034×.
    for (name, model) in [("z-only", &model_z), ("x+y+z", &model_xyz)] {
        for (run, sim) in [("x", &x), ("y", &y), ("z", &z)] {
            let c = check(model, &sim.record);
            for ch in &c.channels {
                assert!(
                    ch.spread_after <= 1.02 * ch.rms_before,
                    "{name} model on the {run} run, {}: spread after {:.4} against rms before {:.4} deg/h",
                    ch.channel,
                    ch.spread_after,
                    ch.rms_before
                );
            }
        }
    }
}

#[test]
fn the_three_run_model_with_added_terms_reads_every_vibrating_axis_and_adds_no_variation() {
    let sim = |n: &str| simulate(&Scenario::builtin(n).unwrap());
    let (x, y, z, flight) = (sim("x-axis"), sim("y-axis"), sim("z-axis"), sim("flight"));
    let calibration = Some(&z.calibration);
    let named = [
        ("x-axis.csv".to_string(), &x.record),
        ("y-axis.csv".to_string(), &y.record),
        ("z-axis.csv".to_string(), &z.record),
    ];
    // `fit --window-signals auto`: the z run alone vibrates along z only
    // (ax 5%, ay 3% of az's dynamic rms); the three runs along every axis.
    let sensor: UnitSensor = paper_fit::sensor(calibration);
    let z_only = sensor.choose_window_signals(&named[2..]).unwrap();
    assert_eq!(z_only.choices[0].taken, ["az"]);
    let chosen = sensor.choose_window_signals(&named).unwrap();
    assert_eq!(
        chosen.choices.len(),
        1,
        "the paper's unit: one choice for every channel"
    );
    assert_eq!(chosen.choices[0].taken, ["ax", "ay", "az"]);
    let mut options = options();
    paper_fit::add(
        &mut options,
        &["X=gg_SS", "X1=gg_SS", "Y=gg_OO", "Y1=gg_II"],
    );
    let window = &mut options.recipe.preprocess.window;
    *window = chosen.window(window.length()).unwrap();
    let (model, _) = fit_records(&named, calibration, &options);
    // Issue 23's transfer bound on every channel of every run and the
    // flight, and the channels with added terms fall on every shaker run
    // (measured, docs/campaign.md §6: at most 1.001×; the added terms'
    // channels 0.51–0.80× on the shaker runs; with the window of az alone
    // Y1 spread 1.031× on the x run and X fell to 0.996× only).
    let added = [Channel::X, Channel::X1, Channel::Y, Channel::Y1].map(|c| c.name());
    for (run, sim) in [("x", &x), ("y", &y), ("z", &z), ("flight", &flight)] {
        let c = check(&model, &sim.record);
        for ch in &c.channels {
            let ratio = ch.spread_after / ch.rms_before;
            assert!(
                ratio <= 1.02,
                "{run} run, {}: spread after {ratio:.4}× rms before",
                ch.channel
            );
            if run != "flight" && added.contains(&ch.channel.as_str()) {
                assert!(ratio < 0.9, "{run} run, {}: {ratio:.4}×", ch.channel);
            }
        }
    }
}
