//! The simulator for any unit: the paper's unit through the unit path is
//! today's simulation bit for bit, every built-in scenario runs on every
//! built-in unit, hidden effects of rate gyros are what the truth says,
//! the scenario's `[unit]` table is checked against the unit, and the
//! written files read back.

use nav_sensors::calibration::{GyroCoefficients, UnitCalibration};
use nav_sensors::rate::RateCoefficients;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, simulate_unit};
use nav_sensors::unit::Unit;

const SCENARIOS: [&str; 9] = [
    "paper_z_random",
    "triaxial_clean",
    "triaxial_hidden",
    "demo",
    "x-axis",
    "y-axis",
    "z-axis",
    "sine-sweep",
    "flight",
];

fn short(name: &str, seconds: f64) -> Scenario {
    Scenario {
        duration_s: seconds,
        ..Scenario::builtin(name).unwrap()
    }
}

/// The paper's unit writes the paper's files (`components.csv`, no
/// `unit.toml`), and they are the files dtg-vib 5b6a72d wrote for the same
/// scenario, byte for byte (`crates/dtg-vib/tests/fixtures/legacy/paper`,
/// its README says how they were made).
#[test]
fn the_paper_unit_writes_the_files_5b6a72d_wrote() {
    let legacy = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../dtg-vib/tests/fixtures/legacy/paper");
    let s = Scenario::load(legacy.join("scenario.toml")).unwrap();
    let sim = simulate_unit(&Unit::paper(), &s).unwrap();
    let dir = std::env::temp_dir().join(format!("nav-sensors-paper-files-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    sim.write_dir(&dir).unwrap();
    for file in [
        "record.csv",
        "calibration.json",
        "truth.json",
        "scenario.toml",
    ] {
        let written = std::fs::read(dir.join(file)).unwrap();
        let before = std::fs::read(legacy.join(file)).unwrap();
        assert!(written == before, "{file} differs from 5b6a72d's");
    }
    assert!(dir.join("components.csv").exists() && !dir.join("unit.toml").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_builtin_scenario_runs_on_every_builtin_unit() {
    for unit_name in Unit::BUILTIN_NAMES {
        let unit = Unit::builtin(unit_name).unwrap();
        for name in SCENARIOS {
            let s = short(name, 2.0);
            let sim =
                simulate_unit(&unit, &s).unwrap_or_else(|e| panic!("{unit_name}/{name}: {e}"));
            assert_eq!(sim.record.len(), 100, "{unit_name}/{name}");
            assert_eq!(sim.record.gyro_names().len(), unit.gyros().len());
            assert_eq!(
                sim.truth.residue_noise_floor_deg_h.len(),
                unit.residue_names().len()
            );
            // The paper's hidden effect names a DTG channel: applied on the
            // paper's unit, reported as not applied on the others.
            let paper_hidden = s.hidden.len();
            if unit.has_paper_geometry() {
                assert_eq!(sim.truth.hidden.len(), paper_hidden, "{unit_name}/{name}");
            } else {
                assert_eq!(
                    sim.truth.not_applied.len(),
                    paper_hidden,
                    "{unit_name}/{name}"
                );
                assert!(sim.truth.hidden.is_empty());
            }
            for ch in &sim.truth.channels {
                assert!(
                    ch.noise_floor_deg_h > 0.0 && ch.noise_floor_deg_h.is_finite(),
                    "{unit_name}/{name}/{}",
                    ch.channel
                );
            }
        }
    }
}

/// `triaxial_clean` with a rate-gyro effect hidden on one channel.
fn hidden_on(channel: &str, coefficients: RateCoefficients, term: &str) -> Scenario {
    let mut s = short("triaxial_clean", 20.0);
    s.unit.rate.insert(channel.into(), coefficients);
    s.unit
        .hidden
        .push(format!("{channel}={term}").parse().unwrap());
    s
}

#[test]
fn a_hidden_rate_gyro_effect_is_in_the_record_the_truth_and_not_the_calibration() {
    let tetra = Unit::builtin("tetra").unwrap();
    let c = RateCoefficients {
        bias_deg_h: 3.0,
        g_y_deg_h_g: 2.0,
        ..Default::default()
    };
    let with = simulate_unit(&tetra, &hidden_on("g2", c, "g_y")).unwrap();
    let h = &with.truth.hidden[0];
    assert_eq!(
        (
            h.channel.as_str(),
            h.term.as_str(),
            h.coefficient,
            h.unit.as_str()
        ),
        ("g2", "g_y", 2.0, "deg/h/g")
    );
    // 1.66 g rms along y: about 3.3 deg/h of g_y drift, far above the noise.
    assert!(h.rms_deg_h > 2.5 && h.ratio_to_noise_floor > 5.0, "{h:?}");
    let GyroCoefficients::Rate(cal) = with.calibration.gyros["g2"] else {
        panic!()
    };
    assert_eq!(cal.g_y_deg_h_g, 0.0, "hidden: zeroed in the calibration");
    assert!(
        (cal.bias_deg_h - 3.0).abs() < 0.2,
        "calibrated: with its error"
    );
    // The record holds g_y·f_y: compensating with the calibration leaves it,
    // and it correlates with a_y.
    let comp = with.calibration.compensate(&tetra, &with.record).unwrap();
    let g2 = comp.gyro_named("g2").unwrap();
    let ay = comp.accel_named("ay").unwrap();
    let slope = regression_slope(ay, g2);
    assert!((slope - 2.0).abs() < 0.1, "slope {slope} deg/h/g");
    // The other channels show no such slope.
    let g1 = comp.gyro_named("g1").unwrap();
    assert!(regression_slope(ay, g1).abs() < 0.1);
}

fn regression_slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

#[test]
fn a_dual_triad_hidden_effect_on_the_second_triad() {
    let dual = Unit::builtin("dual-triad").unwrap();
    let c = RateCoefficients {
        g_x_deg_h_g: -1.5,
        ..Default::default()
    };
    let sim = simulate_unit(&dual, &hidden_on("gx2", c, "g_x")).unwrap();
    assert_eq!(sim.truth.hidden[0].channel, "gx2");
    // It shows in the parity residues (the clean twin's stay at noise).
    let clean = simulate_unit(&dual, &short("triaxial_clean", 20.0)).unwrap();
    let residue_rms = |rec: &Record| {
        let mut sum = 0.0;
        for i in 0..rec.len() {
            sum += dual
                .residues(&rec.gyro_row(i))
                .iter()
                .map(|r| r * r)
                .sum::<f64>();
        }
        (sum / rec.len() as f64).sqrt()
    };
    let (hidden, twin) = (residue_rms(&sim.record), residue_rms(&clean.record));
    assert!(hidden > 3.0 * twin, "{hidden} vs {twin}");
}

#[test]
fn the_unit_table_is_checked_against_the_unit() {
    let tetra = Unit::builtin("tetra").unwrap();
    let err = |s: &Scenario| simulate_unit(&tetra, s).unwrap_err().to_string();
    let mut s = short("triaxial_clean", 1.0);
    s.unit.rate.insert("g5".into(), RateCoefficients::default());
    assert_eq!(
        err(&s),
        "scenario: unit.rate.g5: units/tetra.toml has no gyro 'g5' (its gyros: g1, g2, g3, g4)"
    );
    let mut s = short("triaxial_clean", 1.0);
    s.unit.dtg.insert("g1".into(), Default::default());
    assert_eq!(
        err(&s),
        "scenario: unit.dtg.g1: gyro 'g1' is a \"rate\" gyro in units/tetra.toml: give its coefficients under unit.rate"
    );
    let mut s = short("triaxial_clean", 1.0);
    s.unit.hidden.push("g1=gg_IS".parse().unwrap());
    assert!(
        err(&s).starts_with("scenario: unit.hidden[0]: g1: unknown rate-gyro term 'gg_IS'"),
        "{}",
        err(&s)
    );
    let mut s = short("triaxial_clean", 1.0);
    s.unit.hidden.push("g1=g_x".parse().unwrap());
    assert_eq!(
        err(&s),
        "scenario: unit.hidden[0]: g1=g_x: its truth coefficient is zero (give it under unit.rate.g1)"
    );
    // The table round-trips through the scenario file.
    let mut s = short("triaxial_clean", 1.0);
    s.unit.rate.insert(
        "g2".into(),
        RateCoefficients {
            g_y_deg_h_g: 0.5,
            ..Default::default()
        },
    );
    s.unit.hidden.push("g2=g_y".parse().unwrap());
    let text = s.to_toml().unwrap();
    assert!(text.contains("[unit.rate.g2]"), "{text}");
    assert_eq!(Scenario::from_toml(&text, "s.toml").unwrap(), s);
}

#[test]
fn written_files_read_back_in_the_units_own_units() {
    let triad = Unit::builtin("triad").unwrap();
    let sim = simulate_unit(&triad, &short("triaxial_clean", 2.0)).unwrap();
    let dir = std::env::temp_dir().join("nav-sensors-test-unit-sim-triad");
    sim.write_dir(&dir).unwrap();
    let text = std::fs::read_to_string(dir.join("record.csv")).unwrap();
    assert!(text.starts_with("t,gx,gy,gz,ax,ay,az,temp\n"));
    let back = Record::read_with_unit(
        dir.join("record.csv"),
        &Unit::load(dir.join("unit.toml")).unwrap(),
    )
    .unwrap();
    let rec = &back.records[0];
    assert_eq!(back.records.len(), 1);
    for k in 0..3 {
        for (a, b) in rec.gyro_at(k).iter().zip(sim.record.gyro_at(k)) {
            assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{a} vs {b}");
        }
        for (a, b) in rec.accel_at(k).iter().zip(sim.record.accel_at(k)) {
            assert!((a - b).abs() <= 1e-12, "{a} vs {b}");
        }
    }
    // serde_json parses floats to within an ulp or two.
    let cal = UnitCalibration::load(dir.join("calibration.json")).unwrap();
    for (name, c) in &sim.calibration.gyros {
        for (a, b) in cal.gyros[name].to_vec().iter().zip(c.to_vec()) {
            assert!((a - b).abs() <= 1e-14 * b.abs(), "{name}: {a} vs {b}");
        }
    }
}
