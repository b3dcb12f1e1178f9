//! What a task cost: wall time, CPU time (this process and the `explain`
//! it waited for) and peak memory — what an engine's requests are made of
//! ([`super::plan`]).

use serde::{Deserialize, Serialize};
use std::time::Instant;

/// A task's cost.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cost {
    /// Wall time, s.
    pub seconds: f64,
    /// User + system CPU time of the task and its `explain`, s (none where
    /// the system does not say).
    pub cpu_seconds: Option<f64>,
    /// The larger peak resident memory of the task and its `explain`, bytes.
    pub max_rss_bytes: Option<u64>,
    /// Cores the task could use.
    pub cores: usize,
}

impl Cost {
    /// Cores used on average, `cpu_seconds / seconds`.
    pub fn parallelism(&self) -> Option<f64> {
        self.cpu_seconds
            .filter(|_| self.seconds > 0.0)
            .map(|c| c / self.seconds)
    }
}

/// CPU seconds and peak RSS of this process and of its waited-for children.
#[derive(Debug, Clone, Copy)]
struct Usage {
    cpu_seconds: f64,
    max_rss_bytes: u64,
}

#[cfg(unix)]
fn usage() -> Option<Usage> {
    let get = |who| {
        let mut r = std::mem::MaybeUninit::<libc::rusage>::zeroed();
        // SAFETY: getrusage fills the struct it is handed; on failure we
        // do not read it.
        let rc = unsafe { libc::getrusage(who, r.as_mut_ptr()) };
        // SAFETY: rc == 0: the struct was written.
        (rc == 0).then(|| unsafe { r.assume_init() })
    };
    let (me, kids) = (get(libc::RUSAGE_SELF)?, get(libc::RUSAGE_CHILDREN)?);
    let secs = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    Some(Usage {
        cpu_seconds: secs(me.ru_utime)
            + secs(me.ru_stime)
            + secs(kids.ru_utime)
            + secs(kids.ru_stime),
        // Linux gives ru_maxrss in KiB.
        max_rss_bytes: (me.ru_maxrss.max(kids.ru_maxrss)).max(0) as u64 * 1024,
    })
}

#[cfg(not(unix))]
fn usage() -> Option<Usage> {
    None
}

/// A measurement under way.
#[derive(Debug)]
pub struct Meter {
    start: Instant,
    at_start: Option<Usage>,
}

impl Meter {
    /// Starts measuring.
    pub fn start() -> Self {
        Self {
            start: Instant::now(),
            at_start: usage(),
        }
    }

    /// What was spent since [`Meter::start`]: CPU time as a difference, peak
    /// memory as the process's high-water mark (which a process that ran
    /// other work before counts too: a task is its own process when an
    /// engine runs it).
    pub fn stop(&self) -> Cost {
        let now = usage();
        Cost {
            seconds: self.start.elapsed().as_secs_f64(),
            cpu_seconds: now
                .zip(self.at_start)
                .map(|(n, s)| (n.cpu_seconds - s.cpu_seconds).max(0.0)),
            max_rss_bytes: now.map(|n| n.max_rss_bytes),
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
        }
    }
}
