//! One unit's task: its `explain` (the command line's own, run as a child
//! process with the manifest's options as its flags, so a unit gets
//! exactly what `dtg-vib explain --unit …` gives), then its page
//! ([`crate::page`]) of the final model on its records, all built in
//! a staging folder and renamed into `DIR/units/ID` whole. A unit whose
//! folder holds `task.json` is done and skipped; a unit that fails leaves
//! `failed.json` with the one-line reason (and is run again by a rerun).

use super::layout::{
    DIAGNOSIS, EXPLAIN, EXPLAIN_LOG, FAILED, Layout, LayoutError, MODEL, REPORT, TASK, host,
    read_json, write_json,
};
use super::manifest::{Entry, Manifest, ManifestError};
use super::measure::{Cost, Meter};
use crate::error::DtgVibError;
use crate::page::{Page, write_page};
use crate::unit_sensor::{UnitModel, read_unit_records};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// What a unit was made from: a done unit with other inputs is not
/// skipped but refused (its outputs would not be this manifest's).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Inputs {
    /// The unit (as the manifest wrote it).
    pub unit: String,
    /// The records (as the manifest wrote them).
    pub data: Vec<String>,
    /// The calibration (as the manifest wrote it).
    pub calib: Option<String>,
    /// `explain`'s arguments from `[options]`.
    pub options: Vec<String>,
}

impl Inputs {
    /// The inputs of `entry` in `m`.
    pub fn of(m: &Manifest, entry: &Entry) -> Self {
        Self {
            unit: entry.unit.given.clone(),
            data: entry.data.iter().map(|(g, _)| g.clone()).collect(),
            calib: entry.calib.as_ref().map(|(g, _)| g.clone()),
            options: m.option_args(),
        }
    }
}

/// `task.json`: a done unit, and what it cost.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskRecord {
    /// The unit's id.
    pub id: String,
    /// Its entry (`--index`).
    pub index: usize,
    /// What it was made from.
    pub inputs: Inputs,
    /// What the task cost.
    pub cost: Cost,
    /// Where it ran.
    pub host: String,
}

/// `failed.json`: a unit that failed, and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    /// The unit's id.
    pub id: String,
    /// Its entry (`--index`).
    pub index: usize,
    /// The reason, one line.
    pub reason: String,
    /// What it was run on.
    pub inputs: Inputs,
    /// Wall time until it failed, s.
    pub seconds: f64,
}

/// How a task ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// The unit was done before: nothing run.
    Skipped(TaskRecord),
    /// Done now.
    Done(TaskRecord),
    /// The unit failed (its folder holds `failed.json`).
    Failed(Failure),
}

/// Why a task could not run at all (a unit's own failure is an
/// [`Outcome::Failed`], not an error).
#[derive(Debug, thiserror::Error)]
pub enum TaskError {
    /// The manifest or the index.
    #[error(transparent)]
    Manifest(#[from] ManifestError),
    /// The output folder.
    #[error(transparent)]
    Layout(#[from] LayoutError),
    /// The unit is done with other inputs.
    #[error(
        "{dir}: done with other inputs than the manifest's now (then: {was}): remove the folder to run the unit again, or give another --out"
    )]
    Stale {
        /// The unit's folder.
        dir: PathBuf,
        /// What it was made from.
        was: String,
    },
    /// `explain` could not be started.
    #[error("{program}: {source}: give the dtg-vib binary")]
    Spawn {
        /// The program.
        program: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> LayoutError + '_ {
    move |source| LayoutError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Runs entry `index` of `m` into `out`, with `program` (the `dtg-vib`
/// binary) as its `explain`.
pub fn run(m: &Manifest, index: usize, out: &Layout, program: &Path) -> Result<Outcome, TaskError> {
    let entry = m.entry(index)?;
    let inputs = Inputs::of(m, entry);
    out.claim(m)?;
    let dir = out.unit(&entry.id);
    if dir.join(TASK).exists() {
        let done: TaskRecord = read_json(&dir.join(TASK))?;
        if done.inputs != inputs {
            return Err(TaskError::Stale {
                was: serde_json::to_string(&done.inputs).unwrap_or_default(),
                dir,
            });
        }
        return Ok(Outcome::Skipped(done));
    }
    let meter = Meter::start();
    let stage = out.staging(&entry.id);
    if stage.exists() {
        std::fs::remove_dir_all(&stage).map_err(io(&stage))?;
    }
    std::fs::create_dir_all(&stage).map_err(io(&stage))?;
    let outcome = match explain(m, entry, &stage, &dir, program)? {
        Ok(()) => {
            let done = TaskRecord {
                id: entry.id.clone(),
                index,
                inputs,
                cost: meter.stop(),
                host: host(),
            };
            write_json(&stage.join(TASK), &done)?;
            Outcome::Done(done)
        }
        Err(reason) => {
            let failed = Failure {
                id: entry.id.clone(),
                index,
                reason,
                inputs,
                seconds: meter.stop().seconds,
            };
            write_json(&stage.join(FAILED), &failed)?;
            Outcome::Failed(failed)
        }
    };
    if !publish(&stage, &dir)? {
        // A twin of this task (an engine's retry) finished first: its
        // folder stands.
        return Ok(Outcome::Skipped(read_json(&dir.join(TASK))?));
    }
    Ok(outcome)
}

/// Moves the staging folder into place, over a failed run's folder but
/// never over a done one; false (and the staging folder dropped) when a
/// twin's done folder is there.
fn publish(stage: &Path, dir: &Path) -> Result<bool, LayoutError> {
    if dir.join(FAILED).exists() && !dir.join(TASK).exists() {
        std::fs::remove_dir_all(dir).map_err(io(dir))?;
    }
    match std::fs::rename(stage, dir) {
        Ok(()) => Ok(true),
        Err(_) if dir.join(TASK).exists() => {
            std::fs::remove_dir_all(stage).map_err(io(stage))?;
            Ok(false)
        }
        Err(e) => Err(io(dir)(e)),
    }
}

/// `explain`'s arguments for `entry`, writing into `stage`.
pub fn explain_args(m: &Manifest, entry: &Entry, stage: &Path) -> Vec<String> {
    let mut a = vec![
        "--quiet".to_string(),
        "explain".into(),
        "--unit".into(),
        entry.unit.arg.clone(),
    ];
    for (_, d) in &entry.data {
        a.extend(["--data".to_string(), d.display().to_string()]);
    }
    if let Some((_, c)) = &entry.calib {
        a.extend(["--calib".to_string(), c.display().to_string()]);
    }
    a.extend([
        "--out".to_string(),
        stage.join(MODEL).display().to_string(),
        "--report".into(),
        stage.join(DIAGNOSIS).display().to_string(),
        "--json".into(),
    ]);
    a.extend(m.option_args());
    a
}

/// Runs the unit's `explain` and writes its page; `Ok(Err(reason))` when
/// the unit failed.
fn explain(
    m: &Manifest,
    entry: &Entry,
    stage: &Path,
    dir: &Path,
    program: &Path,
) -> Result<Result<(), String>, TaskError> {
    let json = stage.join(EXPLAIN);
    let log = stage.join(EXPLAIN_LOG);
    let stdout = std::fs::File::create(&json).map_err(io(&json))?;
    let stderr = std::fs::File::create(&log).map_err(io(&log))?;
    let status = Command::new(program)
        .args(explain_args(m, entry, stage))
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr)
        .status()
        .map_err(|source| TaskError::Spawn {
            program: program.to_path_buf(),
            source,
        })?;
    if !status.success() {
        let said = std::fs::read_to_string(&log).unwrap_or_default();
        return Ok(Err(reason(&said, status)));
    }
    Ok(page(m, entry, stage, dir).map_err(|e| format!("the unit's page: {e}")))
}

/// The one line that says why `explain` failed: its `error:` line, or how
/// it ended.
fn reason(stderr: &str, status: std::process::ExitStatus) -> String {
    let line = stderr
        .lines()
        .rev()
        .find_map(|l| l.strip_prefix("error: "))
        .or_else(|| stderr.lines().rev().find(|l| !l.trim().is_empty()));
    match (line, status.code()) {
        (Some(l), _) => l.trim().to_string(),
        (None, Some(c)) => format!("explain exited with status {c} and said nothing"),
        (None, None) => "explain was killed by a signal".to_string(),
    }
}

/// The unit's page: the final model on its records, linking its diagnosis.
fn page(m: &Manifest, entry: &Entry, stage: &Path, dir: &Path) -> Result<(), DtgVibError> {
    let model = UnitModel::load(stage.join(MODEL))?;
    let window = model.inner().preprocess().window.length();
    let mut records = Vec::new();
    for (_, d) in &entry.data {
        records.extend(read_unit_records(d, model.unit(), 2 * window)?.segments);
    }
    let data: Vec<PathBuf> = entry.data.iter().map(|(_, d)| d.clone()).collect();
    write_page(
        &model,
        &records,
        Page {
            files: entry
                .calib
                .iter()
                .map(|(_, c)| ("calibration".to_string(), c.clone()))
                .collect(),
            lead: vec![format!(
                "Unit {} of the lot '{}': the final model of its explain loop on its records.",
                entry.id, m.name
            )],
            links: vec![(
                stage.join(DIAGNOSIS).join("index.html"),
                "The diagnosis of this model (what is left)".to_string(),
            )],
            ..Page::new(&dir.join(MODEL), &data)
        },
        &stage.join(REPORT),
    )?;
    Ok(())
}
