//! The binary as the tests run it: from the workspace root, as the docs'
//! commands run it (paths such as `data/realdata/…` and `units/…` are
//! relative to it), or as a bare command whose success a test asserts.
//! Shared by several test binaries, each of which uses only part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `dtg-vib --quiet ARGS` in the workspace root.
pub fn dtg_vib(args: &[&str]) -> Output {
    bin()
        .arg("--quiet")
        .args(args)
        .current_dir(root())
        .output()
        .unwrap()
}

/// The `dtg-vib` binary, its arguments still to be given.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
}

/// Runs `cmd --quiet`, asserts it succeeded (its stderr in the message),
/// and returns its stdout.
pub fn ok(cmd: &mut Command) -> String {
    let out = cmd.arg("--quiet").output().expect("binary runs");
    assert!(
        out.status.success(),
        "{cmd:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// `COMMAND --unit UNIT --data DATA --effects EFFECTS` with the flight's
/// linear model's flags (unfiltered, one centre, raw input, no smoother),
/// then `more`.
pub fn linear<'a>(
    command: &'a str,
    unit: &'a str,
    data: &'a str,
    effects: &'a str,
    more: &[&'a str],
) -> Vec<&'a str> {
    let mut args = vec![
        command,
        "--unit",
        unit,
        "--data",
        data,
        "--no-filter",
        "--effects",
        effects,
        "--max-centres",
        "1",
        "--input",
        "raw",
        "--smoother",
        "none",
    ];
    args.extend_from_slice(more);
    args
}
