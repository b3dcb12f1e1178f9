//! The flags of a fit, shared by `fit` and `explain`, and what they become,
//! resolved once: the unit's plug-in (its calibration and rate reference),
//! the loop's options with each channel's effects, the records read with
//! the unit, and the window's signals the records chose.

use crate::split::Holdout;
use crate::unit_sensor::{RateReference, UnitEffect, UnitEffectError, UnitSensor, expand_dynamic};
use anyhow::{Result, anyhow};
use clap::Args;
use nav_sensors::record::Record;
use nav_sensors::sim::Site;
use nav_sensors::unit::Unit;
use std::path::PathBuf;
use sysid::fit::ModelChoice;
use sysid::window::signal_choice::WindowSignalsChoice;
use sysid::{CentreMethod, FilterSpec, FitSettings, Sensor, WindowSpec};

use super::records::{Read, check_observable, parity_in_motion, read_records, sensor, unit_of};

use super::parse::{
    parse_count, parse_fraction, parse_hz, parse_latitude, parse_order, parse_rate, parse_ridge,
};

/// The flags of a fit.
#[derive(Args)]
pub struct FitArgs {
    /// Test record (CSV in the unit's columns; the paper's:
    /// t,X,X1,Y,Y1,Z,Z1,ax,ay,az[,extra columns]); repeat to fit several
    /// records together (one calibration; filters and windows run per
    /// record, and per segment of a log with time gaps).
    #[arg(long, required = true)]
    pub data: Vec<PathBuf>,
    /// Ground-calibration file (JSON, the unit's or the paper's format);
    /// without it nothing is compensated.
    #[arg(long)]
    pub calib: Option<PathBuf>,
    /// The sensor unit: a unit file (FILE.toml, docs/formats.md) or a
    /// built-in name (paper, triad, tetra, dual-triad); default paper.
    #[arg(long)]
    pub unit: Option<String>,
    /// Physical effects of every channel, comma-separated (DTG: g_I, gg_IS,
    /// ai_OS, ...; rate gyro: g_x, gg_yz, ...; col:NAME).
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
    /// Windowed signals, comma-separated (the unit's accelerometers or
    /// extra columns), or `auto`: every accelerometer whose dynamic rms is
    /// at least 0.2 × the strongest one's in some training record that
    /// vibrates (its strongest ≥ 0.05 g); a z-shaker record takes az, the
    /// paper's window.
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
    /// Causal mode: causal low-passes, so the model runs on-line with three
    /// periods of latency (`dtg-vib export`) and `compensate` runs sample by sample.
    #[arg(long)]
    pub causal: bool,
    /// Model file to write.
    #[arg(long)]
    pub out: PathBuf,
    /// Print one JSON object on stdout.
    #[arg(long)]
    pub json: bool,
}

/// A fit's flags resolved once: everything a fit of the unit is told.
pub struct FitRecipe {
    /// The unit's plug-in: its calibration and rate reference.
    pub sensor: UnitSensor,
    /// The loop's options: each channel's effects, pre-processing, split,
    /// settings.
    pub options: sysid::FitOptions<UnitEffect>,
    /// The records (a log's segments between time gaps, each a record).
    pub read: Read,
    /// The window's signals the records chose (`--window-signals auto`):
    /// one choice, or one per group of gyros choosing among their own
    /// IMU's accelerometers; empty when the flags named them.
    pub window: Vec<WindowSignalsChoice>,
}

impl FitRecipe {
    /// The flags resolved: the options checked against each other, the
    /// records read with the unit and checked against the flags, the
    /// window's signals chosen.
    pub fn resolve(a: &FitArgs) -> Result<Self> {
        let unit = unit_of(a.unit.as_deref())?;
        let (mut options, reference) = options(a, &unit)?;
        let mut sensor = sensor(unit, a.calib.as_deref(), reference)?;
        let mut read = read_records(&a.data, &sensor.unit, 2 * a.window)?;
        for (_, r) in &read.records {
            check_against_record(a, r)?;
        }
        read.notes
            .extend(parity_in_motion(&mut sensor, &read.records));
        check_observable(&sensor, &read.records)?;
        let window = match window_auto(a)? {
            true => {
                let c = sensor.choose_window_signals(&read.borrowed())?;
                read.notes.extend(sensor.constant_imu_notes(&c));
                let w = &mut options.recipe.preprocess.window;
                *w = c.window(w.length())?;
                c.choices
            }
            false => Vec::new(),
        };
        Ok(Self {
            sensor,
            options,
            read,
            window,
        })
    }

    /// The loop's model with the choice of its window's signals in its
    /// report, when the records chose them.
    pub fn with_window(&self, model: sysid::Model<UnitSensor>) -> sysid::Model<UnitSensor> {
        match self.window.is_empty() {
            false => model.with_window_signals(self.window.clone()),
            true => model,
        }
    }
}

/// The loop's options and the rate reference the flags say for `unit`:
/// `--effects` must suit every channel, `--add-effect CHANNEL=ID` its
/// channel's model.
fn options(a: &FitArgs, unit: &Unit) -> Result<(sysid::FitOptions<UnitEffect>, RateReference)> {
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
    let effects = effects(a, unit)?;
    let (split, validate_on) = split(a)?;
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
    let preprocess = sysid::Preprocess {
        filter,
        input_filter,
        // With auto, the unit's accelerometer along z until the records
        // choose (FitRecipe::resolve).
        window: WindowSpec::new(
            match window_auto(a)? {
                true => crate::unit_sensor::default_window_signals(unit),
                false => a.window_signals.clone(),
            },
            a.window,
        )?,
        causal: a.causal,
        input: match a.input.as_str() {
            "auto" => Default::default(),
            i => i.parse()?,
        },
        smoother: match a.smoother.as_str() {
            "auto" => None,
            s => parse_smoother(s)?,
        },
    };
    let settings = FitSettings {
        centres,
        max_centres: a.max_centres,
        candidates: a.candidates,
        ridge: a.ridge,
        seed: a.seed,
        choice: model_choice(a)?,
        shared_centres: a.shared_centres,
        ..FitSettings::default()
    };
    let recipe = sysid::Recipe {
        preprocess,
        split,
        effects,
        settings,
    };
    let options = sysid::FitOptions {
        recipe,
        validate_on,
    };
    Ok((options, rate_reference))
}

/// Each channel's effects: `--effects` (for every channel, each checked
/// against its model), then its `--add-effect CHANNEL=ID`s, each once. An
/// item may stand for several dynamic effects (`ma_*`, `acc:*`, `@A..B`:
/// [`expand_dynamic`]), expanded for each channel.
fn effects(a: &FitArgs, unit: &Unit) -> Result<Vec<Vec<UnitEffect>>> {
    let items: Vec<&str> = a
        .effects
        .iter()
        .flat_map(|e| e.split(','))
        .map(str::trim)
        .filter(|s| !s.is_empty() && *s != "bias")
        .collect();
    let plug = UnitSensor::new(unit.clone());
    let accels = unit.accel_names();
    let of = |k: usize, item: &str, flag: &str| -> Result<Vec<UnitEffect>> {
        let input = unit.gyros()[k].input;
        expand_dynamic(item, &input, &accels)
            .map_err(|err| anyhow!("{flag}{item}: {err}"))?
            .iter()
            .map(|id| {
                // An id no channel takes is refused as it is.
                id.parse::<UnitEffect>()?;
                plug.parse_effect(k, id)
                    .map_err(|err| anyhow!("{flag}{id}: {err}"))
            })
            .collect()
    };
    let mut per: Vec<Vec<UnitEffect>> = vec![Vec::new(); unit.gyros().len()];
    let mut add = |k: usize, e: Vec<UnitEffect>| {
        for x in e {
            if !per[k].contains(&x) {
                per[k].push(x);
            }
        }
    };
    for k in 0..unit.gyros().len() {
        for item in &items {
            add(k, of(k, item, "--effects ")?);
        }
    }
    for s in &a.add_effect {
        let (channel, id) = s
            .split_once('=')
            .map(|(c, e)| (c.trim(), e.trim()))
            .ok_or_else(|| UnitEffectError::NotAPair { given: s.clone() })?;
        let k = unit
            .gyro_index(channel)
            .ok_or_else(|| UnitEffectError::UnknownChannel {
                given: s.clone(),
                channel: channel.to_string(),
                valid: unit.gyro_names().iter().map(|n| n.to_string()).collect(),
            })?;
        add(k, of(k, id, &format!("--add-effect {channel}="))?);
    }
    Ok(per)
}

/// The split and, with `--split by-record`, the record that validates.
fn split(a: &FitArgs) -> Result<(Holdout, Option<String>)> {
    let by_record = a.split.trim() == "by-record";
    let split = match by_record {
        true => Holdout::Blocked {
            train_fraction: a.train_fraction,
        },
        false => match crate::split::parse(&a.split).map_err(|_| {
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
    Ok((split, validate_on))
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
fn parse_smoother(s: &str) -> Result<Option<sysid::Smoother>> {
    if s.trim() == "none" {
        return Ok(None);
    }
    let cutoff_hz = parse_hz(s).map_err(|e| anyhow::anyhow!("--smoother {s}: {e} (or none)"))?;
    Ok(Some(sysid::Smoother { cutoff_hz }))
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

/// The flags that depend on the record's rate, said with the flag.
fn check_against_record(a: &FitArgs, record: &Record) -> Result<()> {
    for (flag, cutoff) in [
        ("--cutoff", (!a.no_filter).then_some(a.cutoff)),
        ("--input-cutoff", a.input_cutoff),
    ] {
        if let Some(c) = cutoff {
            crate::signal::LowPass::butterworth(a.filter_order, c, 1.0 / record.dt())
                .map_err(|e| anyhow::anyhow!("{flag} {}: {e}", crate::signal::num(c)))?;
        }
    }
    Ok(())
}
