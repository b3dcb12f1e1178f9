//! The binary run from the workspace root, as the docs' commands run it
//! (paths such as `data/realdata/…` and `units/…` are relative to it):
//! shared by the tests of real logs and of the flights.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `dtg-vib --quiet ARGS` in the workspace root.
pub fn dtg_vib(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dtg-vib"))
        .arg("--quiet")
        .args(args)
        .current_dir(root())
        .output()
        .unwrap()
}
