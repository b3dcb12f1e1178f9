//! Number-shaped hostile values (±1e308, 1e-308, NaN, ±inf, −0, and values
//! just inside the readers' ±1e150) in every numeric flag, CSV cell and
//! model number of `rbf`, run as a user would.
//!
//! Every run must end within seconds with exit 0 and finite, readable
//! output, or with a one-line `error:` and a non-zero exit (1, or 2 for a
//! flag clap refuses); never a panic or an abort; and every input file is
//! byte-identical afterwards. The regression tests at the end pin the
//! issue's cases to the messages that now replace them.

use cli_support::testing::{Binary, HOSTILE, s, scratch_dir};
use std::path::Path;
use std::path::PathBuf;
use std::sync::OnceLock;

/// `rbf ARGS` under the harness's contract (exit 0 with nothing non-finite
/// printed, or one `error:` line; within the time limit).
const BIN: Binary = Binary::new(env!("CARGO_BIN_EXE_rbf")).finite_stdout();

fn dir() -> &'static Path {
    scratch_dir("rbf-hostile")
}

/// A smooth surface of two inputs on 60 rows.
fn csv() -> String {
    let mut t = String::from("a,b,y\n");
    for i in 0..60 {
        let a = (i % 7) as f64 / 7.0;
        let b = (i % 11) as f64 / 11.0;
        t.push_str(&format!("{a},{b},{}\n", (3.0 * a).sin() + b * b));
    }
    t
}

fn data() -> &'static Path {
    static D: OnceLock<PathBuf> = OnceLock::new();
    D.get_or_init(|| {
        let p = dir().join("d.csv");
        std::fs::write(&p, csv()).unwrap();
        p
    })
}

/// A model per kernel family that grows with distance, and the Gaussian.
fn model(kernel: &str) -> PathBuf {
    let p = dir().join(format!("m-{kernel}.json"));
    if !p.exists() {
        let r = BIN.check(&[
            "fit",
            "--data",
            s(data()),
            "--target",
            "y",
            "--centers",
            "ols",
            "--max-centers",
            "6",
            "--kernel",
            kernel,
            "--ridge",
            "1e-6",
            "--quiet",
            "--out",
            s(&p),
        ]);
        assert_eq!(r.code, 0, "{}", r.stderr);
    }
    p
}

/// Predictions written by a run that succeeded read back finite.
fn readable(path: &Path) {
    let t = tabular::Table::read(path).unwrap();
    t.numeric("prediction").unwrap();
}

/// Every numeric flag of `fit` and `cv` (and the global `--threads`).
#[test]
fn numeric_flags() {
    let before = std::fs::read(data()).unwrap();
    let out = dir().join("flags.json");
    let fit_flags = [
        "--max-centers",
        "--candidates",
        "--tol",
        "--width",
        "--ridge",
        "--seed",
        "--n-init",
        "--degree",
    ];
    let cv_flags = [
        "--folds", "--gap", "--widths", "--sizes", "--tols", "--ridges",
    ];
    for v in HOSTILE {
        for flag in fit_flags {
            let args = [
                "fit",
                "--data",
                s(data()),
                "--target",
                "y",
                "--centers",
                "ols",
                "--quiet",
                "--out",
                s(&out),
                flag,
                v,
            ];
            let r = BIN.check(&args);
            if r.code == 2 {
                assert!(
                    r.stderr.contains(flag) || r.stderr.contains(v),
                    "{flag} {v}: {}",
                    r.stderr
                );
            }
        }
        for flag in cv_flags {
            let split = if flag == "--gap" { "blocked" } else { "kfold" };
            let r = BIN.check(&[
                "cv",
                "--data",
                s(data()),
                "--target",
                "y",
                "--centers",
                "ols",
                "--max-centers",
                "5",
                "--split",
                split,
                "--quiet",
                flag,
                v,
            ]);
            if r.code == 2 {
                assert!(
                    r.stderr.contains(flag) || r.stderr.contains(v),
                    "{flag} {v}: {}",
                    r.stderr
                );
            }
        }
        let r = BIN.check(&[
            "--threads",
            v,
            "fit",
            "--data",
            s(data()),
            "--target",
            "y",
            "--centers",
            "ols",
            "--out",
            s(&out),
        ]);
        assert_ne!(r.code, 0, "--threads {v}");
    }
    assert_eq!(before, std::fs::read(data()).unwrap(), "the data changed");
}

/// Every cell position kind (input, target) with every hostile value, in
/// `fit` (each centre strategy) and `predict` (each kernel family).
#[test]
fn csv_cells() {
    let text = csv();
    let models: Vec<PathBuf> = ["gaussian", "cubic", "multiquadric", "thin-plate"]
        .iter()
        .map(|k| model(k))
        .collect();
    let models_before: Vec<Vec<u8>> = models.iter().map(|m| std::fs::read(m).unwrap()).collect();
    for col in 0..3 {
        for v in HOSTILE.iter().chain(&["1e149", "-1e149", "1e-200"]) {
            let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
            let mut cells: Vec<&str> = lines[6].split(',').collect();
            cells[col] = v;
            lines[6] = cells.join(",");
            let bad = dir().join("cell.csv");
            std::fs::write(&bad, lines.join("\n") + "\n").unwrap();
            let out = dir().join("cell-out");
            for centres in ["ols", "kmeans", "all"] {
                let mut args = vec![
                    "fit",
                    "--data",
                    s(&bad),
                    "--target",
                    "y",
                    "--centers",
                    centres,
                    "--quiet",
                    "--ridge",
                    "1e-6",
                    "--out",
                    s(&out),
                ];
                if centres != "all" {
                    args.extend(["--max-centers", "5"]);
                }
                let r = BIN.check(&args);
                if r.code != 0 && ["1e308", "-1e308", "NaN", "inf", "-inf"].contains(v) {
                    assert!(
                        r.stderr.contains(&format!("cell.csv:7:{}", col + 1)),
                        "{args:?}: {}",
                        r.stderr
                    );
                }
            }
            for m in &models {
                let _ = std::fs::remove_file(&out);
                let r = BIN.check(&[
                    "predict",
                    "--model",
                    s(m),
                    "--data",
                    s(&bad),
                    "--out",
                    s(&out),
                    "--quiet",
                ]);
                if r.code == 0 {
                    readable(&out);
                }
            }
        }
    }
    let models_after: Vec<Vec<u8>> = models.iter().map(|m| std::fs::read(m).unwrap()).collect();
    assert!(models_before == models_after, "a model changed");
}

/// Numbers of a saved model replaced by hostile ones: `predict` refuses
/// naming the file, or writes predictions that read back.
#[test]
fn model_numbers() {
    for kernel in ["gaussian", "cubic"] {
        let m = model(kernel);
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&m).unwrap()).unwrap();
        let inner = if v.pointer("/rbf/model").is_some() {
            "/rbf/model"
        } else {
            "/rbf"
        };
        let pointers = [
            "/weights/data/0/0",
            "/centres/data/0/0",
            "/widths/uniform",
            "/bias/0",
        ];
        for p in pointers {
            let p = format!("{inner}{p}");
            assert!(v.pointer(&p).is_some(), "{p} not in the model");
            for value in ["1e308", "-1e308", "1e-308", "-0", "1e155", "1e149", "NaN"] {
                let mut e = v.clone();
                *e.pointer_mut(&p).unwrap() = serde_json::json!("HOSTILE");
                let path = dir().join("edited.json");
                std::fs::write(&path, e.to_string().replacen("\"HOSTILE\"", value, 1)).unwrap();
                let out = dir().join("edited.csv");
                let _ = std::fs::remove_file(&out);
                let r = BIN.check(&[
                    "predict",
                    "--model",
                    s(&path),
                    "--data",
                    s(data()),
                    "--out",
                    s(&out),
                    "--quiet",
                ]);
                if r.code == 0 {
                    readable(&out);
                } else {
                    assert!(r.stderr.contains(s(&path)), "{p} = {value}: {}", r.stderr);
                }
            }
        }
    }
}

// ---- Regressions: each case of the issue, as it reads now. ----

/// Inputs of 1e149 (inside the readers' bound) with the kernels that grow
/// with distance: the row is named, nothing is written (cubic wrote NaN).
#[test]
fn predictions_that_overflow_are_named_by_row() {
    let far = dir().join("far.csv");
    std::fs::write(&far, "a,b,y\n0.5,0.5,1\n1e149,0.5,1\n").unwrap();
    let out = dir().join("far-out.csv");
    let err = BIN.refused(&[
        "predict",
        "--model",
        s(&model("cubic")),
        "--data",
        s(&far),
        "--out",
        s(&out),
    ]);
    assert!(err.contains("far.csv:3:") && err.contains("cubic"), "{err}");
    assert!(!out.exists());
}

/// Model weights edited to 1e155 are refused on load, naming the field.
#[test]
fn edited_weights_are_refused_naming_the_field() {
    let m = model("gaussian");
    let text = std::fs::read_to_string(&m).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    *v.pointer_mut("/rbf/model/weights/data/0/0").unwrap() = serde_json::json!(1e155);
    let path = dir().join("w-1e155.json");
    std::fs::write(&path, v.to_string()).unwrap();
    let err = BIN.refused(&[
        "predict",
        "--model",
        s(&path),
        "--data",
        s(data()),
        "--out",
        s(&dir().join("w.csv")),
    ]);
    assert!(err.contains("weights[0][0] = 1e155"), "{err}");
}

/// An input cell of −1e200 is refused at its position (OLS used to stop
/// silently at one centre).
#[test]
fn a_huge_input_cell_is_refused_at_its_position() {
    let text = csv().replacen("\n0,0,", "\n-1e200,0,", 1);
    let bad = dir().join("neg.csv");
    std::fs::write(&bad, text).unwrap();
    let err = BIN.refused(&[
        "fit",
        "--data",
        s(&bad),
        "--target",
        "y",
        "--centers",
        "ols",
        "--out",
        s(&dir().join("n.json")),
    ]);
    assert!(
        err.contains("neg.csv:2:1") && err.contains("±1e150"),
        "{err}"
    );
}

/// A blocked split whose gap empties a fold names the flags and the largest
/// gap that works (it said "fold 0 has 0 training rows"), and that gap works.
#[test]
fn a_gap_that_empties_a_fold_names_the_flags() {
    let cv = |gap: &str| {
        BIN.check(&[
            "cv",
            "--data",
            s(data()),
            "--target",
            "y",
            "--centers",
            "ols",
            "--max-centers",
            "5",
            "--split",
            "blocked",
            "--folds",
            "5",
            "--gap",
            gap,
            "--quiet",
        ])
    };
    let err = cv("200");
    assert_ne!(err.code, 0);
    assert!(
        err.stderr.contains("--gap 200") && err.stderr.contains("--folds 5"),
        "{}",
        err.stderr
    );
    let fix = err
        .stderr
        .split("use --gap ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .to_string();
    assert_eq!(cv(&fix).code, 0, "the proposed --gap {fix} does not work");
}

/// Counts and ridges outside their ranges are refused with the flag as typed
/// and the valid range; no hint proposes "--max-centers ≤ 0" or a ridge of
/// 1e302. (clap names an aliased flag by its primary spelling: `--max-centres`,
/// which is typed here.)
#[test]
fn flags_out_of_range_say_the_valid_range() {
    for (flag, v, range) in [
        ("--candidates", "0", "≥ 1"),
        ("--max-centres", "0", "≥ 1"),
        ("--ridge", "1e302", "0 to 1e12"),
        ("--tol", "-1e308", "from 0 up to"),
        ("--width", "1e-308", "1e-100 to 1e100"),
    ] {
        let err = BIN.refused(&[
            "fit",
            "--data",
            s(data()),
            "--target",
            "y",
            "--centers",
            "ols",
            flag,
            v,
            "--out",
            "m.json",
        ]);
        assert!(
            err.contains(&format!("'{v}'")) && err.contains(flag) && err.contains(range),
            "{err}"
        );
        assert!(!err.contains("≤ 0"), "{err}");
    }
}
