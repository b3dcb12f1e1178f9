//! Running a binary of the workspace as a user would, with hostile inputs and
//! a time limit: the harness of the `dtg-vib` and `rbf` integration tests
//! (feature `testing`, turned on by their dev-dependencies).
//!
//! The contract it checks is the same for both binaries: every run ends
//! within [`LIMIT`] with exit 0, or with exit 1 (2 for a flag clap refuses)
//! and one `error:` line on stderr; never a panic, never an abort.
//!
//! ```
//! use cli_support::testing::Binary;
//! // `true` ignores its arguments and succeeds (any Unix).
//! let r = Binary::new("true").check(&["--anything"]);
//! assert_eq!((r.code, r.stdout.as_str()), (0, ""));
//! ```

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

/// The process's scratch directory, once made.
static SCRATCH: OnceLock<PathBuf> = OnceLock::new();

/// A scratch directory for this test process, made once (the first call's
/// `prefix` names it, with the process id) and removed when the process
/// exits.
///
/// ```
/// let d = cli_support::testing::scratch_dir("cli-support-doc");
/// assert!(d.is_dir());
/// ```
pub fn scratch_dir(prefix: &str) -> &'static Path {
    SCRATCH.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("{prefix}-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("a scratch directory in the temporary directory");
        remove_at_exit();
        d
    })
}

/// Removes the scratch directory when the process exits. A static is never
/// dropped, and the test harness ends by returning from `main` or calling
/// `exit`, both of which run `atexit` handlers: without this every test run
/// left its simulations and models in the temporary directory (tens of
/// MB a test binary, until the disk filled).
#[cfg(unix)]
fn remove_at_exit() {
    extern "C" fn remove() {
        if let Some(d) = SCRATCH.get() {
            // Nothing is left to report to at exit; a failure leaves the
            // folder as it was before this handler existed.
            let _ = std::fs::remove_dir_all(d);
        }
    }
    // SAFETY: `atexit` stores a pointer to a plain function that reads a
    // static; it is called once, by the C runtime, after `main`.
    unsafe {
        libc::atexit(remove);
    }
}

#[cfg(not(unix))]
fn remove_at_exit() {}

/// A path as an argument (the tests' paths are UTF-8).
///
/// ```
/// assert_eq!(cli_support::testing::s(std::path::Path::new("/tmp/m.json")), "/tmp/m.json");
/// ```
pub fn s(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 path")
}

/// What a run gave.
#[derive(Clone, Debug)]
pub struct Run {
    /// The exit status.
    pub code: i32,
    /// Everything printed on stdout.
    pub stdout: String,
    /// Everything printed on stderr.
    pub stderr: String,
}

/// A binary under test and what its runs must satisfy.
#[derive(Clone, Copy, Debug)]
pub struct Binary {
    path: &'static str,
    appended: &'static [&'static str],
    finite_stdout: bool,
}

impl Binary {
    /// The binary at `path` (in a test: `env!("CARGO_BIN_EXE_NAME")`).
    ///
    /// ```
    /// const BIN: cli_support::testing::Binary = cli_support::testing::Binary::new("true");
    /// assert_eq!(BIN.run(&[]).code, 0);
    /// ```
    pub const fn new(path: &'static str) -> Self {
        Self {
            path,
            appended: &[],
            finite_stdout: false,
        }
    }

    /// Appends these arguments to every run (`--quiet`, say).
    ///
    /// ```
    /// let echo = cli_support::testing::Binary::new("echo").appending(&["--quiet"]);
    /// assert_eq!(echo.run(&["fit"]).stdout, "fit --quiet\n");
    /// ```
    pub const fn appending(self, args: &'static [&'static str]) -> Self {
        Self {
            appended: args,
            ..self
        }
    }

    /// A run that succeeds must print no `NaN` or `inf` on stdout.
    ///
    /// ```
    /// let echo = cli_support::testing::Binary::new("echo").finite_stdout();
    /// assert_eq!(echo.check(&["1.5"]).code, 0);
    /// ```
    pub const fn finite_stdout(self) -> Self {
        Self {
            finite_stdout: true,
            ..self
        }
    }

    /// Runs `BIN ARGS`, killing it past [`LIMIT`] (a failure). Both pipes are
    /// drained while it runs, so a chatty command cannot block on a full
    /// pipe and pass for a hang.
    ///
    /// ```
    /// let r = cli_support::testing::Binary::new("false").run(&[]);
    /// assert_eq!(r.code, 1);
    /// ```
    pub fn run(&self, args: &[&str]) -> Run {
        let mut child = Command::new(self.path)
            .args(args)
            .args(self.appended)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("{}: {e}", self.path));
        let drain = |mut pipe: Box<dyn Read + Send>| {
            std::thread::spawn(move || {
                let mut s = String::new();
                pipe.read_to_string(&mut s).expect("UTF-8 output");
                s
            })
        };
        let out = drain(Box::new(child.stdout.take().expect("piped stdout")));
        let err = drain(Box::new(child.stderr.take().expect("piped stderr")));
        let start = Instant::now();
        let status = loop {
            if let Some(s) = child.try_wait().expect("the child's status") {
                break s;
            }
            if start.elapsed() > LIMIT {
                child.kill().expect("killing a run past its time");
                panic!("{args:?} still running after {LIMIT:?}");
            }
            std::thread::sleep(Duration::from_millis(2));
        };
        let stdout = out.join().expect("stdout drained");
        let stderr = err.join().expect("stderr drained");
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

    /// Runs and checks the contract of any run: exit 0, 1 or 2; no panic; a
    /// failure is one `error:` line (and, with [`Binary::finite_stdout`], a
    /// success prints nothing non-finite).
    ///
    /// ```
    /// let r = cli_support::testing::Binary::new("true").check(&[]);
    /// assert_eq!(r.code, 0);
    /// ```
    pub fn check(&self, args: &[&str]) -> Run {
        let r = self.run(args);
        assert!(
            matches!(r.code, 0..=2),
            "{args:?}: exit {}: {}",
            r.code,
            r.stderr
        );
        assert!(
            !r.stderr.contains("panicked"),
            "{args:?} panicked: {}",
            r.stderr
        );
        if r.code != 0 {
            assert!(
                r.stderr.starts_with("error: ") && r.stderr.trim_end().lines().count() == 1,
                "{args:?}: not a one-line error: {}",
                r.stderr
            );
        } else if self.finite_stdout {
            assert!(
                !r.stdout.contains("NaN") && !r.stdout.contains("inf"),
                "{args:?}: non-finite output: {}",
                r.stdout
            );
        }
        r
    }

    /// Runs a command that must fail under the contract of [`Binary::check`]:
    /// its stderr.
    ///
    /// ```should_panic
    /// cli_support::testing::Binary::new("true").refused(&[]); // succeeds: a failure
    /// ```
    pub fn refused(&self, args: &[&str]) -> String {
        let r = self.check(args);
        assert_ne!(r.code, 0, "{args:?} should fail");
        r.stderr
    }
}
