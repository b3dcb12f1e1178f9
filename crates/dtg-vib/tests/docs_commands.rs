//! The docs and the tools say the same thing (issue 26 item 3): every
//! ```sh block of README.md and docs/tutorial.md runs, in order, in a
//! temporary directory (with the repository's shipped data, `peers/`, at
//! hand), with `cargo run --release -p dtg-vib --` and the tutorial's
//! `dtg-vib` alias replaced by the built `dtg-vib` and `cargo run --release
//! -p rbf-cli --` by the built `rbf` beside it; and where a plain ``` block
//! follows a command block (with only prose between), every line of it
//! that holds numbers must match a line the commands printed, its numbers
//! as printed and in order, the quoted lines in the order they were
//! printed. `...` stands for lines left out.
//!
//! Not run, with a notice: `cargo test` (this is it) and, where no C
//! compiler is installed, the lines that compile the exported C. The
//! blocks are shell: the test runs them with bash, on Unix.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The repository root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A fenced block of a Markdown file.
#[derive(Debug)]
struct Block {
    /// The info string (`sh`, or empty).
    lang: String,
    /// Its lines.
    text: String,
    /// The line of the opening fence (1-based).
    line: usize,
    /// Whether a heading or another block lies between the previous block
    /// and this one (then it is no command's output).
    detached: bool,
}

fn blocks(md: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut open: Option<(String, usize, bool)> = None;
    let mut text = String::new();
    let mut heading_since = false;
    for (i, line) in md.lines().enumerate() {
        let t = line.trim_start();
        if let Some(info) = t.strip_prefix("```") {
            match open.take() {
                None => {
                    open = Some((info.trim().to_string(), i + 1, heading_since));
                    text.clear();
                }
                Some((lang, at, detached)) => {
                    out.push(Block {
                        lang,
                        text: std::mem::take(&mut text),
                        line: at,
                        detached,
                    });
                    heading_since = false;
                }
            }
        } else if open.is_some() {
            text.push_str(line);
            text.push('\n');
        } else if t.starts_with('#') {
            heading_since = true;
        }
    }
    out
}

/// The numbers of a line as written: `-27.2%` → `-27.2`, `4.07×` → `4.07`,
/// `7.7e-9` → `7.7e-9`; digits inside names (`K0`, `Y1`, `gg_IS`,
/// `col:temp`, `z1`) are not numbers.
fn numbers(line: &str) -> Vec<String> {
    let c: Vec<char> = line.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    let word = |ch: char| ch.is_alphanumeric() || ch == '_' || ch == ':';
    while i < c.len() {
        let starts_number = c[i].is_ascii_digit()
            || (c[i] == '-' && c.get(i + 1).is_some_and(char::is_ascii_digit));
        if !starts_number || (i > 0 && (word(c[i - 1]) || c[i - 1] == '.')) {
            i += 1;
            continue;
        }
        let start = i;
        if c[i] == '-' {
            i += 1;
        }
        while i < c.len() && c[i].is_ascii_digit() {
            i += 1;
        }
        if i + 1 < c.len() && c[i] == '.' && c[i + 1].is_ascii_digit() {
            i += 1;
            while i < c.len() && c[i].is_ascii_digit() {
                i += 1;
            }
        }
        if i + 1 < c.len()
            && (c[i] == 'e' || c[i] == 'E')
            && (c[i + 1].is_ascii_digit()
                || (c[i + 1] == '-' || c[i + 1] == '+')
                    && c.get(i + 2).is_some_and(char::is_ascii_digit))
        {
            i += 2;
            while i < c.len() && c[i].is_ascii_digit() {
                i += 1;
            }
        }
        // A number glued to letters (`2nd`, `3x3`, `50Hz`-like ids) is a word.
        if i < c.len() && (c[i].is_alphabetic() && c[i] != '×' || c[i] == '_') {
            while i < c.len() && word(c[i]) {
                i += 1;
            }
            continue;
        }
        out.push(c[start..i].iter().collect());
    }
    out
}

/// Whether `want` appears in `have` in order (not necessarily adjacent).
fn in_order(want: &[String], have: &[String]) -> bool {
    let mut it = have.iter();
    want.iter().all(|w| it.any(|h| h == w))
}

/// Compares a quoted output block with what the commands printed: the
/// problems found, one a line.
fn compare(quoted: &str, printed: &str) -> Vec<String> {
    let printed: Vec<(&str, Vec<String>)> = printed.lines().map(|l| (l, numbers(l))).collect();
    let mut from = 0;
    let mut problems = Vec::new();
    for q in quoted.lines() {
        let want = numbers(q);
        if q.trim() == "..." || want.is_empty() {
            continue;
        }
        match printed[from..]
            .iter()
            .position(|(_, have)| in_order(&want, have))
        {
            Some(k) => from += k + 1,
            None => {
                let anywhere = printed.iter().any(|(_, have)| in_order(&want, have));
                problems.push(format!(
                    "quoted {q:?} (numbers {want:?}) {}",
                    if anywhere {
                        "is printed, but before the line quoted above it"
                    } else {
                        "matches no printed line"
                    }
                ));
            }
        }
    }
    problems
}

/// A command block as a bash script: the docs' command forms mapped to the
/// built binaries, what cannot run here replaced by a notice.
fn script(block: &str, cc: bool) -> (String, Vec<String>) {
    let mut s = String::from("set -e -o pipefail\nexec 2>&1\n");
    let mut skipped = Vec::new();
    for line in block.lines() {
        let t = line.trim();
        let skip = if t.starts_with("alias dtg-vib=") {
            Some("")
        } else if t.starts_with("cargo test") {
            Some("this test runs inside cargo test")
        } else if !cc && (t.contains(" cc ") || t.starts_with("cc ")) {
            Some("no C compiler (cc) found")
        } else {
            None
        };
        match skip {
            Some("") => {}
            Some(why) => {
                skipped.push(format!("{t} ({why})"));
                s.push_str(": skipped\n");
            }
            _ => {
                let l = line
                    .replace("cargo run -q --release -p dtg-vib --", "dtg-vib")
                    .replace("cargo run --release -p dtg-vib --", "dtg-vib")
                    .replace("cargo run -q --release -p rbf-cli --", "rbf")
                    .replace("cargo run --release -p rbf-cli --", "rbf");
                s.push_str(&l);
                s.push('\n');
            }
        }
    }
    (s, skipped)
}

/// The built binaries: dtg-vib from this package, rbf beside it (cargo test
/// --workspace builds it; `cargo build --release -p rbf-cli` otherwise).
fn binaries() -> (PathBuf, PathBuf) {
    let dtg = PathBuf::from(env!("CARGO_BIN_EXE_dtg-vib"));
    let rbf = dtg.with_file_name(format!("rbf{}", std::env::consts::EXE_SUFFIX));
    assert!(
        rbf.exists(),
        "{} not found: build it with `cargo build --release -p rbf-cli` (cargo test --workspace does)",
        rbf.display()
    );
    (dtg, rbf)
}

fn have_cc() -> bool {
    Command::new("cc")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Runs every command block of `doc` in order in a fresh directory and
/// compares each quoted output; panics listing every disagreement.
fn run_doc(doc: &str) {
    let t0 = Instant::now();
    let path = root().join(doc);
    let md = std::fs::read_to_string(&path).expect("read doc");
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::os::unix::fs::symlink(root().join("peers"), dir.join("peers")).unwrap();
    // The real IMU logs the tutorial's "Your own unit" reads.
    std::os::unix::fs::symlink(root().join("data"), dir.join("data")).unwrap();
    // The unit files the tutorial's "Flight data" reads.
    std::os::unix::fs::symlink(root().join("units"), dir.join("units")).unwrap();
    let (dtg, rbf) = binaries();
    let prelude = format!(
        "dtg-vib() {{ '{}' \"$@\"; }}\nrbf() {{ '{}' \"$@\"; }}\n",
        dtg.display(),
        rbf.display()
    );
    let cc = have_cc();
    let all = blocks(&md);
    let mut problems = Vec::new();
    let mut ran = 0;
    for (i, b) in all.iter().enumerate() {
        if b.lang != "sh" {
            continue;
        }
        let (body, skipped) = script(&b.text, cc);
        for s in &skipped {
            eprintln!("notice: {doc}:{}: not run: {s}", b.line);
        }
        let t = Instant::now();
        let out = Command::new("bash")
            .current_dir(dir)
            .arg("-c")
            .arg(format!("{prelude}{body}"))
            .output()
            .expect("run bash");
        ran += 1;
        let printed = String::from_utf8_lossy(&out.stdout).into_owned();
        eprintln!(
            "{doc}:{}: block ran in {:.1} s",
            b.line,
            t.elapsed().as_secs_f64()
        );
        if !out.status.success() {
            problems.push(format!(
                "{doc}:{}: the block failed ({}):\n{}\n{printed}",
                b.line, out.status, b.text
            ));
            continue;
        }
        if let Some(q) = all.get(i + 1).filter(|q| q.lang.is_empty() && !q.detached) {
            for p in compare(&q.text, &printed) {
                problems.push(format!("{doc}:{}: {p}", q.line));
            }
            if compare(&q.text, &printed).is_empty() {
                eprintln!(
                    "{doc}:{}: {} quoted numbers match",
                    q.line,
                    q.text.lines().map(|l| numbers(l).len()).sum::<usize>()
                );
            }
        }
    }
    eprintln!("{doc}: {ran} blocks in {:.1} s", t0.elapsed().as_secs_f64());
    assert!(ran > 0, "{doc} has no ```sh block");
    assert!(
        problems.is_empty(),
        "{doc} and the tools disagree:\n{}",
        problems.join("\n")
    );
}

#[test]
fn readme_commands_run_and_print_what_it_quotes() {
    run_doc("README.md");
}

#[test]
fn tutorial_commands_run_and_print_what_it_quotes() {
    run_doc("docs/tutorial.md");
}

#[test]
fn numbers_are_read_as_written_and_names_are_not_numbers() {
    assert_eq!(
        numbers("     K0     15.9316     3.9153                                 4.07×"),
        ["15.9316", "3.9153", "4.07"]
    );
    assert_eq!(
        numbers(
            "  Y1: validation rms 1.6246 deg/h; suggested: col:temp (0.518 ± 0.073 deg/h/°C, 95% CI 0.371 to 0.664; p = 7.7e-9)"
        ),
        ["1.6246", "0.518", "0.073", "95", "0.371", "0.664", "7.7e-9"]
    );
    assert_eq!(
        numbers("     Y1          1.6246         1.1825  -27.2%"),
        ["1.6246", "1.1825", "-27.2"]
    );
    assert_eq!(
        numbers("gg_IS z1 − z2 X1=col:temp 3rd"),
        Vec::<String>::new()
    );
    assert_eq!(numbers("after 2 round(s), p=0.01"), ["2", "0.01"]);
}

#[test]
fn a_quoted_number_the_tool_does_not_print_is_found() {
    let printed = "residue  rms before  rms after\n     K0     15.9316     3.9153   4.07×\n     K1      6.0291     1.4410   4.18×\nthe loop stopped after 2 round(s)\n";
    assert!(compare("     K0     15.9316     3.9153   4.07×\n...\n", printed).is_empty());
    let p = compare("     K0     15.9316     3.9154   4.07×\n", printed);
    assert_eq!(p.len(), 1);
    assert!(p[0].contains("matches no printed line"), "{p:?}");
    // In order: K1 quoted before K0 is a disagreement.
    let p = compare(
        "     K1      6.0291     1.4410   4.18×\n     K0     15.9316     3.9153   4.07×\n",
        printed,
    );
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(p[0].contains("before the line quoted above it"));
    // Prose: "round 3 suggests nothing new" against "after 2 round(s)".
    assert_eq!(
        compare("the loop stopped after 3 round(s)", printed).len(),
        1
    );
    // The block parser: a plain block after a heading is no command's output.
    let b = blocks("```sh\nx\n```\ntext\n```\nout\n```\n## H\n```\nlayout\n```\n");
    assert_eq!(b.len(), 3);
    assert!(!b[1].detached && b[2].detached);
}
