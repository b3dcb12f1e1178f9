//! Running a binary of the workspace with hostile inputs and a time limit:
//! shared by the `dtg-vib` and `rbf` hostile-value tests.

// Each test binary includes this file and uses part of it.
#![allow(dead_code)]

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// The values every numeric input is tried with.
pub const HOSTILE: &[&str] = &["1e308", "-1e308", "1e-308", "NaN", "inf", "-inf", "-0"];

/// Longest any single run may take: the slowest honest run is a fraction of
/// a second; a hang (NaN scores that never retire) would run forever.
pub const LIMIT: Duration = Duration::from_secs(20);

/// A scratch directory for this test process, made once.
pub fn dir(prefix: &str) -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("{prefix}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    })
}

/// What a run gave.
pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `bin ARGS`, killing it past [`LIMIT`] (a failure). Both pipes are
/// drained while it runs, so a chatty command cannot block on a full pipe
/// and pass for a hang.
pub fn run(bin: &str, args: &[&str]) -> Run {
    let mut child = Command::new(bin)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let drain = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            pipe.read_to_string(&mut s).unwrap();
            s
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > LIMIT {
            child.kill().unwrap();
            panic!("{args:?} still running after {LIMIT:?}");
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let (stdout, stderr) = (out.join().unwrap(), err.join().unwrap());
    // A signal (an abort) has no code.
    let code = status
        .code()
        .unwrap_or_else(|| panic!("{args:?} died: {status:?}: {stderr}"));
    Run {
        code,
        stdout,
        stderr,
    }
}
