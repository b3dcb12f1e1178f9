//! The flags of a fit, shared by `fit` and `explain`, and what they become:
//! the library's fit options, checked against each other and the records.

use anyhow::Result;
use clap::Args;
use dtg_vib::effects::{ChannelEffect, Effect};
use dtg_vib::fit::{CentreMethod, FitOptions, FitSettings, ModelChoice};
use dtg_vib::pipeline::{FilterSpec, Preprocess, RateReference};
use dtg_vib::split::Holdout;
use dtg_vib::window::WindowSpec;
use nav_sensors::record::Record;
use nav_sensors::sim::Site;
use std::path::PathBuf;

use super::parse::{
    parse_count, parse_fraction, parse_hz, parse_latitude, parse_order, parse_rate, parse_ridge,
};

/// The flags of a fit.
#[derive(Args)]
pub struct FitArgs {
    /// Test record (CSV: t,X,X1,Y,Y1,Z,Z1,ax,ay,az[,extra columns]); repeat
    /// to fit several records together (one calibration; filters and windows
    /// run per record).
    #[arg(long, required = true)]
    pub data: Vec<PathBuf>,
    /// Ground-calibration file (JSON); without it nothing is compensated.
    #[arg(long)]
    pub calib: Option<PathBuf>,
    /// The sensor unit: a unit file (FILE.toml, docs/formats.md) or a
    /// built-in name (paper, triad, tetra, dual-triad); default paper.
    #[arg(long)]
    pub unit: Option<String>,
    /// Physical effects of every channel, comma-separated (g_I, gg_IS, ai_OS, col:NAME, ...).
    #[arg(long, value_delimiter = ',')]
    pub effects: Vec<String>,
    /// An effect for one channel, CHANNEL=ID (repeatable), e.g. Y1=gg_IS.
    #[arg(long = "add-effect")]
    pub add_effect: Vec<String>,
    /// Centre selection.
    #[arg(long, visible_alias = "centers", default_value = "ols")]
    pub centres: String,
    /// Window length, samples (the paper: 50).
    #[arg(long, default_value_t = 50, value_parser = parse_count, allow_hyphen_values = true)]
    pub window: usize,
    /// Windowed signals, comma-separated (accelerometer axes or extra
    /// columns), or `auto`: every accelerometer axis whose dynamic rms is at
    /// least 0.2 × the strongest axis's in some training record that
    /// vibrates (its strongest axis ≥ 0.05 g); a z-shaker record takes az,
    /// the paper's window.
    #[arg(long = "window-signals", value_delimiter = ',', default_value = "auto")]
    pub window_signals: Vec<String>,
    /// What the networks read of the windows: `raw` (the window itself, the
    /// paper's), `statistics` (per windowed signal: current sample, window
    /// mean, window rms about the mean, in g: 3 inputs a signal) or `auto`
    /// (both tried: the lowest validation rms whose compensation keeps the
    /// Allan deviation within its 68% interval at every τ).
    #[arg(long, default_value = "auto", value_parser = ["auto", "raw", "statistics"])]
    pub input: String,
    /// Low-pass of the network part of each predicted error, Hz (2nd-order
    /// Butterworth; zero-phase, or causal with --causal), `none`, or `auto`
    /// (none, 0.5, 0.2, 0.1, 0.05 Hz tried, chosen as --input auto).
    #[arg(long, default_value = "auto")]
    pub smoother: String,
    /// Training/validation split within each record: blocked (honest) or
    /// interleaved (the paper's); or by-record, with --validate-on.
    #[arg(long, default_value = "blocked")]
    pub split: String,
    /// With --split by-record: the --data record that only validates (the others only train).
    #[arg(long = "validate-on")]
    pub validate_on: Option<PathBuf>,
    /// `records`: also validate each record, whole, by a model fitted on the
    /// others (leave one record out); needs two or more --data.
    #[arg(long, value_parser = ["records"])]
    pub cv: Option<String>,
    /// Fraction of the rows that train in a blocked split.
    #[arg(long = "train-fraction", default_value_t = 0.5, value_parser = parse_fraction, allow_hyphen_values = true)]
    pub train_fraction: f64,
    /// Largest number of RBF centres tried by cross-validation.
    #[arg(long = "max-centres", visible_alias = "max-centers", default_value_t = 60, value_parser = parse_count, allow_hyphen_values = true)]
    pub max_centres: usize,
    /// OLS candidate centres: a seeded subsample of this many training windows.
    #[arg(long, default_value_t = 400, value_parser = parse_count, allow_hyphen_values = true)]
    pub candidates: usize,
    /// Choose centres, width and number of centres once for all channels,
    /// on their targets together (each keeps its own weights), instead of
    /// for each channel on its own.
    #[arg(long = "shared-centres", visible_alias = "shared-centers")]
    pub shared_centres: bool,
    /// Choose centres for each channel on its own, also on a record of
    /// more than 100,000 rows (where one selection for all channels is
    /// otherwise tried on a sample and taken when it costs ≤ 1% of
    /// validation rms there).
    #[arg(
        long = "centres-per-channel",
        visible_alias = "centers-per-channel",
        conflicts_with = "shared_centres"
    )]
    pub centres_per_channel: bool,
    /// Low-pass cut-off of outputs and effects, Hz (zero-phase Butterworth).
    #[arg(long, default_value_t = 5.0, conflicts_with = "no_filter", value_parser = parse_hz, allow_hyphen_values = true)]
    pub cutoff: f64,
    /// Low-pass order.
    #[arg(long = "filter-order", default_value_t = 4, value_parser = parse_order, allow_hyphen_values = true)]
    pub filter_order: usize,
    /// No low-pass at all.
    #[arg(long = "no-filter")]
    pub no_filter: bool,
    /// Also low-pass the windowed inputs at this cut-off, Hz (the paper filtered them).
    #[arg(long = "input-cutoff", value_parser = parse_hz, allow_hyphen_values = true)]
    pub input_cutoff: Option<f64>,
    /// Rate reference: Earth rate at this latitude, deg (cluster x north, z up).
    #[arg(long = "earth-rate", conflicts_with = "table_rate", value_parser = parse_latitude, allow_hyphen_values = true)]
    pub earth_rate: Option<f64>,
    /// Rate reference: a known table rate about cluster x,y,z, deg/s (WX,WY,WZ).
    // "-0.01,0,0" is not one number, so allow_negative_numbers does not cover it.
    #[arg(
        long = "table-rate",
        value_name = "WX,WY,WZ",
        value_parser = parse_rate,
        allow_hyphen_values = true
    )]
    pub table_rate: Option<[f64; 3]>,
    /// Ridge on the output weights.
    #[arg(long, default_value_t = 1e-8, value_parser = parse_ridge, allow_hyphen_values = true)]
    pub ridge: f64,
    /// Seed of the candidate subsample and k-means.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    pub seed: u64,
    /// Causal mode: causal low-passes, so the model runs on-line with one
    /// period of latency (`dtg-vib export`) and `compensate` runs sample by sample.
    #[arg(long)]
    pub causal: bool,
    /// Model file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object on stdout.
    #[arg(long)]
    pub json: bool,
}

/// The fit options the flags say.
pub fn fit_options(a: &FitArgs) -> Result<FitOptions> {
    let (effects, add, options) = fit_options_with(
        a,
        |list| Ok(Effect::parse_list(list)?),
        |s| Ok(s.parse::<ChannelEffect>()?),
    )?;
    Ok(FitOptions {
        effects,
        add,
        ..options
    })
}

/// The fit options the flags say, with the effects of `--effects` and
/// `--add-effect` parsed by the given functions (those of the paper's unit,
/// or of another unit) and returned beside options that hold none.
pub fn fit_options_with<E, A>(
    a: &FitArgs,
    parse_effects: impl Fn(&str) -> Result<Vec<E>>,
    parse_add: impl Fn(&str) -> Result<A>,
) -> Result<(Vec<E>, Vec<A>, FitOptions)> {
    let centres = a.centres.parse::<CentreMethod>()?;
    if centres == CentreMethod::Ols && a.max_centres > a.candidates {
        // OLS picks among the candidates; more centres than that used to
        // run a size ladder far past them (--max-centers 100000000 hung).
        anyhow::bail!(
            "--max-centers {}: OLS picks centres among --candidates {} windows; use --max-centers 1 to {} (or raise --candidates)",
            a.max_centres,
            a.candidates,
            a.candidates
        );
    }
    let effects = parse_effects(&a.effects.join(","))?;
    let add = a
        .add_effect
        .iter()
        .map(|s| parse_add(s))
        .collect::<Result<Vec<_>>>()?;
    let by_record = a.split.trim() == "by-record";
    let split = match by_record {
        true => Holdout::Blocked {
            train_fraction: a.train_fraction,
        },
        false => match dtg_vib::split::parse(&a.split).map_err(|_| {
            anyhow::anyhow!(
                "--split {}: use blocked, interleaved or by-record (with --validate-on)",
                a.split
            )
        })? {
            Holdout::Blocked { .. } => Holdout::Blocked {
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
    let options = FitOptions {
        preprocess: Preprocess {
            filter,
            input_filter,
            // With auto, the paper's signal until the records choose (window_signals).
            window: WindowSpec::new(
                match window_auto(a)? {
                    true => vec!["az".to_string()],
                    false => a.window_signals.clone(),
                },
                a.window,
            )?,
            rate_reference,
            causal: a.causal,
            input: match a.input.as_str() {
                "auto" => Default::default(),
                i => i.parse()?,
            },
            smoother: match a.smoother.as_str() {
                "auto" => None,
                s => parse_smoother(s)?,
            },
        },
        effects: Vec::new(),
        add: Vec::new(),
        split,
        validate_on,
        settings: FitSettings {
            centres,
            max_centres: a.max_centres,
            candidates: a.candidates,
            ridge: a.ridge,
            seed: a.seed,
            choice: model_choice(a)?,
            shared_centres: a.shared_centres,
            ..FitSettings::default()
        },
    };
    Ok((effects, add, options))
}

/// True for `--window-signals auto` (the default); `auto` beside a signal
/// is refused.
pub fn window_auto(a: &FitArgs) -> Result<bool> {
    let auto = a.window_signals.iter().any(|s| s.trim() == "auto");
    if auto && a.window_signals.len() > 1 {
        anyhow::bail!(
            "--window-signals {}: auto chooses the signals itself; give auto alone or a list of signals",
            a.window_signals.join(",")
        );
    }
    Ok(auto)
}

/// With `--window-signals auto`, the window's signals the records choose
/// (`choose`, the sensor's [`sysid::choose_window_signals`]) put into
/// `window`, and the choice to keep in the model's report; otherwise
/// `window` as the flags said and nothing.
pub fn window_signals(
    a: &FitArgs,
    window: &mut WindowSpec,
    choose: impl FnOnce() -> Result<sysid::window::signal_choice::WindowSignalsChoice>,
) -> Result<Option<sysid::window::signal_choice::WindowSignalsChoice>> {
    if !window_auto(a)? {
        return Ok(None);
    }
    let c = choose()?;
    *window = WindowSpec::new(c.taken.clone(), window.length())?;
    Ok(Some(c))
}

/// The candidates of `--input` and `--smoother`: what each names, or every
/// one for `auto`; none to choose among when both name one.
fn model_choice(a: &FitArgs) -> Result<Option<ModelChoice>> {
    if a.input != "auto" && a.smoother != "auto" {
        return Ok(None);
    }
    let all = ModelChoice::default();
    Ok(Some(ModelChoice {
        inputs: match a.input.as_str() {
            "auto" => all.inputs,
            i => vec![i.parse()?],
        },
        smoothers: match a.smoother.as_str() {
            "auto" => all.smoothers,
            s => vec![parse_smoother(s)?],
        },
        try_shared_centres: !a.centres_per_channel,
    }))
}

/// `--smoother`: `none` or a cut-off in Hz.
fn parse_smoother(s: &str) -> Result<Option<dtg_vib::pipeline::Smoother>> {
    if s.trim() == "none" {
        return Ok(None);
    }
    let cutoff_hz = parse_hz(s).map_err(|e| anyhow::anyhow!("--smoother {s}: {e} (or none)"))?;
    Ok(Some(dtg_vib::pipeline::Smoother { cutoff_hz }))
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
pub fn fit_inputs(a: &FitArgs) -> Vec<(&'static str, Option<&std::path::Path>)> {
    a.data
        .iter()
        .map(|d| ("--data", Some(d.as_path())))
        .chain([("--calib", a.calib.as_deref())])
        .collect()
}

/// Refuses a record given twice: fitted twice it would weigh double, and a
/// split by record could not tell its two copies apart.
pub fn once_each(data: &[PathBuf]) -> Result<()> {
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
pub fn read_records(a: &FitArgs) -> Result<Vec<(String, Record)>> {
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
pub fn check_against_record(a: &FitArgs, record: &Record) -> Result<()> {
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
