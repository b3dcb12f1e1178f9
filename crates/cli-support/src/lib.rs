//! What the workspace's two command lines (`dtg-vib` and `rbf`) share: how a
//! failure is told, how a usage error ends, and the progress spinner.
//!
//! Both binaries are glue (parse, call a library, print); this crate is the
//! part of that glue they would otherwise write twice.
//!
//! | module | what |
//! |---|---|
//! | [`failure`] | an error and its causes as one `error:` line on stderr, exit 1 |
//! | [`usage`] | clap's usage errors as one line ending in "(see --help)", exit 2 |
//! | [`progress`] | a spinner on stderr and lines above it for long steps, silent with `--quiet` or when stderr is not a terminal |
//! | `testing` | (feature `testing`) running a binary under a time limit, for the integration tests |
//!
//! ```
//! use cli_support::{Style, failure};
//!
//! let e = anyhow::anyhow!("disk full").context("model.json");
//! assert_eq!(failure::message(&e, Style::TRIMMED), "model.json: disk full");
//! ```

#![warn(missing_docs)]

pub mod failure;
pub mod progress;
pub mod usage;

#[cfg(feature = "testing")]
pub mod testing;

/// How a message of several lines is put on one line.
///
/// The two binaries grew different habits before they shared this crate.
/// Both now print errors [`Style::TRIMMED`]; `dtg-vib` keeps
/// [`Style::VERBATIM`]'s "; " between clap's usage lines.
///
/// ```
/// use cli_support::Style;
/// assert!(Style::TRIMMED.trim_lines && !Style::TRIMMED.usage_semicolons);
/// assert!(!Style::VERBATIM.trim_lines && Style::VERBATIM.usage_semicolons);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Style {
    /// Error lines are trimmed and blank ones dropped before they are joined
    /// with "; "; otherwise every line break becomes "; " as it stands.
    pub trim_lines: bool,
    /// clap's lines are joined with "; " (a space after a line ending in ':');
    /// otherwise with a space.
    pub usage_semicolons: bool,
}

impl Style {
    /// Trimmed error lines, usage lines joined by spaces (`rbf`'s; both
    /// binaries' errors).
    pub const TRIMMED: Style = Style {
        trim_lines: true,
        usage_semicolons: false,
    };
    /// Error lines as they stand, usage lines joined by "; " (`dtg-vib`'s
    /// usage errors).
    pub const VERBATIM: Style = Style {
        trim_lines: false,
        usage_semicolons: true,
    };
}
