//! The `dtg-vib` command line, driven as a user would: the happy path's
//! contracts (flags, JSON keys, CSV columns), and a table of bad inputs,
//! each of which must give a one-line error and its exit status, never a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
}

fn dir() -> &'static Path {
    cli_support::testing::scratch_dir("dtg-vib-cli")
}

fn run(args: &[&str]) -> Output {
    bin()
        .args(args)
        .arg("--quiet")
        .output()
        .expect("binary runs")
}

fn ok(args: &[&str]) -> String {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Runs a command that must fail; returns its stderr after checking it is one
/// line, says `error:` and holds no panic.
fn fails(args: &[&str]) -> String {
    let out = run(args);
    assert!(!out.status.success(), "{args:?} should fail");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{args:?}: not one line: {err}"
    );
    assert!(err.starts_with("error: "), "{err}");
    err
}

/// The built-in demo record (the paper's test, temperature column included),
/// simulated once for all tests.
fn sim() -> &'static Path {
    static SIM: OnceLock<PathBuf> = OnceLock::new();
    SIM.get_or_init(|| {
        let d = dir().join("sim");
        ok(&[
            "simulate",
            "--builtin",
            "demo",
            "--out",
            d.to_str().unwrap(),
        ]);
        d
    })
}

fn record() -> String {
    sim().join("record.csv").display().to_string()
}

/// A model fitted with `col:temp` on every channel, once for all tests:
/// its file and what `fit` printed.
fn fitted_model() -> &'static (String, String) {
    static MODEL: OnceLock<(String, String)> = OnceLock::new();
    MODEL.get_or_init(|| {
        let m = dir().join("model.json").display().to_string();
        let calib = sim().join("calibration.json").display().to_string();
        let printed = ok(&[
            "fit",
            "--data",
            &record(),
            "--calib",
            &calib,
            "--effects",
            "col:temp",
            "--max-centers",
            "10",
            "--out",
            &m,
        ]);
        (m, printed)
    })
}

/// The file of [`fitted_model`].
fn model() -> &'static str {
    &fitted_model().0
}

/// Writes a variant of the record: `edit` gets the lines and changes them.
fn variant(name: &str, edit: impl FnOnce(&mut Vec<String>)) -> String {
    let text = std::fs::read_to_string(record()).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    edit(&mut lines);
    let p = dir().join(name);
    std::fs::write(&p, lines.join("\n") + "\n").unwrap();
    p.display().to_string()
}

/// `fit --data RECORD ARGS… --out DIR/NAME`, which must succeed: the model
/// file's bytes.
fn fit_bytes(name: &str, args: &[&str]) -> Vec<u8> {
    let out = dir().join(name);
    let r = record();
    let mut all = vec!["fit", "--data", r.as_str()];
    all.extend_from_slice(args);
    all.extend(["--out", out.to_str().unwrap()]);
    ok(&all);
    std::fs::read(out).unwrap()
}

/// A small model (5 centres at most) fitted with these flags, as JSON.
fn fitted(name: &str, args: &[&str]) -> serde_json::Value {
    let mut all = vec!["--max-centers", "5"];
    all.extend_from_slice(args);
    serde_json::from_slice(&fit_bytes(name, &all)).unwrap()
}

/// A command that must fail: its exit status (1, or 2 for a flag clap
/// refuses), the fragments its one `error:` line must hold, and a path it
/// must not have written.
struct Refusal {
    what: &'static str,
    args: Vec<String>,
    exit: i32,
    says: Vec<String>,
    writes_nothing_at: Option<PathBuf>,
}

/// `what`: `dtg-vib ARGS…` exits with `exit`, saying every one of `says`.
fn refusal(what: &'static str, exit: i32, args: &[&str], says: &[&str]) -> Refusal {
    Refusal {
        what,
        args: args.iter().map(|a| a.to_string()).collect(),
        exit,
        says: says.iter().map(|s| s.to_string()).collect(),
        writes_nothing_at: None,
    }
}

/// `what`: `fit --data DATA ARGS… --out /dev/null` exits 1, saying `says`.
fn fit_refusal(what: &'static str, data: &str, args: &[&str], says: &[&str]) -> Refusal {
    let mut all = vec!["fit", "--data", data];
    all.extend_from_slice(args);
    all.extend(["--out", "/dev/null"]);
    refusal(what, 1, &all, says)
}

/// Runs every refusal and lists each way one broke the contract: a panic,
/// another exit, more than one line, a missing fragment, a file written.
fn broken(cases: &[Refusal]) -> Vec<String> {
    let mut broken = Vec::new();
    for c in cases {
        let args: Vec<&str> = c.args.iter().map(String::as_str).collect();
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        let mut fault = |why: String| broken.push(format!("{}: {args:?}: {why}: {err}", c.what));
        if err.contains("panicked") {
            fault("panicked".into());
        }
        if out.status.code() != Some(c.exit) {
            fault(format!("exit {:?}, not {}", out.status.code(), c.exit));
        }
        if !err.starts_with("error: ") || err.trim_end().lines().count() != 1 {
            fault("not one `error:` line".into());
        }
        for s in c.says.iter().filter(|s| !err.contains(s.as_str())) {
            fault(format!("does not say {s:?}"));
        }
        if let Some(p) = c.writes_nothing_at.as_ref().filter(|p| p.exists()) {
            fault(format!("wrote {}", p.display()));
        }
    }
    broken
}

/// Bad records: each is named with the file, and where it has a position,
/// with line and column.
fn bad_records() -> Vec<Refusal> {
    let no_az = variant("no-az.csv", |l| {
        for line in l.iter_mut() {
            let mut cells: Vec<&str> = line.split(',').collect();
            cells.remove(9); // az
            *line = cells.join(",");
        }
    });
    let text = variant("text.csv", |l| {
        let mut cells: Vec<String> = l[7].split(',').map(str::to_string).collect();
        cells[3] = "oops".into(); // column 4 (Y) of file line 8
        l[7] = cells.join(",");
    });
    let nan = variant("nan.csv", |l| {
        let mut cells: Vec<String> = l[100].split(',').map(str::to_string).collect();
        cells[9] = "NaN".into();
        l[100] = cells.join(",");
    });
    let short = variant("short.csv", |l| l.truncate(31));
    // Rows 11 and 12 swapped: line 12 is the first whose time does not increase.
    let time = variant("time.csv", |l| l.swap(10, 11));
    let no_temp = variant("no-temp.csv", |l| {
        for line in l.iter_mut() {
            let cut = line.rfind(',').unwrap();
            line.truncate(cut);
        }
    });
    // One full window is one compensated sample: not a record.
    let one = variant("short50.csv", |l| l.truncate(51));
    // A hostile cell: 1e308 in az is refused where it enters.
    let big = variant("big-cell.csv", |l| {
        let az = l[0].split(',').position(|h| h == "az").unwrap();
        let mut cells: Vec<String> = l[300].split(',').map(str::to_string).collect();
        cells[az] = "1e308".into();
        l[300] = cells.join(",");
    });
    let az = 1 + record_header().iter().position(|h| h == "az").unwrap();
    let m = model();
    vec![
        fit_refusal("missing column", &no_az, &[], &["no-az.csv", "'az'"]),
        fit_refusal(
            "text cell at file:line:column",
            &text,
            &[],
            &["text.csv:8:4", "'oops' is not a number"],
        ),
        refusal(
            "NaN at file:line:column",
            1,
            &["residues", "--data", &nan, "--out", "/dev/null"],
            &["nan.csv:101:10", "not finite"],
        ),
        fit_refusal(
            "record shorter than a window",
            &short,
            &[],
            &["30 samples", "window of 50"],
        ),
        fit_refusal(
            "time that does not increase",
            &time,
            &[],
            &["time.csv:12:1", "does not increase"],
        ),
        refusal(
            "model fitted on other columns",
            1,
            &[
                "compensate",
                "--model",
                m,
                "--data",
                &no_temp,
                "--out",
                "/dev/null",
            ],
            &["col:temp", "no extra column 'temp'"],
        ),
        refusal(
            "one window is not a record",
            1,
            &[
                "compensate",
                "--model",
                m,
                "--data",
                &one,
                "--out",
                "/dev/null",
            ],
            &["1 windows, need at least 2"],
        ),
        fit_refusal(
            "hostile cell where it enters",
            &big,
            &[],
            &[&format!("big-cell.csv:301:{az}"), "1e150"],
        ),
    ]
}

fn record_header() -> Vec<String> {
    let text = std::fs::read_to_string(record()).unwrap();
    text.lines()
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect()
}

/// Effects a record cannot identify, and effect or channel names that do
/// not exist: named, with the valid ones.
fn bad_effects() -> Vec<Refusal> {
    let r = record();
    // A thermal chamber held at 25 °C: col:temp cannot be told from the bias.
    let held = variant("held.csv", |lines| {
        let temp = lines[0].split(',').position(|c| c == "temp").unwrap();
        for l in lines.iter_mut().skip(1) {
            let mut cells: Vec<&str> = l.split(',').collect();
            cells[temp] = "25.0";
            *l = cells.join(",");
        }
    });
    vec![
        fit_refusal(
            "unknown effect lists the valid ones",
            &r,
            &["--effects", "gg_XY"],
            &["unknown effect 'gg_XY'", "gg_IS", "col:NAME"],
        ),
        fit_refusal(
            "unknown channel lists the valid ones",
            &r,
            &["--add-effect", "Q1=g_I"],
            &["unknown channel 'Q1'", "X, X1, Y, Y1, Z, Z1"],
        ),
        fit_refusal(
            "a constant effect is named, not numbered",
            &held,
            &["--add-effect", "Y1=col:temp"],
            &["channel Y1", "col:temp", "does not vary"],
        ),
        // On a shaker the rate is Earth rate plus gyro noise: rate products would
        // fit the gyros' own errors (validation rms 1.23 → 0.21 deg/h on X before
        // this was refused, far below the simulated floor).
        fit_refusal(
            "anisoinertia on a stationary test",
            &r,
            &["--add-effect", "X=ai_IO"],
            &["channel X", "ai_IO", "varying angular rate"],
        ),
        // Under Z-axis vibration X's six g² regressors are not independent.
        fit_refusal(
            "collinear effects are named, not numbered",
            &r,
            &["--effects", "gg_II,gg_OO,gg_SS,gg_IO,gg_IS,gg_OS"],
            &[
                "linear combination of the bias and gg_II",
                "cannot tell them apart",
            ],
        ),
    ]
}

/// Flags clap refuses (exit 2), on one line too, with the flag and its
/// valid range: usage errors and number-shaped hostile values (which used
/// to hang selection with NaN scores, or save models of NaN).
fn bad_flags() -> Vec<Refusal> {
    let r = record();
    let fit = |args: &[&str], says: &[&str]| {
        let mut all = vec!["fit", "--data", r.as_str()];
        all.extend_from_slice(args);
        all.extend(["--out", "/dev/null"]);
        refusal("a flag clap refuses", 2, &all, says)
    };
    vec![
        // A negative cut-off is a value, refused with the flag and the valid range.
        fit(
            &["--cutoff", "-1"],
            &["'-1'", "--cutoff", "positive frequency"],
        ),
        fit(&["--table-rate", "1,2"], &["--table-rate", "WX,WY,WZ"]),
        fit(&["--window", "ten"], &["'ten'", "--window"]),
        fit(&["--cutoff", "3", "--no-filter"], &["--no-filter"]),
        fit(
            &["--table-rate", "1e200,0,0"],
            &["--table-rate", "±10000 deg/s"],
        ),
        fit(
            &["--table-rate", "1e160,0,0"],
            &["--table-rate", "±10000 deg/s"],
        ),
        fit(
            &["--table-rate", "nan,0,0"],
            &["--table-rate", "±10000 deg/s"],
        ),
        fit(&["--earth-rate", "91"], &["--earth-rate", "from -90 to 90"]),
        fit(
            &["--earth-rate", "NaN"],
            &["--earth-rate", "from -90 to 90"],
        ),
        refusal(
            "a misspelt flag",
            2,
            &["diagnose", "--modle", "m.json"],
            &["--modle"],
        ),
        refusal(
            "missing flags, all named",
            2,
            &["compensate", "--data", &r],
            &["not provided: --model <MODEL>; --out <OUT>"],
        ),
    ]
}

/// Models that are not what they claim: a file of another kind, and a
/// filter cut-off edited to 1e-9 Hz (diagnose used to try to allocate 32 TB
/// and abort).
fn bad_models() -> Vec<Refusal> {
    let corrupt = dir().join("corrupt.json");
    std::fs::write(&corrupt, "{\"kind\": \"something else\"}").unwrap();
    let text = std::fs::read_to_string(model()).unwrap();
    assert!(text.contains("\"cutoff_hz\": 5.0"));
    let edited = dir().join("cutoff-edited.json");
    std::fs::write(
        &edited,
        text.replacen("\"cutoff_hz\": 5.0", "\"cutoff_hz\": 1e-9", 1),
    )
    .unwrap();
    let r = record();
    vec![
        refusal(
            "a file that is no model",
            1,
            &[
                "diagnose",
                "--model",
                corrupt.to_str().unwrap(),
                "--data",
                &r,
            ],
            &["not a dtg-vib model file"],
        ),
        refusal(
            "a model with an absurd cut-off",
            1,
            &[
                "diagnose",
                "--model",
                edited.to_str().unwrap(),
                "--data",
                &r,
            ],
            &["0.005 Hz"],
        ),
    ]
}

/// Physical ranges of a scenario are checked before anything is simulated
/// (these used to write records of NaN with exit 0).
fn bad_scenarios() -> Vec<Refusal> {
    let text = std::fs::read_to_string(sim().join("scenario.toml")).unwrap();
    let cases = [
        (
            "latitude_deg = 8.5",
            "latitude_deg = 91.0",
            "from -90 to 90",
        ),
        ("latitude_deg = 8.5", "latitude_deg = nan", "from -90 to 90"),
        ("gain_db = 0.0", "gain_db = nan", "must be finite"),
        ("[350.0, 0.04]", "[350.0, 1e300]", "at most 1000 g"),
    ];
    let mut refusals = Vec::new();
    for (k, (from, to, needle)) in cases.iter().enumerate() {
        assert!(text.contains(from), "{from} not in the demo scenario");
        let bad = dir().join(format!("bad-scenario-{k}.toml"));
        std::fs::write(&bad, text.replacen(from, to, 1)).unwrap();
        let out = dir().join(format!("bad-scenario-{k}"));
        let (b, o) = (bad.to_str().unwrap(), out.to_str().unwrap());
        refusals.push(Refusal {
            writes_nothing_at: Some(out.join("record.csv")),
            ..refusal(
                "a scenario out of physical range",
                1,
                &["simulate", "--scenario", b, "--out", o],
                &[*needle, b],
            )
        });
    }
    refusals
}

/// A scenario that is not TOML: the parse error's position, and its excerpt
/// on one line with each line trimmed at its ends (it read "…;   |; 1 |
/// seed = ;   |        ^; …", as rbf's errors no longer do).
fn bad_toml() -> Vec<Refusal> {
    let bad = dir().join("not-toml.toml");
    std::fs::write(&bad, "seed = \n").unwrap();
    let out = dir().join("not-toml");
    let (b, o) = (bad.to_str().unwrap(), out.to_str().unwrap());
    vec![Refusal {
        writes_nothing_at: Some(out.join("record.csv")),
        ..refusal(
            "a scenario that is not TOML",
            1,
            &["simulate", "--scenario", b, "--out", o],
            &[b, "line 1, column 8; |; 1 | seed =; |", "^; string values"],
        )
    }]
}

/// What `explain` cannot do, said with why: records given twice (also to
/// `diagnose`), `--cv`, a by-record split of one record; no model written.
fn explain_refusals() -> Vec<Refusal> {
    let r = record();
    let out = dir().join("explain-refused.json");
    let o = out.to_str().unwrap();
    let cases = [
        refusal(
            "explain: a record given twice",
            1,
            &["explain", "--data", &r, "--data", &r, "--out", o],
            &["is the same file as", "give each record once"],
        ),
        refusal(
            "diagnose: a record given twice",
            1,
            &["diagnose", "--model", o, "--data", &r, "--data", &r],
            &["give each record once"],
        ),
        refusal(
            "explain does not take --cv",
            1,
            &["explain", "--data", &r, "--cv", "records", "--out", o],
            &["does not take --cv", "fit --cv records"],
        ),
        // A by-record split needs a second record to train on.
        refusal(
            "explain: a by-record split of one record",
            1,
            &[
                "explain",
                "--data",
                &r,
                "--split",
                "by-record",
                "--validate-on",
                &r,
                "--out",
                o,
            ],
            &["cannot both train and validate"],
        ),
    ];
    cases
        .into_iter()
        .map(|c| Refusal {
            writes_nothing_at: Some(out.clone()),
            ..c
        })
        .collect()
}

/// Every bad input is one `error:` line with the exit status it should
/// have, naming what is wrong and where (file:line:column, or the flag with
/// its valid range), never a panic.
#[test]
fn bad_inputs_are_refused_in_one_line() {
    let r = record();
    let mut cases = Vec::new();
    cases.extend(bad_records());
    cases.extend(bad_effects());
    cases.extend(bad_flags());
    cases.extend(bad_models());
    cases.extend(bad_scenarios());
    cases.extend(bad_toml());
    cases.extend(explain_refusals());
    cases.push(refusal(
        "allan --report on an input",
        1,
        &["allan", "--data", &r, "--report", &r],
        &["--report"],
    ));
    let broken = broken(&cases);
    assert!(
        broken.is_empty(),
        "{} of {} refusals broke the contract:\n{}",
        broken.len(),
        cases.len(),
        broken.join("\n")
    );
}

#[test]
fn fit_json_has_the_contract_keys() {
    let calib = sim().join("calibration.json").display().to_string();
    let out = dir().join("json-model.json").display().to_string();
    let text = ok(&[
        "fit",
        "--data",
        &record(),
        "--calib",
        &calib,
        "--add-effect",
        "Y1=col:temp",
        "--max-centers",
        "10",
        "--out",
        &out,
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(text.trim()).expect("one JSON object");
    let channels = v["channels"].as_array().unwrap();
    assert_eq!(channels.len(), 6);
    for (c, name) in channels.iter().zip(["X", "X1", "Y", "Y1", "Z", "Z1"]) {
        assert_eq!(c["channel"], name);
        for key in ["effects", "n_centers", "train_rms", "val_rms"] {
            assert!(!c[key].is_null(), "{key} missing in {c}");
        }
        let val = c["val_rms"].as_f64().unwrap();
        assert!(val > 0.0 && val < 10.0, "{val}");
    }
    assert_eq!(channels[3]["effects"], serde_json::json!(["col:temp"]));
    assert_eq!(channels[0]["effects"], serde_json::json!([]));
}

/// The line `fit` (and `explain`'s final table) prints for each effect of
/// the model file `model` (JSON): id, coefficient ± standard error, unit and
/// the stored 95% interval; one entry per channel, `None` without effects.
fn coefficient_cells(model: &serde_json::Value) -> Vec<Option<String>> {
    model["model"]["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let cells: Vec<String> = c["effects"]
                .as_array()
                .unwrap()
                .iter()
                .zip(c["coefficients"].as_array()?)
                .map(|(id, k)| {
                    let f = |v: &serde_json::Value| format!("{:.4}", v.as_f64().unwrap());
                    format!(
                        "{} {} ± {} {} ({} to {})",
                        id.as_str().unwrap(),
                        f(&k["value"]),
                        f(&k["se"]),
                        k["unit"].as_str().unwrap(),
                        f(&k["ci95"][0]),
                        f(&k["ci95"][1])
                    )
                })
                .collect();
            (!cells.is_empty()).then(|| cells.join(", "))
        })
        .collect()
}

/// `fit`'s table gives each effect's coefficient with its standard error
/// and the 95% interval the model file stores (it used to stop at ± SE).
#[test]
fn fit_prints_each_coefficient_with_its_interval() {
    let (out, text) = fitted_model();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("unit: paper: "), "{}", lines[0]);
    let lines = &lines[1..];
    assert_eq!(
        lines[0],
        "channel  centres  train rms  val rms  (deg/h)  effects (coefficient ± standard error, 95% CI)"
    );
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(out).unwrap()).unwrap();
    let cells = coefficient_cells(&m);
    assert!(
        cells
            .iter()
            .all(|c| c.as_deref().unwrap().starts_with("col:temp "))
    );
    for (line, cell) in lines[1..7].iter().zip(&cells) {
        match cell {
            Some(cell) => assert!(line.ends_with(&format!("  {cell}")), "{line} / {cell}"),
            None => assert!(line.ends_with("  —"), "{line}"),
        }
    }
}

/// `diagnose` says under its findings what their terms mean, each once and
/// only where it was printed: the candidates not ranked (anisoinertia, and
/// what would excite it), every failing correlation test in words (a name
/// like billings_voon_u2_e:ax said nothing), a negative fit (worse than the
/// mean), and the findings' own words. The tri-axial record with hidden
/// effects and a small model has all of them.
#[test]
fn diagnose_says_what_its_terms_mean() {
    let tri = dir().join("tri");
    ok(&[
        "simulate",
        "--builtin",
        "triaxial_hidden",
        "--out",
        tri.to_str().unwrap(),
    ]);
    let (rec, calib, m) = (
        tri.join("record.csv").display().to_string(),
        tri.join("calibration.json").display().to_string(),
        dir().join("tri.json").display().to_string(),
    );
    ok(&[
        "fit",
        "--data",
        &rec,
        "--calib",
        &calib,
        "--max-centers",
        "10",
        "--out",
        &m,
    ]);
    let args = ["diagnose", "--model", m.as_str(), "--data", rec.as_str()];
    let v: serde_json::Value =
        serde_json::from_str(&ok(&[&args[..], &["--json"]].concat())).unwrap();
    let text = ok(&args);
    let lines: Vec<&str> = text.lines().collect();
    let at = lines
        .iter()
        .position(|l| *l == "terms used above:")
        .unwrap_or_else(|| panic!("no terms:\n{text}"));
    let legend = &lines[at + 1..];
    assert!(legend.iter().all(|l| l.starts_with("  ")), "{text}");
    let mut unique = legend.to_vec();
    unique.dedup();
    assert_eq!(unique.len(), legend.len(), "a term said twice: {text}");
    let says = |start: &str| legend.iter().find(|l| l[2..].starts_with(start)).copied();
    let channels = v["channels"].as_array().unwrap();
    let (mut failing, mut negative, mut findings) = (vec![], vec![], String::new());
    for c in channels {
        for u in c["unexcited"].as_array().unwrap() {
            let id = u["effect"].as_str().unwrap();
            let l = legend
                .iter()
                .find(|l| l.contains(id))
                .unwrap_or_else(|| panic!("{id} not explained: {text}"));
            if id.starts_with("ai_") {
                assert!(
                    l.contains("anisoinertia") && l.contains("excites them"),
                    "{l}"
                );
            }
        }
        for f in c["failing"].as_array().unwrap() {
            failing.push(f.as_str().unwrap());
        }
        if c["compare"]["val_fit_percent"].as_f64().unwrap() < 0.0 {
            negative.push(c["channel"].as_str().unwrap());
        }
        for f in c["findings"].as_array().unwrap() {
            findings.push_str(f.as_str().unwrap());
        }
    }
    assert!(failing.contains(&"billings_voon_u2_e:ax"), "{failing:?}");
    for name in &failing {
        assert!(says(&format!("{name}: ")).is_some(), "{name}: {text}");
    }
    assert_eq!(
        says("billings_voon_u2_e:ax: "),
        Some(
            "  billings_voon_u2_e:ax: Billings–Voon test, the residual against ax²: an even function of ax (a g² term) is left"
        )
    );
    assert!(!negative.is_empty(), "{text}");
    let fit = says("fit % = ").unwrap_or_else(|| panic!("no negative fit line: {text}"));
    assert!(
        fit.contains(&format!("below 0 on {}:", negative.join(", ")))
            && fit.ends_with("worse than the mean"),
        "{fit}"
    );
    for (word, start) in [
        ("cross-fitted", "cross-fitted residual: "),
        ("|r|", "|r|: "),
        ("σ)", "(Nσ): "),
        ("white floor", "white floor: "),
    ] {
        assert_eq!(
            findings.contains(word),
            says(start).is_some(),
            "{word}: {text}"
        );
    }
}

#[test]
fn residues_columns_without_and_with_a_model() {
    let out = dir().join("res.csv");
    ok(&[
        "residues",
        "--data",
        &record(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().next().unwrap(), "t,K0,K1,K2,K3,K4,K5");
    assert_eq!(text.lines().count(), 5001);
    let out2 = dir().join("res2.csv");
    let printed = ok(&[
        "residues",
        "--data",
        &record(),
        "--model",
        model(),
        "--out",
        out2.to_str().unwrap(),
    ]);
    let header = std::fs::read_to_string(&out2)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_string();
    assert!(
        header.starts_with("t,K0,K1,K2,K3,K4,K5,K0_pre,"),
        "{header}"
    );
    assert!(
        header.ends_with(",K5_comp,K0_out,K1_out,K2_out,K3_out,K4_out,K5_out"),
        "{header}"
    );
    assert!(
        printed.contains("  change\n") && printed.contains("\n pooled "),
        "{printed}"
    );
}

#[test]
fn compensate_writes_the_record_format() {
    let out = dir().join("comp.csv");
    ok(&[
        "compensate",
        "--model",
        model(),
        "--data",
        &record(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        text.lines().next().unwrap(),
        "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp"
    );
    // The first 49 samples have no full 50-sample window.
    assert_eq!(text.lines().count(), 1 + 5000 - 49);
}

/// `diagnose --json` of `model` on the record.
fn diagnosis(model: &str) -> serde_json::Value {
    let text = ok(&["diagnose", "--model", model, "--data", &record(), "--json"]);
    serde_json::from_str(text.trim()).expect("one JSON object")
}

#[test]
fn diagnose_json_has_the_contract_keys() {
    let v = diagnosis(model());
    // Without a rate reference no rate family is said observable.
    assert!(v.get("observable").is_none(), "{}", v["observable"]);
    let channels = v["channels"].as_array().unwrap();
    assert_eq!(channels.len(), 6);
    for c in channels {
        assert!(c["channel"].is_string() && c["rms"].is_f64() && c["suggested"].is_array());
        let cands = c["candidates"].as_array().unwrap();
        assert!(!cands.is_empty());
        for k in cands {
            for key in ["effect", "err", "coef", "description"] {
                assert!(!k[key].is_null(), "{key} missing in {k}");
            }
        }
        let errs: Vec<f64> = cands.iter().map(|k| k["err"].as_f64().unwrap()).collect();
        assert!(
            errs.windows(2).all(|w| w[0] >= w[1]),
            "candidates not sorted by err: {errs:?}"
        );
        // col:temp is in the model already, so it is no candidate.
        assert!(cands.iter().all(|k| k["effect"] != "col:temp"));
    }
}

#[test]
fn a_hand_edited_model_that_disagrees_with_itself_is_refused() {
    let text = std::fs::read_to_string(model()).unwrap();
    // (file name, the edit, what the error must say)
    type Edit = (&'static str, fn(&mut serde_json::Value), &'static str);
    let edits: [Edit; 4] = [
        (
            "window-length",
            // The raw window's length: a statistics input's dimension
            // does not depend on it, so the edit names the raw input too.
            |m| {
                m["model"]["preprocess"]["window"]["length"] = 10.into();
                m["model"]["preprocess"]["input"] = "raw".into();
            },
            "the raw input of a window of 10 samples",
        ),
        (
            "window-zero",
            |m| m["model"]["preprocess"]["window"]["length"] = 0.into(),
            "at least one sample",
        ),
        (
            "window-signals",
            |m| m["model"]["preprocess"]["window"]["signals"] = serde_json::json!(["ax", "az"]),
            "× 2 signals",
        ),
        (
            "rbf-dim",
            |m| m["model"]["channels"][2]["rbf"]["dim"] = 7.into(),
            "channel Y",
        ),
    ];
    for (name, edit, want) in edits {
        let mut m: serde_json::Value = serde_json::from_str(&text).unwrap();
        edit(&mut m);
        let p = dir().join(format!("edited-{name}.json"));
        std::fs::write(&p, m.to_string()).unwrap();
        for cmd in ["compensate", "diagnose"] {
            let mut args = vec![cmd, "--model", p.to_str().unwrap(), "--data"];
            let rec = record();
            args.push(&rec);
            if cmd == "compensate" {
                args.extend(["--out", "/dev/null"]);
            }
            let err = fails(&args);
            assert!(
                err.contains("not a dtg-vib model file") && err.contains(want),
                "{name} {cmd}: {err}"
            );
        }
    }
}

#[test]
fn table_rate_takes_the_documented_comma_form() {
    // docs/dtg-vib.md: `--table-rate WX,WY,WZ` (deg/s).
    let m = fitted("table-rate.json", &["--table-rate", "0,0,0.01"]);
    assert_eq!(
        m["model"]["preprocess"]["rate_reference"]["rate_deg_s"],
        serde_json::json!([0.0, 0.0, 0.01])
    );
    // Against the table rate the diagnosis says each gyro's own rate terms
    // are observable (issue 34 §2); in parity it says only their
    // differences are (tests/flight.rs); without a reference it says
    // nothing (diagnose_json_has_the_contract_keys).
    let d = diagnosis(dir().join("table-rate.json").to_str().unwrap());
    let lines = d["observable"].as_array().expect("an observable list");
    assert_eq!(lines.len(), 3, "one line per family: {lines:?}");
    let sf = lines[0].as_str().unwrap();
    assert!(
        sf.starts_with("sf, sf@k (scale-factor error): against the rate reference each gyro's own is observable"),
        "{sf}"
    );
    assert!(!sf.contains("differences between gyros"), "{sf}");
}

#[test]
fn negative_numbers_are_values_not_flags() {
    // A southern site and a table turning backwards are ordinary tests.
    let m = fitted("south.json", &["--earth-rate", "-33.9"]);
    assert_eq!(
        m["model"]["preprocess"]["rate_reference"]["site"]["latitude_deg"],
        serde_json::json!(-33.9)
    );
    let m = fitted("backwards.json", &["--table-rate", "-0.01,0,0"]);
    assert_eq!(
        m["model"]["preprocess"]["rate_reference"]["rate_deg_s"],
        serde_json::json!([-0.01, 0.0, 0.0])
    );
}

#[test]
fn a_record_too_short_to_split_is_still_compensated() {
    // 150 samples: 101 full windows, too few for the model's blocked split,
    // which compensation does not need.
    let short = variant("short150.csv", |l| l.truncate(151));
    let out = dir().join("comp-short.csv");
    ok(&[
        "compensate",
        "--model",
        model(),
        "--data",
        &short,
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().count(), 1 + 150 - 49);
    let res = dir().join("res-short.csv");
    ok(&[
        "residues",
        "--data",
        &short,
        "--model",
        model(),
        "--out",
        res.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read_to_string(&res).unwrap().lines().count(),
        1 + 150 - 49
    );
}

/// `--out` naming an input is refused before any work, naming both flags, and
/// the input is byte-identical afterwards; so is a missing output directory.
#[test]
fn outputs_never_overwrite_inputs() {
    let s = sim();
    let data = s.join("record.csv");
    let calib = s.join("calibration.json");
    let model = dir().join("guard-model.json");
    ok(&[
        "fit",
        "--data",
        data.to_str().unwrap(),
        "--calib",
        calib.to_str().unwrap(),
        "--max-centers",
        "5",
        "--out",
        model.to_str().unwrap(),
    ]);
    let before: Vec<Vec<u8>> = [&data, &calib, &model]
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    // The same file spelled differently is still the same file.
    let data_alias = s.join(".").join("record.csv");
    let (d, c, m, a) = (
        data.to_str().unwrap(),
        calib.to_str().unwrap(),
        model.to_str().unwrap(),
        data_alias.to_str().unwrap(),
    );
    let cases: [(&[&str], &str); 6] = [
        (&["fit", "--data", d, "--calib", c, "--out", a], "--data"),
        (&["fit", "--data", d, "--calib", c, "--out", c], "--calib"),
        (
            &["compensate", "--model", m, "--data", d, "--out", d],
            "--data",
        ),
        (
            &["compensate", "--model", m, "--data", d, "--out", m],
            "--model",
        ),
        (
            &["residues", "--data", d, "--model", m, "--out", m],
            "--model",
        ),
        (&["residues", "--data", d, "--out", a], "--data"),
    ];
    for (args, flag) in cases {
        let err = fails(args);
        assert!(
            err.contains("--out") && err.contains(&format!("same file as {flag}")),
            "{args:?}: {err}"
        );
    }
    let after: Vec<Vec<u8>> = [&data, &calib, &model]
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    assert!(before == after, "an input changed");
    // simulate --scenario S --out DIR where DIR/scenario.toml is S.
    let scen = s.join("scenario.toml");
    let scen_before = std::fs::read(&scen).unwrap();
    let err = fails(&[
        "simulate",
        "--scenario",
        scen.to_str().unwrap(),
        "--out",
        s.to_str().unwrap(),
    ]);
    assert!(err.contains("--scenario"), "{err}");
    assert_eq!(std::fs::read(&scen).unwrap(), scen_before);
    // A directory that does not exist: said before any work.
    let missing = dir().join("no-such-dir").join("m.json");
    let err = fails(&["fit", "--data", d, "--out", missing.to_str().unwrap()]);
    assert!(err.contains("does not exist"), "{err}");
}

#[test]
fn allan_json_has_the_contract_keys_and_after_is_what_compensate_writes() {
    let json = |args: &[&str]| -> serde_json::Value {
        serde_json::from_str(&ok(args)).expect("one JSON object on stdout")
    };
    let plain = json(&["allan", "--data", &record(), "--json"]);
    let with = json(&["allan", "--data", &record(), "--model", model(), "--json"]);
    for (j, after) in [(&plain, false), (&with, true)] {
        let channels = j["channels"].as_array().unwrap();
        let names: Vec<&str> = channels
            .iter()
            .map(|c| c["channel"].as_str().unwrap())
            .collect();
        assert_eq!(names, ["X", "X1", "Y", "Y1", "Z", "Z1"]);
        assert_eq!(j["residues"].as_array().unwrap().len(), 6);
        for c in channels {
            let n = c["tau_s"].as_array().unwrap().len();
            assert_eq!(c["adev_before"].as_array().unwrap().len(), n);
            assert_eq!(c.get("adev_after").is_some(), after);
            for key in ["arw_deg_per_sqrt_h", "bias_instability_deg_per_h"] {
                let v = &c[key];
                assert!(v["before"].is_number() || v["before"].is_null(), "{v}");
                assert_eq!(v.get("after").is_some(), after, "{key}");
            }
        }
    }
    // 5000 samples from sample 0, or 4951 from the first full 50-sample
    // window: m = 1 … 256 (up to a tenth of the record), τ = 0.02 … 5.12 s.
    assert_eq!(
        (plain["samples"].as_u64(), plain["first_sample"].as_u64()),
        (Some(5000), Some(0))
    );
    assert_eq!(
        (with["samples"].as_u64(), with["first_sample"].as_u64()),
        (Some(4951), Some(49))
    );
    for j in [&plain, &with] {
        let tau = j["channels"][0]["tau_s"].as_array().unwrap();
        assert_eq!((tau.len(), tau[8].as_f64()), (9, Some(5.12)));
    }

    // "after" is the Allan deviation of what `compensate` writes.
    let comp = dir().join("allan-comp.csv");
    ok(&[
        "compensate",
        "--model",
        model(),
        "--data",
        &record(),
        "--out",
        comp.to_str().unwrap(),
    ]);
    let rec = nav_sensors::record::Record::read_csv(&comp).unwrap();
    let y1 = rec
        .gyro_named(nav_sensors::geometry::Channel::Y1.name())
        .unwrap();
    let factors: Vec<usize> = (0..9).map(|k| 1 << k).collect();
    let expected = nav_sensors::noise::overlapping_adev(y1, 0.02, &factors).unwrap();
    let got = with["channels"][3]["adev_after"].as_array().unwrap();
    for (g, e) in got.iter().zip(&expected) {
        assert!((g.as_f64().unwrap() / e - 1.0).abs() < 1e-12, "{g} vs {e}");
    }
}

/// `allan` says why it starts at a later sample with a model (its first
/// full window, so before and after cover the same samples) and names the
/// noise terms in words; "not resolved" is said once under the tables.
#[test]
fn allan_says_where_it_starts_and_what_its_terms_are() {
    let with = ok(&["allan", "--data", &record(), "--model", model()]);
    let first = with.lines().next().unwrap();
    assert!(
        first.contains(": 4951 samples from sample 49 (the first with a full window of the model: before and after cover the same samples), τ = "),
        "{first}"
    );
    let plain = ok(&["allan", "--data", &record()]);
    let first = plain.lines().next().unwrap();
    assert!(
        first.contains(": 5000 samples from sample 0, τ = "),
        "{first}"
    );
    for text in [&with, &plain] {
        for head in [
            "angle random walk (deg/√h)  before",
            "bias instability (deg/h)    before",
            "rate random walk (deg/h/√h) before",
        ] {
            assert_eq!(
                text.lines().filter(|l| l.starts_with(head)).count(),
                1,
                "{text}"
            );
        }
        let (explained, unresolved): (Vec<&str>, Vec<&str>) = text
            .lines()
            .filter(|l| l.contains("(not resolved)"))
            .partition(|l| l.starts_with("< bound (not resolved): "));
        assert_eq!(
            explained.len(),
            usize::from(!unresolved.is_empty()),
            "{text}"
        );
    }
}

#[test]
fn allan_report_writes_its_figures() {
    let report = dir().join("allan-report");
    std::fs::create_dir_all(&report).unwrap();
    let out = ok(&[
        "allan",
        "--data",
        &record(),
        "--model",
        model(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert!(out.contains("angle random walk (deg/√h)"), "{out}");
    for f in [
        "index.html",
        "allan_channels.png",
        "allan_channels.svg",
        "allan_residues.png",
        "allan_residues.svg",
    ] {
        assert!(report.join(f).is_file(), "{f} missing");
    }
}

#[test]
fn simulate_lists_every_file_it_writes() {
    let d = dir().join("sim-listed");
    let printed = ok(&[
        "simulate",
        "--builtin",
        "demo",
        "--out",
        d.to_str().unwrap(),
    ]);
    let wrote: Vec<&str> = printed
        .lines()
        .filter_map(|l| l.strip_prefix("wrote "))
        .collect();
    let on_disk = std::fs::read_dir(&d).unwrap().count();
    assert_eq!(wrote.len(), on_disk, "{printed}");
    for f in wrote {
        assert!(Path::new(f).is_file(), "{f}");
    }
}

#[test]
fn report_with_a_baseline_prints_each_channel_before_and_after() {
    let out = dir().join("report-baseline");
    let printed = ok(&[
        "report",
        "--model",
        model(),
        "--baseline",
        model(),
        "--data",
        &record(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(printed.contains("val rms baseline"), "{printed}");
    for ch in ["X", "X1", "Y", "Y1", "Z", "Z1"] {
        assert!(
            printed
                .lines()
                .any(|l| l.trim_start().starts_with(&format!("{ch} ")) && l.ends_with("+0.0%")),
            "{ch}: {printed}"
        );
    }
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("SHA-256") && html.contains("baseline model"));
}

#[test]
fn compensate_says_which_rate_reference_it_removes() {
    let out = dir().join("comp-ref.csv");
    let o = run(&[
        "compensate",
        "--model",
        model(),
        "--data",
        &record(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("rate reference removed: no rate reference") && err.contains("--earth-rate"),
        "{err}"
    );
}

/// Columns of the pseudo-terminal the terminal tests run on.
const COLUMNS: usize = 100;

/// Runs `dtg-vib ARGS…` on a pseudo-terminal (util-linux `script`) of
/// [`COLUMNS`] columns, as a user at a terminal would see it: stdout and
/// stderr together, the spinner drawn. `None` where `script` is absent.
fn on_terminal(args: &[&str]) -> Option<String> {
    let quote = |s: &str| format!("'{}'", s.replace('\'', r"'\''"));
    // script's terminal has no size of its own; give it one, so that lines
    // padded to the width wrap where a user's terminal would wrap them.
    let mut cmd = format!("stty cols {COLUMNS} rows 50; exec ");
    cmd.push_str(&quote(env!("CARGO_BIN_EXE_dtg-vib")));
    for a in args {
        cmd.push(' ');
        cmd.push_str(&quote(a));
    }
    let out = Command::new("script")
        .args(["-qec", &cmd, "/dev/null"])
        .env("TERM", "xterm")
        .output()
        .ok()?;
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    Some(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The lines a terminal of [`COLUMNS`] columns shows once `raw` is drawn:
/// a carriage return goes back to the start of the line, a line feed down
/// one, a character past the last column wraps to the next line, `ESC [ 2K`
/// clears the line, `ESC [ n A` moves up n lines, `ESC [ J` clears below;
/// other escape sequences draw nothing. Trailing blanks and blank lines at
/// the end are dropped.
fn screen_lines(raw: &str) -> Vec<String> {
    let mut screen: Vec<Vec<char>> = vec![Vec::new()];
    let (mut row, mut col) = (0usize, 0usize);
    let mut chars = raw.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\r' => col = 0,
            '\n' => row += 1,
            '\x1b' => {
                // CSI: ESC [ parameters… final byte in @..~
                if chars.peek() != Some(&'[') {
                    chars.next();
                    continue;
                }
                chars.next();
                let mut params = String::new();
                let mut last = ' ';
                for d in chars.by_ref() {
                    if ('@'..='~').contains(&d) {
                        last = d;
                        break;
                    }
                    params.push(d);
                }
                let n: usize = params.parse().unwrap_or(1);
                match last {
                    'K' => {
                        if let Some(line) = screen.get_mut(row) {
                            // 2K: the whole line; K, 0K: from the cursor on.
                            line.truncate(if params == "2" { 0 } else { col });
                        }
                    }
                    'A' => row = row.saturating_sub(n),
                    'J' => {
                        screen.truncate(row + 1);
                        if let Some(line) = screen.get_mut(row) {
                            line.truncate(col);
                        }
                    }
                    _ => {}
                }
            }
            c => {
                if col == COLUMNS {
                    row += 1;
                    col = 0;
                }
                while screen.len() <= row {
                    screen.push(Vec::new());
                }
                let line = &mut screen[row];
                while line.len() <= col {
                    line.push(' ');
                }
                line[col] = c;
                col += 1;
            }
        }
        while screen.len() <= row {
            screen.push(Vec::new());
        }
    }
    let mut lines: Vec<String> = screen
        .iter()
        .map(|l| l.iter().collect::<String>().trim_end().to_string())
        .collect();
    while lines.last().is_some_and(String::is_empty) {
        lines.pop();
    }
    lines
}

/// The spinner's glyphs (indicatif's default tick strings are braille).
fn has_spinner(line: &str) -> bool {
    line.chars().any(|c| ('\u{2800}'..='\u{28ff}').contains(&c))
}

#[test]
fn no_spinner_is_left_on_a_terminal() {
    let Some(raw) = on_terminal(&["allan", "--data", &record(), "--model", model()]) else {
        eprintln!("notice: util-linux `script` not found, the terminal check is skipped");
        return;
    };
    let lines = screen_lines(&raw);
    assert!(
        lines[0].starts_with("Overlapping Allan deviation"),
        "first line: {:?}",
        lines[0]
    );
    assert!(!lines.iter().any(|l| has_spinner(l)), "{lines:#?}");
    // fit prints its note on stderr after the spinner is gone too.
    let out = dir().join("terminal-fit.json").display().to_string();
    let raw = on_terminal(&[
        "fit",
        "--data",
        &record(),
        "--max-centers",
        "5",
        "--out",
        &out,
    ])
    .expect("script ran once");
    let lines = screen_lines(&raw);
    assert!(!lines.iter().any(|l| has_spinner(l)), "{lines:#?}");
    assert!(
        lines[0].starts_with("unit: paper") || lines[0].starts_with("note:"),
        "{lines:#?}"
    );
}

/// `explain` over several records takes tens of seconds: on a terminal it
/// leaves a line per round and per channel fitted, and one when it
/// diagnoses, above its results; the spinner is gone at the end, and with
/// `--quiet` there are no such lines.
#[test]
fn explain_shows_each_round_and_channel_on_a_terminal() {
    let out = dir().join("terminal-explain.json").display().to_string();
    let args = [
        "explain",
        "--data",
        &record(),
        "--max-rounds",
        "1",
        "--max-centres",
        "5",
        "--out",
        &out,
    ];
    let Some(raw) = on_terminal(&args) else {
        eprintln!("notice: util-linux `script` not found, the terminal check is skipped");
        return;
    };
    let lines = screen_lines(&raw);
    assert!(!lines.iter().any(|l| has_spinner(l)), "{lines:#?}");
    // Each progress line: seconds since the start, then the step.
    let step = |l: &str| -> Option<String> {
        let (secs, rest) = l.trim_start().split_once(" s  ")?;
        secs.parse::<f64>().ok()?;
        Some(rest.to_string())
    };
    let steps: Vec<String> = lines.iter().filter_map(|l| step(l)).collect();
    assert_eq!(
        steps.first().map(String::as_str),
        Some("round 1: fitting the 6 channels"),
        "{lines:#?}"
    );
    for ch in ["X", "X1", "Y", "Y1", "Z", "Z1"] {
        assert_eq!(
            steps
                .iter()
                .filter(|s| s.starts_with(&format!("round 1: {ch} fitted (")))
                .count(),
            1,
            "{ch}: {lines:#?}"
        );
    }
    assert!(
        steps.iter().any(|s| s.ends_with("fitted (6 of 6)")),
        "{lines:#?}"
    );
    assert_eq!(
        steps.last().map(String::as_str),
        Some("round 1: diagnosing (the model's mirror, then every candidate effect)"),
        "{lines:#?}"
    );
    // The steps come first, then the results (the unit, then each round)
    // as without a terminal.
    let first_result = lines
        .iter()
        .position(|l| l.starts_with("unit: paper"))
        .expect("results");
    assert_eq!(first_result, steps.len(), "{lines:#?}");
    assert_eq!(lines[first_result + 1], "round 1:", "{lines:#?}");
    // --quiet: the results alone.
    let quiet: Vec<&str> = args.iter().copied().chain(["--quiet"]).collect();
    let lines = screen_lines(&on_terminal(&quiet).expect("script ran once"));
    assert!(lines[0].starts_with("unit: paper"), "{lines:#?}");
    assert_eq!(lines[1], "round 1:", "{lines:#?}");
    assert!(!lines.iter().any(|l| step(l).is_some()), "{lines:#?}");
}

/// `export --lang text --out DIR` writes what `--lang text` prints into
/// DIR/equations.txt and says where (it used to print and ignore `--out`),
/// never over the model it reads.
#[test]
fn export_text_with_out_writes_the_equations_there() {
    let printed = ok(&["export", "--model", model(), "--lang", "text"]);
    assert!(printed.contains("deg/h"), "{printed}");
    let out = dir().join("export-text");
    let said = ok(&[
        "export",
        "--model",
        model(),
        "--lang",
        "text",
        "--out",
        out.to_str().unwrap(),
    ]);
    let file = out.join("equations.txt");
    assert_eq!(said, format!("wrote {}\n", file.display()));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), printed);
    // A model that is DIR/equations.txt is refused as the output.
    let inside = dir().join("export-inside");
    std::fs::create_dir_all(&inside).unwrap();
    let m = inside.join("equations.txt");
    std::fs::copy(model(), &m).unwrap();
    let before = std::fs::read(&m).unwrap();
    let err = fails(&[
        "export",
        "--model",
        m.to_str().unwrap(),
        "--lang",
        "text",
        "--out",
        inside.to_str().unwrap(),
    ]);
    assert!(
        err.contains("--out") && err.contains("same file as --model"),
        "{err}"
    );
    assert_eq!(std::fs::read(&m).unwrap(), before);
}

/// `--centres` and `--max-centres` are the flags; `--centers` and
/// `--max-centers` (the spelling of earlier releases) stay as aliases that
/// fit the same model.
#[test]
fn centre_flags_and_their_aliases_fit_the_same_model() {
    let primary = fit_bytes(
        "centres.json",
        &["--centres", "kmeans", "--max-centres", "5"],
    );
    let alias = fit_bytes(
        "centers.json",
        &["--centers", "kmeans", "--max-centers", "5"],
    );
    assert!(primary == alias, "the aliases fit another model");
    let m: serde_json::Value = serde_json::from_slice(&primary).unwrap();
    // --max-centres bounds the sizes cross-validation tries.
    for c in m["model"]["channels"].as_array().unwrap() {
        let k = c["rbf"]["centres"]["rows"].as_u64().unwrap();
        assert!((1..=5).contains(&k), "{k} centres");
    }
}

/// A reader that stops early (`dtg-vib export --lang text | head -c 1`)
/// closes the pipe: the program ends quietly (killed by SIGPIPE, as `cat` is),
/// with no panic and no backtrace on stderr.
#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_the_program_quietly() {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = bin()
        .args(["export", "--model", model(), "--lang", "text"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read one byte, then close the pipe while the program still writes.
    let mut stdout = child.stdout.take().unwrap();
    let mut one = [0u8; 1];
    stdout.read_exact(&mut one).unwrap();
    drop(stdout);
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!stderr.contains("Broken pipe"), "{stderr}");
}

#[test]
fn window_signals_auto_takes_the_vibrating_axes_and_a_named_list_is_kept() {
    let signals = |m: &serde_json::Value| -> Vec<String> {
        serde_json::from_value(m["model"]["preprocess"]["window"]["signals"].clone()).unwrap()
    };
    let fast = ["--input", "raw", "--smoother", "none"];
    // The demo record vibrates along z alone (ax 5%, ay 3% of az's): auto,
    // the default, takes az, and the model's choice report says why.
    let m = fitted("window-auto.json", &fast);
    assert_eq!(signals(&m), ["az"]);
    let w = &m["model"]["choice"]["window_signals"];
    assert_eq!(w["taken"], serde_json::json!(["az"]));
    let shares: Vec<f64> = (0..3)
        .map(|k| w["signals"][k]["share"].as_f64().unwrap())
        .collect();
    assert!(
        shares[0] < 0.1 && shares[1] < 0.1 && shares[2] == 1.0,
        "{w}"
    );
    // The same record with az's vibration copied onto ax: auto takes both.
    let shaken = variant("shaken-x.csv", |lines| {
        for line in lines.iter_mut().skip(1) {
            let mut cells: Vec<String> = line.split(',').map(String::from).collect();
            let az: f64 = cells[9].parse().unwrap();
            cells[7] = format!("{}", az - 1.0);
            *line = cells.join(",");
        }
    });
    let fit_on = |name: &str, args: &[&str]| -> serde_json::Value {
        let out = dir().join(name);
        let mut all = vec!["fit", "--data", shaken.as_str(), "--max-centers", "5"];
        all.extend_from_slice(&fast);
        all.extend_from_slice(args);
        all.extend(["--out", out.to_str().unwrap()]);
        ok(&all);
        serde_json::from_slice(&std::fs::read(out).unwrap()).unwrap()
    };
    assert_eq!(signals(&fit_on("window-auto-x.json", &[])), ["ax", "az"]);
    // A named list means exactly that list, and the report chooses nothing.
    let named = fit_on("window-az.json", &["--window-signals", "az"]);
    assert_eq!(signals(&named), ["az"]);
    assert!(
        named["model"]["choice"]["window_signals"].is_null(),
        "{named}"
    );
    // `fit` prints one line of what auto measured.
    let out = dir().join("window-auto-print.json");
    let printed = ok(&[
        "fit",
        "--data",
        &shaken,
        "--max-centers",
        "5",
        "--input",
        "raw",
        "--smoother",
        "none",
        "--out",
        out.to_str().unwrap(),
    ]);
    let line = printed
        .lines()
        .find(|l| l.starts_with("window signals: "))
        .unwrap_or_else(|| panic!("no window line: {printed}"));
    assert!(line.starts_with("window signals: ax,az (auto;"), "{line}");
}

#[test]
fn window_signals_auto_refuses_what_it_cannot_choose() {
    // Every accelerometer axis constant: no window can vary.
    let still = variant("still.csv", |lines| {
        for line in lines.iter_mut().skip(1) {
            let mut cells: Vec<String> = line.split(',').map(String::from).collect();
            cells[7] = "0".into();
            cells[8] = "0".into();
            cells[9] = "1".into();
            *line = cells.join(",");
        }
    });
    let cases = [
        fit_refusal(
            "auto with every axis constant",
            &still,
            &[],
            &["--window-signals auto", "none of ax, ay, az varies"],
        ),
        fit_refusal(
            "auto beside a signal",
            &record(),
            &["--window-signals", "auto,ax"],
            &["--window-signals auto,ax", "auto alone"],
        ),
    ];
    let b = broken(&cases);
    assert!(b.is_empty(), "{}", b.join("\n"));
}
