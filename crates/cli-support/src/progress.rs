//! A spinner on stderr while a command works, and lines above it for the
//! steps worth keeping in view, drawn only where someone watches: never with
//! `--quiet`, never when stderr is a file or a pipe (so logs and tests see
//! only the results).

use std::borrow::Cow;
use std::io::IsTerminal;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Whether to draw progress: stderr is a terminal and `--quiet` was not given.
///
/// ```
/// assert!(!cli_support::progress::visible(true));
/// ```
pub fn visible(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// How often a spinner turns.
const TICK: Duration = Duration::from_millis(120);

/// A spinner drawn on stderr with this indicatif template and message,
/// turning on its own until it is finished.
///
/// ```
/// let s = cli_support::progress::spinner("{spinner} {msg}", "working");
/// s.finish_and_clear();
/// ```
pub fn spinner(template: &str, message: impl Into<Cow<'static, str>>) -> ProgressBar {
    let bar = ProgressBar::new_spinner();
    bar.set_draw_target(ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style);
    }
    bar.set_message(message);
    bar.enable_steady_tick(TICK);
    bar
}

/// A spinner whose message says what the command is doing now, or nothing
/// when not shown; cleared by [`Progress::clear`] before results print, and
/// when dropped.
///
/// ```
/// use cli_support::progress::Progress;
/// let p = Progress::new(false);
/// p.say("reading the record");
/// p.clear();
/// ```
#[derive(Debug)]
pub struct Progress(Option<ProgressBar>);

impl Progress {
    /// The spinner (elapsed seconds, then the message) if `show` (see [`visible`]).
    ///
    /// ```
    /// let p = cli_support::progress::Progress::new(cli_support::progress::visible(true));
    /// p.say("nothing is drawn");
    /// ```
    pub fn new(show: bool) -> Self {
        Self(show.then(|| spinner("{spinner} {elapsed:>3} {msg}", "")))
    }

    /// Changes the message.
    ///
    /// ```
    /// cli_support::progress::Progress::new(false).say(format!("round {}: fitting", 1));
    /// ```
    pub fn say(&self, msg: impl Into<String>) {
        if let Some(pb) = &self.0 {
            pb.set_message(msg.into());
        }
    }

    /// Prints `msg` on a line of its own above the spinner, after the
    /// seconds since the start, where it stays when the spinner is cleared:
    /// for a long command's steps (a round begun, a channel fitted), so the
    /// terminal keeps the record of what was done and how long it took.
    /// Nothing when not shown.
    ///
    /// ```
    /// cli_support::progress::Progress::new(false).line("round 1: X fitted (1 of 6)");
    /// ```
    pub fn line(&self, msg: impl AsRef<str>) {
        if let Some(pb) = &self.0 {
            pb.println(format!(
                "{:>6.1} s  {}",
                pb.elapsed().as_secs_f64(),
                msg.as_ref()
            ));
        }
    }

    /// Clears the spinner before the command prints its results.
    ///
    /// ```
    /// cli_support::progress::Progress::new(false).clear();
    /// ```
    pub fn clear(&self) {
        if let Some(pb) = &self.0 {
            pb.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.clear();
    }
}
