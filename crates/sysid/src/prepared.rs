//! From raw records to model inputs: the plug-in's calibration and targets,
//! the window's signals chosen from the calibrated records when the
//! pre-processing leaves them to the records
//! ([`crate::window::WindowSignals::Auto`]), the low-pass (zero-phase, or
//! causal in [`Preprocess::causal`] mode), the windows and the effects'
//! regressors, each record on its own and laid end to end.

use crate::error::SysidError;
use crate::preprocess::Preprocess;
use crate::sensor::{Sensor, every_operating_signal};
use crate::signals::{INTERVAL_TOLERANCE, Signals};
use crate::window::signal_choice::{ChannelSignals, WindowSignalsChoice, choose_per_channel};
use crate::window::{WindowSpec, Windows};
use faer::{Mat, MatRef};
use iir::LowPass;

/// Records prepared for fitting, prediction or diagnosis, with the sensor
/// (its calibration) and pre-processing they were prepared with: a fit on
/// them keeps both, so nothing prepared one way is fitted as if it were
/// another.
///
/// Row `r` of the windows (and of every per-row quantity) is sample
/// `first_sample() + r` of [`Prepared::calibrated`].
///
/// ```
/// # use sysid::example::Line;
/// let t: Vec<f64> = (0..100).map(|i| i as f64 * 0.1).collect();
/// let u: Vec<f64> = t.iter().map(|t| t.sin()).collect();
/// let y: Vec<f64> = u.iter().map(|u| 2.0 * u).collect();
/// let rec = sysid::Signals::new(t, vec![("y".into(), y), ("u".into(), u)])?;
/// let pre = sysid::Preprocess { filter: None, window: sysid::WindowSpec::new(vec!["u".into()], 10)?, ..Default::default() };
/// let p = sysid::Prepared::new(&Line, &rec, &pre)?;
/// assert_eq!((p.rows(), p.first_sample()), (91, 9));
/// assert_eq!(p.target(0)[0], 2.0 * p.windows(0).row(0)[9]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Prepared<S: Sensor> {
    sensor: S,
    preprocess: Preprocess,
    calibrated: Signals,
    /// The records of a multi-record preparation, each calibrated and
    /// untrimmed, with their rows; empty for one record.
    parts: Vec<Part>,
    filter: Option<LowPass>,
    /// Filtered targets per channel, full length.
    targets: Vec<Vec<f64>>,
    /// The windows of each group of channels that read the same signals
    /// ([`WindowSpec::groups`]): one for a window every channel shares.
    windows: Vec<Windows>,
    /// Each channel's entry of `windows`.
    group_of: Vec<usize>,
    /// The window's signals as the records chose them (one choice per group
    /// of channels choosing among the same signals), when the
    /// pre-processing asked them to ([`crate::window::WindowSignals::Auto`]);
    /// empty when it named them.
    window_choice: Vec<WindowSignalsChoice>,
}

/// One record of a multi-record preparation.
#[derive(Debug, Clone)]
struct Part {
    name: String,
    calibrated: Signals,
    rows: std::ops::Range<usize>,
}

/// A plug-in's error as the loop's.
pub(crate) fn sensor_error(e: crate::sensor::SensorError) -> SysidError {
    SysidError::Sensor(e)
}

impl<S: Sensor> Prepared<S> {
    /// Calibrates `raw` (the sensor's), chooses the window's signals if the
    /// pre-processing leaves them to the record, takes the targets, filters
    /// and forms windows.
    pub fn new(sensor: &S, raw: &Signals, pre: &Preprocess) -> Result<Self, SysidError> {
        Self::one(sensor, (String::new(), raw), pre)
    }

    /// [`Prepared::new`] of a record named `name` (for the window choice's
    /// report).
    fn one(
        sensor: &S,
        (name, raw): (String, &Signals),
        pre: &Preprocess,
    ) -> Result<Self, SysidError> {
        let calibrated = sensor.calibrate(raw).map_err(sensor_error)?;
        let (pre, window_choice) = chosen_window(sensor, pre, &[(name, &calibrated)])?;
        let mut prepared = Self::from_calibrated(sensor, calibrated, &pre)?;
        prepared.window_choice = window_choice;
        Ok(prepared)
    }

    /// [`Prepared::new`] on a record already calibrated by `sensor`.
    fn from_calibrated(
        sensor: &S,
        calibrated: Signals,
        pre: &Preprocess,
    ) -> Result<Self, SysidError> {
        let causal = pre.causal;
        let design = |f: Option<crate::preprocess::FilterSpec>| {
            f.map(|f| LowPass::butterworth(f.order, f.cutoff_hz, 1.0 / calibrated.dt()))
                .transpose()
        };
        let filter = design(pre.filter)?;
        let targets = sensor
            .targets(&calibrated)
            .map_err(sensor_error)?
            .iter()
            .map(|y| apply(&filter, causal, y))
            .collect::<Result<Vec<_>, _>>()?;
        let (windows, group_of) = inputs(sensor, &calibrated, pre)?;
        Ok(Self {
            sensor: sensor.clone(),
            preprocess: pre.clone(),
            calibrated,
            parts: Vec::new(),
            filter,
            targets,
            windows,
            group_of,
            window_choice: Vec::new(),
        })
    }

    /// The window's signals as the records chose them (each signal's
    /// dynamic rms, what was taken and why: one choice per group of
    /// channels choosing among the same signals), when the pre-processing
    /// asked them to ([`crate::window::WindowSignals::Auto`]); empty when it
    /// named them.
    pub fn window_choice(&self) -> &[WindowSignalsChoice] {
        &self.window_choice
    }

    /// The same records with the network's input `input` (a fit's choice
    /// tries each): only the inputs are formed again.
    pub fn with_input(&self, input: crate::input::ModelInput) -> Result<Self, SysidError> {
        let mut pre = self.preprocess.clone();
        pre.input = input;
        let windows = if self.parts.is_empty() {
            inputs(&self.sensor, &self.calibrated, &pre)?.0
        } else {
            let parts = self
                .parts
                .iter()
                .map(|p| Ok(inputs(&self.sensor, &p.calibrated, &pre)?.0))
                .collect::<Result<Vec<_>, SysidError>>()?;
            concat_groups(&parts)
        };
        Ok(Self {
            preprocess: pre,
            windows,
            ..self.clone()
        })
    }

    /// Several records prepared one by one (calibration, filter and windows
    /// never cross from one record to the next) and laid end to end, named
    /// (by their file, say) for errors and per-record scores.
    ///
    /// Row `r` is still sample `first_sample() + r` of
    /// [`Prepared::calibrated`], which holds the records one after another
    /// with each later record's warm-up (the samples before its first full
    /// window) left out and its time restamped to continue the first
    /// record's. The records must share their sample interval (median steps
    /// within [`INTERVAL_TOLERANCE`]) and their extra columns. One record gives exactly [`Prepared::new`].
    pub fn new_many(
        sensor: &S,
        records: &[(String, &Signals)],
        pre: &Preprocess,
    ) -> Result<Self, SysidError> {
        let Some(((first_name, first_record), rest)) = records.split_first() else {
            return Err(SysidError::NoRecords);
        };
        if rest.is_empty() {
            return Self::one(sensor, (first_name.clone(), first_record), pre);
        }
        let extras = |r: &Signals| {
            let mut names = sensor.extra_columns(r);
            names.sort_unstable();
            names
        };
        let names = extras(first_record);
        for (name, r) in rest {
            let dt = (first_record.median_dt(), r.median_dt());
            if (dt.0 - dt.1).abs() > INTERVAL_TOLERANCE * dt.0 {
                return Err(SysidError::RecordsDiffer {
                    first: first_name.clone(),
                    other: name.clone(),
                    what: format!(
                        "median sampling interval {} s against {} s, {:.2} % apart (at most {} % is one rate)",
                        dt.0,
                        dt.1,
                        100.0 * (dt.1 / dt.0 - 1.0).abs(),
                        100.0 * INTERVAL_TOLERANCE
                    ),
                });
            }
            let other = extras(r);
            if other != names {
                return Err(SysidError::RecordsDiffer {
                    first: first_name.clone(),
                    other: name.clone(),
                    what: format!(
                        "extra columns [{}] against [{}]",
                        names.join(", "),
                        other.join(", ")
                    ),
                });
            }
        }
        let calibrated = calibrate_each(sensor, records)?;
        let named: Vec<(String, &Signals)> = records
            .iter()
            .zip(&calibrated)
            .map(|((name, _), c)| (name.clone(), c))
            .collect();
        let (pre, window_choice) = chosen_window(sensor, pre, &named)?;
        let prepared = records
            .iter()
            .zip(calibrated)
            .map(|((name, _), c)| {
                Self::from_calibrated(sensor, c, &pre).map_err(|e| e.in_record(name, records.len()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let names = records.iter().map(|(name, _)| name.clone()).collect();
        let mut prepared = Self::concat(prepared, names);
        prepared.window_choice = window_choice;
        Ok(prepared)
    }

    /// `chunks` spans of `rows_each` rows (fewer where a record ends first)
    /// spread evenly over the rows, each prepared again on its own from its
    /// calibrated samples (filters and windows restart in it) and laid end
    /// to end, named `sample 1`, `sample 2`, …: a small stand-in for a large
    /// record, on which a choice is cheap to make. `None` when the records
    /// are too short for a chunk of more than half of `rows_each` rows.
    pub(crate) fn sample(
        &self,
        chunks: usize,
        rows_each: usize,
    ) -> Result<Option<Self>, SysidError> {
        let (n, first) = (self.rows(), self.first_sample());
        let span = n / chunks.max(1);
        if span < rows_each {
            return Ok(None);
        }
        let mut prepared = Vec::with_capacity(chunks);
        for c in 0..chunks {
            // Each chunk in the middle of its span of rows.
            let row = c * span + (span - rows_each) / 2;
            let (record, sample) = self.locate(row);
            let from = sample - first;
            let to = (sample + rows_each).min(record.len());
            if to - sample < rows_each / 2 {
                return Ok(None);
            }
            let columns = record
                .columns()
                .iter()
                .map(|(name, v)| (name.clone(), v[from..to].to_vec()))
                .collect();
            let part = Signals::new(record.t()[from..to].to_vec(), columns)?;
            prepared.push(Self::from_calibrated(&self.sensor, part, &self.preprocess)?);
        }
        let names = (1..=chunks).map(|c| format!("sample {c}")).collect();
        Ok(Some(Self::concat(prepared, names)))
    }

    /// Prepared records laid end to end, each later one without its warm-up.
    fn concat(prepared: Vec<Self>, names: Vec<String>) -> Self {
        let first = prepared[0].first_sample();
        let trim = |k: usize| if k == 0 { 0 } else { first };
        let mut parts = Vec::with_capacity(prepared.len());
        let mut row = 0;
        for (p, name) in prepared.iter().zip(names) {
            let rows = p.rows();
            parts.push(Part {
                name,
                calibrated: p.calibrated.clone(),
                rows: row..row + rows,
            });
            row += rows;
        }
        let targets: Vec<Vec<f64>> = (0..prepared[0].targets.len())
            .map(|k| {
                prepared
                    .iter()
                    .enumerate()
                    .flat_map(|(i, p)| p.targets[k][trim(i)..].iter().copied())
                    .collect()
            })
            .collect();
        let calibrated = Signals::concat(
            &prepared.iter().map(|p| &p.calibrated).collect::<Vec<_>>(),
            first,
        );
        let windows = concat_groups(
            &prepared
                .iter()
                .map(|p| p.windows.clone())
                .collect::<Vec<_>>(),
        );
        let head = prepared.into_iter().next().expect("two or more records");
        Self {
            sensor: head.sensor,
            preprocess: head.preprocess,
            calibrated,
            parts,
            filter: head.filter,
            targets,
            windows,
            group_of: head.group_of,
            window_choice: head.window_choice,
        }
    }

    /// The sensor the records were calibrated and read by.
    pub fn sensor(&self) -> &S {
        &self.sensor
    }

    /// How the records were prepared.
    pub fn preprocess(&self) -> &Preprocess {
        &self.preprocess
    }

    /// The records and their rows: one entry per record of
    /// [`Prepared::new_many`], and one named `""` for [`Prepared::new`].
    pub fn record_rows(&self) -> Vec<(&str, std::ops::Range<usize>)> {
        if self.parts.is_empty() {
            return vec![("", 0..self.rows())];
        }
        self.parts
            .iter()
            .map(|p| (p.name.as_str(), p.rows.clone()))
            .collect()
    }

    /// The record (calibrated, whole) a row belongs to, and the sample of
    /// that record its window ends at: a window's span `sample + 1 −
    /// length ..= sample` then lies inside one record.
    pub fn locate(&self, row: usize) -> (&Signals, usize) {
        let first = self.first_sample();
        match self.parts.iter().find(|p| p.rows.contains(&row)) {
            Some(p) => (&p.calibrated, first + row - p.rows.start),
            None => (&self.calibrated, first + row),
        }
    }

    /// A per-record series over the full (concatenated) sample range:
    /// computed on each record alone, filtered on it alone, warm-up of each
    /// later record left out.
    fn per_record(
        &self,
        f: impl Fn(&Signals) -> Result<Vec<Vec<f64>>, SysidError>,
    ) -> Result<Vec<Vec<f64>>, SysidError> {
        if self.parts.is_empty() {
            return f(&self.calibrated);
        }
        let first = self.first_sample();
        let mut out: Vec<Vec<f64>> = Vec::new();
        for (k, p) in self.parts.iter().enumerate() {
            let cols = f(&p.calibrated).map_err(|e| SysidError::InRecord {
                record: p.name.clone(),
                source: Box::new(e),
            })?;
            out.resize_with(cols.len(), || Vec::with_capacity(self.calibrated.len()));
            for (o, c) in out.iter_mut().zip(cols) {
                o.extend(c.into_iter().skip(if k == 0 { 0 } else { first }));
            }
        }
        Ok(out)
    }

    /// The records' median sample interval, s: the first record's, which
    /// [`Prepared::new_many`] checks the others' against (the records laid
    /// end to end are restamped on an even grid, whose median is its mean).
    pub fn median_dt(&self) -> f64 {
        self.parts
            .first()
            .map_or(&self.calibrated, |p| &p.calibrated)
            .median_dt()
    }

    /// The calibrated (not filtered) records, end to end (restamped on the
    /// first one's grid).
    pub fn calibrated(&self) -> &Signals {
        &self.calibrated
    }

    /// Number of rows (windows).
    pub fn rows(&self) -> usize {
        self.windows[0].len()
    }

    /// Record sample of row 0.
    pub fn first_sample(&self) -> usize {
        self.windows[0].first_sample()
    }

    /// Channel `channel`'s windows as an `rows × dim` matrix.
    pub fn window_matrix(&self, channel: usize) -> Mat<f64> {
        let w = self.windows(channel);
        Mat::from_fn(w.len(), w.dim(), |i, j| w.row(i)[j])
    }

    /// Channel `channel`'s windows as an `rows × dim` matrix view of the
    /// prepared windows themselves ([`Windows::matrix`]; nothing is
    /// copied): what [`Prepared::window_matrix`] holds, without its copy
    /// (400 MB for a 1M-row record of 50-sample windows).
    pub fn window_view(&self, channel: usize) -> MatRef<'_, f64> {
        self.windows(channel).matrix()
    }

    /// Channel `channel`'s windows.
    pub fn windows(&self, channel: usize) -> &Windows {
        &self.windows[self.group_of[channel]]
    }

    /// The channels that read the same windows, each group with a view of
    /// them ([`WindowSpec::groups`]): one group of every channel when they
    /// share one window.
    pub fn window_groups(&self) -> Vec<(Vec<usize>, MatRef<'_, f64>)> {
        self.windows
            .iter()
            .enumerate()
            .map(|(g, w)| {
                let members = (0..self.group_of.len())
                    .filter(|&k| self.group_of[k] == g)
                    .collect();
                (members, w.matrix())
            })
            .collect()
    }

    /// Channel `channel`'s filtered target over the whole record.
    pub fn target_full(&self, channel: usize) -> &[f64] {
        &self.targets[channel]
    }

    /// Channel `channel`'s target on the rows.
    pub fn target(&self, channel: usize) -> &[f64] {
        &self.targets[channel][self.first_sample()..]
    }

    /// The filtered regressors of `effects` of channel `channel` over the
    /// whole record.
    pub fn effect_columns_full(
        &self,
        channel: usize,
        effects: &[S::Effect],
    ) -> Result<Vec<Vec<f64>>, SysidError> {
        // No effects, no columns: a record's regressors (0.5 GB of rates
        // and covariances for a 1M-sample inertial record) are not worked
        // out for nothing.
        if effects.is_empty() {
            return Ok(Vec::new());
        }
        // Regressors first, filter second: the sensor saw the regressor (a
        // product of inputs, say), and the filtered output holds the
        // filtered regressor, not one of filtered inputs.
        self.per_record(|record| {
            let cols = self
                .sensor
                .regressors(record, channel, effects)
                .map_err(sensor_error)?;
            cols.iter()
                .map(|c| apply(&self.filter, self.preprocess.causal, c))
                .collect()
        })
    }

    /// The regressors of `effects` of channel `channel` on the rows, not
    /// filtered, as an `rows × effects` matrix: what compensation subtracts
    /// from the unfiltered output (θ·z), where the filtered regressor would
    /// leave the effect's part above the cut-off in it.
    pub fn effect_matrix_unfiltered(
        &self,
        channel: usize,
        effects: &[S::Effect],
    ) -> Result<Mat<f64>, SysidError> {
        if effects.is_empty() {
            return Ok(Mat::zeros(self.rows(), 0));
        }
        let cols = self.per_record(|record| {
            self.sensor
                .regressors(record, channel, effects)
                .map_err(sensor_error)
        })?;
        let first = self.first_sample();
        Ok(Mat::from_fn(self.rows(), cols.len(), |i, j| {
            cols[j][first + i]
        }))
    }

    /// The regressors of channel `channel` on the rows, as an
    /// `rows × effects` matrix.
    pub fn effect_matrix(
        &self,
        channel: usize,
        effects: &[S::Effect],
    ) -> Result<Mat<f64>, SysidError> {
        let cols = self.effect_columns_full(channel, effects)?;
        let first = self.first_sample();
        Ok(Mat::from_fn(self.rows(), cols.len(), |i, j| {
            cols[j][first + i]
        }))
    }

    /// A record signal (an operating signal or an extra column), filtered,
    /// over the whole record.
    pub fn signal_full(&self, name: &str) -> Result<Vec<f64>, SysidError> {
        let filtered = |r: &Signals| {
            apply(
                &self.filter,
                self.preprocess.causal,
                signal(&self.sensor, r, name)?,
            )
            .map(|v| vec![v])
        };
        Ok(self.per_record(filtered)?.pop().unwrap_or_default())
    }

    /// A series over the whole record (one sample per record sample)
    /// through the filter the targets went through, zero-phase or causal:
    /// e.g. a simulator's per-sample noise floor as the model's target sees
    /// it. For a preparation of one record (a series over several would be
    /// filtered across their boundaries).
    pub fn filter_like_targets(&self, x: &[f64]) -> Result<Vec<f64>, SysidError> {
        apply(&self.filter, self.preprocess.causal, x)
    }

    /// True when prepared in causal mode ([`Preprocess::causal`]).
    pub fn causal(&self) -> bool {
        self.preprocess.causal
    }

    /// The designed filter, if any.
    pub fn filter(&self) -> Option<&LowPass> {
        self.filter.as_ref()
    }

    /// Samples over which one sample influences its filtered neighbours on
    /// each side (where the impulse response, zero-phase or causal, exceeds
    /// 10⁻³ of its peak); 0 without a filter. Train and validation rows are
    /// kept this far apart, plus a window length, so nothing leaks across.
    pub fn filter_memory(&self) -> usize {
        let Some(f) = &self.filter else { return 0 };
        if self.preprocess.causal {
            let mut impulse = vec![0.0; 4000];
            impulse[0] = 1.0;
            let h = f.filter(&impulse);
            let peak = h.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            return (1..h.len())
                .rev()
                .find(|&k| h[k].abs() > 1e-3 * peak)
                .unwrap_or(0);
        }
        let half = 2000;
        let mut impulse = vec![0.0; 2 * half + 1];
        impulse[half] = 1.0;
        let Ok(h) = f.filtfilt(&impulse) else {
            return 0;
        };
        let peak = h[half].abs();
        (1..half)
            .rev()
            .find(|&k| h[half + k].abs() > 1e-3 * peak)
            .unwrap_or(0)
    }
}

/// The window's signals for `sensor` chosen from its raw `records` (each
/// calibrated first) by [`crate::window::signal_choice`]'s rule, each
/// channel's among its own operating signals
/// ([`Sensor::operating_signals_of`]): what [`Prepared`] does for a window
/// of [`crate::window::WindowSignals::Auto`].
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let c = sysid::choose_window_signals(&Line, &[("r".into(), &line_record(500, 1.0, 1))])?;
/// assert_eq!(c.signals, [["u"]]);
/// # Ok::<(), sysid::SysidError>(())
/// ```
pub fn choose_window_signals<S: Sensor>(
    sensor: &S,
    records: &[(String, &Signals)],
) -> Result<ChannelSignals, SysidError> {
    if records.is_empty() {
        return Err(SysidError::NoRecords);
    }
    let calibrated = calibrate_each(sensor, records)?;
    let named: Vec<(String, &Signals)> = records
        .iter()
        .zip(&calibrated)
        .map(|((n, _), c)| (n.clone(), c))
        .collect();
    choose_on_calibrated(sensor, &named)
}

/// Each of `records` calibrated by `sensor`, an error named by its record
/// when there are several.
fn calibrate_each<S: Sensor>(
    sensor: &S,
    records: &[(String, &Signals)],
) -> Result<Vec<Signals>, SysidError> {
    records
        .iter()
        .map(|(n, r)| {
            sensor
                .calibrate(r)
                .map_err(|e| sensor_error(e).in_record(n, records.len()))
        })
        .collect()
}

/// Each channel's candidates for its window's signals: its own operating
/// signals ([`Sensor::operating_signals_of`]), or the shared ones
/// ([`Sensor::operating_signals`]) when every channel's are alike.
pub fn window_candidates<S: Sensor>(sensor: &S) -> Vec<Vec<String>> {
    let n = sensor.channels().len();
    let own: Vec<Vec<String>> = (0..n).map(|k| sensor.operating_signals_of(k)).collect();
    match own.iter().all(|o| *o == own[0]) {
        true => vec![sensor.operating_signals(); n],
        false => own,
    }
}

/// [`choose_window_signals`] on records `sensor` calibrated.
fn choose_on_calibrated<S: Sensor>(
    sensor: &S,
    calibrated: &[(String, &Signals)],
) -> Result<ChannelSignals, SysidError> {
    let names: Vec<String> = sensor.channels().iter().map(|c| c.to_string()).collect();
    Ok(choose_per_channel(
        &window_candidates(sensor),
        &sensor.signal_order(),
        &names,
        calibrated,
        sensor.operating_scale(),
        &sensor.wording().operating_unit,
    )?)
}

/// `pre` with its window's signals named: as it is when it names them, else
/// chosen from the calibrated records (with the choices). Every
/// preparation starts here, so the sensor's channels and the window's
/// lists of them are checked here ([`check_channels`]).
fn chosen_window<S: Sensor>(
    sensor: &S,
    pre: &Preprocess,
    calibrated: &[(String, &Signals)],
) -> Result<(Preprocess, Vec<WindowSignalsChoice>), SysidError> {
    check_channels(sensor.channels().len(), &pre.window)?;
    if !pre.window.is_auto() {
        return Ok((pre.clone(), Vec::new()));
    }
    let chosen = choose_on_calibrated(sensor, calibrated)?;
    let mut named = pre.clone();
    named.window = chosen.window(pre.window.length())?;
    Ok((named, chosen.choices))
}

/// A sensor of `channels` channels, at least one, and a window that names
/// either one list of signals for all of them or one list for each.
fn check_channels(channels: usize, window: &WindowSpec) -> Result<(), SysidError> {
    if channels == 0 {
        return Err(SysidError::NoChannels);
    }
    match window.channel_lists() {
        Some(lists) if lists != channels => Err(SysidError::WindowChannels { lists, channels }),
        _ => Ok(()),
    }
}

/// The network's inputs of one calibrated record: for each group of
/// channels that read the same signals ([`WindowSpec::groups`]), its
/// windowed signals through the input low-pass, formed as `pre.input`
/// says; and each channel's group.
fn inputs<S: Sensor>(
    sensor: &S,
    calibrated: &Signals,
    pre: &Preprocess,
) -> Result<(Vec<Windows>, Vec<usize>), SysidError> {
    let input_filter = pre
        .input_filter
        .map(|f| LowPass::butterworth(f.order, f.cutoff_hz, 1.0 / calibrated.dt()))
        .transpose()?;
    let groups = pre.window.groups(sensor.channels().len());
    let mut group_of = vec![0; sensor.channels().len()];
    let mut windows = Vec::with_capacity(groups.len());
    for (g, (members, spec)) in groups.iter().enumerate() {
        members.iter().for_each(|&k| group_of[k] = g);
        windows.push(group_inputs(sensor, calibrated, pre, &input_filter, spec)?);
    }
    Ok((windows, group_of))
}

/// The network's inputs of one group's window `spec` on one record.
fn group_inputs<S: Sensor>(
    sensor: &S,
    calibrated: &Signals,
    pre: &Preprocess,
    input_filter: &Option<LowPass>,
    spec: &WindowSpec,
) -> Result<Windows, SysidError> {
    let mut signals = Vec::with_capacity(spec.signals().len());
    for name in spec.signals() {
        signals.push(apply(
            input_filter,
            pre.causal,
            signal(sensor, calibrated, name)?,
        )?);
    }
    let refs: Vec<&[f64]> = signals.iter().map(Vec::as_slice).collect();
    Ok(pre.input.build(spec, &refs)?)
}

/// Each group's windows of several records, one after another
/// ([`Windows::concat`]): `parts[r][g]` is record r's of group g.
fn concat_groups(parts: &[Vec<Windows>]) -> Vec<Windows> {
    (0..parts[0].len())
        .map(|g| Windows::concat(&parts.iter().map(|p| p[g].clone()).collect::<Vec<_>>()))
        .collect()
}

/// `x` through the filter (forward–backward, or one causal pass), or as it
/// is without one.
fn apply(filter: &Option<LowPass>, causal: bool, x: &[f64]) -> Result<Vec<f64>, SysidError> {
    Ok(match filter {
        Some(f) if causal => {
            if let Some(i) = x.iter().position(|v| !v.is_finite()) {
                return Err(iir::FilterError::NotFinite { index: i }.into());
            }
            f.filter_causal(x)
        }
        Some(f) => f.filtfilt(x)?,
        None => x.to_vec(),
    })
}

/// A signal a window or a test may read: one of the sensor's operating
/// signals (shared, or of any channel: [`Sensor::operating_signals_of`])
/// or an extra column of the record (never its outputs).
pub fn signal<'r, S: Sensor>(
    sensor: &S,
    record: &'r Signals,
    name: &str,
) -> Result<&'r [f64], SysidError> {
    let operating = every_operating_signal(sensor);
    let extras = sensor.extra_columns(record);
    let known = operating.iter().chain(&extras).any(|n| n == name);
    match record.column(name) {
        Some(v) if known => Ok(v),
        _ => Err(SysidError::WindowSignal {
            name: name.to_string(),
            operating,
            available: extras,
        }),
    }
}
