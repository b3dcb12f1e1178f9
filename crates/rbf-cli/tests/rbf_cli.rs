//! The `rbf` binary end to end: small CSV files in a temporary directory, the built
//! binary run on them, its stdout/stderr/exit status and output files checked.
//!
//! Refusals are one table ([`REFUSALS`]): each row writes its files, gives the command
//! line and the fragments its one-line error must contain. Hints that propose a value
//! are followed ([`every_hint_proposes_a_value_that_works`]). Successful runs, which
//! check more than a message, keep a test each.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rbf_cli::data;
use rbf_cli::saved::SavedModel;
use rbf_cli::settings::{Centres, FitSettings, WidthArg};
use serde_json::Value;
use tabular::Table;

// ---- harness ----

/// A fresh directory per test or table row (tests run in parallel).
struct Scratch(PathBuf);

/// The directory goes with its test (a run left about 15 MB behind).
impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("rbf-cli-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        Self(dir)
    }

    /// The path of `name` in the directory (not created).
    fn path(&self, name: &str) -> String {
        self.0.join(name).display().to_string()
    }

    /// Writes `text` to `name`; its path.
    fn file(&self, name: &str, text: &str) -> String {
        let p = self.path(name);
        std::fs::write(&p, text).expect("writes");
        p
    }

    /// `rbf fit` on `csv` (written as d.csv) into m.json with `extra` flags, and
    /// `--centres ols --max-centres 2` unless `extra` chooses the centres.
    fn fit(&self, csv: &str, extra: &[&str]) -> Vec<String> {
        let mut a = args(&["fit", "--data", &self.file("d.csv", csv), "--target", "y"]);
        a.extend(args(&["--out", &self.path("m.json")]));
        a.extend(args(extra));
        if !extra.iter().any(|f| *f == "--centres" || *f == "--centers") {
            a.extend(args(&["--centres", "ols", "--max-centres", "2"]));
        }
        a
    }

    /// A model fitted on 40 smooth rows (OLS, 5 centres): (data, model).
    fn saved_model(&self) -> (String, String) {
        let data = self.file("d.csv", &smooth_csv(40, None));
        let model = self.path("m.json");
        succeeds(&rbf(&[
            "fit",
            "--data",
            &data,
            "--target",
            "y",
            "--centres",
            "ols",
            "--max-centres",
            "5",
            "--out",
            &model,
            "--quiet",
        ]));
        (data, model)
    }

    /// `rbf predict` of `data` with `model` into p.csv.
    fn predict(&self, model: &str, data: &str) -> Vec<String> {
        args(&[
            "predict",
            "--model",
            model,
            "--data",
            data,
            "--out",
            &self.path("p.csv"),
        ])
    }
}

fn args(parts: &[&str]) -> Vec<String> {
    parts.iter().map(|s| s.to_string()).collect()
}

fn rbf<S: AsRef<OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rbf"))
        .args(args)
        .output()
        .expect("runs the rbf binary")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn succeeds(out: &Output) {
    assert!(
        out.status.success(),
        "rbf failed: {}\nstdout: {}",
        stderr(out),
        stdout(out)
    );
}

/// Non-zero exit, one line on stderr that contains every needle, no panic.
fn refused_with(out: &Output, needles: &[&str]) -> Result<(), String> {
    let err = stderr(out);
    if out.status.success() {
        return Err(format!("expected failure, stderr: {err}"));
    }
    if err.contains("panicked") {
        return Err(format!("panic: {err}"));
    }
    if err.trim_end().lines().count() != 1 {
        return Err(format!("not one line: {err:?}"));
    }
    match needles.iter().find(|n| !err.contains(*n)) {
        Some(n) => Err(format!("{n:?} not in {err:?}")),
        None => Ok(()),
    }
}

fn fails_with(out: &Output, needles: &[&str]) {
    if let Err(e) = refused_with(out, needles) {
        panic!("{e}");
    }
}

/// Deterministic smooth data: inputs a, b on a scrambled grid, a text column, the
/// target y = sin(2a)·cos(b) with a small deterministic wiggle.
fn smooth_csv(n: usize, split: Option<&dyn Fn(usize) -> &'static str>) -> String {
    let mut s = String::from("a,label,b,y");
    if split.is_some() {
        s.push_str(",split");
    }
    s.push('\n');
    for i in 0..n {
        let a = ((i * 37) % n) as f64 / n as f64 * 3.0 - 1.5;
        let b = ((i * 11) % 17) as f64 / 17.0 * 3.0 - 1.5;
        let y = (2.0 * a).sin() * b.cos() + 0.002 * ((i * 7919) % 13) as f64;
        s.push_str(&format!("{a},L{},{b},{y}", i % 3));
        if let Some(f) = split {
            s.push(',');
            s.push_str(f(i));
        }
        s.push('\n');
    }
    s
}

/// `rows` rows of y = sin(3a) + b on a grid of (a, b).
fn two_inputs(rows: u64) -> String {
    let mut text = String::from("a,b,y\n");
    for i in 0..rows {
        let a = (i % 997) as f64 / 997.0;
        let b = (i % 1009) as f64 / 1009.0;
        text.push_str(&format!("{a},{b},{}\n", (3.0 * a).sin() + b));
    }
    text
}

/// Every row four times: the even (training) rows hold each point twice, so the
/// all-points kernel matrix is singular.
fn repeated_rows() -> String {
    let mut csv = String::from("a,y\n");
    for i in 0..10 {
        let a = i as f64 / 10.0;
        for _ in 0..4 {
            csv.push_str(&format!("{a},{}\n", a * a));
        }
    }
    csv
}

/// 40 smooth rows whose 5th data row has a target of 1e308.
fn overflowing_target() -> String {
    let text = smooth_csv(40, None);
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut cells: Vec<String> = lines[5].split(',').map(str::to_string).collect();
    let last = cells.len() - 1;
    cells[last] = "1e308".into();
    lines[5] = cells.join(",");
    lines.join("\n") + "\n"
}

/// The sunspot file of the peers, in the repository.
fn sunspots() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../peers/data/sunspots/sunspots_lags9.csv")
        .display()
        .to_string()
}

const SUNSPOT_INPUTS: &str = "lag1,lag2,lag3,lag4,lag5,lag6,lag7,lag8,lag9";

/// `rbf fit` on the sunspots with `extra` flags.
fn sunspot_fit(out: &str, extra: &[&str]) -> Vec<String> {
    let mut a = args(&["fit", "--data", &sunspots(), "--target", "y"]);
    a.extend(args(&["--inputs", SUNSPOT_INPUTS]));
    a.extend(args(extra));
    a.extend(args(&["--out", out]));
    a
}

fn json(out: &Output) -> Value {
    serde_json::from_str(stdout(out).trim()).expect("stdout is one JSON object")
}

// ---- refusals: one line on stderr, non-zero exit, no panic ----

/// One refusal: `args` writes the files the run needs into the scratch directory and
/// returns the command line; the error must contain every fragment of `says`, and
/// `leaves_no` (if set) must not exist afterwards.
struct Refusal {
    name: &'static str,
    args: fn(&Scratch) -> Vec<String>,
    says: &'static [&'static str],
    leaves_no: Option<&'static str>,
}

const fn refusal(
    name: &'static str,
    args: fn(&Scratch) -> Vec<String>,
    says: &'static [&'static str],
) -> Refusal {
    Refusal {
        name,
        args,
        says,
        leaves_no: None,
    }
}

#[rustfmt::skip]
const REFUSALS: &[Refusal] = &[
    refusal("missing target column lists the available ones",
        |s| s.fit("a,b,z\n1,2,3\n4,5,6\n", &[]),
        &["d.csv", "no column 'y'", "a, b, z"]),
    refusal("missing input column lists the available ones",
        |s| s.fit("a,b,y\n1,2,3\n4,5,6\n", &["--inputs", "a,c"]),
        &["no column 'c'", "a, b, y"]),
    refusal("non-numeric cell names file, line and column",
        |s| s.fit("a,b,y\n1,2,3\n4,5,6\n7,eight,9\n", &["--inputs", "a,b"]),
        &["d.csv:4:2:", "column 'b'", "'eight' is not a number"]),
    refusal("NaN cell is refused with its position",
        |s| s.fit("a,b,y\n1,2,3\n4,5,NaN\n7,8,9\n", &[]),
        &["d.csv:3:3:", "'NaN' is not finite"]),
    refusal("infinite cell is refused with its position",
        |s| s.fit("a,b,y\n1,2,3\n4,-inf,6\n7,8,9\n", &[]),
        &["d.csv:3:2:", "'-inf' is not finite"]),
    // 10 training rows take 9 k-means centres and the bias
    refusal("fewer rows than centres says how many fit",
        |s| s.fit(&smooth_csv(20, None), &["--centres", "kmeans", "--max-centres", "15"]),
        &["15 centres", "10 training rows", "use --max-centers ≤ 9"]),
    refusal("unknown kernel lists the valid names",
        |s| s.fit(&smooth_csv(20, None), &["--kernel", "gauss"]),
        &["unknown kernel", "gaussian", "thin-plate", "wendland-c2"]),
    refusal("singular all-points fit suggests a ridge",
        |s| s.fit(&repeated_rows(), &["--centres", "all", "--width", "1"]),
        &["fit failed", "use --ridge 1e-8"]),
    refusal("bad split value names the allowed ones",
        |s| s.fit("a,y,s\n1,2,train\n3,4,test\n", &["--split-column", "s"]),
        &["d.csv:3:3:", "'test'", "allowed: train, val"]),
    refusal("unreadable data file is named",
        |s| args(&["fit", "--data", &s.path("nope.csv"), "--target", "y", "--centres", "ols", "--out", "m.json"]),
        &["nope.csv", "No such file"]),
    refusal("missing required flag is one line",
        |_| args(&["fit", "--data", "d.csv", "--target", "y", "--centres", "ols"]),
        &["--out"]),
    refusal("corrupt model file",
        |s| {
            let (data, model) = s.saved_model();
            let text = std::fs::read_to_string(&model).unwrap();
            std::fs::write(&model, &text[..text.len() / 2]).unwrap();
            s.predict(&model, &data)
        },
        &["m.json", "corrupt model file"]),
    refusal("model file of another format version",
        |s| {
            let (data, model) = s.saved_model();
            let text = std::fs::read_to_string(&model).unwrap();
            let edited = text.replacen("\"format_version\": 1", "\"format_version\": 99", 1);
            std::fs::write(&model, edited).unwrap();
            s.predict(&model, &data)
        },
        &["format_version 99", "reads 1"]),
    Refusal {
        name: "predict data lacking a model input",
        args: |s| {
            let (_, model) = s.saved_model();
            s.predict(&model, &s.file("other.csv", "a,y\n0.1,0.2\n"))
        },
        says: &["needs input columns a, b", "no column 'b'", "the header has: a, y"],
        leaves_no: Some("p.csv"),
    },
    // A model whose `linear` block is not empty (edited, or from the library's forced
    // columns) is refused with the reason; it used to panic.
    refusal("edited model with linear terms",
        |s| {
            let (data, model) = s.saved_model();
            let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&model).unwrap()).unwrap();
            v["rbf"]["model"]["linear"] = serde_json::json!({"cols": 1, "data": [[2.0]], "rows": 1});
            s.predict(&s.file("linear.json", &v.to_string()), &data)
        },
        &["linear", "rbf fit"]),
    // --threads outside 1..=256 is refused at once with the valid range (10,000 used
    // to hang while the pool started).
    refusal("--threads 0", |_| threads("0"), &["--threads", "1 to 256"]),
    refusal("--threads 10000", |_| threads("10000"), &["--threads", "1 to 256"]),
    refusal("--threads two", |_| threads("two"), &["--threads", "1 to 256"]),
    refusal("--threads 1e3", |_| threads("1e3"), &["--threads", "1 to 256"]),
    // --folds beyond the rows is refused at once, with the flag and the valid range (a
    // billion folds used to abort allocating).
    refusal("--folds 1000000000", |s| folds(s, "1000000000"), &["--folds", "use --folds 2 to 30"]),
    refusal("--folds 31", |s| folds(s, "31"), &["--folds", "use --folds 2 to 30"]),
    refusal("--folds 1", |s| folds(s, "1"), &["--folds", "use --folds 2 to 30"]),
    // Cells whose squares would overflow are refused at the file, line and column (a
    // 1e308 target used to save a model of NaN with exit 0).
    Refusal {
        name: "overflowing cells are refused with their position",
        args: |s| {
            let data = s.file("h.csv", &overflowing_target());
            let fit = ["fit", "--data", &data, "--target", "y", "--centres", "kmeans"];
            [args(&fit), args(&["--max-centres", "5", "--out", &s.path("m.json")])].concat()
        },
        says: &["h.csv:6:", "1e150"],
        leaves_no: Some("m.json"),
    },
    // OLS over every training row as a candidate needs an N × N kernel matrix: on
    // 200,000 rows (320 GB) it is refused before the allocation, with the --candidates
    // that fits (it used to abort in the allocator). Selection on all 100 000 training
    // rows, as before issue 15; by default rbf fit selects on 20 000 of them.
    Refusal {
        name: "a candidate matrix beyond memory names the flag that fits",
        args: |s| {
            let data = s.file("big.csv", &two_inputs(200_000));
            let fit = ["fit", "--data", &data, "--target", "y", "--centres", "ols"];
            [args(&fit), args(&["--selection-rows", "100000", "--out", &s.path("m.json")])].concat()
        },
        says: &["GiB", "use --candidates"],
        leaves_no: Some("m.json"),
    },
    refusal("--stop k:0",
        |s| sunspot_fit(&s.path("m.json"), &["--split-column", "split", "--stop", "k:0"]),
        &["--stop"]),
    refusal("--stop err:RHO with --tol",
        |s| sunspot_fit(&s.path("m.json"), &["--stop", "err:0.1", "--tol", "0.1"]),
        &["--stop err:RHO and --tol"]),
    refusal("--n-init is for k-means only",
        |s| s.fit(&smooth_csv(80, None), &["--centres", "ols", "--n-init", "3"]),
        &["--n-init applies to --centers kmeans only"]),
    refusal("thin-plate interpolation needs degree 1 (degree 0)",
        |s| s.fit(&smooth_csv(80, None), &["--centres", "all", "--kernel", "thin-plate", "--degree", "0"]),
        &["degree ≥ 1"]),
    refusal("thin-plate interpolation needs degree 1 (degree -1)",
        |s| s.fit(&smooth_csv(80, None), &["--centres", "all", "--kernel", "thin-plate", "--degree", "-1"]),
        &["degree ≥ 1"]),
    refusal("degree 3 lists the valid degrees",
        |s| s.fit(&smooth_csv(80, None), &["--centres", "random", "--degree", "3"]),
        &["valid degrees: -1 (none), 0, 1, 2"]),
    refusal("--ols-stream f16 lists the valid precisions",
        |s| s.fit(&smooth_csv(300, None), &["--ols-stream", "f16"]),
        &["f32", "f64"]),
    refusal("--ols-stream is for OLS only",
        |s| s.fit(&smooth_csv(300, None), &["--centres", "kmeans", "--max-centres", "5", "--ols-stream", "f64"]),
        &["--ols-stream applies to --centers ols only"]),
];

/// `rbf --threads N fit ...` on a file that does not exist: the flag is refused first.
fn threads(n: &str) -> Vec<String> {
    let fit = [
        "fit",
        "--data",
        "x.csv",
        "--target",
        "y",
        "--centres",
        "ols",
        "--out",
        "m.json",
    ];
    [args(&["--threads", n]), args(&fit)].concat()
}

/// `rbf cv --folds N` on 30 rows.
fn folds(s: &Scratch, n: &str) -> Vec<String> {
    let data = s.file("d.csv", &smooth_csv(30, None));
    let cv = ["cv", "--data", &data, "--target", "y", "--centres", "ols"];
    [args(&cv), args(&["--split", "kfold", "--folds", n])].concat()
}

/// Every refusal of the table, each in its own directory; all the broken rows are
/// reported at once.
#[test]
fn refusals_say_what_where_and_how_to_fix() {
    let broken: Vec<String> = REFUSALS
        .iter()
        .enumerate()
        .filter_map(|(i, r)| {
            let s = Scratch::new(&format!("refusal-{i}"));
            let out = rbf(&(r.args)(&s));
            let mut verdict = refused_with(&out, r.says);
            if let Some(f) = r.leaves_no
                && Path::new(&s.path(f)).exists()
            {
                verdict = Err(format!("{f} was written"));
            }
            verdict.err().map(|e| format!("{}: {e}", r.name))
        })
        .collect();
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

// ---- hints are followed ----

/// A refusal whose hint proposes a value ("use FLAG ≤ K", "use --gap K or less"): the
/// command run again with that value succeeds.
struct Hint {
    name: &'static str,
    /// The data rows (smooth data) and the command after `--data FILE --target y`.
    rows: usize,
    command: &'static [&'static str],
}

#[rustfmt::skip]
const HINTS: &[Hint] = &[
    Hint { name: "fit kmeans, 15 training rows", rows: 30, command: &["fit", "--centres", "kmeans"] },
    Hint { name: "fit random, 15 training rows", rows: 30, command: &["fit", "--centres", "random"] },
    Hint { name: "fit ols, 15 training rows", rows: 30, command: &["fit", "--centres", "ols"] },
    Hint { name: "fit kmeans with a quadratic tail", rows: 30, command: &["fit", "--centres", "kmeans", "--degree", "2"] },
    Hint { name: "fit kmeans with a ridge", rows: 30, command: &["fit", "--centres", "kmeans", "--ridge", "1e-6"] },
    Hint { name: "fit kmeans, standardised inputs", rows: 30, command: &["fit", "--centres", "kmeans", "--standardize"] },
    Hint { name: "cv kmeans, 5 k-folds of 30 rows", rows: 30, command: &["cv", "--centres", "kmeans", "--split", "kfold", "--folds", "5"] },
    Hint { name: "cv kmeans, 5 blocks of 30 rows", rows: 30, command: &["cv", "--centres", "kmeans", "--split", "blocked", "--folds", "5"] },
    Hint { name: "cv random, 5 interleaved folds", rows: 30, command: &["cv", "--centres", "random", "--split", "interleaved", "--folds", "5"] },
    Hint { name: "cv ols, 5 k-folds of 30 rows", rows: 30, command: &["cv", "--centres", "ols", "--split", "kfold", "--folds", "5"] },
    Hint { name: "cv kmeans, --sizes beyond a gapped fold", rows: 30,
        command: &["cv", "--centres", "kmeans", "--split", "blocked", "--folds", "5", "--gap", "2", "--sizes", "5,40"] },
    Hint { name: "cv, a gap that empties a fold", rows: 60,
        command: &["cv", "--centres", "ols", "--max-centres", "5", "--split", "blocked", "--folds", "5", "--gap", "200"] },
];

/// The flag and value a hint proposes, from "use FLAG ≤ K" or "use FLAG K or less".
fn proposal(err: &str) -> Option<(String, String)> {
    let rest = err.rsplit_once("use ")?.1;
    let mut words = rest.split_whitespace();
    let flag = words.next()?.to_string();
    let value = match words.next()? {
        "≤" => words.next()?,
        v => v,
    };
    let value = value.trim_end_matches([';', ')', '.']).to_string();
    (flag.starts_with("--") && value.parse::<usize>().is_ok()).then_some((flag, value))
}

/// `command` with `flag` set to `value` (replaced, or added).
fn with_flag(command: &[String], flag: &str, value: &str) -> Vec<String> {
    let spellings = [flag.to_string(), flag.replace("centers", "centres")];
    let mut out = command.to_vec();
    match out.iter().position(|a| spellings.contains(a)) {
        Some(i) => out[i + 1] = value.to_string(),
        None => out.extend([flag.to_string(), value.to_string()]),
    }
    out
}

#[test]
fn every_hint_proposes_a_value_that_works() {
    let broken: Vec<String> = HINTS
        .iter()
        .enumerate()
        .filter_map(|(i, h)| {
            let s = Scratch::new(&format!("hint-{i}"));
            let data = s.file("d.csv", &smooth_csv(h.rows, None));
            let mut command = args(&h.command[..1]);
            command.extend(args(&["--data", &data, "--target", "y", "--quiet"]));
            command.extend(args(&h.command[1..]));
            if h.command[0] == "fit" {
                command.extend(args(&["--out", &s.path("m.json")]));
            }
            let out = rbf(&command);
            if let Err(e) = refused_with(&out, &["use "]) {
                return Some(format!("{}: {e}", h.name));
            }
            let err = stderr(&out);
            let Some((flag, value)) = proposal(&err) else {
                return Some(format!("{}: no value proposed in {err:?}", h.name));
            };
            let again = rbf(&with_flag(&command, &flag, &value));
            (!again.status.success()).then(|| {
                format!(
                    "{}: {flag} {value}, proposed by {err:?}, fails: {}",
                    h.name,
                    stderr(&again)
                )
            })
        })
        .collect();
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

// ---- successful runs ----

#[test]
fn fit_then_predict_round_trip_matches_the_library() {
    let s = Scratch::new("roundtrip");
    let out = rbf(&s.fit(
        &smooth_csv(120, None),
        &[
            "--centres",
            "ols",
            "--max-centres",
            "12",
            "--width",
            "1",
            "--json",
            "--quiet",
        ],
    ));
    let (data_path, model_path) = (s.path("d.csv"), s.path("m.json"));
    succeeds(&out);
    let v = json(&out);
    for key in [
        "n_train",
        "n_val",
        "dim",
        "n_centers",
        "fit_seconds",
        "train_rmse",
        "val_rmse",
        "val_nmse",
        "kernel",
        "width",
        "condition",
        "ols",
    ] {
        assert!(v.get(key).is_some(), "missing key {key} in {v}");
    }
    assert_eq!(v["n_train"], 60);
    assert_eq!(v["n_val"], 60);
    assert_eq!(v["dim"], 2, "the text column is not an input");
    assert_eq!(v["n_centers"], 12);
    assert_eq!(v["kernel"], "gaussian");
    assert_eq!(v["width"], 1.0);
    let secs = v["fit_seconds"].as_f64().unwrap();
    assert!(secs > 0.0 && secs < 10.0, "{secs}");
    let (tr, vr, vn) = (
        v["train_rmse"].as_f64().unwrap(),
        v["val_rmse"].as_f64().unwrap(),
        v["val_nmse"].as_f64().unwrap(),
    );
    assert!(tr > 0.0 && tr < 0.1 && vr > 0.0 && vr < 0.2, "{tr} {vr}");
    assert!(vn > 0.0 && vn < 0.05, "{vn}");
    let picks = v["ols"]["picks"].as_array().unwrap();
    assert_eq!(picks.len(), 12);
    assert!(
        picks.iter().all(|p| p["row"].as_u64().unwrap() % 2 == 0),
        "centres are training (even) rows"
    );

    succeeds(&rbf(&s.predict(&model_path, &data_path)));
    let pred = Table::read(s.path("p.csv")).unwrap();
    assert_eq!(pred.header(), ["prediction", "y", "residual"]);
    let cli_pred = pred.numeric("prediction").unwrap();

    // The saved model, through the library, predicts exactly what the CLI wrote.
    let saved = SavedModel::load(&model_path).unwrap();
    assert_eq!(saved.inputs, ["a", "b"]);
    let table = Table::read(&data_path).unwrap();
    let x = data::numeric_matrix(&table, &saved.inputs).unwrap();
    let lib_pred = data::column(saved.model.predict(x.as_ref()).as_ref(), 0);
    assert_eq!(cli_pred, lib_pred);

    // A library fit on the even rows with the same settings gives the same model.
    let params = FitSettings {
        centres: Centres::Ols,
        max_centres: Some(12),
        width: WidthArg::Fixed(1.0),
        ..FitSettings::default()
    }
    .params(60, 2)
    .unwrap();
    let y = data::numeric_matrix(&table, &["y".to_string()]).unwrap();
    let even = data::interleaved(120).train;
    let model = params
        .fit(
            data::take_rows(x.as_ref(), &even).as_ref(),
            data::take_rows(y.as_ref(), &even).as_ref(),
        )
        .unwrap();
    let direct = data::column(model.predict(x.as_ref()).as_ref(), 0);
    for (a, b) in direct.iter().zip(&cli_pred) {
        assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()), "{a} vs {b}");
    }
    let resid = pred.numeric("residual").unwrap();
    let yv = pred.numeric("y").unwrap();
    for i in 0..120 {
        assert_eq!(resid[i], yv[i] - cli_pred[i]);
    }
}

#[test]
fn fit_prints_a_human_summary_without_json() {
    let s = Scratch::new("summary");
    let out = rbf(&s.fit(
        &smooth_csv(80, None),
        &["--centres", "all", "--width", "0.5", "--ridge", "1e-8"],
    ));
    succeeds(&out);
    let text = stdout(&out);
    assert!(text.contains("40 training / 40 validation rows"), "{text}");
    assert!(text.contains("40 centres (all)"), "{text}");
    assert!(text.contains("model written to"), "{text}");
    assert!(
        stderr(&out).is_empty(),
        "no progress when stderr is not a terminal"
    );
}

#[test]
fn split_column_chooses_training_and_validation_rows() {
    let s = Scratch::new("split");
    let role: &dyn Fn(usize) -> &'static str = &|i| if i % 4 == 3 { "val" } else { "train" };
    let out = rbf(&s.fit(
        &smooth_csv(100, Some(role)),
        &[
            "--split-column",
            "split",
            "--centres",
            "kmeans",
            "--max-centres",
            "10",
            "--width",
            "0.8",
            "--seed",
            "3",
            "--standardize",
            "--json",
            "--threads",
            "1",
        ],
    ));
    succeeds(&out);
    let v = json(&out);
    assert_eq!(v["threads"], 1);
    assert_eq!(
        (v["n_train"].as_u64(), v["n_val"].as_u64()),
        (Some(75), Some(25))
    );
    assert_eq!(v["dim"], 2, "the split column is not an input");
    assert_eq!(v["n_centers"], 10);
    assert!(v["ols"].is_null());
    assert!(v["val_nmse"].as_f64().unwrap() < 0.2);
}

#[test]
fn cv_grid_search_reports_every_point_and_the_best() {
    let s = Scratch::new("cv");
    let data = s.file("d.csv", &smooth_csv(90, None));
    let cv = |extra: &[&str]| {
        rbf(&[args(&["cv", "--data", &data, "--target", "y"]), args(extra)].concat())
    };
    let out = cv(&[
        "--centres",
        "ols",
        "--split",
        "blocked",
        "--folds",
        "3",
        "--gap",
        "2",
        "--sizes",
        "4,8",
        "--widths",
        "0.8,auto",
        "--ridges",
        "0,1e-6",
        "--json",
    ]);
    succeeds(&out);
    let v = json(&out);
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 8);
    let best = v["best"].as_u64().unwrap() as usize;
    assert_eq!(v["best_point"], points[best]);
    assert_eq!(points[best]["folds"].as_array().unwrap().len(), 3);
    let best_nmse = points[best]["mean"]["nmse"].as_f64().unwrap();
    assert!(
        points
            .iter()
            .all(|p| p["mean"]["nmse"].as_f64().unwrap() >= best_nmse)
    );

    let out = cv(&[
        "--centres",
        "random",
        "--max-centres",
        "8",
        "--width",
        "1",
        "--split",
        "kfold",
        "--folds",
        "3",
    ]);
    succeeds(&out);
    let text = stdout(&out);
    assert!(
        text.contains("best:") && text.contains("val NMSE"),
        "{text}"
    );
}

#[test]
fn predict_without_the_target_writes_predictions_only() {
    let s = Scratch::new("notarget");
    succeeds(&rbf(&s.fit(
        &smooth_csv(60, None),
        &["--centres", "random", "--max-centres", "6", "--quiet"],
    )));
    // Columns in another order, no target: inputs are found by name.
    let new_path = s.file("new.csv", "b,a\n0.5,0.1\n-0.5,0.2\n");
    let out = rbf(&[s.predict(&s.path("m.json"), &new_path), args(&["--json"])].concat());
    succeeds(&out);
    assert_eq!(json(&out)["n_rows"], 2);
    let pred = Table::read(s.path("p.csv")).unwrap();
    assert_eq!(pred.header(), ["prediction"]);
    let saved = SavedModel::load(s.path("m.json")).unwrap();
    let x = rbf::faer::mat![[0.1, 0.5], [0.2, -0.5]];
    assert_eq!(
        pred.numeric("prediction").unwrap(),
        data::column(saved.model.predict(x.as_ref()).as_ref(), 0)
    );
}

/// `--out` naming an input is refused before any work, naming both flags;
/// every input is byte-identical afterwards.
#[test]
fn outputs_never_overwrite_inputs() {
    let s = Scratch::new("guard");
    let (data, m) = s.saved_model();
    let before = (std::fs::read(&data).unwrap(), std::fs::read(&m).unwrap());
    let fit = [
        "fit",
        "--data",
        &data,
        "--target",
        "y",
        "--centres",
        "ols",
        "--out",
        &data,
    ];
    fails_with(&rbf(&fit), &["--out", "same file as --data"]);
    let predict = |out: &str| rbf(&["predict", "--model", &m, "--data", &data, "--out", out]);
    fails_with(&predict(&data), &["--out", "same file as --data"]);
    fails_with(&predict(&m), &["--out", "same file as --model"]);
    let after = (std::fs::read(&data).unwrap(), std::fs::read(&m).unwrap());
    assert_eq!(before, after);
    // No partial file is left behind by the refused or the successful runs.
    let parts: Vec<_> = std::fs::read_dir(&s.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".part"))
        .collect();
    assert!(parts.is_empty(), "{parts:?}");
}

#[test]
fn large_files_select_on_a_row_subsample_and_fit_every_row_by_default() {
    let s = Scratch::new("subsample");
    let data = s.file("big.csv", &two_inputs(60_000));
    let out = s.path("m.json");
    let run = rbf(&[
        "fit",
        "--data",
        &data,
        "--target",
        "y",
        "--max-centres",
        "20",
        "--json",
        "--quiet",
        "--out",
        &out,
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let j = json(&run);
    assert_eq!(j["n_train"], 30_000);
    assert_eq!(j["selection_rows"], 20_000);
    assert_eq!(j["ols_candidates"], 2000);
    assert_eq!(j["centers"], "ols");
    assert!(j["val_rmse"].as_f64().unwrap() < 0.05, "{j}");
    let crit = j["criterion"].as_array().unwrap();
    assert_eq!(crit.len(), 21);
    assert!(crit[20]["press"].as_f64().unwrap() < crit[0]["press"].as_f64().unwrap());
}

/// The least of `key` over `items`.
fn least<'a>(items: &'a [Value], key: &str) -> &'a Value {
    items
        .iter()
        .min_by(|a, b| {
            a[key]
                .as_f64()
                .unwrap()
                .total_cmp(&b[key].as_f64().unwrap())
        })
        .unwrap()
}

#[test]
fn stop_press_keeps_the_size_with_the_least_leave_one_out_error() {
    let s = Scratch::new("press");
    let out = s.path("m.json");
    let fit = |stop: &str| {
        let flags = [
            "--split-column",
            "split",
            "--stop",
            stop,
            "--json",
            "--quiet",
        ];
        rbf(&sunspot_fit(&out, &flags))
    };
    for rule in ["press", "gcv"] {
        let run = fit(rule);
        assert!(run.status.success(), "{}", stderr(&run));
        let j = json(&run);
        let crit = j["criterion"].as_array().unwrap();
        // --max-centres defaults to a tenth of the 212 training rows
        assert_eq!(crit.len(), 22);
        assert_eq!(j["n_centers"], least(crit, rule)["k"], "{rule}");
        assert_eq!(j["ols"]["stop"], rule);
        assert_eq!(j["stop"], rule);
        // --width auto searched five widths and kept the least PRESS
        let trials = j["width_search"].as_array().unwrap();
        assert_eq!(trials.len(), 5);
        let won = least(trials, "criterion");
        assert_eq!(j["width"], won["width"]);
        assert_eq!(j["n_centers"], won["k"]);
    }
    assert_eq!(json(&fit("k:7"))["n_centers"], 7);
}

/// The code says `centres`; the command line's flags are `--centres` and
/// `--max-centres`, and `--centers` and `--max-centers`, the earlier spelling, stay
/// as aliases with the same model.
#[test]
fn centers_spelling_is_an_alias_of_centres() {
    let s = Scratch::new("centres-alias");
    let csv = smooth_csv(60, None);
    let read = |spelling: [&str; 2]| {
        succeeds(&rbf(&s.fit(
            &csv,
            &[spelling[0], "kmeans", spelling[1], "5", "--width", "0.5"],
        )));
        std::fs::read_to_string(s.path("m.json")).unwrap()
    };
    let british = read(["--centres", "--max-centres"]);
    let american = read(["--centers", "--max-centers"]);
    assert_eq!(american, british);
    let help = stdout(&rbf(&["fit", "--help"]));
    assert!(
        help.contains("--centres <") && help.contains("--max-centres <"),
        "{help}"
    );
    assert!(
        help.contains("--centers") && help.contains("--max-centers"),
        "{help}"
    );
}

/// `--degree` puts a unit-box polynomial tail in the saved model, for least-squares
/// centres too; `--n-init` and `--kmeans-init` reach k-means (their refusals are in
/// the table).
#[test]
fn degree_and_kmeans_seeding_flags() {
    let s = Scratch::new("degree");
    let out = rbf(&s.fit(
        &smooth_csv(80, None),
        &[
            "--centres",
            "kmeans",
            "--max-centres",
            "6",
            "--width",
            "0.5",
            "--degree",
            "2",
            "--n-init",
            "3",
            "--kmeans-init",
            "plusplus",
        ],
    ));
    succeeds(&out);
    let model = std::fs::read_to_string(s.path("m.json")).unwrap();
    assert!(
        model.contains("\"poly\"") && model.contains("\"quadratic\""),
        "{model}"
    );
}

/// `--ols-stream f32` (the default) and `f64` save the same centres: the streaming
/// precision changes the bytes read a pick, never the picks.
#[test]
fn ols_stream_precision_keeps_the_picks() {
    let s = Scratch::new("ols-stream");
    let csv = smooth_csv(300, None);
    let centres = |extra: &[&str]| {
        let flags = [
            &["--centres", "ols", "--max-centres", "25", "--width", "0.6"][..],
            extra,
        ]
        .concat();
        succeeds(&rbf(&s.fit(&csv, &flags)));
        let model: Value =
            serde_json::from_str(&std::fs::read_to_string(s.path("m.json")).unwrap()).unwrap();
        model["rbf"]["model"]["centres"].clone()
    };
    let default = centres(&[]);
    assert!(default.is_array() || default.is_object(), "{default}");
    assert_eq!(default, centres(&["--ols-stream", "f32"]));
    assert_eq!(default, centres(&["--ols-stream", "f64"]));
}
