//! Issue 4's acceptance: on the default simulated test, the paper's procedure
//! lowers every parity residue's rms at least threefold on the validation
//! part of a blocked split.

use dtg_vib::apply::Applied;
use dtg_vib::fit::{FitOptions, FitSettings, fit};
use nav_sensors::geometry::Channel;
use nav_sensors::sim::{Scenario, simulate};

#[test]
fn residues_fall_at_least_threefold_on_blocked_validation() {
    let sim = simulate(&Scenario::default()).unwrap();
    let model = fit(
        &sim.record,
        Some(&sim.calibration),
        &FitOptions::default(),
        &|_| {},
    )
    .unwrap();
    let applied = Applied::new(&model, &sim.record).unwrap();
    let stats = applied.validation_residues();
    // Measured (seed 20051021): 4.2 to 4.3 on every residue.
    for s in &stats {
        assert!(
            s.reduction >= 3.0,
            "{:?}: {:.3} -> {:.3} deg/h, only {:.2}x",
            s.residue,
            s.rms_before,
            s.rms_after,
            s.reduction
        );
    }
    // And every channel's validation residual is below what a bias-only model leaves.
    for c in model.channels() {
        assert!(
            c.scores().val_rms < 0.8 * c.scores().val_rms_bias_only,
            "{:?}",
            c.scores()
        );
    }
}

/// A 30-s default test fitted with at most 10 centres.
fn short_fit() -> (
    nav_sensors::sim::Simulation,
    dtg_vib::model::CompensationModel,
) {
    let sim = simulate(&Scenario {
        duration_s: 30.0,
        ..Scenario::default()
    })
    .unwrap();
    let model = fit(
        &sim.record,
        Some(&sim.calibration),
        &short_options(),
        &|_| {},
    )
    .unwrap();
    (sim, model)
}

/// At most 10 centres.
fn short_options() -> FitOptions {
    FitOptions {
        settings: FitSettings {
            max_centres: 10,
            ..FitSettings::default()
        },
        ..FitOptions::default()
    }
}

#[test]
fn a_saved_model_compensates_identically_after_loading() {
    let (sim, model) = short_fit();
    let path = std::env::temp_dir().join(format!("dtg-vib-model-{}.json", std::process::id()));
    model.save(&path).unwrap();
    let back = dtg_vib::model::CompensationModel::load(&path).unwrap();
    assert_eq!(back, model);
    let (a, b) = (
        Applied::new(&model, &sim.record).unwrap(),
        Applied::new(&back, &sim.record).unwrap(),
    );
    assert_eq!(a.predicted, b.predicted);
    std::fs::remove_file(path).ok();
}

#[test]
fn a_report_on_another_record_shows_that_records_channel_scores() {
    let short = |seed| Scenario {
        duration_s: 30.0,
        seed,
        ..Scenario::default()
    };
    let sim = simulate(&short(1)).unwrap();
    let options = FitOptions {
        settings: FitSettings {
            max_centres: 10,
            ..FitSettings::default()
        },
        ..FitOptions::default()
    };
    let model = fit(&sim.record, Some(&sim.calibration), &options, &|_| {}).unwrap();
    let other = simulate(&short(2)).unwrap().record;
    let applied = Applied::new(&model, &other).unwrap();
    let dir = std::env::temp_dir().join(format!("dtg-vib-report-other-{}", std::process::id()));
    // The one page of every unit, on the paper's model file read as the
    // paper unit's model.
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("model.json");
    model.save(&path).unwrap();
    let unit_model = dtg_vib::unit_sensor::UnitModel::load(&path).unwrap();
    let data = [dir.join("other.csv")];
    let written = dtg_vib::unit_page::write_page(
        &unit_model,
        &[("other".to_string(), other.clone())],
        dtg_vib::unit_page::Page::new(&path, &data),
        &dir.join("report"),
    )
    .unwrap();
    for (c, (name, shown)) in model.channels().iter().zip(&written.numbers.channels) {
        assert_eq!(name, c.channel().name());
        let y = applied.prepared.target(c.channel());
        let p = &applied.predicted[c.channel().index()];
        let rms = |rows: &[usize]| {
            (rows.iter().map(|&r| (y[r] - p[r]).powi(2)).sum::<f64>() / rows.len() as f64).sqrt()
        };
        assert!((shown.val_rms - rms(&applied.val)).abs() < 1e-12);
        assert!((shown.train_rms - rms(&applied.train)).abs() < 1e-12);
        // Not the numbers of the record the model was fitted on.
        assert_ne!(shown.val_rms, c.scores().val_rms);
    }
    // On the fitting record, the same numbers as at fit time.
    let own = Applied::new(&model, &sim.record).unwrap();
    for c in model.channels() {
        assert_eq!(own.scores(c.channel()), *c.scores());
    }
    std::fs::remove_dir_all(dir).ok();
}

/// Issue 25 §1: the six channels share one centre selection (equal centres
/// and width), and each keeps its own least-squares weights on it: on its
/// training rows the residual is orthogonal to every column of the shared
/// basis (bias and kernels), which another channel's weights would not be.
#[test]
fn the_six_channels_share_one_centre_selection_and_keep_their_own_weights() {
    // The demo's record: its vibration levels change, so the networks have
    // something to predict and the keep step leaves them (on a record of
    // one level a network adds nothing to the bias and is shrunk to zero).
    let sim = simulate(&Scenario::builtin("demo").unwrap()).unwrap();
    let mut options = short_options();
    options.settings.shared_centres = true;
    let model = fit(&sim.record, Some(&sim.calibration), &options, &|_| {}).unwrap();
    assert!(model.fit_settings().shared_centres);
    let first = &model.channels()[0];
    let applied = Applied::new(&model, &sim.record).unwrap();
    let windows = applied.prepared.window_matrix();
    let rows = &applied.train;
    let x = faer::Mat::from_fn(rows.len(), windows.ncols(), |i, j| windows[(rows[i], j)]);
    let basis = first.rbf().features(x.as_ref());
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let own_residual_gradient = |weights_of: &dtg_vib::model::ChannelModel, y_of: Channel| {
        let rbf = weights_of.rbf();
        let y: Vec<f64> = rows
            .iter()
            .map(|&r| applied.prepared.target(y_of)[r])
            .collect();
        let r: Vec<f64> = (0..rows.len())
            .map(|i| {
                let fit = rbf.bias().unwrap()[0]
                    + (0..rbf.n_centres())
                        .map(|k| basis[(i, k + 1)] * rbf.weights()[(k, 0)])
                        .sum::<f64>();
                y[i] - fit
            })
            .collect();
        let worst = (0..basis.ncols())
            .map(|j| {
                (0..rows.len())
                    .map(|i| basis[(i, j)] * r[i])
                    .sum::<f64>()
                    .abs()
            })
            .fold(0.0, f64::max);
        worst / (basis.norm_l2() * norm(&y))
    };
    // A channel whose network the keep step shrank (to zero, its weights
    // solved against a constant, or to a share of its output, listed in the
    // choice report as `CHANNEL × SHARE: …`) is no least-squares fit on the
    // basis; the others are.
    let scaled: Vec<String> = model
        .inner()
        .choice()
        .map(|c| c.networks_shrunk.clone())
        .unwrap_or_default();
    let shrunk = |c: &dtg_vib::model::ChannelModel| {
        let scale = 1.0 + c.rbf().bias().unwrap()[0].abs();
        let zero = c
            .rbf()
            .weights()
            .col(0)
            .iter()
            .all(|w| w.abs() < 1e-9 * scale);
        zero || scaled
            .iter()
            .any(|s| s.starts_with(&format!("{} ×", c.channel())))
    };
    let mut kept = Vec::new();
    for c in model.channels() {
        assert_eq!(c.rbf().centres(), first.rbf().centres(), "{}", c.channel());
        assert_eq!(c.width(), first.width(), "{}", c.channel());
        if shrunk(c) {
            continue;
        }
        let own = own_residual_gradient(c, c.channel());
        assert!(own < 1e-7, "{}: {own:e} ({scaled:?})", c.channel());
        kept.push(c);
    }
    // Two are enough to tell one channel's weights from another's.
    assert!(
        kept.len() >= 2,
        "only {} channels kept a network",
        kept.len()
    );
    // One channel's weights are not a least-squares fit of another: each
    // channel has its own.
    let (a, b) = (kept[0], kept[1].channel());
    assert!(own_residual_gradient(a, b) > 1e-4);
}
