//! `dtg-vib fleet`: a lot of units ([`dtg_vib::fleet`]) — one unit's task,
//! every task on this machine, a plan for a batch engine, the lot's
//! summary. The manifest's `[options]` are `explain`'s own flags, read
//! here from `explain`'s definition.

use anyhow::{Result, anyhow};
use clap::{Args, CommandFactory, Parser, Subcommand};
use cli_support::progress::Progress;
use dtg_vib::fleet::family::{DEFAULT_THRESHOLD, MIN_UNITS};
use dtg_vib::fleet::layout::{Layout, TASK};
use dtg_vib::fleet::manifest::{Catalogue, FlagKind, Manifest};
use dtg_vib::fleet::measure::Cost;
use dtg_vib::fleet::plan::{Engine, Target};
use dtg_vib::fleet::summary::Summary;
use dtg_vib::fleet::task::{Outcome, TaskRecord, explain_args};
use dtg_vib::fleet::{page, plan, run, summary, task};
use std::path::{Path, PathBuf};

/// The flags of `fleet`.
#[derive(Args)]
pub struct FleetArgs {
    #[command(subcommand)]
    command: FleetCommand,
}

#[derive(Subcommand)]
enum FleetCommand {
    /// Run one unit (entry --index K of the manifest) into DIR/units/ID: its
    /// explain, model and page; skipped when done; failed.json and exit 1
    /// when the unit fails.
    Task {
        /// The lot manifest (TOML, docs/formats.md).
        #[arg(long)]
        manifest: PathBuf,
        /// The entry, from 0 (a Slurm array's $SLURM_ARRAY_TASK_ID, a
        /// Kubernetes Indexed Job's $JOB_COMPLETION_INDEX).
        #[arg(long)]
        index: usize,
        /// The lot's output folder.
        #[arg(long)]
        out: PathBuf,
    },
    /// Run every unit's task on this machine, --jobs at a time, skipping done units.
    Run {
        /// The lot manifest.
        #[arg(long)]
        manifest: PathBuf,
        /// The lot's output folder.
        #[arg(long)]
        out: PathBuf,
        /// Tasks at a time (default: one per core; each then gets cores / jobs threads).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
        jobs: Option<u64>,
    },
    /// Write a Slurm job-array script or a Kubernetes Indexed Job for the
    /// lot into DIR/plan, its requests from a measured task (task 0 is run
    /// first when no unit is done).
    Plan {
        /// The lot manifest.
        #[arg(long)]
        manifest: PathBuf,
        /// The lot's output folder.
        #[arg(long)]
        out: PathBuf,
        /// The engine.
        #[arg(long, value_parser = ["slurm", "kubernetes"])]
        engine: String,
        /// The dtg-vib the elements run (default: this one for slurm, `dtg-vib` in the image for kubernetes).
        #[arg(long)]
        program: Option<PathBuf>,
        /// Kubernetes: the image holding dtg-vib.
        #[arg(long, default_value = "dtg-vib:latest")]
        image: String,
        /// Kubernetes: the PersistentVolumeClaim holding the lot's files and --out.
        #[arg(long, default_value = "fleet-lot")]
        claim: String,
    },
    /// Summarise the lot in DIR: coefficients per channel and effect, units
    /// out of family, failing the spec, failed; writes DIR/index.html and DIR/summary.json.
    Summary {
        /// The lot's output folder.
        #[arg(long)]
        out: PathBuf,
        /// Print the summary as one JSON object.
        #[arg(long)]
        json: bool,
        /// Robust z beyond which a unit is out of family (with its interval excluding the lot's median).
        #[arg(long = "robust-z", default_value_t = DEFAULT_THRESHOLD, value_parser = parse_z)]
        robust_z: f64,
    },
}

/// `--robust-z`: a positive number.
fn parse_z(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!(
            "'{s}': a robust z threshold is a positive number of robust standard deviations (e.g. 5)"
        )),
    }
}

/// `explain`'s flags as manifest options.
fn catalogue() -> Catalogue {
    let cli = super::Cli::command();
    let explain = cli
        .find_subcommand("explain")
        .expect("explain is a subcommand");
    let flags = explain
        .get_arguments()
        .filter_map(|a| {
            let long = a.get_long()?;
            let kind = match a.get_action() {
                clap::ArgAction::SetTrue => FlagKind::Switch,
                clap::ArgAction::Append => match a.get_value_delimiter() {
                    Some(d) => FlagKind::Joined(d),
                    None => FlagKind::Repeated,
                },
                _ => FlagKind::Value,
            };
            Some((long.replace('-', "_"), kind))
        })
        .filter(|(k, _)| k != "help")
        .collect();
    Catalogue { flags }
}

/// The manifest, its options checked by `explain`'s own parser.
fn load(path: &Path) -> Result<Manifest> {
    let m = Manifest::load(path, &catalogue())?;
    let mut args = vec!["dtg-vib".to_string()];
    args.extend(explain_args(&m, &m.entries[0], Path::new("/tmp/check")));
    if let Err(e) = super::Cli::try_parse_from(&args) {
        let text = e.to_string();
        let first = text
            .lines()
            .next()
            .unwrap_or("")
            .trim_start_matches("error: ");
        anyhow::bail!(
            "{}: [options]: explain refuses them: {first}",
            path.display()
        );
    }
    Ok(m)
}

fn program() -> Result<PathBuf> {
    std::env::current_exe().map_err(|e| anyhow!("the dtg-vib binary's path: {e}"))
}

fn cost_line(c: &Cost) -> String {
    let cpu = c
        .cpu_seconds
        .map_or(String::new(), |s| format!(", {s:.1} s CPU"));
    let rss = c.max_rss_bytes.map_or(String::new(), |b| {
        format!(", peak {:.0} MiB", b as f64 / 1048576.0)
    });
    format!("{:.1} s{cpu}{rss}", c.seconds)
}

/// Runs `fleet`.
pub fn run(a: FleetArgs, progress: Progress) -> Result<()> {
    match a.command {
        FleetCommand::Task {
            manifest,
            index,
            out,
        } => run_task(&manifest, index, &out),
        FleetCommand::Run {
            manifest,
            out,
            jobs,
        } => run_all(&manifest, &out, jobs, progress),
        FleetCommand::Plan {
            manifest,
            out,
            engine,
            program: given,
            image,
            claim,
        } => {
            let engine: Engine = engine.parse().map_err(|e| anyhow!("--engine {e}"))?;
            let program = match (given, engine) {
                (Some(p), _) => p,
                (None, Engine::Slurm) => program()?,
                (None, Engine::Kubernetes) => PathBuf::from("dtg-vib"),
            };
            write_plan(
                &manifest,
                &out,
                engine,
                Target {
                    program,
                    image,
                    claim,
                },
                progress,
            )
        }
        FleetCommand::Summary {
            out,
            json,
            robust_z,
        } => summarise(&out, json, robust_z),
    }
}

fn run_task(manifest: &Path, index: usize, out: &Path) -> Result<()> {
    let m = load(manifest)?;
    let layout = Layout::new(out);
    match task::run(&m, index, &layout, &program()?)? {
        Outcome::Skipped(t) => println!(
            "{}: already done ({}): skipped",
            t.id,
            layout.unit(&t.id).join(TASK).display()
        ),
        Outcome::Done(t) => println!(
            "{}: done in {} ({})",
            t.id,
            cost_line(&t.cost),
            layout.unit(&t.id).display()
        ),
        Outcome::Failed(f) => anyhow::bail!(
            "{} failed: {} ({})",
            f.id,
            f.reason,
            layout.unit(&f.id).join("failed.json").display()
        ),
    }
    Ok(())
}

fn run_all(manifest: &Path, out: &Path, jobs: Option<u64>, progress: Progress) -> Result<()> {
    let m = load(manifest)?;
    let layout = Layout::new(out);
    let jobs = jobs.map_or_else(
        || std::thread::available_parallelism().map_or(1, |n| n.get()),
        |j| j as usize,
    );
    let r = run::run(&m, &layout, &program()?, jobs, &|p| progress.say(p.line()))?;
    progress.clear();
    let finished = r.done.len() + r.failed.len() + r.errors.len();
    println!(
        "{} units: {} done now, {} already done, {} failed ({:.1} s; {})",
        m.entries.len(),
        r.done.len(),
        r.skipped.len(),
        r.failed.len() + r.errors.len(),
        r.seconds,
        match finished {
            0 => "nothing to run".to_string(),
            n => format!("{:.1} s a unit with {jobs} at a time", r.seconds / n as f64),
        }
    );
    if let Some(line) = done_cost(&r.done) {
        println!("{line}");
    }
    for f in &r.failed {
        println!("{} failed: {}", f.id, f.reason);
    }
    for (id, e) in &r.errors {
        println!("{id}: its task did not run: {e}");
    }
    println!("summary: dtg-vib fleet summary --out {}", out.display());
    if !r.failed.is_empty() || !r.errors.is_empty() {
        anyhow::bail!(
            "{} of {} units failed (their reasons above and in DIR/units/ID/failed.json)",
            r.failed.len() + r.errors.len(),
            m.entries.len()
        );
    }
    Ok(())
}

/// What the units done now cost on average (the figure to plan a lot
/// with: CPU time does not grow with the tasks run side by side as wall
/// time does), and the largest peak memory.
fn done_cost(done: &[TaskRecord]) -> Option<String> {
    let cpu: Vec<f64> = done.iter().filter_map(|t| t.cost.cpu_seconds).collect();
    let rss = done.iter().filter_map(|t| t.cost.max_rss_bytes).max();
    if cpu.is_empty() {
        return None;
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let wall: Vec<f64> = done.iter().map(|t| t.cost.seconds).collect();
    Some(format!(
        "a unit done now: {:.2} s CPU, {:.2} s wall on average over {}{}",
        mean(&cpu),
        mean(&wall),
        cpu.len(),
        rss.map_or(String::new(), |b| format!(
            "; peak memory {:.0} MiB",
            b as f64 / 1048576.0
        ))
    ))
}

/// The costliest done task of the lot, if any.
fn measured(m: &Manifest, layout: &Layout) -> Option<TaskRecord> {
    m.entries
        .iter()
        .filter_map(|e| {
            dtg_vib::fleet::layout::read_json::<TaskRecord>(&layout.unit(&e.id).join(TASK)).ok()
        })
        .max_by(|a, b| a.cost.seconds.total_cmp(&b.cost.seconds))
}

fn write_plan(
    manifest: &Path,
    out: &Path,
    engine: Engine,
    t: Target,
    progress: Progress,
) -> Result<()> {
    let m = load(manifest)?;
    let layout = Layout::new(out);
    layout.claim(&m)?;
    let mut k = 0;
    while measured(&m, &layout).is_none() && k < m.entries.len().min(3) {
        progress.say(format!(
            "measuring a task: running {} (--index {k})",
            m.entries[k].id
        ));
        // A failed unit exits 1: the next one is tried.
        let _ = run::task_command(&program()?, &m.path, k, out).output();
        k += 1;
    }
    progress.clear();
    let done = measured(&m, &layout).ok_or_else(|| {
        anyhow!(
            "no task could be measured: the first {k} units failed (see {}/units/ID/failed.json)",
            out.display()
        )
    })?;
    let p = plan::write(&m, &layout, engine, &t, &done.cost)?;
    println!(
        "measured: {} ({}) on {}",
        done.id,
        cost_line(&done.cost),
        done.host
    );
    println!(
        "requests: {} CPU, {} MiB, {} min a unit",
        p.requests.cpus, p.requests.memory_mib, p.requests.minutes
    );
    println!("plan: {}", p.file.display());
    println!("submit: {}", p.submit);
    println!("when every element has ended: {}", p.summarise);
    Ok(())
}

fn summarise(out: &Path, json: bool, robust_z: f64) -> Result<()> {
    let layout = Layout::new(out);
    let s = summary::summarise(&layout, robust_z, MIN_UNITS)?;
    dtg_vib::fleet::layout::write_json(&out.join("summary.json"), &s)?;
    let index = page::write(&s, out)?;
    if json {
        println!("{}", serde_json::to_string(&s)?);
        eprintln!("page: {}", index.display());
        return Ok(());
    }
    print_summary(&s);
    println!("page: {}", index.display());
    Ok(())
}

fn print_summary(s: &Summary) {
    use dtg_vib::fleet::summary::Status;
    let count = |st| s.units.iter().filter(|u| u.status == st).count();
    println!(
        "lot '{}': {} units: {} done, {} failed, {} not run",
        s.lot,
        s.units.len(),
        count(Status::Done),
        count(Status::Failed),
        count(Status::NotRun)
    );
    println!("channel  effect  units  median  MAD  robust σ  (the coefficient's unit)");
    for g in &s.groups {
        println!(
            "{:>7}  {:>6}  {:>5}  {:.4}  {:.4}  {:.4}  {}{}",
            g.channel,
            g.effect,
            g.members.len(),
            g.median,
            g.mad,
            g.robust_sigma,
            g.unit,
            if g.judged {
                ""
            } else {
                "  (too few units to judge)"
            }
        );
    }
    println!(
        "out of family (robust z beyond {} and the 95% interval excluding the lot's median): {}",
        s.threshold,
        if s.out_of_family.is_empty() {
            "none"
        } else {
            ""
        }
    );
    for o in &s.out_of_family {
        println!(
            "  {}  {} {}  {:.4} {} (95% CI {:.4} to {:.4}), z {:.1}, lot median {:.4}",
            o.unit,
            o.channel,
            o.effect,
            o.value,
            o.coefficient_unit,
            o.ci95[0],
            o.ci95[1],
            o.z,
            o.median
        );
    }
    println!(
        "failing the spec: {}",
        if s.failing_spec.is_empty() {
            "none"
        } else {
            ""
        }
    );
    for f in &s.failing_spec {
        println!(
            "  {}  {}  {} {:.4} > limit {} {}",
            f.unit, f.channel, f.limit_key, f.value, f.limit, f.value_unit
        );
    }
    println!("failed: {}", if s.failed.is_empty() { "none" } else { "" });
    for f in &s.failed {
        println!("  {}: {}", f.unit, f.reason);
    }
    if !s.not_run.is_empty() {
        println!("not run yet: {}", s.not_run.join(", "));
    }
}
