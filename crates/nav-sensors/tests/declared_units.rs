//! The declared units checked against the data, on the real recordings of
//! `data/realdata/` (provenance and licences in its README.md): read as
//! declared they give no warning; a deg/s log declared deg/h warns on its
//! still noise (bench) and on its tilt change (hand-held), and a g log
//! declared m/s² warns on its specific force, each naming the likely unit.
//! The still-noise check catches a quiet MEMS log (the CubeOrange's); a
//! noisy one in deg/s taken for deg/h reads like a navigation-grade gyro
//! (the bench log's gx, 0.07 deg/h/√Hz) and is left to the tilt check.
//! The tilt check stays silent on the real three-IMU quadrotor flights
//! (`data/realdata/multi-imu/`), whose accelerometers read the thrust that
//! turns with the body, and its false-alarm rate on clean pieces of every
//! real and simulated log is measured by the ignored test below.

use nav_sensors::record::{
    DeclaredUnitWarning, Record, TILT_EXPLAINED, declared_unit_warnings, tilt_misses,
};
use nav_sensors::unit::{RateUnit, SpecificForceUnit, Unit};

fn path(file: &str) -> String {
    format!("{}/../../data/realdata/{file}", env!("CARGO_MANIFEST_DIR"))
}

fn triad() -> Unit {
    Unit::builtin("triad").unwrap()
}

/// The triad declaring other units.
fn declaring(rate: &str, force: &str) -> Unit {
    let toml = Unit::builtin_toml("triad")
        .unwrap()
        .replace("\"deg/s\"", &format!("\"{rate}\""))
        .replace("\"m/s^2\"", &format!("\"{force}\""));
    Unit::from_toml(&toml, "declared.toml").unwrap()
}

fn multi_imu() -> Unit {
    Unit::load(format!(
        "{}/../../units/multi-imu.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

fn longest(file: &str, unit: &Unit) -> Record {
    let r = Record::read_with_unit(path(file), unit).unwrap();
    r.records.into_iter().max_by_key(Record::len).unwrap()
}

#[test]
fn logs_read_as_declared_give_no_warning() {
    let multi = multi_imu();
    for file in [
        "multi-imu/qdr_horizontal_path11.csv",
        "multi-imu/qdr_vertical_path1.csv",
    ] {
        let w = declared_unit_warnings(&multi, &longest(file, &multi), false);
        assert!(w.is_empty(), "{file}: {w:?}");
    }
    for (file, still) in [
        ("px4_fmuv4pro_bench.csv", true),
        ("px4_cubeorange_vtol_ground.csv", true),
        ("px4_auav_x21_handheld.csv", false),
        ("xio_fusion_handheld.csv", false),
    ] {
        let rec = longest(file, &triad());
        let w = declared_unit_warnings(&triad(), &rec, still);
        assert!(w.is_empty(), "{file}: {w:?}");
    }
}

#[test]
fn a_deg_s_log_declared_deg_h_warns_on_its_still_noise() {
    let unit = declaring("deg/h", "m/s^2");
    let rec = longest("px4_cubeorange_vtol_ground.csv", &unit);
    let w = declared_unit_warnings(&unit, &rec, true);
    assert_eq!(w.len(), 3, "{w:?}");
    for (k, w) in w.iter().enumerate() {
        let DeclaredUnitWarning::GyroNoise { column, likely, .. } = w else {
            panic!("{w:?}")
        };
        assert_eq!(
            (column.as_str(), *likely),
            (["gx", "gy", "gz"][k], RateUnit::DegPerSecond)
        );
        eprintln!("{w}");
        assert!(
            w.to_string()
                .contains("the log is likely in deg/s; set rate = \"deg/s\"")
        );
    }
}

#[test]
fn a_deg_s_log_declared_deg_h_warns_on_its_tilt_change() {
    let unit = declaring("deg/h", "m/s^2");
    let rec = longest("px4_auav_x21_handheld.csv", &unit);
    let w = declared_unit_warnings(&unit, &rec, false);
    assert_eq!(w.len(), 1, "{w:?}");
    eprintln!("{}", w[0]);
    assert!(matches!(
        w[0],
        DeclaredUnitWarning::TiltChange {
            likely: RateUnit::DegPerSecond,
            ..
        }
    ));
}

#[test]
fn a_g_log_declared_m_s2_warns_on_its_specific_force() {
    // The bench log written in g, then read with the triad (m/s²).
    let rec = longest("px4_fmuv4pro_bench.csv", &triad());
    let in_g = declaring("deg/s", "g");
    let mut text = Vec::new();
    rec.write_with_unit(&mut text, "g.csv", &in_g).unwrap();
    let read = Record::from_reader_with_unit(text.as_slice(), "g.csv", &triad()).unwrap();
    let w = declared_unit_warnings(&triad(), &read.records[0], true);
    assert_eq!(w.len(), 1, "{w:?}");
    eprintln!("{}", w[0]);
    let DeclaredUnitWarning::SpecificForce {
        columns,
        magnitude_g,
        likely,
        ..
    } = &w[0]
    else {
        panic!("{w:?}")
    };
    assert_eq!(columns, &["ax", "ay", "az"]);
    assert_eq!(*likely, SpecificForceUnit::G);
    assert!((magnitude_g * 9.80665 - 1.0).abs() < 0.05, "{magnitude_g}");
}

/// A calibration of a built-in unit (the paper's, in its format) given
/// with another unit is refused naming the unit it belongs to.
#[test]
fn a_paper_format_calibration_with_another_unit_is_refused_naming_the_format() {
    use nav_sensors::calibration::{UnitCalibration, UnitCalibrationError};
    let paper = UnitCalibration::ideal(&Unit::paper());
    assert_eq!(paper.check(&Unit::paper()), Ok(()));
    let err = paper.check(&triad()).unwrap_err();
    assert!(
        matches!(err, UnitCalibrationError::OtherBuiltin { .. }),
        "{err}"
    );
    assert!(
        err.to_string().starts_with("the calibration is of the built-in unit 'paper' (gyros X, X1, Y, Y1, Z, Z1: --unit paper), but units/triad.toml has gyros gx, gy, gz: give a unit calibration"),
        "{err}"
    );
    // Another unit's calibration with a name the unit lacks stays `Unknown`.
    let mut cal = UnitCalibration::ideal(&triad());
    cal.gyros.insert("gq".into(), cal.gyros["gx"]);
    assert!(matches!(
        cal.check(&triad()),
        Err(UnitCalibrationError::Unknown { .. })
    ));
}

/// Whether the tilt check warns on `rec` read with `unit`.
fn tilt_warns(unit: &Unit, rec: &Record) -> bool {
    declared_unit_warnings(unit, rec, false)
        .iter()
        .any(|w| matches!(w, DeclaredUnitWarning::TiltChange { .. }))
}

/// `rec` (deg/h inside) as a deg/s log read with a unit declaring deg/h:
/// every rate 3600× too small.
fn as_if_deg_h(rec: &Record) -> Record {
    let n = rec.gyro_names().len();
    rec.with_gyro_series(
        (0..n)
            .map(|k| rec.gyro_at(k).iter().map(|w| w / 3600.0).collect())
            .collect(),
    )
}

/// The tilt check on 30-s pieces of clean logs, read as declared: every
/// real log of `data/realdata/` (two quadrotor flights, two hand-held, a
/// bench and a ground log) and three seeds of the simulated 12-min flight
/// (`scenarios/flight.toml`, a triad: coordinated turns, S-turns, take-off
/// roll). The false-alarm rate: none of the 78 pieces warns
/// (asserted: at most 1). The same pieces as deg/s logs declared deg/h
/// (the hand-held and simulated ones that turn by 20 deg or more) warn
/// on 11 of 75 (printed per log: the others turn less than 20 deg or
/// their accelerometers read manoeuvre, not gravity).
#[test]
#[ignore = "statistical: the tilt check's false-alarm rate on 78 clean pieces (about 15 s)"]
fn the_tilt_check_false_alarm_rate_on_clean_pieces() {
    let mut logs: Vec<(String, Unit, Record)> = Vec::new();
    let multi = multi_imu();
    for f in [
        "multi-imu/qdr_horizontal_path11.csv",
        "multi-imu/qdr_vertical_path1.csv",
    ] {
        logs.push((f.into(), multi.clone(), longest(f, &multi)));
    }
    for f in [
        "px4_auav_x21_handheld.csv",
        "xio_fusion_handheld.csv",
        "px4_fmuv4pro_bench.csv",
        "px4_cubeorange_vtol_ground.csv",
    ] {
        logs.push((f.into(), triad(), longest(f, &triad())));
    }
    let scenario = nav_sensors::sim::Scenario::load(format!(
        "{}/../../scenarios/flight.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    for seed in 1..=3 {
        let s = nav_sensors::sim::Scenario {
            seed,
            ..scenario.clone()
        };
        let sim = nav_sensors::sim::simulate_unit(&triad(), &s).unwrap();
        logs.push((
            format!("simulated flight, seed {seed}"),
            triad(),
            sim.record,
        ));
    }
    let deg_h = declaring("deg/h", "m/s^2");
    let (mut pieces, mut alarms, mut wrong, mut caught) = (0, 0, 0, 0);
    for (name, unit, rec) in &logs {
        let caught_before = caught;
        let per = (30.0 / rec.dt()).round() as usize;
        for start in (0..rec.len().saturating_sub(per / 2)).step_by(per) {
            let piece = rec.slice(start..(start + per).min(rec.len()));
            pieces += 1;
            if tilt_warns(unit, &piece) {
                alarms += 1;
                eprintln!("false alarm: {name} from sample {start}");
            }
            if unit.name() == triad().name() {
                wrong += 1;
                caught += usize::from(tilt_warns(&deg_h, &as_if_deg_h(&piece)));
            }
        }
        eprintln!(
            "{name}: declared deg/h, caught in {} piece(s)",
            caught - caught_before
        );
    }
    eprintln!(
        "tilt check: {alarms} false alarm(s) in {pieces} clean pieces; deg/s declared deg/h caught in {caught} of {wrong} triad pieces"
    );
    assert!(alarms <= 1, "{alarms} of {pieces}");
}

/// The figures [`TILT_EXPLAINED`]'s documentation gives for choosing 0.5,
/// measured: on the real quadrotor flights the declared deg/s rates miss
/// the accelerometers' tilt change by more than a gyro turning nothing
/// (their accelerometers read the thrust, which turns with the body), so
/// no unit explains it and the check says nothing; on the hand-held log
/// the declared rates miss by a quarter of what turning nothing misses,
/// well inside the bound. Tolerance: half a unit in the documented last
/// digit.
#[test]
fn the_tilt_bound_sits_between_a_quadrotor_and_a_hand_held_log() {
    let multi = multi_imu();
    let cases = [
        (
            "multi-imu/qdr_horizontal_path11.csv",
            &multi,
            6.7,
            2.4,
            0.05,
        ),
        ("multi-imu/qdr_vertical_path1.csv", &multi, 8.2, 6.2, 0.05),
    ];
    for (file, unit, declared, unturned, tol) in cases {
        let m = tilt_misses(unit, &longest(file, unit)).unwrap();
        eprintln!(
            "{file}: tilt {:.0} deg; miss per step as declared {:.2} deg, turning nothing {:.2} deg, best {:.2} deg in {}",
            m.tilt_deg, m.as_declared_deg, m.unturned_deg, m.best_deg, m.likely
        );
        assert!((m.as_declared_deg - declared).abs() <= tol, "{file}: {m:?}");
        assert!((m.unturned_deg - unturned).abs() <= tol, "{file}: {m:?}");
        assert!(
            m.best_deg > TILT_EXPLAINED * m.unturned_deg,
            "{file}: {m:?}"
        );
    }
    let hand = longest("px4_auav_x21_handheld.csv", &triad());
    let m = tilt_misses(&triad(), &hand).unwrap();
    eprintln!(
        "hand-held: miss per step as declared {:.3} deg, turning nothing {:.3} deg",
        m.as_declared_deg, m.unturned_deg
    );
    assert!((m.as_declared_deg - 0.26).abs() <= 0.005, "{m:?}");
    assert!((m.unturned_deg - 1.01).abs() <= 0.005, "{m:?}");
    assert!(m.as_declared_deg < TILT_EXPLAINED * m.unturned_deg, "{m:?}");
}
