//! Issue 33: one path for every unit. The files written before it (the
//! fixtures under `tests/fixtures/legacy/`, made by main 5b6a72d) still
//! load and give their numbers; every unit gets the terminal's union of
//! what the paper's path and the unit path printed (residue tables in
//! `check`, the choice table and stride note in `fit`, the channel table
//! against a baseline in `report`, `residues --json` and fault detection,
//! one `allan --json` shape, causal compensation through the onboard
//! evaluator); and `demo` runs on a unit whatever its accelerometers are
//! called, with `--window-signals`.

use cli_support::testing::{Binary, s, scratch_dir};
use dtg_vib::unit_sensor::{Applied, UnitModel, load_calibration};
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use std::path::{Path, PathBuf};

const DTG_VIB: Binary = Binary::new(env!("CARGO_BIN_EXE_dtg-vib")).appending(&["--quiet"]);

fn legacy(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/legacy")
        .join(path)
}

/// A CSV's header and rows.
fn csv(path: &Path) -> (String, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// Every model file of 5b6a72d on its record: `compensate` gives the
/// numbers 5b6a72d wrote, within 1e-9 deg/h (the paper's model files carry
/// no unit and the paper's calibration format; the causal models run
/// through the onboard evaluator now, the tetra's as a batch then).
#[test]
fn files_written_before_compensate_as_they_did() {
    let dir = scratch_dir("dtg-vib-one-path-legacy");
    for (model, record, written) in [
        (
            "paper/model.json",
            "paper/record.csv",
            "paper/compensated-model.csv",
        ),
        (
            "paper/causal-gg_IS.json",
            "paper/record.csv",
            "paper/compensated-causal.csv",
        ),
        (
            "tetra/model.json",
            "tetra/record.csv",
            "tetra/compensated.csv",
        ),
        (
            "tetra/causal.json",
            "tetra/record.csv",
            "tetra/compensated-causal.csv",
        ),
    ] {
        let out = dir.join(model.replace('/', "-") + ".csv");
        let r = DTG_VIB.check(&[
            "compensate",
            "--model",
            s(&legacy(model)),
            "--data",
            s(&legacy(record)),
            "--out",
            s(&out),
        ]);
        assert_eq!(r.code, 0, "{model}: {}", r.stderr);
        let (h0, then) = csv(&legacy(written));
        let (h1, now) = csv(&out);
        assert_eq!(h0, h1, "{model}");
        assert_eq!(then.len(), now.len(), "{model}");
        let worst = then
            .iter()
            .zip(&now)
            .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
            .fold(0.0, f64::max);
        assert!(worst <= 1e-9, "{model}: {worst} deg/h from 5b6a72d's");
    }
}

/// The paper's calibration file reads as the paper unit's calibration
/// (gyros by channel, accelerometers by column), fits with it, and the
/// model written now stores the unit and a unit calibration.
#[test]
fn the_papers_calibration_reads_and_new_models_carry_their_unit() {
    let cal = load_calibration(&legacy("paper/calibration.json")).unwrap();
    let text = std::fs::read_to_string(legacy("paper/calibration.json")).unwrap();
    let paper: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(paper["gyros"].as_object().unwrap().len(), 6);
    assert_eq!(cal.gyros.len(), 6);
    let nav_sensors::calibration::GyroCoefficients::Dtg(y1) = cal.gyros["Y1"] else {
        panic!("Y1 reads as a DTG table");
    };
    assert_eq!(
        serde_json::to_value(y1).unwrap(),
        paper["gyros"]["Y1"],
        "every value as written"
    );
    cal.check(&Unit::paper()).unwrap();
    assert!(cal.accels.contains_key("az") && cal.gyros.contains_key("Y1"));
    let dir = scratch_dir("dtg-vib-one-path-calibration");
    let model = dir.join("m.json");
    let r = DTG_VIB.check(&[
        "fit",
        "--data",
        s(&legacy("paper/record.csv")),
        "--calib",
        s(&legacy("paper/calibration.json")),
        "--input",
        "raw",
        "--smoother",
        "none",
        "--max-centres",
        "5",
        "--candidates",
        "40",
        "--out",
        s(&model),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.starts_with("unit: paper"), "{}", r.stdout);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&model).unwrap()).unwrap();
    assert!(json["model"]["unit"]["gyro"].is_array());
    assert_eq!(json["model"]["calibration"]["gyros"]["X"]["model"], "dtg");
    // Read back, it is the paper unit's model, calibrated as before.
    let m = UnitModel::load(&model).unwrap();
    assert_eq!(m.unit(), &Unit::paper());
    assert_eq!(m.inner().sensor().calibration.as_ref(), Some(&cal));
}

/// `check` prints the residue tables (before, after, unfaded, pooled) for
/// a unit of four gyros, and its JSON holds them; a unit of three says it
/// has none.
#[test]
fn check_prints_residue_tables_for_every_redundant_unit() {
    let (model, record) = (legacy("tetra/model.json"), legacy("tetra/record.csv"));
    let args = ["check", "--model", s(&model), "--data", s(&record)];
    let text = DTG_VIB.check(&args);
    for want in [
        "residue  rms before  rms after  (deg/h, every row)",
        "     P0 ",
        " pooled ",
        "no fade: pooled residue rms after",
        "│ no fade: rms after",
    ] {
        assert!(text.stdout.contains(want), "{want}: {}", text.stdout);
    }
    let json = DTG_VIB.check(&[&args[..], &["--json"]].concat());
    let v: serde_json::Value = serde_json::from_str(&json.stdout).unwrap();
    assert_eq!(v["residues"][0]["residue"], "P0");
    assert!(v["residues_unfaded"][0]["rms_after"].is_number());
    assert!(v["unit"].as_str().unwrap().starts_with("tetra"));
    assert!(v["rate_std_deg_s"].is_number());
    // Three gyros: the notice where the table would be.
    let dir = scratch_dir("dtg-vib-one-path-triad");
    let sim = dir.join("sim");
    DTG_VIB.check(&[
        "simulate",
        "--unit",
        "triad",
        "--builtin",
        "triaxial_clean",
        "--duration",
        "15",
        "--out",
        s(&sim),
    ]);
    let model = dir.join("m.json");
    let fit = DTG_VIB.check(&[
        "fit",
        "--unit",
        "triad",
        "--data",
        s(&sim.join("record.csv")),
        "--input",
        "raw",
        "--smoother",
        "none",
        "--max-centres",
        "4",
        "--candidates",
        "30",
        "--out",
        s(&model),
    ]);
    assert_eq!(fit.code, 0, "{}", fit.stderr);
    let r = DTG_VIB.check(&[
        "check",
        "--model",
        s(&model),
        "--data",
        s(&sim.join("record.csv")),
    ]);
    assert!(
        r.stdout.contains("has 3 gyros: nothing is redundant"),
        "{}",
        r.stdout
    );
    assert!(!r.stdout.contains("pooled"), "{}", r.stdout);
}

/// `fit` on another unit prints the choice of input and smoother and, on a
/// long record, the stride of its centre selection.
#[test]
fn fit_prints_its_choice_table_and_stride_note_on_any_unit() {
    let dir = scratch_dir("dtg-vib-one-path-fit");
    let r = DTG_VIB.check(&[
        "fit",
        "--data",
        s(&legacy("tetra/record.csv")),
        "--calib",
        s(&legacy("tetra/calibration.json")),
        "--unit",
        "tetra",
        "--max-centres",
        "4",
        "--candidates",
        "30",
        "--out",
        s(&dir.join("choice.json")),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stdout.contains("input and smoother: chosen"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("  raw         none "), "{}", r.stdout);
    // 60,000 samples of a still tetra (noise, gravity on z): 30,000
    // training windows, every second one of them selects.
    let n = 60_000;
    let mut text = String::from("t,g1,g2,g3,g4,ax,ay,az\n");
    let mut x: u64 = 7;
    let mut noise = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((x >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    for i in 0..n {
        let g: Vec<String> = (0..4).map(|_| format!("{:.6}", noise())).collect();
        let az = 1.0 + 0.1 * noise();
        text += &format!("{},{},0,0,{az:.6}\n", i as f64 * 0.02, g.join(","));
    }
    let record = dir.join("long.csv");
    std::fs::write(&record, text).unwrap();
    let r = DTG_VIB.check(&[
        "fit",
        "--data",
        s(&record),
        "--unit",
        "tetra",
        "--input",
        "raw",
        "--smoother",
        "none",
        "--window-signals",
        "az",
        "--window",
        "5",
        "--no-filter",
        "--max-centres",
        "3",
        "--candidates",
        "20",
        "--out",
        s(&dir.join("long.json")),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stderr
            .contains("training windows: cross-validation and centre selection used every 2th"),
        "{}",
        r.stderr
    );
}

/// `report` prints each channel against a baseline, on any unit.
#[test]
fn report_prints_the_channel_table_against_a_baseline_on_any_unit() {
    let dir = scratch_dir("dtg-vib-one-path-report");
    let r = DTG_VIB.check(&[
        "report",
        "--model",
        s(&legacy("tetra/causal.json")),
        "--baseline",
        s(&legacy("tetra/model.json")),
        "--data",
        s(&legacy("tetra/record.csv")),
        "--out",
        s(&dir.join("page")),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stdout
            .contains("channel  val rms baseline  val rms this model  (deg/h)  change"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("\n     g4 "), "{}", r.stdout);
    assert!(
        r.stdout.contains("fault detection, compensated"),
        "{}",
        r.stdout
    );
}

/// `residues --json` and the fault-detection flags on the paper's unit:
/// the residues K0 … K5, the validation table, and the test as stated.
#[test]
fn residues_json_and_fault_detection_work_on_the_papers_unit() {
    let dir = scratch_dir("dtg-vib-one-path-residues");
    let out = dir.join("res.csv");
    let r = DTG_VIB.check(&[
        "residues",
        "--model",
        s(&legacy("paper/model.json")),
        "--data",
        s(&legacy("paper/record.csv")),
        "--out",
        s(&out),
        "--json",
        "--fdi-sigma",
        "0.2",
        "--fdi-false-alarm",
        "1e-4",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["residues"][5]["residue"], "K5");
    assert_eq!(v["fdi"]["sigma_source"], "given");
    assert_eq!(v["fdi"]["false_alarm_probability"], 1e-4);
    assert_eq!(v["validation"][0]["residue"], "K0");
    let (header, rows) = csv(&out);
    assert!(
        header.starts_with("t,K0,K1,K2,K3,K4,K5,K0_pre,"),
        "{header}"
    );
    assert!(header.contains(",K5_comp,K0_out,") && header.ends_with(",K5_out"));
    assert_eq!(rows.len(), v["samples"].as_u64().unwrap() as usize);
}

/// `allan --json` has one shape on every unit: `channel` / `residue` and
/// `adev_before` / `adev_after`, with the unit and segment named.
#[test]
fn allan_json_has_one_shape_for_every_unit() {
    for unit in ["paper", "tetra"] {
        let r = DTG_VIB.check(&[
            "allan",
            "--model",
            s(&legacy(&format!("{unit}/model.json"))),
            "--data",
            s(&legacy(&format!("{unit}/record.csv"))),
            "--json",
        ]);
        assert_eq!(r.code, 0, "{unit}: {}", r.stderr);
        let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
        let ch = &v["channels"][0];
        assert!(
            ch["channel"].is_string() && ch.get("name").is_none(),
            "{unit}"
        );
        let n = ch["tau_s"].as_array().unwrap().len();
        assert_eq!(ch["adev_before"].as_array().unwrap().len(), n, "{unit}");
        assert_eq!(ch["adev_after"].as_array().unwrap().len(), n, "{unit}");
        assert!(v["residues"][0]["residue"].is_string(), "{unit}");
        assert!(v["unit"].as_str().unwrap().starts_with(unit), "{unit}");
        assert_eq!(v["compensated"], true, "{unit}");
    }
}

/// A causal model of any unit is compensated by the onboard evaluator: its
/// output is the evaluator's, to the bit.
#[test]
fn causal_compensation_runs_through_the_onboard_evaluator() {
    let m = UnitModel::load(legacy("tetra/causal.json")).unwrap();
    let read = Record::read_with_unit(legacy("tetra/record.csv"), m.unit()).unwrap();
    let record = &read.records[0];
    let applied = Applied::unsplit(&m, &[("r".into(), record)]).unwrap();
    let compensated = applied.compensated().unwrap().remove(0);
    let stepped = dtg_vib::onboard::step_record(&m, record).unwrap();
    for k in 0..4 {
        assert_eq!(
            compensated.gyro_at(k),
            &stepped.rate_deg_h[k][..],
            "g{}",
            k + 1
        );
    }
}

/// `demo` on a unit whose accelerometers are not called ax, ay, az: the
/// window reads the unit's own accelerometer along z, the hidden effects
/// and notes name its own channels (nothing of the paper's Y1 or Z), and
/// `--window-signals` sets the window.
#[test]
fn demo_runs_on_any_unit_and_takes_window_signals() {
    let dir = scratch_dir("dtg-vib-one-path-demo");
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../units/tetra.toml"),
    )
    .unwrap()
    .replace("name = \"ax\"", "name = \"acc_x\"")
    .replace("name = \"ay\"", "name = \"acc_y\"")
    .replace("name = \"az\"", "name = \"acc_z\"")
    .replace("name = \"tetra:", "name = \"renamed tetra:");
    let unit = dir.join("renamed.toml");
    std::fs::write(&unit, text).unwrap();
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
            .arg("--quiet")
            .args(args)
            .output()
            .unwrap();
        let stdout = String::from_utf8(out.stdout).unwrap();
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(out.status.success(), "{args:?}: {stderr}");
        stdout + &stderr
    };
    let out = dir.join("renamed");
    let said = run(&["demo", "--unit", s(&unit), "--out", s(&out)]);
    assert!(
        said.contains("hidden from the calibration: g1=g_y"),
        "{said}"
    );
    assert!(!said.contains("Y1") && !said.contains("Z="), "{said}");
    let window = |dir: &Path| {
        let m = UnitModel::load(dir.join("final/model.json")).unwrap();
        m.inner().preprocess().window.signals().to_vec()
    };
    assert_eq!(window(&out), ["acc_z"]);
    assert!(out.join("index.html").exists());
    let triad = dir.join("triad");
    run(&[
        "demo",
        "--unit",
        "triad",
        "--window-signals",
        "ay,az",
        "--out",
        s(&triad),
    ]);
    assert_eq!(window(&triad), ["ay", "az"]);
    let e = DTG_VIB.refused(&[
        "demo",
        "--window-signals",
        "auto,az",
        "--out",
        s(&dir.join("x")),
    ]);
    assert!(e.contains("give auto alone or a list of signals"), "{e}");
}

/// `residues` and `report` state one fault-detection test: without
/// `--fdi-sigma` both read σ from the record's parity vectors V·m, so on
/// the paper's unit (whose named residues, such as K0 = x0 − x1, have
/// another scale than V·m) they print the same σ and the same alarms.
#[test]
fn residues_and_report_read_one_sigma_on_the_papers_unit() {
    let dir = scratch_dir("dtg-vib-one-path-one-sigma");
    let (model, data) = (legacy("paper/model.json"), legacy("paper/record.csv"));
    let r = DTG_VIB.check(&[
        "residues",
        "--model",
        s(&model),
        "--data",
        s(&data),
        "--out",
        s(&dir.join("res.csv")),
        "--json",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["fdi"]["sigma_source"], "estimated");
    let alarms = v["fdi"]["before"]["alarms"].as_u64().unwrap();
    let tests = v["fdi"]["before"]["tests"].as_u64().unwrap();
    let page = DTG_VIB.check(&[
        "report",
        "--model",
        s(&model),
        "--data",
        s(&data),
        "--out",
        s(&dir.join("page")),
    ]);
    assert_eq!(page.code, 0, "{}", page.stderr);
    let said = format!("fault detection, as logged: {alarms} of {tests} samples alarmed");
    assert!(page.stdout.contains(&said), "{said}\n{}", page.stdout);
}
