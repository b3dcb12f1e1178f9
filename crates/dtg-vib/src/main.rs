//! `dtg-vib`: the command line. Parsing, reading, calling the library,
//! printing; nothing else lives here.

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};
use cli_support::Style;
use cli_support::progress::Progress;
use dtg_vib::apply::{Applied, write_residues};
use dtg_vib::diagnose::{DiagnoseOptions, diagnose_records};
use dtg_vib::effects::{ChannelEffect, Effect};
use dtg_vib::explain::ExplainStage;
use dtg_vib::fit::{CentreMethod, FitOptions, FitStage, fit_records};
use dtg_vib::model::CompensationModel;
use dtg_vib::pipeline::{FilterSpec, Preprocess, RateReference};
use dtg_vib::report::{Baseline, Provenance, ReportExtras, build_report, write_diagnosis_report};
use dtg_vib::split::SplitKind;
use dtg_vib::window::WindowSpec;
use nav_sensors::calibration::Calibration;
use nav_sensors::record::Record;
use nav_sensors::sim::{Scenario, Site, simulate};
use std::path::{Path, PathBuf};

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
        /// A built-in scenario (each is scenarios/NAME.toml): paper_z_random,
        /// triaxial_clean, triaxial_hidden, demo; the campaign x-axis, y-axis,
        /// z-axis, sine-sweep, flight.
        #[arg(long)]
        builtin: Option<String>,
        /// Override the scenario's seed.
        #[arg(long)]
        seed: Option<u64>,
        /// Override the scenario's duration, s (a shorter run of a long
        /// profile: the schedule and motion are cut, not compressed).
        #[arg(long)]
        duration: Option<f64>,
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
    /// Does a model hold on a record it was not fitted on? Rms before and
    /// after, residues, and the share of windows outside the training range.
    Check {
        /// Model file from `fit`.
        #[arg(long)]
        model: PathBuf,
        /// A record the model was not fitted on (CSV).
        #[arg(long)]
        data: PathBuf,
        /// Warn when more than this share of the windows lies outside the training range.
        #[arg(long = "outside-threshold", default_value_t = dtg_vib::check::DEFAULT_OUTSIDE_THRESHOLD, value_parser = parse_share, allow_hyphen_values = true)]
        outside_threshold: f64,
        /// Print one JSON object on stdout.
        #[arg(long)]
        json: bool,
        /// Also write the model's report on this record (figures and index.html) here.
        #[arg(long)]
        report: Option<PathBuf>,
    },
    /// Find what a model is missing: compare, locate failures, rank candidate effects.
    Diagnose {
        /// Model file from `fit`.
        #[arg(long)]
        model: PathBuf,
        /// The test record it was fitted on; repeat for the records of a
        /// model fitted on several (candidates are ranked on all of them).
        #[arg(long, required = true)]
        data: Vec<PathBuf>,
        /// Print one JSON object on stdout.
        #[arg(long)]
        json: bool,
        /// Write figures and index.html into this directory.
        #[arg(long)]
        report: Option<PathBuf>,
        #[command(flatten)]
        thresholds: Thresholds,
    },
    /// The whole loop: fit, diagnose, add every suggested effect, refit, until nothing new is suggested.
    #[command(allow_negative_numbers = true)]
    Explain(Box<ExplainArgs>),
    /// Overlapping Allan deviation and IEEE 952 noise terms of every channel and residue, before and after a model.
    Allan {
        /// Test record (CSV).
        #[arg(long)]
        data: PathBuf,
        /// Model file from `fit`: adds the curves after its compensation.
        #[arg(long)]
        model: Option<PathBuf>,
        /// Two-sided confidence level of the intervals.
        #[arg(long, default_value_t = 0.683)]
        confidence: f64,
        /// Print one JSON object on stdout.
        #[arg(long)]
        json: bool,
        /// Write the log-log figures and index.html into this directory.
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

/// When the diagnosis suggests an effect.
#[derive(Args, Clone, Copy)]
struct Thresholds {
    /// False-alarm level of a record: the chance, on a record with nothing
    /// missing, that any channel gets a suggestion (Bonferroni over channels and candidates).
    #[arg(long, default_value_t = 0.01, value_parser = parse_alpha)]
    alpha: f64,
    /// Worth threshold: suggest an effect only if adding it cuts the channel's residual rms by at least this fraction.
    #[arg(long = "min-gain", default_value_t = 0.1, value_parser = parse_gain)]
    min_gain: f64,
}

impl Thresholds {
    fn options(self) -> DiagnoseOptions {
        let mut o = DiagnoseOptions::default();
        o.rank.alpha = self.alpha;
        o.rank.min_rms_reduction = self.min_gain;
        o
    }
}

fn parse_alpha(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err(format!(
            "'{s}': a false-alarm level must lie strictly between 0 and 1 (e.g. 0.01)"
        )),
    }
}

fn parse_gain(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..1.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "'{s}': a gain is a fraction of the rms from 0 to below 1 (e.g. 0.1 for 10%)"
        )),
    }
}

#[derive(Args)]
struct ExplainArgs {
    #[command(flatten)]
    fit: FitArgs,
    #[command(flatten)]
    thresholds: Thresholds,
    /// Most fits to make (the first one included).
    #[arg(long = "max-rounds", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=50))]
    max_rounds: u64,
    /// Write the final model's diagnosis figures and index.html into this directory.
    #[arg(long)]
    report: Option<PathBuf>,
}

#[derive(Args)]
struct FitArgs {
    /// Test record (CSV: t,X,X1,Y,Y1,Z,Z1,ax,ay,az[,extra columns]); repeat
    /// to fit several records together (one calibration; filters and windows
    /// run per record).
    #[arg(long, required = true)]
    data: Vec<PathBuf>,
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
    #[arg(long, default_value_t = 50, value_parser = parse_count, allow_hyphen_values = true)]
    window: usize,
    /// Windowed signals, comma-separated (accelerometer axes or extra columns).
    #[arg(long = "window-signals", value_delimiter = ',', default_value = "az")]
    window_signals: Vec<String>,
    /// Training/validation split within each record: blocked (honest) or
    /// interleaved (the paper's); or by-record, with --validate-on.
    #[arg(long, default_value = "blocked")]
    split: String,
    /// With --split by-record: the --data record that only validates (the others only train).
    #[arg(long = "validate-on")]
    validate_on: Option<PathBuf>,
    /// `records`: also validate each record, whole, by a model fitted on the
    /// others (leave one record out); needs two or more --data.
    #[arg(long, value_parser = ["records"])]
    cv: Option<String>,
    /// Fraction of the rows that train in a blocked split.
    #[arg(long = "train-fraction", default_value_t = 0.5, value_parser = parse_fraction, allow_hyphen_values = true)]
    train_fraction: f64,
    /// Largest number of RBF centres tried by cross-validation.
    #[arg(long = "max-centers", default_value_t = 60, value_parser = parse_count, allow_hyphen_values = true)]
    max_centers: usize,
    /// OLS candidate centres: a seeded subsample of this many training windows.
    #[arg(long, default_value_t = 400, value_parser = parse_count, allow_hyphen_values = true)]
    candidates: usize,
    /// Low-pass cut-off of outputs and effects, Hz (zero-phase Butterworth).
    #[arg(long, default_value_t = 5.0, conflicts_with = "no_filter", value_parser = parse_hz, allow_hyphen_values = true)]
    cutoff: f64,
    /// Low-pass order.
    #[arg(long = "filter-order", default_value_t = 4, value_parser = parse_order, allow_hyphen_values = true)]
    filter_order: usize,
    /// No low-pass at all.
    #[arg(long = "no-filter")]
    no_filter: bool,
    /// Also low-pass the windowed inputs at this cut-off, Hz (the paper filtered them).
    #[arg(long = "input-cutoff", value_parser = parse_hz, allow_hyphen_values = true)]
    input_cutoff: Option<f64>,
    /// Rate reference: Earth rate at this latitude, deg (cluster x north, z up).
    #[arg(long = "earth-rate", conflicts_with = "table_rate", value_parser = parse_latitude, allow_hyphen_values = true)]
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
    #[arg(long, default_value_t = 1e-8, value_parser = parse_ridge, allow_hyphen_values = true)]
    ridge: f64,
    /// Seed of the candidate subsample and k-means.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
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

fn main() -> std::process::ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return cli_support::usage::exit(e, Style::VERBATIM),
    };
    cli_support::failure::exit(run(cli), Style::VERBATIM)
}

fn run(cli: Cli) -> Result<()> {
    let progress = Progress::new(cli_support::progress::visible(cli.quiet));
    match cli.command {
        Command::Simulate {
            scenario,
            builtin,
            seed,
            duration,
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
            if let Some(d) = duration {
                s.duration_s = d;
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
            sim.write_dir(&out).with_context(|| {
                format!(
                    "scenario '{}' gives values no reader takes: check the magnitudes and units of its numbers",
                    s.name
                )
            })?;
            drop(progress);
            for name in nav_sensors::sim::Simulation::FILES {
                println!("wrote {}", out.join(name).display());
            }
        }
        Command::Fit(args) => fit_command(*args, &progress)?,
        Command::Explain(args) => explain_command(*args, &progress)?,
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
            progress.clear();
            eprintln!(
                "{}",
                rate_reference_note(&model.preprocess().rate_reference)
            );
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
                    Some((bm, ba, b.as_path()))
                }
                None => None,
            };
            progress.say("drawing figures");
            let summary = model_report(
                (&m, &model),
                (&record, &data),
                &applied,
                base.as_ref().map(|(bm, ba, path)| (bm, ba, *path)),
                &out,
            )?;
            drop(progress);
            print_residues(&summary.residues);
            if let Some((_, ba, _)) = &base {
                print_baseline_table(ba, &summary.channels);
            }
            println!("report: {}", summary.index.display());
        }
        Command::Check {
            model,
            data,
            outside_threshold,
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
            progress.say("applying the model");
            let (c, page) = match &report {
                // The report needs the split rows too: apply once, with them.
                Some(dir) => {
                    let applied = Applied::new(&m, &record)?;
                    let c = dtg_vib::check::check_applied(&m, &applied, outside_threshold)?;
                    progress.say("drawing figures");
                    let summary =
                        model_report((&m, &model), (&record, &data), &applied, None, dir)?;
                    (c, Some(summary.index))
                }
                None => (dtg_vib::check::check(&m, &record, outside_threshold)?, None),
            };
            progress.clear();
            if json {
                println!("{}", serde_json::to_string(&c)?);
            } else {
                print_check(&c);
                if let Some(p) = page {
                    println!("report: {}", p.display());
                }
            }
            if let Some(w) = &c.warning {
                eprintln!("warning: {w}");
            }
            if let Some(n) = &c.note {
                eprintln!("note: {n}");
            }
        }
        Command::Diagnose {
            model,
            data,
            json,
            report,
            thresholds,
        } => {
            if let Some(dir) = &report {
                let inputs: Vec<(&str, Option<&Path>)> =
                    std::iter::once(("--model", Some(model.as_path())))
                        .chain(data.iter().map(|d| ("--data", Some(d.as_path()))))
                        .collect();
                outfile::guard_dir("--report", dir, &["index.html"], &inputs)?;
            }
            once_each(&data)?;
            let m = CompensationModel::load(&model)?;
            let records = data
                .iter()
                .map(|d| Ok((d.display().to_string(), Record::read_csv(d)?)))
                .collect::<Result<Vec<(String, Record)>>>()?;
            let named: Vec<(String, &Record)> =
                records.iter().map(|(n, r)| (n.clone(), r)).collect();
            progress.say("diagnosing (the model's mirror is fitted on its validation rows)");
            let options = thresholds.options();
            let d = diagnose_records(&m, &named, &options)?;
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
        Command::Allan {
            data,
            model,
            confidence,
            json,
            report,
        } => allan_command(data, model, confidence, json, report, &progress)?,
        Command::Demo { out } => {
            outfile::guard_dir("--out", &out, &[], &[])?;
            let summary = dtg_vib::demo::run(&out, &|step| progress.say(step.to_string()))?;
            drop(progress);
            print_demo(&summary);
        }
    }
    Ok(())
}

/// The fit options the flags say.
fn fit_options(a: &FitArgs) -> Result<FitOptions> {
    let centres = a.centers.parse::<CentreMethod>()?;
    if centres == CentreMethod::Ols && a.max_centers > a.candidates {
        // OLS picks among the candidates; more centres than that used to
        // run a size ladder far past them (--max-centers 100000000 hung).
        anyhow::bail!(
            "--max-centers {}: OLS picks centres among --candidates {} windows; use --max-centers 1 to {} (or raise --candidates)",
            a.max_centers,
            a.candidates,
            a.candidates
        );
    }
    let effects = Effect::parse_list(&a.effects.join(","))?;
    let add = a
        .add_effect
        .iter()
        .map(|s| s.parse::<ChannelEffect>())
        .collect::<Result<Vec<_>, _>>()?;
    let by_record = a.split.trim() == "by-record";
    let split = match by_record {
        true => SplitKind::Blocked {
            train_fraction: a.train_fraction,
        },
        false => match dtg_vib::split::parse(&a.split).map_err(|_| {
            anyhow::anyhow!(
                "--split {}: use blocked, interleaved or by-record (with --validate-on)",
                a.split
            )
        })? {
            SplitKind::Blocked { .. } => SplitKind::Blocked {
                train_fraction: a.train_fraction,
            },
            other => other,
        },
    };
    let validate_on = match (by_record, &a.validate_on) {
        (true, Some(v)) => Some(record_name(&a.data, v)?),
        (true, None) => anyhow::bail!(
            "--split by-record: say which record validates with --validate-on (one of the --data files)"
        ),
        (false, Some(v)) => {
            anyhow::bail!("--validate-on {}: only with --split by-record", v.display())
        }
        (false, None) => None,
    };
    if a.cv.is_some() && a.data.len() < 2 {
        anyhow::bail!("--cv records: leaving one record out needs two or more --data records");
    }
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
    Ok(FitOptions {
        preprocess: Preprocess {
            filter,
            input_filter,
            window: WindowSpec::new(a.window_signals.clone(), a.window)?,
            rate_reference,
            causal: a.causal,
        },
        effects,
        add,
        centres,
        max_centres: a.max_centers,
        candidates: a.candidates,
        ridge: a.ridge,
        split,
        validate_on,
        seed: a.seed,
        ..FitOptions::default()
    })
}

/// The name of the --data record that `path` names (the same file), for
/// `--validate-on`.
fn record_name(data: &[PathBuf], path: &std::path::Path) -> Result<String> {
    let canonical = |p: &std::path::Path| std::fs::canonicalize(p).ok();
    let same =
        |d: &PathBuf| d == path || (canonical(d).is_some() && canonical(d) == canonical(path));
    match data.iter().find(|d| same(d)) {
        Some(d) if data.len() > 1 => Ok(d.display().to_string()),
        Some(_) => anyhow::bail!(
            "--split by-record: one --data record cannot both train and validate; give two or more"
        ),
        None => anyhow::bail!(
            "--validate-on {}: not one of the --data records ({}); name one of them",
            path.display(),
            data.iter()
                .map(|d| d.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The --data and --calib inputs, for the guards that keep outputs off them.
fn fit_inputs(a: &FitArgs) -> Vec<(&'static str, Option<&std::path::Path>)> {
    a.data
        .iter()
        .map(|d| ("--data", Some(d.as_path())))
        .chain([("--calib", a.calib.as_deref())])
        .collect()
}

/// Refuses a record given twice: fitted twice it would weigh double, and a
/// split by record could not tell its two copies apart.
fn once_each(data: &[PathBuf]) -> Result<()> {
    let canonical = |p: &PathBuf| std::fs::canonicalize(p).unwrap_or_else(|_| p.clone());
    for (i, d) in data.iter().enumerate() {
        if let Some(e) = data[..i].iter().find(|e| canonical(e) == canonical(d)) {
            anyhow::bail!(
                "--data {} is the same file as --data {}: give each record once",
                d.display(),
                e.display()
            );
        }
    }
    Ok(())
}

/// Reads every --data record, checking the rate-dependent flags against each.
fn read_records(a: &FitArgs) -> Result<Vec<(String, Record)>> {
    once_each(&a.data)?;
    a.data
        .iter()
        .map(|d| {
            let r = Record::read_csv(d)?;
            check_against_record(a, &r)?;
            Ok((d.display().to_string(), r))
        })
        .collect()
}

/// The flags that depend on the record's rate, said with the flag.
fn check_against_record(a: &FitArgs, record: &Record) -> Result<()> {
    for (flag, cutoff) in [
        ("--cutoff", (!a.no_filter).then_some(a.cutoff)),
        ("--input-cutoff", a.input_cutoff),
    ] {
        if let Some(c) = cutoff {
            dtg_vib::signal::LowPass::butterworth(a.filter_order, c, 1.0 / record.dt())
                .map_err(|e| anyhow::anyhow!("{flag} {}: {e}", dtg_vib::signal::num(c)))?;
        }
    }
    Ok(())
}

fn fit_command(a: FitArgs, progress: &Progress) -> Result<()> {
    outfile::guard_file("--out", &a.out, &fit_inputs(&a))?;
    let options = fit_options(&a)?;
    let records = read_records(&a)?;
    let calibration = a.calib.as_ref().map(Calibration::load).transpose()?;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let start = std::time::Instant::now();
    let named: Vec<(String, &Record)> = records.iter().map(|(n, r)| (n.clone(), r)).collect();
    let (model, prepared) = fit_records(
        &named,
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
    let per_record = match a.cv.is_some() {
        true => {
            progress.say("leaving one record out");
            Some(dtg_vib::fit::leave_one_record_out(
                &prepared,
                calibration.as_ref(),
                &options,
            )?)
        }
        false if records.len() > 1 => Some(dtg_vib::fit::record_scores(&model, &prepared)?),
        false => None,
    };
    let fit_seconds = start.elapsed().as_secs_f64();
    model.save(&a.out)?;
    progress.clear();
    let n_train = model.channels()[0].scores().n_train;
    let stride = dtg_vib::fit::selection_stride(n_train);
    if stride > 1 {
        eprintln!(
            "note: {n_train} training windows: cross-validation and centre selection used every {stride}th of them ({}); the weights were solved on all",
            n_train.div_ceil(stride)
        );
    }
    if a.json {
        let mut report = FitReport::new(&model, fit_seconds);
        if let Some(per) = &per_record {
            for (c, r) in report.channels.iter_mut().zip(per) {
                c.records = Some(r.clone());
            }
            report.cv = a.cv.clone();
        }
        println!("{}", serde_json::to_string(&report)?);
    } else {
        print_fit(&model);
        if let Some(per) = &per_record {
            print_record_scores(per, a.cv.is_some());
        }
        println!("model: {} ({:.2} s)", a.out.display(), fit_seconds);
    }
    Ok(())
}

/// Validation rms of each channel on each record.
fn print_record_scores(per: &[Vec<dtg_vib::fit::RecordScore>; 6], loro: bool) {
    println!(
        "validation rms per record, deg/h ({}):",
        if loro {
            "each record validated by a model fitted on the others"
        } else {
            "each record's validation rows"
        }
    );
    for (k, scores) in per.iter().enumerate() {
        let cells: Vec<String> = scores
            .iter()
            .map(|s| format!("{} {:.4}", s.file, s.val_rms))
            .collect();
        println!(
            "{:>7}  {}",
            nav_sensors::geometry::Channel::ALL[k].name(),
            cells.join(", ")
        );
    }
}

fn print_fit(model: &CompensationModel) {
    println!(
        "channel  centres  train rms  val rms  (deg/h)  effects (coefficient ± standard error)"
    );
    for c in model.channels() {
        let s = c.scores();
        let e: Vec<String> = c
            .effects()
            .iter()
            .enumerate()
            .map(|(j, e)| match c.coefficients() {
                Some(k) => format!(
                    "{} {:.4} ± {:.4} {}",
                    e.id(),
                    k[j].value,
                    k[j].se,
                    k[j].unit
                ),
                None => e.id(),
            })
            .collect();
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
}

/// `fit --json`.
#[derive(serde::Serialize)]
struct FitReport {
    channels: Vec<ChannelReport>,
    split: String,
    fit_seconds: f64,
    /// `records` with `--cv records`.
    #[serde(skip_serializing_if = "Option::is_none")]
    cv: Option<String>,
}

#[derive(serde::Serialize)]
struct ChannelReport {
    channel: nav_sensors::geometry::Channel,
    effects: Vec<String>,
    n_centers: usize,
    train_rms: f64,
    val_rms: f64,
    val_rms_bias_only: f64,
    val_fit_percent: f64,
    width: f64,
    bias: f64,
    effect_coefficients: std::collections::BTreeMap<String, CoefficientReport>,
    /// Validation rms per record, with several records.
    #[serde(skip_serializing_if = "Option::is_none")]
    records: Option<Vec<dtg_vib::fit::RecordScore>>,
}

#[derive(serde::Serialize)]
struct CoefficientReport {
    value: f64,
    unit: String,
    /// Absent for a model file that predates standard errors.
    #[serde(skip_serializing_if = "Option::is_none")]
    se: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ci95: Option<[f64; 2]>,
}

impl FitReport {
    fn new(model: &CompensationModel, fit_seconds: f64) -> Self {
        let channels = model
            .channels()
            .iter()
            .map(|c| {
                let s = c.scores();
                let effect_coefficients = c
                    .effects()
                    .iter()
                    .zip(c.effect_coefficients())
                    .enumerate()
                    .map(|(j, (e, v))| {
                        let k = c.coefficients().map(|k| &k[j]);
                        (
                            e.id(),
                            CoefficientReport {
                                value: v,
                                unit: e.unit(),
                                se: k.map(|k| k.se),
                                ci95: k.map(|k| k.ci95),
                            },
                        )
                    })
                    .collect();
                ChannelReport {
                    channel: c.channel(),
                    effects: c.effects().iter().map(|e| e.id()).collect(),
                    n_centers: c.n_centres(),
                    train_rms: s.train_rms,
                    val_rms: s.val_rms,
                    val_rms_bias_only: s.val_rms_bias_only,
                    val_fit_percent: s.val_fit_percent,
                    width: c.width(),
                    bias: c.bias(),
                    effect_coefficients,
                    records: None,
                }
            })
            .collect();
        let split = match model.validated_on() {
            Some(name) => format!("by record (validated on {name})"),
            None => model.split().to_string(),
        };
        Self {
            channels,
            split,
            fit_seconds,
            cv: None,
        }
    }
}

/// The fit flag `explain` cannot honour, refused with why and what to do
/// instead: its rounds judge effects on the model's own split.
fn explain_takes(f: &FitArgs) -> Result<()> {
    if f.cv.is_some() {
        anyhow::bail!(
            "explain does not take --cv: each round judges effects on the model's own split; run dtg-vib fit --cv records with the effects explain added (--add-effect CHANNEL=ID) to see each record predicted by a model of the others"
        );
    }
    Ok(())
}

fn explain_command(a: ExplainArgs, progress: &Progress) -> Result<()> {
    let f = &a.fit;
    outfile::guard_file("--out", &f.out, &fit_inputs(f))?;
    if let Some(dir) = &a.report {
        outfile::guard_dir("--report", dir, &["index.html"], &fit_inputs(f))?;
    }
    explain_takes(f)?;
    let options = fit_options(f)?;
    let records = read_records(f)?;
    let named: Vec<(String, &Record)> = records.iter().map(|(n, r)| (n.clone(), r)).collect();
    let calibration = f.calib.as_ref().map(Calibration::load).transpose()?;
    let diagnose_options = a.thresholds.options();
    let start = std::time::Instant::now();
    let e = dtg_vib::explain::explain_records(
        &named,
        calibration.as_ref(),
        &options,
        &diagnose_options,
        a.max_rounds as usize,
        &|stage| match stage {
            ExplainStage::Fitting(n) => progress.say(format!("round {n}: fitting")),
            ExplainStage::Diagnosing(n) => progress.say(format!("round {n}: diagnosing")),
        },
    )?;
    let seconds = start.elapsed().as_secs_f64();
    e.model.save(&f.out)?;
    let page = match &a.report {
        Some(dir) => {
            progress.say("drawing figures");
            let last = &e.rounds.last().expect("at least one round").diagnosis;
            Some(write_diagnosis_report(
                last,
                diagnose_options.rank.min_err(),
                dir,
            )?)
        }
        None => None,
    };
    progress.clear();
    if f.json {
        #[derive(serde::Serialize)]
        struct Out<'a> {
            rounds: &'a [dtg_vib::explain::Round],
            converged: bool,
            #[serde(rename = "final")]
            final_fit: FitReport,
        }
        println!(
            "{}",
            serde_json::to_string(&Out {
                rounds: &e.rounds,
                converged: e.converged,
                final_fit: FitReport::new(&e.model, seconds),
            })?
        );
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    for (k, r) in e.rounds.iter().enumerate() {
        println!("round {}:", k + 1);
        if k == 0 {
            println!("  fitted with the given effects");
        }
        for x in &r.added {
            println!(
                "  added {}={}: explains {:.0}% of what was left (p {}), coefficient {:.4} ± {:.4} {} (95% CI {:.4} to {:.4}){}",
                x.channel,
                x.effect,
                100.0 * x.err,
                dtg_vib::diagnose::p_text(x.p),
                x.coef,
                x.se,
                x.unit,
                x.ci95[0],
                x.ci95[1],
                if x.alternatives.is_empty() {
                    String::new()
                } else {
                    format!(
                        "; this record cannot tell it from {}",
                        x.alternatives.join(", ")
                    )
                }
            );
        }
        for x in r.added.iter().filter_map(|x| x.separation.as_ref()) {
            println!("    {}", x.advice);
        }
        for x in &r.added {
            for sep in &x.record_separations {
                println!(
                    "    {} and {} are collinear on {} alone; {}",
                    x.effect,
                    sep.effect,
                    sep.collinear_on.join(", "),
                    if sep.separated_by.is_empty() {
                        "the records together tell them apart".to_string()
                    } else {
                        format!("{} told them apart", sep.separated_by.join(", "))
                    }
                );
            }
        }
        let rms: Vec<String> = r
            .channels
            .iter()
            .map(|c| format!("{} {:.4}", c.channel, c.val_rms))
            .collect();
        println!("  validation rms (deg/h): {}", rms.join(", "));
    }
    if e.converged {
        println!(
            "nothing new suggested: the loop stopped after {} round(s)",
            e.rounds.len()
        );
    } else {
        println!(
            "stopped at --max-rounds {}: the last diagnosis still suggests something (run `dtg-vib diagnose` on the model)",
            a.max_rounds
        );
    }
    print_fit(&e.model);
    println!("model: {} ({:.1} s)", f.out.display(), seconds);
    if let Some(p) = &page {
        println!("report: {}", p.display());
    }
    Ok(())
}

fn allan_command(
    data: PathBuf,
    model: Option<PathBuf>,
    confidence: f64,
    json: bool,
    report: Option<PathBuf>,
    progress: &Progress,
) -> Result<()> {
    if let Some(dir) = &report {
        outfile::guard_dir(
            "--report",
            dir,
            &["index.html"],
            &[("--data", Some(&data)), ("--model", model.as_deref())],
        )?;
    }
    let record = Record::read_csv(&data)?;
    let m = model.as_ref().map(CompensationModel::load).transpose()?;
    progress.say("computing Allan deviations");
    let a = dtg_vib::allan::AllanAnalysis::new(&record, m.as_ref(), confidence)?;
    let page = match &report {
        Some(dir) => {
            progress.say("drawing figures");
            Some(dtg_vib::report::write_allan_report(
                &a,
                &data.display().to_string(),
                dir,
            )?)
        }
        None => None,
    };
    progress.clear();
    if json {
        println!("{}", serde_json::to_string(&a.to_json())?);
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    let tau = &a.channels[0].before.points;
    println!(
        "Overlapping Allan deviation of {}: {} samples from sample {}, τ = {} to {} s; {:.1}% intervals",
        data.display(),
        a.samples,
        a.first_sample,
        tau.first().map_or(0.0, |p| p.tau_s),
        tau.last().map_or(0.0, |p| p.tau_s),
        100.0 * a.confidence
    );
    let text = dtg_vib::allan::term_text;
    for (what, pick) in [
        (
            "ARW (deg/√h)",
            (|t| &t.arw) as fn(&nav_sensors::noise::NoiseTerms) -> &nav_sensors::noise::NoiseTerm,
        ),
        ("bias instability (deg/h)", |t| &t.bias_instability),
        ("RRW (deg/h/√h)", |t| &t.rrw),
    ] {
        println!("{what:<26} {:<40} after", "before");
        for s in a.channels.iter().chain(&a.residues) {
            println!(
                "{:>26} {:<40} {}",
                s.name,
                text(pick(&s.terms_before)),
                s.terms_after.as_ref().map_or("—".into(), |t| text(pick(t)))
            );
        }
    }
    if let Some(p) = &page {
        println!("report: {}", p.display());
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

/// A count (window samples, centres, candidates): a whole number ≥ 1.
fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("must be a whole number ≥ 1".into()),
    }
}

fn parse_fraction(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err("must be a number strictly between 0 and 1".into()),
    }
}

/// A cut-off frequency: positive and finite here; its upper bound (the
/// record's Nyquist frequency) is checked once the record is read.
fn parse_hz(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err("must be a positive frequency in Hz, below the record's Nyquist frequency".into()),
    }
}

fn parse_order(s: &str) -> Result<usize, String> {
    let max = dtg_vib::signal::MAX_ORDER;
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!("must be a whole number from 1 to {max}")),
    }
}

/// The largest `--ridge`: beyond it the penalty swamps the unpenalised bias
/// and effect columns and the solve reports them rank deficient (measured:
/// 1e18 still fits, 1e30 does not); at 1e12 the kernel weights are zero.
const MAX_RIDGE: f64 = 1e12;

fn parse_ridge(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=MAX_RIDGE).contains(&v) => Ok(v.abs()),
        _ => Err(format!("must be a number from 0 to {MAX_RIDGE:e}")),
    }
}

fn parse_latitude(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() <= 90.0 => Ok(v),
        _ => Err(format!(
            "'{s}': a latitude must be a number from -90 to 90 (deg)"
        )),
    }
}

/// The report of a model on a record, with the files' provenance: `report`
/// and `check --report`.
fn model_report(
    (m, model): (&CompensationModel, &PathBuf),
    (record, data): (&Record, &PathBuf),
    applied: &Applied,
    baseline: Option<(&CompensationModel, &Applied, &std::path::Path)>,
    dir: &std::path::Path,
) -> Result<dtg_vib::report::ReportSummary> {
    let mut files = vec![("model", model.clone()), ("data", data.clone())];
    files.extend(baseline.map(|(_, _, b)| ("baseline model", b.to_path_buf())));
    let provenance = Provenance::of_this_process(files);
    let extras = ReportExtras {
        provenance: Some(&provenance),
        ..ReportExtras::default()
    };
    let (summary, page) = build_report(
        m,
        applied,
        record,
        &data.display().to_string(),
        baseline.map(|(model, applied, _)| Baseline {
            label: "baseline",
            model,
            applied,
        }),
        &extras,
        dir,
    )?;
    page.write(dir)?;
    Ok(summary)
}

fn print_check(c: &dtg_vib::check::TransferCheck) {
    let cell = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4}"));
    println!(
        "channel  rms before  rms after  mean after  fit %   inside  outside   (deg/h; before: about the record's mean)"
    );
    for ch in &c.channels {
        println!(
            "{:>7}  {:>10.4}  {:>9.4}  {:>10.4}  {:>5.1}  {:>7}  {:>7}",
            ch.channel.name(),
            ch.rms_before,
            ch.rms_after,
            ch.mean_after,
            ch.fit_percent,
            cell(ch.rms_inside),
            cell(ch.rms_outside)
        );
    }
    match c.outside_fraction {
        Some(f) => println!(
            "windows outside the training range: {:.1}% of {} (median distance to the training points {:.2} × the reference, outside above {})",
            100.0 * f,
            c.windows,
            c.median_relative_distance.unwrap_or(f64::NAN),
            dtg_vib::operating::OUTSIDE_FACTOR
        ),
        None => {
            println!("windows outside the training range: unknown (model without operating points)")
        }
    }
    print_residues_on(&c.residues, "every row");
}

fn parse_share(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("{s:?} is not a share between 0 and 1 (e.g. 0.05)")),
    }
}

/// Each channel's validation rms under the baseline and this model.
fn print_baseline_table(base: &Applied, this: &[dtg_vib::model::ChannelScores]) {
    println!("channel  val rms baseline  val rms this model  (deg/h)  change");
    for (c, s) in nav_sensors::geometry::Channel::ALL.into_iter().zip(this) {
        let b = base.scores(c).val_rms;
        println!(
            "{:>7}  {:>16.4}  {:>18.4}  {:>15}",
            c.name(),
            b,
            s.val_rms,
            format!("{:+.1}%", 100.0 * (s.val_rms / b - 1.0))
        );
    }
}

/// What `compensate` removes as the rate reference, and how to change it.
fn rate_reference_note(r: &dtg_vib::pipeline::RateReference) -> String {
    use dtg_vib::pipeline::RateReference;
    let what = match r {
        RateReference::None => "no rate reference (the model was fitted without one)".to_string(),
        RateReference::Earth { site } => format!(
            "the Earth rate at latitude {}° (cluster x north, z up)",
            site.latitude_deg
        ),
        RateReference::Table { rate_deg_s } => format!(
            "a table rate of {}, {}, {} deg/s about cluster x, y, z",
            rate_deg_s[0], rate_deg_s[1], rate_deg_s[2]
        ),
    };
    format!(
        "rate reference removed: {what}, as stored in the model; to change it, refit with --earth-rate LAT or --table-rate WX,WY,WZ"
    )
}

fn print_residues(stats: &[dtg_vib::parity::ResidueStats]) {
    print_residues_on(stats, "validation rows");
}

fn print_residues_on(stats: &[dtg_vib::parity::ResidueStats], rows: &str) {
    println!("residue  rms before  rms after  (deg/h, {rows:<15})  reduction");
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
        // Each suggestion with its coefficient and 95% interval.
        let suggested: Vec<String> = c
            .suggested
            .iter()
            .map(|id| match c.candidates.iter().find(|k| &k.effect == id) {
                Some(k) => format!(
                    "{id} ({:.3} ± {:.3} {}, 95% CI {:.3} to {:.3})",
                    k.coef, k.coef_se, k.unit, k.coef_ci95[0], k.coef_ci95[1]
                ),
                None => id.clone(),
            })
            .collect();
        println!(
            "  {:>3}: validation rms {:.4} deg/h; suggested: {}",
            c.channel,
            c.rms,
            if suggested.is_empty() {
                "nothing".into()
            } else {
                suggested.join(", ")
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
    println!("reports (start with {}):", s.index.display());
    println!("  paper's procedure: {}", s.baseline_report.display());
    println!("  diagnosis:         {}", s.diagnosis_report.display());
    println!("  after the refit:   {}", s.final_report.display());
}
