//! What the commands show of a unit other than the paper's beyond the fit:
//! parity fault detection and isolation by `residues` (a step on one gyro
//! of the dual triad is isolated to it; four gyros detect but cannot
//! isolate; three have no test), its `--json` keys, and the refusals of
//! the flags only the unit path takes and of a baseline of another unit;
//! and that a unit's final page has every section and figure the paper's
//! has. (The unit's pages and their links: `report_links`.)

use cli_support::testing::{Binary, s, scratch_dir};
use std::collections::BTreeSet;
use std::path::Path;

const DTG_VIB: Binary = Binary::new(env!("CARGO_BIN_EXE_dtg-vib")).appending(&["--quiet"]);

/// A 20-s clean tri-axial record of `unit` under `dir/NAME`.
fn simulate(dir: &Path, unit: &str, name: &str) -> std::path::PathBuf {
    let out = dir.join(name);
    let r = DTG_VIB.check(&[
        "simulate",
        "--unit",
        unit,
        "--builtin",
        "triaxial_clean",
        "--duration",
        "20",
        "--out",
        s(&out),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    out
}

/// The record at `from` with `step` deg/h added to column `column` from
/// the middle on, written to `to`.
fn with_step(from: &Path, to: &Path, column: &str, step: f64) {
    let text = std::fs::read_to_string(from).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let k = header.split(',').position(|c| c == column).unwrap();
    let rows: Vec<&str> = lines.collect();
    let mut out = format!("{header}\n");
    for (i, row) in rows.iter().enumerate() {
        let mut cells: Vec<String> = row.split(',').map(str::to_string).collect();
        if i >= rows.len() / 2 {
            let v: f64 = cells[k].parse().unwrap();
            cells[k] = format!("{}", v + step);
        }
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    std::fs::write(to, out).unwrap();
}

fn residues_json(unit: &str, data: &Path, out: &Path) -> serde_json::Value {
    let r = DTG_VIB.check(&[
        "residues",
        "--unit",
        unit,
        "--data",
        s(data),
        "--out",
        s(out),
        "--json",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    serde_json::from_str(&r.stdout).unwrap()
}

#[test]
fn a_step_on_one_gyro_of_the_dual_triad_is_detected_and_isolated_to_it() {
    let dir = scratch_dir("dtg-vib-unit-reports");
    let sim = simulate(dir, "dual-triad", "dual");
    let clean = residues_json("dual-triad", &sim.join("record.csv"), &dir.join("c.csv"));
    let faulty_csv = dir.join("faulty.csv");
    // 30 deg/h on gy2 (deg/h, as the unit logs): far above the noise.
    with_step(&sim.join("record.csv"), &faulty_csv, "gy2", 30.0);
    let faulty = residues_json("dual-triad", &faulty_csv, &dir.join("f.csv"));
    let f = &faulty["fdi"];
    for key in [
        "false_alarm_probability",
        "sigma_deg_h",
        "sigma_source",
        "threshold_deg_h",
        "isolation_possible",
    ] {
        assert!(f.get(key).is_some(), "fdi.{key} missing: {f}");
    }
    assert_eq!(f["sigma_source"], "estimated");
    assert_eq!(f["isolation_possible"], true);
    let (tests, alarms) = (
        f["before"]["tests"].as_u64().unwrap(),
        f["before"]["alarms"].as_u64().unwrap(),
    );
    let clean_alarms = clean["fdi"]["before"]["alarms"].as_u64().unwrap();
    assert!(alarms * 5 >= tests * 2, "{alarms} of {tests}: {f}");
    assert!(
        alarms >= 10 * clean_alarms.max(1),
        "{alarms} vs {clean_alarms}"
    );
    assert_eq!(f["before"]["most_isolated"], "gy2", "{f}");
    assert!(f["before"]["isolated"]["gy2"].as_u64().unwrap() * 10 >= alarms * 9);
    assert_eq!(faulty["residues"].as_array().unwrap().len(), 3);
    // The text says it in a line.
    let r = DTG_VIB.check(&[
        "residues",
        "--unit",
        "dual-triad",
        "--data",
        s(&faulty_csv),
        "--out",
        s(&dir.join("f2.csv")),
    ]);
    assert!(r.stdout.contains("isolated to gy2"), "{}", r.stdout);
}

#[test]
fn four_gyros_detect_three_have_no_test_and_unit_only_flags_are_refused() {
    let dir = scratch_dir("dtg-vib-unit-reports");
    let tetra = simulate(dir, "tetra", "tetra");
    let faulty = dir.join("tetra-faulty.csv");
    with_step(&tetra.join("record.csv"), &faulty, "g3", 30.0);
    let t_csv = dir.join("t.csv");
    let with_sigma = |sigma: &str| {
        DTG_VIB.check(&[
            "residues",
            "--unit",
            "tetra",
            "--data",
            s(&faulty),
            "--out",
            s(&t_csv),
            "--fdi-sigma",
            sigma,
        ])
    };
    let r = with_sigma("0.5");
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stdout.contains("four gyros detect but cannot isolate"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("(--fdi-sigma)"), "{}", r.stdout);
    let triad = simulate(dir, "triad", "triad");
    let e = DTG_VIB.refused(&[
        "residues",
        "--unit",
        "triad",
        "--data",
        s(&triad.join("record.csv")),
        "--out",
        s(&dir.join("x.csv")),
        "--json",
    ]);
    assert!(
        e.contains(
            "has 3 gyros: nothing is redundant, so it has no parity residue and no fault detection"
        ),
        "{e}"
    );
    // The paper's path keeps its output: the unit-only flags are refused.
    let paper = dir.join("paper");
    DTG_VIB.check(&[
        "simulate",
        "--builtin",
        "triaxial_clean",
        "--duration",
        "5",
        "--out",
        s(&paper),
    ]);
    let (record, p_csv) = (paper.join("record.csv"), dir.join("p.csv"));
    for flag in [
        &["--json"][..],
        &["--fdi-sigma", "0.2"],
        &["--fdi-false-alarm", "0.01"],
    ] {
        let mut args = vec!["residues", "--data", s(&record), "--out", s(&p_csv)];
        args.extend_from_slice(flag);
        let e = DTG_VIB.refused(&args);
        assert!(
            e.contains(&format!(
                "{}: residues takes it on the unit path only",
                flag[0]
            )),
            "{e}"
        );
    }
    let r = with_sigma("1e308");
    assert_eq!(r.code, 1, "{}", r.stdout);
    assert!(
        r.stderr.contains(
            "fault detection with --fdi-sigma 1e308 and --fdi-false-alarm 1e-3: threshold = inf"
        ),
        "{}",
        r.stderr
    );
    let r = with_sigma("0");
    assert_eq!(r.code, 2, "{}", r.stdout);
    let e = r.stderr;
    assert!(
        e.contains("a noise level must be a positive number of deg/h"),
        "{e}"
    );
}

#[test]
fn a_baseline_of_another_unit_is_refused() {
    let dir = scratch_dir("dtg-vib-unit-reports");
    let mut models = Vec::new();
    for unit in ["tetra", "triad"] {
        let sim = simulate(dir, unit, &format!("{unit}-b"));
        let m = dir.join(format!("{unit}.json"));
        let r = DTG_VIB.check(&[
            "fit",
            "--unit",
            unit,
            "--data",
            s(&sim.join("record.csv")),
            "--calib",
            s(&sim.join("calibration.json")),
            "--max-centres",
            "4",
            "--out",
            s(&m),
        ]);
        assert_eq!(r.code, 0, "{}", r.stderr);
        models.push((m, sim));
    }
    let e = DTG_VIB.refused(&[
        "report",
        "--model",
        s(&models[0].0),
        "--baseline",
        s(&models[1].0),
        "--data",
        s(&models[0].1.join("record.csv")),
        "--out",
        s(&dir.join("rep")),
    ]);
    assert!(
        e.contains("a baseline must be a model of the same unit"),
        "{e}"
    );
}

/// The `<h2>` headings (but the table of contents) and the figure stems
/// (`src` of each PNG, without folder and extension) of a page.
fn kinds(page: &Path) -> (BTreeSet<String>, BTreeSet<String>) {
    let html = std::fs::read_to_string(page).unwrap();
    let between = |open: &str, close: char| -> Vec<String> {
        html.split(open)
            .skip(1)
            .map(|s| s[..s.find(close).unwrap()].to_string())
            .collect()
    };
    let sections = between("<h2>", '<')
        .into_iter()
        .filter(|h| h != "Contents")
        .map(|h| h.replace("&#39;", "'"))
        .collect();
    let figures = between(" src=\"", '"')
        .into_iter()
        .filter(|s| s.ends_with(".png"))
        .map(|s| {
            let file = s.rsplit('/').next().unwrap();
            file.trim_end_matches(".png").to_string()
        })
        .collect();
    (sections, figures)
}

/// One page for every unit (issue 33 §2): the final page of `demo --unit
/// tetra` has every section and every figure of the paper's demo's final
/// page, the paper's own figures (Figs. 3, 5, 6, 7) included, since tetra
/// has a parity residue.
#[test]
fn tetras_final_page_has_every_section_and_figure_of_the_papers() {
    let dir = scratch_dir("dtg-vib-unit-reports");
    let (paper, tetra) = (dir.join("demo-paper"), dir.join("demo-tetra"));
    for (out, unit) in [(&paper, None), (&tetra, Some("tetra"))] {
        let mut args = vec!["demo", "--out", s(out)];
        args.extend(unit.iter().flat_map(|u| ["--unit", *u]));
        let r = DTG_VIB.check(&args);
        assert_eq!(r.code, 0, "{}", r.stderr);
    }
    let (p_sections, p_figures) = kinds(&paper.join("index.html"));
    let (t_sections, t_figures) = kinds(&tetra.join("index.html"));
    eprintln!(
        "paper: {} sections, {} figures; tetra: {} sections, {} figures",
        p_sections.len(),
        p_figures.len(),
        t_sections.len(),
        t_figures.len()
    );
    let missing: Vec<&String> = p_sections.difference(&t_sections).collect();
    assert!(
        missing.is_empty(),
        "sections missing for tetra: {missing:?}"
    );
    let missing: Vec<&String> = p_figures.difference(&t_figures).collect();
    assert!(missing.is_empty(), "figures missing for tetra: {missing:?}");
    // The union of the two pages before issue 33: the paper's twelve
    // sections and eleven figures, and the unit page's effects found and
    // fault detection.
    for heading in [
        "Summary",
        "Measured against predicted",
        "Where it fails",
        "Diagnosis",
        "Allan deviation: parity residues",
        "Parity residues",
        "Residual distribution against the noise floor",
        "Channel models",
        "Effects found",
        "Before and after",
        "The paper's figures",
    ] {
        assert!(t_sections.contains(heading), "{heading}: {t_sections:?}");
    }
    assert!(t_figures.len() >= 11, "{t_figures:?}");
    let page = std::fs::read_to_string(tetra.join("index.html")).unwrap();
    assert!(
        page.contains("fault detection, compensated: "),
        "fault detection"
    );
    let page = std::fs::read_to_string(paper.join("index.html")).unwrap();
    assert!(
        page.contains("fault detection, compensated: "),
        "the paper's too"
    );
}
