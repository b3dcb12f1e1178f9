//! Every task of a lot on this machine, `jobs` at a time: each task is the
//! same `dtg-vib fleet task` an engine's array element runs, as a child
//! process (its cost measured alone, a crash confined to its unit); no
//! scheduling beyond that. Units already done are counted, not started.

use super::layout::{FAILED, Layout, TASK, read_json};
use super::manifest::Manifest;
use super::task::{Failure, Inputs, TaskRecord};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Where the lot stands, for a progress line.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Progress {
    /// Units in the lot.
    pub total: usize,
    /// Units done before this run.
    pub skipped: usize,
    /// Units done by this run.
    pub done: usize,
    /// Units failed in this run.
    pub failed: usize,
    /// The ids running now.
    pub running: Vec<String>,
    /// Wall seconds since the run started.
    pub seconds: f64,
}

impl Progress {
    /// One line: how many are done, failed and running, and the time each
    /// finished unit took on average with `jobs` at a time.
    pub fn line(&self) -> String {
        let finished = self.done + self.failed;
        let per = match finished {
            0 => String::new(),
            n => format!(", {:.1} s a unit", self.seconds / n as f64),
        };
        format!(
            "{}/{} units: {} done, {} failed, {} already done; running {}{per}",
            finished + self.skipped,
            self.total,
            self.done,
            self.failed,
            self.skipped,
            match self.running.is_empty() {
                true => "none".to_string(),
                false => self.running.join(", "),
            }
        )
    }
}

/// What a run did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunReport {
    /// Units done before (not run again).
    pub skipped: Vec<String>,
    /// Units done now.
    pub done: Vec<TaskRecord>,
    /// Units that failed, with their reasons.
    pub failed: Vec<Failure>,
    /// Tasks that could not run at all (their error line).
    pub errors: Vec<(String, String)>,
    /// Wall seconds.
    pub seconds: f64,
}

/// The one `fleet task` command line of entry `index`.
pub fn task_command(program: &Path, manifest: &Path, index: usize, out: &Path) -> Command {
    let mut c = Command::new(program);
    c.args(["--quiet", "fleet", "task", "--manifest"])
        .arg(manifest)
        .arg("--index")
        .arg(index.to_string())
        .arg("--out")
        .arg(out);
    c
}

/// Whether entry `index`'s unit is done with the manifest's inputs.
fn is_done(m: &Manifest, index: usize, out: &Layout) -> bool {
    let e = &m.entries[index];
    read_json::<TaskRecord>(&out.unit(&e.id).join(TASK)).is_ok_and(|t| t.inputs == Inputs::of(m, e))
}

/// Runs entry `index` as a child `fleet task` and reads how it ended.
fn one(m: &Manifest, index: usize, out: &Layout, program: &Path, threads: usize) -> Ended {
    let id = m.entries[index].id.clone();
    let mut c = task_command(program, &m.path, index, out.root());
    if std::env::var_os("RAYON_NUM_THREADS").is_none() {
        c.env("RAYON_NUM_THREADS", threads.to_string());
    }
    let output = c.stdin(Stdio::null()).output();
    let dir = out.unit(&id);
    let inputs = Inputs::of(m, &m.entries[index]);
    match read_json::<TaskRecord>(&dir.join(TASK)) {
        Ok(t) if t.inputs == inputs => return Ended::Done(t),
        _ => {}
    }
    match read_json::<Failure>(&dir.join(FAILED)) {
        Ok(f) if f.inputs == inputs => return Ended::Failed(f),
        _ => {}
    }
    let said = match output {
        Ok(o) => String::from_utf8_lossy(&o.stderr)
            .lines()
            .rev()
            .find(|l| !l.trim().is_empty())
            .map_or_else(
                || format!("fleet task ended with {}", o.status),
                |l| l.trim().to_string(),
            ),
        Err(e) => format!("{}: {e}", program.display()),
    };
    Ended::Error(id, said)
}

enum Ended {
    Done(TaskRecord),
    Failed(Failure),
    Error(String, String),
}

/// Runs every task of `m` into `out`, `jobs` at a time, calling `show`
/// whenever a task starts or ends.
pub fn run(
    m: &Manifest,
    out: &Layout,
    program: &Path,
    jobs: usize,
    show: &(dyn Fn(&Progress) + Sync),
) -> Result<RunReport, super::layout::LayoutError> {
    out.claim(m)?;
    let start = std::time::Instant::now();
    let (done_before, todo): (Vec<usize>, Vec<usize>) =
        (0..m.entries.len()).partition(|&k| is_done(m, k, out));
    let jobs = jobs.clamp(1, todo.len().max(1));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = (cores / jobs).max(1);
    let state = Mutex::new((
        Progress {
            total: m.entries.len(),
            skipped: done_before.len(),
            ..Progress::default()
        },
        RunReport {
            skipped: done_before
                .iter()
                .map(|&k| m.entries[k].id.clone())
                .collect(),
            ..RunReport::default()
        },
    ));
    let next = AtomicUsize::new(0);
    let tell = |f: &dyn Fn(&mut Progress, &mut RunReport)| {
        let mut s = state.lock().unwrap_or_else(|p| p.into_inner());
        let (p, r) = &mut *s;
        f(p, r);
        p.seconds = start.elapsed().as_secs_f64();
        show(p);
    };
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            scope.spawn(|| {
                while let Some(&k) = todo.get(next.fetch_add(1, Ordering::Relaxed)) {
                    let id = m.entries[k].id.clone();
                    tell(&|p, _| p.running.push(id.clone()));
                    let ended = one(m, k, out, program, threads);
                    tell(&|p, r| {
                        p.running.retain(|x| *x != id);
                        match &ended {
                            Ended::Done(t) => {
                                p.done += 1;
                                r.done.push(t.clone());
                            }
                            Ended::Failed(f) => {
                                p.failed += 1;
                                r.failed.push(f.clone());
                            }
                            Ended::Error(i, e) => {
                                p.failed += 1;
                                r.errors.push((i.clone(), e.clone()));
                            }
                        }
                    });
                }
            });
        }
    });
    let (_, mut report) = state.into_inner().unwrap_or_else(|p| p.into_inner());
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}
