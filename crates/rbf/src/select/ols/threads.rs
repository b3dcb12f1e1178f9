//! How many threads the streaming passes run on: the parallelism asked for where it
//! helps, one thread where it does not.
//!
//! A pass is bound by memory. Two threads read faster than one when both cores are
//! free and the candidates do not fit in cache; when another process holds a core, or
//! the candidates are few, the second thread costs more than it brings. The engine
//! therefore times its passes: the first four after the first pick alternate between the
//! parallelism asked for and one thread, and the faster (per candidate entry read) is
//! kept, the parallel one only if it is at least [`GAIN`] times faster; the trial is
//! repeated every [`RETRY`] passes, as the load of a shared machine changes. A pass
//! gives the same numbers on any number of threads (each candidate's products are
//! summed by one thread, in one order), so the choice changes the time, never a pick.
//! This is the one place the library reads a clock.

use std::fmt;

use faer::Par;

/// The parallel passes are kept only when at least this much faster than one thread.
const GAIN: f64 = 1.1;
/// Passes between two trials.
const RETRY: usize = 32;
/// Trial passes: parallel, one thread, parallel, one thread.
const TRIAL: usize = 4;
/// Below this many bytes a pass reads (the second-level caches of two cores) it is not
/// split: a few microseconds of work, less than waking a thread.
const SMALL: usize = 2 << 20;

/// The threads the streaming passes of an OLS selection ran on, and why.
///
/// ```
/// use faer::{Mat, Par};
/// let x = Mat::from_fn(50, 8, |i, j| ((i * (j + 3)) as f64 * 0.29).cos());
/// let y = Mat::from_fn(50, 1, |i, _| x[(i, 5)]);
/// let opts = rbf::OlsOptions::new(2).par(Par::Seq);
/// let path = rbf::forward_select(x.as_ref(), Mat::<f64>::zeros(50, 0).as_ref(), y.as_ref(), &opts).unwrap();
/// let t = path.pass_threads();
/// assert_eq!((t.threads, &t.reason), (1, &rbf::PassThreadsReason::Asked));
/// assert_eq!(t.to_string(), "one thread, as asked");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PassThreads {
    /// The threads most passes ran on.
    pub threads: usize,
    /// Why.
    pub reason: PassThreadsReason,
}

/// Why the passes ran on the threads they did.
///
/// ```
/// let r = rbf::PassThreadsReason::Small { bytes: 1000 };
/// assert!(rbf::PassThreads { threads: 1, reason: r }.to_string().contains("too small"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum PassThreadsReason {
    /// One thread was asked for.
    Asked,
    /// A pass reads too few bytes to be worth splitting.
    Small {
        /// Bytes a pass read.
        bytes: usize,
    },
    /// Timed: the fastest trial pass on one thread and on `threads`, in seconds per
    /// million candidate entries read (the last trial).
    Timed {
        /// The parallelism asked for.
        threads: usize,
        /// One thread.
        one: f64,
        /// `threads` threads.
        many: f64,
    },
    /// No pass after the first pick (the selection stopped before).
    NoPass,
}

impl fmt::Display for PassThreads {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let on = if self.threads == 1 {
            "one thread".to_string()
        } else {
            format!("{} threads", self.threads)
        };
        match &self.reason {
            PassThreadsReason::Asked => write!(f, "{on}, as asked"),
            PassThreadsReason::Small { bytes } => {
                write!(f, "{on}: a pass reads {bytes} bytes, too small to split")
            }
            PassThreadsReason::Timed { threads, one, many } => write!(
                f,
                "{on}: a pass took {:.3} ms per million entries on {threads} threads and {:.3} ms on one",
                many * 1e3 * 1e6,
                one * 1e3 * 1e6
            ),
            PassThreadsReason::NoPass => write!(f, "{on}: no pass after the first pick"),
        }
    }
}

/// The engine's choice of parallelism pass by pass.
pub(crate) struct Schedule {
    asked: Par,
    /// Bytes the first pass reads (candidates shrink by a pick a pass: close enough).
    small: Option<usize>,
    /// Passes since the current trial began.
    pass: usize,
    /// Use the parallelism asked for after the current trial.
    many: bool,
    /// Best seconds per entry in the current trial: one thread, parallel.
    trial: (f64, f64),
    /// The last complete trial's.
    last: Option<(f64, f64)>,
    passes_one: usize,
    passes_many: usize,
}

impl Schedule {
    /// For passes of `bytes` bytes (the first) with parallelism `asked`.
    pub(crate) fn new(asked: Par, bytes: usize) -> Self {
        Self {
            asked,
            small: (bytes < SMALL).then_some(bytes),
            pass: 0,
            many: false,
            trial: (f64::INFINITY, f64::INFINITY),
            last: None,
            passes_one: 0,
            passes_many: 0,
        }
    }

    fn decides(&self) -> bool {
        self.asked.degree() > 1 && self.small.is_none()
    }

    /// The parallelism of the next pass.
    pub(crate) fn par(&self) -> Par {
        if !self.decides() {
            return Par::Seq;
        }
        let parallel = if self.pass < TRIAL {
            self.pass.is_multiple_of(2)
        } else {
            self.many
        };
        if parallel { self.asked } else { Par::Seq }
    }

    /// A pass ran with `par` and took `seconds` to read `entries` candidate entries.
    pub(crate) fn record(&mut self, par: Par, seconds: f64, entries: usize) {
        let parallel = par.degree() > 1;
        if parallel {
            self.passes_many += 1;
        } else {
            self.passes_one += 1;
        }
        if !self.decides() {
            return;
        }
        if self.pass < TRIAL {
            let per = seconds / entries.max(1) as f64;
            let slot = if parallel {
                &mut self.trial.1
            } else {
                &mut self.trial.0
            };
            *slot = slot.min(per);
            if self.pass + 1 == TRIAL {
                let (one, many) = self.trial;
                self.many = one >= GAIN * many;
                self.last = Some(self.trial);
                self.trial = (f64::INFINITY, f64::INFINITY);
            }
        }
        self.pass = (self.pass + 1) % (TRIAL + RETRY);
    }

    /// What the passes ran on.
    pub(crate) fn summary(&self) -> PassThreads {
        let threads = if self.passes_many > self.passes_one {
            self.asked.degree()
        } else {
            1
        };
        let reason = if self.asked.degree() <= 1 {
            PassThreadsReason::Asked
        } else if let Some(bytes) = self.small {
            PassThreadsReason::Small { bytes }
        } else {
            match self
                .last
                .or((self.passes_one + self.passes_many > 0).then_some(self.trial))
            {
                Some((one, many)) => PassThreadsReason::Timed {
                    threads: self.asked.degree(),
                    one,
                    many,
                },
                None => PassThreadsReason::NoPass,
            }
        };
        PassThreads { threads, reason }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The trial alternates, keeps the parallel passes only when they are at least
    /// GAIN times faster, and tries again after RETRY passes.
    #[test]
    fn keeps_the_parallel_passes_only_where_they_help() {
        for (one, many, parallel) in [(2.0, 1.0, true), (1.0, 1.0, false), (1.05, 1.0, false)] {
            let mut s = Schedule::new(Par::rayon(2), 100 << 20);
            let mut used = Vec::new();
            for _ in 0..TRIAL + RETRY + 1 {
                let par = s.par();
                let t = if par.degree() > 1 { many } else { one };
                used.push(par.degree() > 1);
                s.record(par, t, 1);
            }
            assert_eq!(&used[..TRIAL], &[true, false, true, false]);
            assert!(
                used[TRIAL..TRIAL + RETRY].iter().all(|&u| u == parallel),
                "{one} {many}"
            );
            assert!(used[TRIAL + RETRY], "a new trial starts parallel");
            let sum = s.summary();
            assert_eq!(sum.threads, if parallel { 2 } else { 1 });
            assert!(matches!(
                sum.reason,
                PassThreadsReason::Timed { threads: 2, .. }
            ));
        }
        let s = Schedule::new(Par::rayon(2), 1000);
        assert_eq!(s.par(), Par::Seq);
        assert_eq!(s.summary().reason, PassThreadsReason::Small { bytes: 1000 });
    }
}
