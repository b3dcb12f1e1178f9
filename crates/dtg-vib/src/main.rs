//! `dtg-vib`: the command line. Parsing, reading, calling the library,
//! printing; nothing else lives here.

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use dtg_vib::apply::{Applied, write_residues};
use dtg_vib::diagnose::{DiagnoseOptions, diagnose};
use dtg_vib::effects::{ChannelEffect, Effect};
use dtg_vib::figures::{Baseline, write_diagnosis_report, write_report};
use dtg_vib::fit::{CentreMethod, FitOptions, FitStage, fit};
use dtg_vib::model::CompensationModel;
use dtg_vib::pipeline::{FilterSpec, Preprocess, RateReference};
use dtg_vib::split::SplitKind;
use dtg_vib::window::WindowSpec;
use indicatif::{ProgressBar, ProgressStyle};
use nav_sensors::calibration::Calibration;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, Site, simulate};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Duration;

#[derive(Parser)]
#[command(
    name = "dtg-vib",
    version,
    about = "Identify and compensate vibration-induced DTG errors with RBF networks, and find what the model is missing"
)]
struct Cli {
    /// No progress display on stderr.
    #[arg(long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a sensor-unit vibration test (default: the paper's Z-axis random test).
    Simulate {
        /// Scenario file (TOML, see docs/formats.md).
        #[arg(long, conflicts_with = "builtin")]
        scenario: Option<PathBuf>,
        /// A built-in scenario: paper_z_random, triaxial_clean, triaxial_hidden, demo.
        #[arg(long)]
        builtin: Option<String>,
        /// Override the scenario's seed.
        #[arg(long)]
        seed: Option<u64>,
        /// Output directory (record.csv, calibration.json, truth.json, components.csv, scenario.toml).
        #[arg(long)]
        out: PathBuf,
    },
    /// Fit the six channel models on a test record.
    // Negative numbers are values here: a southern latitude (--earth-rate -33.9),
    // a table turning backwards (--table-rate -1,0,0).
    #[command(allow_negative_numbers = true)]
    Fit(Box<FitArgs>),
    /// Write the record compensated by a model.
    Compensate {
        /// Model file from `fit`.
        #[arg(long)]
        model: PathBuf,
        /// Test record (CSV).
        #[arg(long)]
        data: PathBuf,
        /// Output CSV (same columns; rows from the first full window on).
        #[arg(long)]
        out: PathBuf,
    },
    /// Write the parity residues K0..K5 (eq. 6), and with a model the compensated ones.
    Residues {
        /// Test record (CSV).
        #[arg(long)]
        data: PathBuf,
        /// Model file: adds K*_pre (calibrated, filtered) and K*_comp (compensated) columns.
        #[arg(long)]
        model: Option<PathBuf>,
        /// Output CSV.
        #[arg(long)]
        out: PathBuf,
    },
    /// Write the figures and index.html of a model on a record.
    Report {
        /// Model file from `fit`.
        #[arg(long)]
        model: PathBuf,
        /// Test record (CSV).
        #[arg(long)]
        data: PathBuf,
        /// An earlier model of the same record, to show each channel's error before and after.
        #[arg(long)]
        baseline: Option<PathBuf>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
    },
    /// Find what a model is missing: compare, locate failures, rank candidate effects.
    Diagnose {
        /// Model file from `fit`.
        #[arg(long)]
        model: PathBuf,
        /// The test record it was fitted on.
        #[arg(long)]
        data: PathBuf,
        /// Print one JSON object on stdout.
        #[arg(long)]
        json: bool,
        /// Write figures and index.html into this directory.
        #[arg(long)]
        report: Option<PathBuf>,
    },
    /// Export a causal model for onboard use: C99 sources and tables (--lang c), or equations (--lang text).
    Export {
        /// Model file from `fit --causal` (any model for --lang text).
        #[arg(long)]
        model: PathBuf,
        /// c: dtg_model.h, dtg_model.c, main.c and model.dtgo into --out; text: equations on stdout.
        #[arg(long)]
        lang: String,
        /// Output directory (--lang c).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Tables and arithmetic of the C: f64 (equal to `compensate`) or f32.
        #[arg(long, default_value = "f64")]
        precision: String,
    },
    /// The main job on a built-in default: simulate, fit, compensate, report, diagnose, refit.
    Demo {
        /// Output directory.
        #[arg(long, default_value = "demo-out")]
        out: PathBuf,
    },
}

#[derive(Args)]
struct FitArgs {
    /// Test record (CSV: t,X,X1,Y,Y1,Z,Z1,ax,ay,az[,extra columns]).
    #[arg(long)]
    data: PathBuf,
    /// Ground-calibration file (JSON); without it nothing is compensated.
    #[arg(long)]
    calib: Option<PathBuf>,
    /// Physical effects of every channel, comma-separated (g_I, gg_IS, ai_OS, col:NAME, ...).
    #[arg(long, value_delimiter = ',')]
    effects: Vec<String>,
    /// An effect for one channel, CHANNEL=ID (repeatable), e.g. Y1=gg_IS.
    #[arg(long = "add-effect")]
    add_effect: Vec<String>,
    /// Centre selection.
    #[arg(long, default_value = "ols")]
    centers: String,
    /// Window length, samples (the paper: 50).
    #[arg(long, default_value_t = 50)]
    window: usize,
    /// Windowed signals, comma-separated (accelerometer axes or extra columns).
    #[arg(long = "window-signals", value_delimiter = ',', default_value = "az")]
    window_signals: Vec<String>,
    /// Training/validation split: blocked (honest) or interleaved (the paper's).
    #[arg(long, default_value = "blocked")]
    split: String,
    /// Fraction of the rows that train in a blocked split.
    #[arg(long = "train-fraction", default_value_t = 0.5)]
    train_fraction: f64,
    /// Largest number of RBF centres tried by cross-validation.
    #[arg(long = "max-centers", default_value_t = 60)]
    max_centers: usize,
    /// OLS candidate centres: a seeded subsample of this many training windows.
    #[arg(long, default_value_t = 400)]
    candidates: usize,
    /// Low-pass cut-off of outputs and effects, Hz (zero-phase Butterworth).
    #[arg(long, default_value_t = 5.0, conflicts_with = "no_filter")]
    cutoff: f64,
    /// Low-pass order.
    #[arg(long = "filter-order", default_value_t = 4)]
    filter_order: usize,
    /// No low-pass at all.
    #[arg(long = "no-filter")]
    no_filter: bool,
    /// Also low-pass the windowed inputs at this cut-off, Hz (the paper filtered them).
    #[arg(long = "input-cutoff")]
    input_cutoff: Option<f64>,
    /// Rate reference: Earth rate at this latitude, deg (cluster x north, z up).
    #[arg(long = "earth-rate", conflicts_with = "table_rate", value_parser = parse_latitude)]
    earth_rate: Option<f64>,
    /// Rate reference: a known table rate about cluster x,y,z, deg/s (WX,WY,WZ).
    // "-0.01,0,0" is not one number, so allow_negative_numbers does not cover it.
    #[arg(
        long = "table-rate",
        value_name = "WX,WY,WZ",
        value_parser = parse_rate,
        allow_hyphen_values = true
    )]
    table_rate: Option<[f64; 3]>,
    /// Ridge on the output weights.
    #[arg(long, default_value_t = 1e-8)]
    ridge: f64,
    /// Seed of the candidate subsample and k-means.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Causal mode: causal low-passes, so the model runs on-line with one
    /// period of latency (`dtg-vib export`) and `compensate` runs sample by sample.
    #[arg(long)]
    causal: bool,
    /// Model file to write.
    #[arg(long)]
    out: PathBuf,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// `dtg-vib export`: the model as C99 sources and onboard tables, or as equations.
fn export_command(
    model_path: &std::path::Path,
    lang: &str,
    out: Option<&std::path::Path>,
    precision: &str,
) -> anyhow::Result<()> {
    let model = CompensationModel::load(model_path)?;
    match lang {
        "text" => {
            print!("{}", dtg_vib::export::equations(&model));
            Ok(())
        }
        "c" => {
            let Some(out) = out else {
                anyhow::bail!("--lang c writes files: give the directory with --out DIR");
            };
            let precision: dtg_vib::export::Precision = precision.parse()?;
            let files = ["dtg_model.h", "dtg_model.c", "main.c", "model.dtgo"];
            outfile::guard_dir("--out", out, &files, &[("--model", Some(model_path))])?;
            let c = dtg_vib::export::c_sources(&model, precision)?;
            let tables = dtg_vib::export::tables(&model)?;
            std::fs::create_dir_all(out)
                .map_err(|e| anyhow::anyhow!("--out {}: {e}", out.display()))?;
            for (name, text) in c.files() {
                outfile::write_bytes(out.join(name), text)
                    .map_err(|e| anyhow::anyhow!("{}: {e}", out.join(name).display()))?;
            }
            let bin = out.join("model.dtgo");
            outfile::write_bytes(&bin, &tables.bytes)
                .map_err(|e| anyhow::anyhow!("{}: {e}", bin.display()))?;
            let m = dtg_onboard::Model::parse(&tables.bytes).map_err(|e| anyhow::anyhow!("{e}"))?;
            println!(
                "wrote {}: dtg_model.h, dtg_model.c, main.c (cc -O2 -std=c99 *.c -lm), model.dtgo ({} bytes of tables, {} f64 of state, {} flops per step; extra columns: {})",
                out.display(),
                m.size_bytes(),
                m.state_len(),
                m.flops_per_step(),
                if tables.extra.is_empty() {
                    "none".to_string()
                } else {
                    tables.extra.join(", ")
                }
            );
            Ok(())
        }
        other => anyhow::bail!("--lang {other}: use c (C99 sources) or text (equations)"),
    }
}

fn main() {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => usage_error(e),
    };
    if let Err(e) = run(cli) {
        // One line: what, where (the library's errors carry file:line:column),
        // how to fix. Causes are joined unless the message already quotes them
        // (many errors print their source themselves).
        let mut msg = String::new();
        for cause in e.chain().map(|c| c.to_string()) {
            if msg.is_empty() {
                msg = cause;
            } else if !msg.contains(&cause) {
                msg = format!("{msg}: {cause}");
            }
        }
        eprintln!("error: {}", msg.replace('\n', "; "));
        std::process::exit(1);
    }
}

/// A command-line usage error on one line, like every other error: clap's
/// message and any tip, without the usage block (`--help` has it). Help and
/// version requests print as clap prints them.
fn usage_error(e: clap::Error) -> ! {
    use clap::error::ErrorKind;
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        e.exit();
    }
    let text = e.to_string();
    let mut line = String::new();
    for part in text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
    {
        if !line.is_empty() {
            line.push_str(if line.ends_with(':') { " " } else { "; " });
        }
        line.push_str(part);
    }
    eprintln!("{line} (see --help)");
    std::process::exit(2);
}

/// A spinner on stderr, or nothing when quiet or not a terminal.
struct Progress(Option<ProgressBar>);

impl Progress {
    fn new(quiet: bool) -> Self {
        if quiet || !std::io::stderr().is_terminal() {
            return Self(None);
        }
        let pb = ProgressBar::new_spinner();
        pb.set_style(
            ProgressStyle::with_template("{spinner} {elapsed:>3} {msg}").expect("static template"),
        );
        pb.enable_steady_tick(Duration::from_millis(120));
        Self(Some(pb))
    }
    fn say(&self, msg: impl Into<String>) {
        if let Some(pb) = &self.0 {
            pb.set_message(msg.into());
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(pb) = &self.0 {
            pb.finish_and_clear();
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    let progress = Progress::new(cli.quiet);
    match cli.command {
        Command::Simulate {
            scenario,
            builtin,
            seed,
            out,
        } => {
            let scenario_path = scenario.clone();
            let mut s = match (scenario, builtin) {
                (Some(path), _) => Scenario::load(&path)?,
                (None, Some(name)) => Scenario::builtin(&name).with_context(|| {
                    format!(
                        "unknown built-in scenario '{name}' (valid: {})",
                        Scenario::BUILTIN.join(", ")
                    )
                })?,
                (None, None) => Scenario::default(),
            };
            if let Some(seed) = seed {
                s.seed = seed;
            }
            if let Some(p) = &scenario_path {
                // Named with the file, before anything is written.
                s.validate()
                    .map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))?;
            }
            outfile::guard_dir(
                "--out",
                &out,
                &nav_sensors::sim::Simulation::FILES,
                &[("--scenario", scenario_path.as_deref())],
            )?;
            progress.say(format!("simulating '{}' ({} s)", s.name, s.duration_s));
            let sim = simulate(&s)?;
            sim.write_dir(&out)?;
            drop(progress);
            println!("wrote {}", out.join("record.csv").display());
        }
        Command::Fit(args) => fit_command(*args, &progress)?,
        Command::Export {
            model,
            lang,
            out,
            precision,
        } => export_command(&model, &lang, out.as_deref(), &precision)?,
        Command::Compensate { model, data, out } => {
            outfile::guard_file(
                "--out",
                &out,
                &[("--model", Some(&model)), ("--data", Some(&data))],
            )?;
            let model = CompensationModel::load(&model)?;
            let record = Record::read_csv(&data)?;
            progress.say("compensating");
            let applied = Applied::unsplit(&model, &record)?;
            applied.compensated_record().write_csv(&out)?;
            drop(progress);
            eprintln!(
                "wrote {} ({} rows: the first {} samples have no full window)",
                out.display(),
                record.len() - applied.prepared.first_sample(),
                applied.prepared.first_sample()
            );
        }
        Command::Residues { data, model, out } => {
            outfile::guard_file(
                "--out",
                &out,
                &[("--data", Some(&data)), ("--model", model.as_deref())],
            )?;
            let record = Record::read_csv(&data)?;
            let applied = match &model {
                Some(m) => {
                    let m = CompensationModel::load(m)?;
                    let a = Applied::unsplit(&m, &record)?;
                    Some((m, a))
                }
                None => None,
            };
            write_residues(&out, &record, applied.as_ref().map(|(_, a)| a))?;
            drop(progress);
            // The validation rows of the model's split, if this record has them.
            if let Some((m, a)) = &applied
                && let Ok((_, val)) = m.rows(&a.prepared)
            {
                print_residues(&a.residues.stats(&val));
            }
            eprintln!("wrote {}", out.display());
        }
        Command::Report {
            model,
            data,
            baseline,
            out,
        } => {
            outfile::guard_dir(
                "--out",
                &out,
                &["index.html"],
                &[
                    ("--model", Some(&model)),
                    ("--data", Some(&data)),
                    ("--baseline", baseline.as_deref()),
                ],
            )?;
            let m = CompensationModel::load(&model)?;
            let record = Record::read_csv(&data)?;
            progress.say("applying the model");
            let applied = Applied::new(&m, &record)?;
            let base = match &baseline {
                Some(b) => {
                    let bm = CompensationModel::load(b)?;
                    let ba = Applied::new(&bm, &record)?;
                    Some((bm, ba))
                }
                None => None,
            };
            progress.say("drawing figures");
            let summary = write_report(
                &m,
                &applied,
                &record,
                &data.display().to_string(),
                base.as_ref().map(|(model, applied)| Baseline {
                    label: "baseline",
                    model,
                    applied,
                }),
                &out,
            )?;
            drop(progress);
            print_residues(&summary.residues);
            println!("report: {}", summary.index.display());
        }
        Command::Diagnose {
            model,
            data,
            json,
            report,
        } => {
            if let Some(dir) = &report {
                outfile::guard_dir(
                    "--report",
                    dir,
                    &["index.html"],
                    &[("--model", Some(&model)), ("--data", Some(&data))],
                )?;
            }
            let m = CompensationModel::load(&model)?;
            let record = Record::read_csv(&data)?;
            progress.say("diagnosing");
            let options = DiagnoseOptions::default();
            let d = diagnose(&m, &record, &options)?;
            let page = match &report {
                Some(dir) => {
                    progress.say("drawing figures");
                    Some(write_diagnosis_report(&d, options.rank.min_err(), dir)?)
                }
                None => None,
            };
            drop(progress);
            if json {
                // stdout holds the one JSON object; the page goes to stderr.
                println!("{}", serde_json::to_string(&d)?);
                if let Some(p) = &page {
                    eprintln!("report: {}", p.display());
                }
            } else {
                for c in &d.channels {
                    println!(
                        "{:>3}: validation rms {:.4} deg/h, fit {:.1}%; suggested: {}",
                        c.channel,
                        c.rms,
                        c.compare.val_fit_percent,
                        if c.suggested.is_empty() {
                            "nothing".to_string()
                        } else {
                            c.suggested.join(", ")
                        }
                    );
                    for f in &c.findings {
                        println!("     {f}");
                    }
                }
                if let Some(p) = &page {
                    println!("report: {}", p.display());
                }
            }
        }
        Command::Demo { out } => {
            outfile::guard_dir("--out", &out, &[], &[])?;
            let summary = dtg_vib::demo::run(&out, &|step| progress.say(step.to_string()))?;
            drop(progress);
            print_demo(&summary);
        }
    }
    Ok(())
}

fn fit_command(a: FitArgs, progress: &Progress) -> Result<()> {
    outfile::guard_file(
        "--out",
        &a.out,
        &[("--data", Some(&a.data)), ("--calib", a.calib.as_deref())],
    )?;
    let record = Record::read_csv(&a.data)?;
    let calibration = a.calib.as_ref().map(Calibration::load).transpose()?;
    let effects = Effect::parse_list(&a.effects.join(","))?;
    let add = a
        .add_effect
        .iter()
        .map(|s| s.parse::<ChannelEffect>())
        .collect::<Result<Vec<_>, _>>()?;
    let split = match a.split.parse::<SplitKind>()? {
        SplitKind::Blocked { .. } => SplitKind::Blocked {
            train_fraction: a.train_fraction,
        },
        other => other,
    };
    let filter = (!a.no_filter).then_some(FilterSpec {
        order: a.filter_order,
        cutoff_hz: a.cutoff,
    });
    let input_filter = a.input_cutoff.map(|c| FilterSpec {
        order: a.filter_order,
        cutoff_hz: c,
    });
    let rate_reference = match (a.earth_rate, &a.table_rate) {
        (Some(lat), _) => RateReference::Earth {
            site: Site {
                latitude_deg: lat,
                ..Site::default()
            },
        },
        (None, Some(w)) => RateReference::Table { rate_deg_s: *w },
        (None, None) => RateReference::None,
    };
    let options = FitOptions {
        preprocess: Preprocess {
            filter,
            input_filter,
            window: WindowSpec::new(a.window_signals.clone(), a.window)?,
            rate_reference,
            causal: a.causal,
        },
        effects,
        add,
        centres: a.centers.parse::<CentreMethod>()?,
        max_centres: a.max_centers,
        candidates: a.candidates,
        ridge: a.ridge,
        split,
        seed: a.seed,
        ..FitOptions::default()
    };
    let done = std::sync::atomic::AtomicUsize::new(0);
    let start = std::time::Instant::now();
    let model = fit(
        &record,
        calibration.as_ref(),
        &options,
        &|stage| match stage {
            FitStage::Preparing => progress.say("preparing the record"),
            FitStage::ChannelDone(ch) => {
                let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress.say(format!("fitted {n}/6 channels (last {ch})"));
            }
        },
    )?;
    let fit_seconds = start.elapsed().as_secs_f64();
    model.save(&a.out)?;
    if a.json {
        let channels: Vec<serde_json::Value> = model
            .channels()
            .iter()
            .map(|c| {
                let s = c.scores();
                serde_json::json!({
                    "channel": c.channel(),
                    "effects": c.effects().iter().map(|e| e.id()).collect::<Vec<_>>(),
                    "n_centers": c.n_centres(),
                    "train_rms": s.train_rms,
                    "val_rms": s.val_rms,
                    "val_rms_bias_only": s.val_rms_bias_only,
                    "val_fit_percent": s.val_fit_percent,
                    "width": c.width(),
                    "bias": c.bias(),
                    "effect_coefficients": c.effects().iter().zip(c.effect_coefficients()).map(|(e, v)| (e.id(), serde_json::json!({"value": v, "unit": e.unit()}))).collect::<serde_json::Map<_, _>>(),
                })
            })
            .collect();
        println!(
            "{}",
            serde_json::json!({ "channels": channels, "split": model.split().to_string(), "fit_seconds": fit_seconds })
        );
    } else {
        println!("channel  centres  train rms  val rms  (deg/h)  effects");
        for c in model.channels() {
            let s = c.scores();
            let e: Vec<String> = c.effects().iter().map(|e| e.id()).collect();
            println!(
                "{:>7}  {:>7}  {:>9.4}  {:>7.4}           {}",
                c.channel().name(),
                c.n_centres(),
                s.train_rms,
                s.val_rms,
                if e.is_empty() {
                    "—".into()
                } else {
                    e.join(", ")
                }
            );
        }
        println!("model: {} ({:.2} s)", a.out.display(), fit_seconds);
    }
    Ok(())
}

/// `WX,WY,WZ`: three numbers, comma-separated (clap's `num_args = 3` with a
/// delimiter would count `0,0,10` as one value and refuse it).
fn parse_rate(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|c| c.trim().parse::<f64>().map_err(|e| format!("'{c}': {e}")))
        .collect::<Result<_, _>>()?;
    if v.iter()
        .any(|w| !(w.is_finite() && w.abs() <= MAX_TABLE_RATE_DEG_S))
    {
        return Err(format!(
            "each rate must be finite and within ±{MAX_TABLE_RATE_DEG_S} deg/s"
        ));
    }
    v.try_into()
        .map_err(|v: Vec<f64>| format!("expected WX,WY,WZ (three numbers, deg/s), got {}", v.len()))
}

/// The fastest table rate `--table-rate` takes, deg/s: rate tables turn at
/// up to a few thousand deg/s; beyond, the rate reference only overflows.
const MAX_TABLE_RATE_DEG_S: f64 = 10_000.0;

fn parse_latitude(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() <= 90.0 => Ok(v),
        _ => Err(format!(
            "'{s}': a latitude must be a number from -90 to 90 (deg)"
        )),
    }
}

fn print_residues(stats: &[dtg_vib::residue::ResidueStats]) {
    println!("residue  rms before  rms after  (deg/h, validation rows)  reduction");
    for s in stats {
        println!(
            "{:>7}  {:>10.4}  {:>9.4}  {:>35.2}×",
            s.residue.name(),
            s.rms_before,
            s.rms_after,
            s.reduction
        );
    }
}

fn print_demo(s: &dtg_vib::demo::DemoSummary) {
    println!(
        "The paper's procedure on the simulated Z-axis random vibration test ({}):",
        s.record.display()
    );
    print_residues(&s.baseline_residues);
    println!();
    println!(
        "Diagnosis (hidden in the simulation: {}):",
        s.hidden.join(", ")
    );
    for c in &s.diagnosis.channels {
        println!(
            "  {:>3}: validation rms {:.4} deg/h; suggested: {}",
            c.channel,
            c.rms,
            if c.suggested.is_empty() {
                "nothing".into()
            } else {
                c.suggested.join(", ")
            }
        );
    }
    let added: Vec<String> = s
        .suggested
        .iter()
        .map(|a| format!("{}={}", a.channel, a.effect))
        .collect();
    println!();
    println!(
        "Refitted with {}:",
        if added.is_empty() {
            "nothing to add".into()
        } else {
            added.join(", ")
        }
    );
    println!("channel  val rms before  val rms after  (deg/h)");
    for (ch, b, a) in &s.channel_rms {
        println!(
            "{:>7}  {:>14.4}  {:>13.4}  {:+.1}%",
            ch.name(),
            b,
            a,
            100.0 * (a / b - 1.0)
        );
    }
    print_residues(&s.final_residues);
    println!();
    println!("reports:");
    println!("  paper's procedure: {}", s.baseline_report.display());
    println!("  diagnosis:         {}", s.diagnosis_report.display());
    println!("  after the refit:   {}", s.final_report.display());
}
