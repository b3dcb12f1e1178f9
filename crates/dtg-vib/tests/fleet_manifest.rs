//! The lot manifest's refusals, each one line naming the entry, option or
//! limit, before any unit runs; and a manifest's options becoming
//! `explain`'s own flags.

mod fleet_common;

use fleet_common::{dtg, text};
use std::path::Path;

/// A lot folder with two records and a calibration, and `manifest` as lot.toml.
fn lot(dir: &Path, manifest: &str) -> String {
    std::fs::create_dir_all(dir.join("SN1")).unwrap();
    std::fs::write(dir.join("SN1/x.csv"), "t,g1,g2,g3,g4,ax,ay,az\n").unwrap();
    std::fs::write(dir.join("SN1/y.csv"), "t,g1,g2,g3,g4,ax,ay,az\n").unwrap();
    std::fs::write(dir.join("SN1/calibration.json"), "{}").unwrap();
    let m = dir.join("lot.toml");
    std::fs::write(&m, manifest).unwrap();
    m.to_str().unwrap().to_string()
}

/// `fleet task --index 0` on `manifest`: refused, one line, saying all of `says`.
fn refused(manifest: &str, says: &[&str]) {
    let tmp = tempfile::tempdir().unwrap();
    let m = lot(tmp.path(), manifest);
    let out = tmp.path().join("out");
    let o = dtg(&[
        "fleet",
        "task",
        "--manifest",
        &m,
        "--index",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
    for s in says {
        assert!(err.contains(s), "'{s}' in: {err}");
    }
    assert!(!out.join("units").exists(), "nothing written: {err}");
}

const HEAD: &str = "name = \"lot 2026-48\"\nunit = \"tetra\"\n";
const ENTRY: &str = "[[entry]]\nid = \"SN1\"\ndata = [\"SN1/x.csv\", \"SN1/y.csv\"]\ncalib = \"SN1/calibration.json\"\n";

#[test]
fn a_missing_file_is_refused_naming_the_entry() {
    let m = format!("{HEAD}{ENTRY}[[entry]]\nid = \"SN2\"\ndata = [\"SN2/x.csv\"]\n");
    refused(
        &m,
        &[
            "entry 1 (id 'SN2')",
            "data 'SN2/x.csv' is not a file",
            "relative to the manifest",
        ],
    );
    let m = format!(
        "{HEAD}[[entry]]\nid = \"SN1\"\ndata = [\"SN1/x.csv\"]\ncalib = \"SN1/cal.json\"\n"
    );
    refused(&m, &["entry 0 (id 'SN1')", "calib 'SN1/cal.json'"]);
}

#[test]
fn two_entries_with_one_id_are_refused() {
    refused(
        &format!("{HEAD}{ENTRY}{ENTRY}"),
        &["entry 1 (id 'SN1')", "entry 0 has the same id"],
    );
}

#[test]
fn an_unknown_option_is_refused_naming_it_and_the_valid_ones() {
    let m = format!("{HEAD}[options]\nwindow_signal = [\"az\"]\n{ENTRY}");
    refused(
        &m,
        &[
            "[options] window_signal",
            "not an option of explain",
            "window_signals",
            "max_rounds",
        ],
    );
    let m = format!("{HEAD}[options]\nout = \"x.json\"\n{ENTRY}");
    refused(&m, &["[options] out", "set by the lot"]);
    // Known, but a value explain refuses.
    let m = format!("{HEAD}[options]\nmax_rounds = 0\n{ENTRY}");
    refused(&m, &["[options]", "explain refuses them", "max-rounds"]);
}

#[test]
fn a_limit_on_no_effect_of_the_unit_is_refused() {
    let m = format!("{HEAD}[spec]\ng_yy = 1.0\n{ENTRY}");
    refused(&m, &["[spec] g_yy", "not an effect id"]);
    let m = format!("{HEAD}[spec]\ng_y = -1.0\n{ENTRY}");
    refused(&m, &["[spec] g_y", "positive"]);
}

#[test]
fn entries_keys_ids_and_units_are_checked() {
    refused(
        &format!("{HEAD}[[entry]]\nid = \"SN1\"\ndata = [\"SN1/x.csv\"]\ncalibration = \"x\"\n"),
        &["entry 0 (id 'SN1')", "calibration"],
    );
    refused(
        &format!("{HEAD}[[entry]]\nid = \"../SN1\"\ndata = [\"SN1/x.csv\"]\n"),
        &["entry 0", "letters, digits"],
    );
    refused(
        &format!("name = \"l\"\n{ENTRY}"),
        &["entry 0 (id 'SN1')", "no unit"],
    );
    refused(
        &format!("name = \"l\"\nunit = \"tetrahedron\"\n{ENTRY}"),
        &["unit 'tetrahedron'", "built-in"],
    );
    refused(
        &format!("{HEAD}[[entry]]\nid = \"SN1\"\ndata = [\"SN1/x.csv\", \"./SN1/x.csv\"]\n"),
        &["entry 0", "same file"],
    );
    refused(HEAD, &["no [[entry]]"]);
}

#[test]
fn the_options_become_explains_flags() {
    let tmp = tempfile::tempdir().unwrap();
    let m = lot(
        tmp.path(),
        &format!(
            "{HEAD}[options]\nwindow_signals = [\"ax\", \"az\"]\nadd_effect = [\"g2=g_y\", \"g1=g_x\"]\nmax_rounds = 2\ncausal = true\nshared_centres = false\n{ENTRY}"
        ),
    );
    let catalogue_from = |args: &[&str]| {
        let o = dtg(args);
        String::from_utf8_lossy(&o.stdout).to_string() + &String::from_utf8_lossy(&o.stderr)
    };
    let out = tmp.path().join("out");
    // The records are header-only, so explain fails: failed.json keeps
    // what it was run with.
    let said = catalogue_from(&[
        "fleet",
        "task",
        "--manifest",
        &m,
        "--index",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(said.contains("SN1 failed"), "{said}");
    let f: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("units/SN1/failed.json")).unwrap())
            .unwrap();
    let opts: Vec<&str> = f["inputs"]["options"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(
        opts,
        [
            "--add-effect",
            "g2=g_y",
            "--add-effect",
            "g1=g_x",
            "--causal",
            "--max-rounds",
            "2",
            "--window-signals",
            "ax,az"
        ]
    );
    assert!(!f["reason"].as_str().unwrap().is_empty());
}
