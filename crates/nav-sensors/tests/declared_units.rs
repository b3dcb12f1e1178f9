//! The declared units checked against the data, on the real recordings of
//! `data/realdata/` (provenance and licences in its README.md): read as
//! declared they give no warning; a deg/s log declared deg/h warns on its
//! still noise (bench) and on its tilt change (hand-held), and a g log
//! declared m/s² warns on its specific force, each naming the likely unit.
//! The still-noise check catches a quiet MEMS log (the CubeOrange's); a
//! noisy one in deg/s taken for deg/h reads like a navigation-grade gyro
//! (the bench log's gx, 0.07 deg/h/√Hz) and is left to the tilt check.

use nav_sensors::record::{DeclaredUnitWarning, Record, declared_unit_warnings};
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

fn longest(file: &str, unit: &Unit) -> Record {
    let r = Record::read_with_unit(path(file), unit).unwrap();
    r.records.into_iter().max_by_key(Record::len).unwrap()
}

#[test]
fn logs_read_as_declared_give_no_warning() {
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
