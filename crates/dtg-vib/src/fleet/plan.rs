//! What an existing batch engine needs to run a lot: a Slurm job-array
//! script or a Kubernetes Indexed Job, one element per unit running
//! `dtg-vib fleet task --index K`, with CPU, memory and time requests
//! taken from a measured task, and the command that summarises the lot
//! once the elements have ended.

use super::layout::Layout;
use super::manifest::Manifest;
use super::measure::Cost;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// The engines a plan is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engine {
    /// A Slurm job array (`sbatch`).
    Slurm,
    /// A Kubernetes Indexed Job (`kubectl apply -f`).
    Kubernetes,
}

impl std::str::FromStr for Engine {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "slurm" => Ok(Self::Slurm),
            "kubernetes" => Ok(Self::Kubernetes),
            other => Err(format!("'{other}': use slurm or kubernetes")),
        }
    }
}

/// What one task asks of a node, from a measured task.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Requests {
    /// Cores: the measured average rounded (at least 1).
    pub cpus: usize,
    /// Memory, MiB: 1.5 × the measured peak, in steps of 64 MiB, at least 128.
    pub memory_mib: u64,
    /// Time limit, minutes: 5 × the measured wall time, at least 5.
    pub minutes: u64,
}

impl Requests {
    /// The requests `cost` calls for (memory 1 GiB when it was not measured).
    pub fn of(cost: &Cost) -> Self {
        let cpus = cost
            .parallelism()
            .map_or(1, |p| p.round().max(1.0) as usize);
        let memory_mib = match cost.max_rss_bytes {
            Some(b) => {
                let mib = (1.5 * b as f64 / (1024.0 * 1024.0)).ceil() as u64;
                mib.div_ceil(64).max(2) * 64
            }
            None => 1024,
        };
        let minutes = ((5.0 * cost.seconds / 60.0).ceil() as u64).max(5);
        Self {
            cpus,
            memory_mib,
            minutes,
        }
    }
}

/// Where the engine finds things, and what a Kubernetes pod runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    /// The `dtg-vib` the elements run (Slurm: a path every node sees;
    /// Kubernetes: the command in the image).
    pub program: PathBuf,
    /// Kubernetes: the image holding `dtg-vib`.
    pub image: String,
    /// Kubernetes: the PersistentVolumeClaim holding the lot and `DIR`,
    /// mounted at their common folder.
    pub claim: String,
}

/// A written plan.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// The file to submit.
    pub file: PathBuf,
    /// The requests of each element.
    pub requests: Requests,
    /// How to submit it.
    pub submit: String,
    /// What to run once every element has ended.
    pub summarise: String,
}

/// A path quoted for a POSIX shell.
fn sh(p: &Path) -> String {
    format!("'{}'", p.display().to_string().replace('\'', r"'\''"))
}

/// A name Kubernetes takes (lowercase letters, digits and '-', ≤ 40
/// characters, leaving room for the index in pod names).
fn k8s_name(lot: &str) -> String {
    let mut s: String = lot
        .to_lowercase()
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    while s.contains("--") {
        s = s.replace("--", "-");
    }
    let s = format!("fleet-{}", s.trim_matches('-'));
    s.chars()
        .take(40)
        .collect::<String>()
        .trim_end_matches('-')
        .to_string()
}

/// The Slurm job-array script of `m`'s lot into `out`.
pub fn slurm_script(m: &Manifest, out: &Layout, t: &Target, r: &Requests, cost: &Cost) -> String {
    let n = m.entries.len();
    let dir = out.root();
    let summary = format!("{} fleet summary --out {}", sh(&t.program), sh(dir));
    format!(
        "#!/bin/bash
# The lot '{name}' ({manifest}): one array element per unit, each running
# `dtg-vib fleet task --index $SLURM_ARRAY_TASK_ID`; a rerun skips done units.
# Requests from a measured task: {secs:.1} s wall, {cpu} CPU, peak {rss}.
# Submit:     sbatch {script}
# When every element has ended: {summary}
#   (or at once: sbatch --dependency=afterany:JOBID --wrap \"{summary}\")
#SBATCH --job-name={job}
#SBATCH --array=0-{last}
#SBATCH --cpus-per-task={cpus}
#SBATCH --mem={mem}M
#SBATCH --time={min}
#SBATCH --output={logs}/task-%a.log
export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-{cpus}}}\"
exec {program} --quiet fleet task --manifest {manifest_sh} --index \"$SLURM_ARRAY_TASK_ID\" --out {dir_sh}
",
        name = m.name,
        manifest = m.path.display(),
        secs = cost.seconds,
        cpu = cost
            .cpu_seconds
            .map_or("unmeasured".to_string(), |c| format!("{c:.1} s")),
        rss = cost.max_rss_bytes.map_or("unmeasured".to_string(), |b| format!(
            "{:.0} MiB",
            b as f64 / 1048576.0
        )),
        script = out.root().join("plan").join("slurm-array.sh").display(),
        job = k8s_name(&m.name),
        last = n.saturating_sub(1),
        cpus = r.cpus,
        mem = r.memory_mib,
        min = r.minutes,
        logs = dir.join("logs").display(),
        program = sh(&t.program),
        manifest_sh = sh(&m.path),
        dir_sh = sh(dir),
    )
}

/// The deepest folder holding both `a` and `b`.
fn common_folder(a: &Path, b: &Path) -> PathBuf {
    a.components()
        .zip(b.components())
        .take_while(|(x, y)| x == y)
        .map(|(x, _)| x)
        .collect()
}

/// The Kubernetes Indexed Job of `m`'s lot into `out`, as JSON values.
pub fn kubernetes_job(m: &Manifest, out: &Layout, t: &Target, r: &Requests) -> Value {
    let n = m.entries.len();
    let dir = std::path::absolute(out.root()).unwrap_or_else(|_| out.root().to_path_buf());
    let lot_dir = m.path.parent().unwrap_or(Path::new("/"));
    let mount = common_folder(lot_dir, &dir);
    let mem = format!("{}Mi", r.memory_mib);
    json!({
        "apiVersion": "batch/v1",
        "kind": "Job",
        "metadata": {
            "name": k8s_name(&m.name),
            "labels": { "app.kubernetes.io/name": "dtg-vib-fleet" },
            "annotations": { "dtg-vib/lot": m.name, "dtg-vib/manifest": m.path.display().to_string() }
        },
        "spec": {
            "completionMode": "Indexed",
            "completions": n,
            "parallelism": n,
            // A failed unit fails its index only; the lot goes on.
            "backoffLimitPerIndex": 1,
            "maxFailedIndexes": n,
            "podFailurePolicy": { "rules": [{
                "action": "FailIndex",
                "onExitCodes": { "containerName": "task", "operator": "In", "values": [1] }
            }]},
            "template": { "spec": {
                "restartPolicy": "Never",
                "activeDeadlineSeconds": r.minutes * 60,
                "containers": [{
                    "name": "task",
                    "image": t.image,
                    "command": [t.program.display().to_string()],
                    "args": ["--quiet", "fleet", "task",
                             "--manifest", m.path.display().to_string(),
                             "--index", "$(JOB_COMPLETION_INDEX)",
                             "--out", dir.display().to_string()],
                    "env": [{ "name": "RAYON_NUM_THREADS", "value": r.cpus.to_string() }],
                    "resources": {
                        "requests": { "cpu": r.cpus.to_string(), "memory": mem },
                        "limits": { "memory": mem }
                    },
                    "volumeMounts": [{ "name": "lot", "mountPath": mount.display().to_string() }]
                }],
                "volumes": [{ "name": "lot", "persistentVolumeClaim": { "claimName": t.claim } }]
            }}
        }
    })
}

/// Writes the plan for `engine` into `DIR/plan/`.
pub fn write(
    m: &Manifest,
    out: &Layout,
    engine: Engine,
    t: &Target,
    cost: &Cost,
) -> Result<Plan, super::layout::LayoutError> {
    let r = Requests::of(cost);
    // The engine runs elsewhere, from another folder: every path absolute.
    let out = &Layout::new(std::path::absolute(out.root()).map_err(|source| {
        super::layout::LayoutError::Io {
            path: out.root().to_path_buf(),
            source,
        }
    })?);
    let plan_dir = out.root().join("plan");
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| super::layout::LayoutError::Io { path, source }
    };
    std::fs::create_dir_all(&plan_dir).map_err(io(&plan_dir))?;
    let summarise = format!(
        "{} fleet summary --out {}",
        t.program.display(),
        out.root().display()
    );
    let (file, text, submit) = match engine {
        Engine::Slurm => {
            let logs = out.root().join("logs");
            std::fs::create_dir_all(&logs).map_err(io(&logs))?;
            let f = plan_dir.join("slurm-array.sh");
            let submit = format!("sbatch {}", f.display());
            (f, slurm_script(m, out, t, &r, cost), submit)
        }
        Engine::Kubernetes => {
            let f = plan_dir.join("job.yaml");
            let header = format!(
                "# The lot '{}': a Kubernetes Indexed Job, one index per unit.\n# Submit: kubectl apply -f {}\n# When it has ended: {summarise}\n",
                m.name,
                f.display()
            );
            let submit = format!("kubectl apply -f {}", f.display());
            (f, header + &yaml(&kubernetes_job(m, out, t, &r)), submit)
        }
    };
    outfile::write_bytes(&file, text).map_err(io(&file))?;
    Ok(Plan {
        file,
        requests: r,
        submit,
        summarise,
    })
}

/// A JSON value as block YAML: strings as JSON strings (a YAML
/// double-quoted scalar), so nothing needs YAML's own quoting rules.
pub fn yaml(v: &Value) -> String {
    let mut out = String::new();
    block(v, 0, &mut out);
    out
}

/// A key YAML reads as the same string unquoted.
fn plain_key(k: &str) -> bool {
    k.starts_with(|c: char| c.is_ascii_alphabetic())
        && k.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '/' | '-' | '_'))
}

fn scalar(v: &Value) -> String {
    match v {
        Value::Object(o) if o.is_empty() => "{}".into(),
        Value::Array(a) if a.is_empty() => "[]".into(),
        other => other.to_string(),
    }
}

fn nested(v: &Value) -> bool {
    matches!(v, Value::Object(o) if !o.is_empty()) || matches!(v, Value::Array(a) if !a.is_empty())
}

fn block(v: &Value, indent: usize, out: &mut String) {
    let pad = " ".repeat(indent);
    match v {
        Value::Object(o) => {
            for (k, x) in o {
                let key = match plain_key(k) {
                    true => k.clone(),
                    false => Value::String(k.clone()).to_string(),
                };
                match nested(x) {
                    true => {
                        out.push_str(&format!("{pad}{key}:\n"));
                        block(x, indent + 2, out);
                    }
                    false => out.push_str(&format!("{pad}{key}: {}\n", scalar(x))),
                }
            }
        }
        Value::Array(a) => {
            for x in a {
                match nested(x) {
                    true => {
                        // The item's first line after "- ", the rest indented under it.
                        let mut inner = String::new();
                        block(x, indent + 2, &mut inner);
                        let trimmed = inner.get(indent + 2..).unwrap_or("");
                        out.push_str(&format!("{pad}- {trimmed}"));
                    }
                    false => out.push_str(&format!("{pad}- {}\n", scalar(x))),
                }
            }
        }
        other => out.push_str(&format!("{pad}{}\n", scalar(other))),
    }
}
