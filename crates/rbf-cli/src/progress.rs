//! Progress of a fit on stderr, and where its time went.
//!
//! The library reports [`rbf::Progress`] events (a stage, then every OLS pick) and never
//! times anything; [`FitProgress`] turns them into an indicatif bar — hidden when
//! stderr is not a terminal or with `--quiet` — and timestamps them, so `--json` can
//! say how long each stage took and what one OLS pick costs.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rbf::{Progress, Stage};
use serde::Serialize;

pub use cli_support::progress::visible;

/// The library's name for a stage, as printed and as a JSON key.
///
/// ```
/// assert_eq!(rbf_cli::progress::stage_name(rbf::Stage::KernelMatrix), "kernel_matrix");
/// ```
pub fn stage_name(stage: Stage) -> &'static str {
    match stage {
        Stage::Widths => "widths",
        Stage::KernelMatrix => "kernel_matrix",
        Stage::Clustering => "clustering",
        Stage::Selection => "selection",
        Stage::Weights => "weights",
    }
}

/// Seconds spent in each stage of a fit, in order.
///
/// A stage runs from its first event to the next stage's first event (the last to
/// the end of the fit). The library reports an OLS pick when it is made, so the
/// `selection` stage starts after the first pick: its time and `seconds_per_pick`
/// cover picks 2…K, and the first pick is counted with the kernel matrix.
///
/// ```
/// let t = rbf_cli::progress::StageTimes::default();
/// assert!(t.stages.is_empty() && t.seconds_per_pick.is_none());
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct StageTimes {
    /// (stage, seconds) in the order the stages ran.
    pub stages: Vec<(String, f64)>,
    /// Mean time of an OLS pick (from the second pick on), if there were two or more.
    pub seconds_per_pick: Option<f64>,
}

/// Draws a fit's progress and records when each event arrived.
///
/// ```
/// use rbf::{Progress, Stage};
/// let p = rbf_cli::progress::FitProgress::new(false);
/// p.observe(Progress { stage: Stage::KernelMatrix, done: 0, total: 1 });
/// for done in 1..=3 {
///     p.observe(Progress { stage: Stage::Selection, done, total: 3 });
/// }
/// p.observe(Progress { stage: Stage::Weights, done: 0, total: 1 });
/// let t = p.finish();
/// let names: Vec<&str> = t.stages.iter().map(|(s, _)| s.as_str()).collect();
/// assert_eq!(names, ["kernel_matrix", "selection", "weights"]);
/// assert!(t.seconds_per_pick.unwrap() >= 0.0);
/// ```
#[derive(Debug)]
pub struct FitProgress {
    bar: ProgressBar,
    events: Mutex<Vec<(Progress, Instant)>>,
}

impl FitProgress {
    /// A recorder; `show` draws the bar on stderr (see [`visible`]).
    ///
    /// ```
    /// let p = rbf_cli::progress::FitProgress::new(false);
    /// assert_eq!(p.finish(), rbf_cli::progress::StageTimes::default());
    /// ```
    pub fn new(show: bool) -> Self {
        let target = if show {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        let bar = ProgressBar::with_draw_target(None, target);
        Self {
            bar,
            events: Mutex::new(Vec::new()),
        }
    }

    /// Records one event and updates the bar (the library's progress callback).
    ///
    /// ```
    /// let p = rbf_cli::progress::FitProgress::new(false);
    /// p.observe(rbf::Progress { stage: rbf::Stage::Widths, done: 0, total: 1 });
    /// assert_eq!(p.finish().stages.len(), 1);
    /// ```
    pub fn observe(&self, p: Progress) {
        let now = Instant::now();
        let first_of_stage = {
            let mut ev = self.events.lock().unwrap_or_else(|e| e.into_inner());
            let first = ev.last().is_none_or(|(q, _)| q.stage != p.stage);
            ev.push((p, now));
            first
        };
        if self.bar.is_hidden() {
            return;
        }
        self.bar.set_length(p.total as u64);
        self.bar.set_position(p.done as u64);
        if first_of_stage {
            let style = if p.stage == Stage::Selection {
                ProgressStyle::with_template(
                    "{msg:>14} [{bar:30}] {pos}/{len} picks, {elapsed_precise}",
                )
            } else {
                ProgressStyle::with_template("{spinner} {msg:>14} {elapsed_precise}")
            };
            if let Ok(style) = style {
                self.bar.set_style(style.progress_chars("=> "));
            }
            self.bar.set_message(stage_name(p.stage));
            self.bar.enable_steady_tick(Duration::from_millis(120));
        }
    }

    /// Clears the bar and returns the stage times up to now.
    ///
    /// ```
    /// let p = rbf_cli::progress::FitProgress::new(false);
    /// assert!(p.finish().stages.is_empty());
    /// ```
    pub fn finish(&self) -> StageTimes {
        let end = Instant::now();
        self.bar.finish_and_clear();
        let ev = self.events.lock().unwrap_or_else(|e| e.into_inner());
        let mut stages: Vec<(String, f64)> = Vec::new();
        for (i, (p, t)) in ev.iter().enumerate() {
            let next_stage_start = ev[i + 1..]
                .iter()
                .find(|(q, _)| q.stage != p.stage)
                .map_or(end, |(_, t)| *t);
            let is_first = i == 0 || ev[i - 1].0.stage != p.stage;
            if is_first {
                let secs = next_stage_start.duration_since(*t).as_secs_f64();
                stages.push((stage_name(p.stage).to_string(), secs));
            }
        }
        let picks: Vec<Instant> = ev
            .iter()
            .filter(|(p, _)| p.stage == Stage::Selection)
            .map(|(_, t)| *t)
            .collect();
        let seconds_per_pick = (picks.len() >= 2).then(|| {
            picks[picks.len() - 1]
                .duration_since(picks[0])
                .as_secs_f64()
                / (picks.len() - 1) as f64
        });
        StageTimes {
            stages,
            seconds_per_pick,
        }
    }
}

/// A spinner for work without inner progress (cross-validation), hidden like the bar.
///
/// ```
/// let s = rbf_cli::progress::spinner(false, "cross-validating");
/// s.finish_and_clear();
/// ```
pub fn spinner(show: bool, message: &'static str) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    cli_support::progress::spinner("{spinner} {msg} {elapsed_precise}", message)
}
