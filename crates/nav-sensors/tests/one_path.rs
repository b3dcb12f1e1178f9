//! The paper's files read as the unit's (issue 33): the paper's
//! calibration JSON (a file, or the `calibration` embedded in a paper
//! model file written before) as a `UnitCalibration`, and the paper's truth file as a `UnitTruth`; a record of
//! any unit, the paper's CSV included, through the one unit reader. On the
//! fixtures dtg-vib 5b6a72d wrote (`crates/dtg-vib/tests/fixtures/legacy`).

use std::path::PathBuf;

use nav_sensors::calibration::{GyroCoefficients, UnitCalibration};
use nav_sensors::record::Record;
use nav_sensors::sim::UnitTruth;
use nav_sensors::unit::Unit;

fn legacy(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../dtg-vib/tests/fixtures/legacy")
        .join(file)
}

/// Every table of the paper's calibration JSON `paper` is the unit
/// calibration's, value for value: gyros by channel (as DTG tables),
/// accelerometers by axis `x`, `y`, `z` under their columns.
fn assert_same_tables(unit_cal: &UnitCalibration, paper: &serde_json::Value) {
    let gyros = paper["gyros"].as_object().unwrap();
    assert_eq!(unit_cal.gyros.len(), gyros.len());
    for (name, table) in gyros {
        let GyroCoefficients::Dtg(t) = unit_cal.gyros[name] else {
            panic!("{name} reads as a DTG table");
        };
        assert_eq!(&serde_json::to_value(t).unwrap(), table, "{name}");
    }
    let accels = paper["accels"].as_object().unwrap();
    assert_eq!(unit_cal.accels.len(), accels.len());
    for (axis, table) in accels {
        let column = format!("a{axis}");
        assert_eq!(
            &serde_json::to_value(unit_cal.accels[&column]).unwrap(),
            table,
            "{axis}"
        );
    }
}

#[test]
fn the_paper_calibration_reads_as_the_unit_calibration() {
    let path = legacy("paper/calibration.json");
    let unit_cal = UnitCalibration::load(&path).unwrap();
    let paper: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_same_tables(&unit_cal, &paper);
    assert_eq!(unit_cal.gyros.len(), 6);
    assert_eq!(
        unit_cal
            .accels
            .keys()
            .map(String::as_str)
            .collect::<Vec<_>>(),
        ["ax", "ay", "az"]
    );
    let unit = Unit::paper();
    unit_cal.check(&unit).unwrap();
    // Written back, it is a unit calibration (every table says its model).
    assert_eq!(
        UnitCalibration::from_json(&unit_cal.to_json(), "mem").unwrap(),
        unit_cal
    );
    assert!(unit_cal.to_json().contains("\"model\": \"dtg\""));

    // Its numbers: `compensate` of the paper model fixtures (which carry
    // this calibration) within 1e-9 deg/h of 5b6a72d's, in dtg-vib's
    // tests/one_path.rs.
}

#[test]
fn a_paper_model_files_embedded_calibration_reads_as_the_unit_calibration() {
    let text = std::fs::read_to_string(legacy("paper/model.json")).unwrap();
    let model: serde_json::Value = serde_json::from_str(&text).unwrap();
    let embedded = &model["model"]["calibration"];
    let unit_cal: UnitCalibration = serde_json::from_value(embedded.clone()).unwrap();
    assert_same_tables(&unit_cal, embedded);
    // A tetra model's embedded calibration is a unit calibration as before.
    let text = std::fs::read_to_string(legacy("tetra/model.json")).unwrap();
    let model: serde_json::Value = serde_json::from_str(&text).unwrap();
    let tetra: UnitCalibration =
        serde_json::from_value(model["model"]["calibration"].clone()).unwrap();
    tetra.check(&Unit::builtin("tetra").unwrap()).unwrap();
}

#[test]
fn the_calibration_formats_are_told_apart_with_a_message_that_says_how() {
    let untagged_rate =
        r#"{"format_version": 1, "gyros": {"g1": {"bias_deg_h": 1.0}}, "accels": {}}"#;
    let err = UnitCalibration::from_json(untagged_rate, "c.json")
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("c.json: gyro 'g1' has no \"model\": a table without one is the paper's calibration format, whose gyros are X, X1, Y, Y1, Z, Z1"),
        "{err}"
    );
    let mixed = r#"{"format_version": 1, "gyros": {"X": {"bias_deg_h": 1.0}, "g1": {"model": "rate"}}, "accels": {}}"#;
    let err = UnitCalibration::from_json(mixed, "c.json")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("some gyro tables say their \"model\" and some do not"),
        "{err}"
    );
    let rate_terms = r#"{"format_version": 1, "gyros": {"X": {"g_x_deg_h_g": 1.0}}, "accels": {}}"#;
    let err = UnitCalibration::from_json(rate_terms, "c.json")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("unknown field `g_x_deg_h_g`")
            && err.contains("read as the paper's DTG table"),
        "{err}"
    );
    let bad_axis = r#"{"format_version": 1, "gyros": {"X": {}}, "accels": {"w": {}}}"#;
    let err = UnitCalibration::from_json(bad_axis, "c.json")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("accelerometer 'w' in the paper's calibration format"),
        "{err}"
    );
}

#[test]
fn the_paper_truth_reads_as_the_unit_truth() {
    let path = legacy("paper/truth.json");
    let unit_truth = UnitTruth::load(&path).unwrap();
    let paper: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(
        unit_truth.channels.len(),
        paper["channels"].as_object().unwrap().len()
    );
    assert_eq!(unit_truth.unit, Unit::paper());
    assert_eq!(unit_truth.channels[3].channel, "Y1");
    assert_eq!(
        unit_truth.channels[3].noise_floor_deg_h,
        paper["channels"]["Y1"]["noise_floor_deg_h"]
            .as_f64()
            .unwrap()
    );
    assert_eq!(unit_truth.hidden.len(), 2);
    assert_eq!(
        unit_truth.residue_after_true_compensation_rms_deg_h.len(),
        6
    );
    // A unit truth written before the budget's union reads, the fields it
    // lacks empty.
    let tetra = UnitTruth::load(legacy("tetra/truth.json")).unwrap();
    assert_eq!(tetra.unit, Unit::builtin("tetra").unwrap());
    assert!(tetra.residue_after_true_compensation_rms_deg_h.is_empty());
    assert!(tetra.channels.iter().all(|c| c.collinear.is_empty()));
}

#[test]
fn one_reader_reads_the_papers_record_with_the_same_values() {
    let path = legacy("paper/record.csv");
    let strict = Record::read_csv(&path).unwrap();
    let read = Record::read_with_unit(&path, &Unit::paper()).unwrap();
    assert_eq!(read.records, vec![strict]);
    assert!(read.time.gaps.is_empty());
    let tetra =
        Record::read_with_unit(legacy("tetra/record.csv"), &Unit::builtin("tetra").unwrap())
            .unwrap();
    assert_eq!(tetra.records.len(), 1);
    assert_eq!(tetra.records[0].gyro_names(), ["g1", "g2", "g3", "g4"]);
}
