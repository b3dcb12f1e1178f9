//! What every section of the page reads: the model's channels on the
//! record(s), the parity residues before and after, the baseline's scores
//! and what else is known, read once from the loop's model and preparation
//! of any unit, so that no section asks which unit or which plug-in it is.

use super::inputs::{Evaluated, NoiseFloor, ResidueRms};
use crate::unit_sensor::residues_of;
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use sysid::inference::Coefficient;
use sysid::{ChannelScores, Effect, Sensor};

/// One effect of a channel model, as the tables show it.
pub(super) struct EffectView {
    /// Its id (`g_y`, `col:temp`, `gg_II`).
    pub(super) id: String,
    /// The unit of its coefficient.
    pub(super) unit: String,
    /// Its coefficient, when the model file has one.
    pub(super) value: Option<f64>,
    /// With standard error and interval, in files written since.
    pub(super) coefficient: Option<Coefficient>,
}

/// One channel's model on the record(s).
pub(super) struct ChannelView<'a> {
    pub(super) name: String,
    pub(super) effects: Vec<EffectView>,
    pub(super) n_centres: usize,
    /// Kernel width, in window units (g).
    pub(super) width: f64,
    /// Scores on these rows (not the fit-time ones: the record may be another).
    pub(super) scores: ChannelScores,
    /// The filtered target on the rows.
    pub(super) target: &'a [f64],
    /// The filtered target on every sample.
    pub(super) target_full: &'a [f64],
    /// The prediction on the rows.
    pub(super) predicted: &'a [f64],
}

/// A baseline model on the same record(s): its effects and scores.
pub(super) struct BaselineView {
    pub(super) label: String,
    pub(super) effect_ids: Vec<String>,
    pub(super) scores: Vec<ChannelScores>,
}

/// The parity residues of the pre-processed outputs, per row, before and
/// after subtracting each channel's prediction.
pub(super) struct Residues {
    pub(super) names: Vec<String>,
    pub(super) before: Vec<Vec<f64>>,
    pub(super) after: Vec<Vec<f64>>,
}

/// What every section of the page reads.
pub(super) struct Ctx<'a> {
    pub(super) unit: &'a Unit,
    pub(super) channels: Vec<ChannelView<'a>>,
    /// Time of each row, s.
    pub(super) rows_t: Vec<f64>,
    /// Time of each sample of the calibrated record(s), s.
    pub(super) t_all: &'a [f64],
    /// Samples in the record(s) and their interval, s.
    pub(super) samples: usize,
    pub(super) dt: f64,
    pub(super) train: &'a [usize],
    pub(super) val: &'a [usize],
    /// The model's split, as its file says it.
    pub(super) split: String,
    /// The acceleration window's length, s.
    pub(super) window_s: f64,
    pub(super) residues: Residues,
    /// Residue rms before/after on the validation rows.
    pub(super) stats: Vec<ResidueRms>,
    pub(super) baseline: Option<BaselineView>,
    /// The channel the single-channel figures show.
    pub(super) show: usize,
    /// The window's first signal: the thrust-axis acceleration of a
    /// vibration test along it.
    pub(super) thrust: String,
    /// It as recorded and after the model's pre-filter, every sample.
    pub(super) thrust_raw: Option<Vec<f64>>,
    pub(super) thrust_processed: Option<Vec<f64>>,
    /// The first residue of the record(s) as given (no calibration, no
    /// filter), every sample; none for three gyros.
    pub(super) raw_residue: Option<(String, Vec<f64>)>,
    /// Per channel, the noise floor's standard deviation on the validation
    /// rows as the model's target sees it, deg/h, and where it comes from.
    pub(super) floor: Option<(Vec<f64>, String)>,
}

impl<'a> Ctx<'a> {
    /// Reads `on` (and a baseline on the same records) of `unit` on the
    /// `raw` record(s), with the noise floor if known.
    pub(super) fn new<S: Sensor>(
        unit: &'a Unit,
        on: &Evaluated<'a, S>,
        baseline: Option<(&str, &Evaluated<'_, S>)>,
        raw: &[&Record],
        noise_floor: Option<&NoiseFloor<'_>>,
    ) -> Self {
        let channels: Vec<ChannelView<'a>> = on
            .model
            .channels()
            .iter()
            .enumerate()
            .map(|(k, c)| ChannelView {
                name: c.channel().to_string(),
                effects: effect_views(c),
                n_centres: c.n_centres(),
                width: c.width(),
                scores: on.scores(k),
                target: on.prepared.target(k),
                target_full: on.prepared.target_full(k),
                predicted: &on.predicted[k],
            })
            .collect();
        let first = on.prepared.first_sample();
        let calibrated = on.prepared.calibrated();
        let thrust = on
            .model
            .preprocess()
            .window
            .signals()
            .first()
            .cloned()
            .unwrap_or_else(|| "az".into());
        let residues = residues_of_rows(unit, &channels);
        let stats = validation_stats(&residues, on.val);
        let baseline = baseline.map(|(label, b)| BaselineView {
            label: label.to_string(),
            effect_ids: b
                .model
                .channels()
                .iter()
                .map(|c| {
                    c.effects()
                        .iter()
                        .map(Effect::id)
                        .collect::<Vec<_>>()
                        .join(", ")
                })
                .collect(),
            scores: (0..b.model.channels().len()).map(|k| b.scores(k)).collect(),
        });
        let floor =
            noise_floor.and_then(|f| Some((floor_sd(on, f, channels.len())?, f.source.clone())));
        Ctx {
            unit,
            show: showcase(&channels),
            rows_t: calibrated.t()[first..].to_vec(),
            t_all: calibrated.t(),
            samples: raw.iter().map(|r| r.len()).sum(),
            dt: on.model.dt_s(),
            train: on.train,
            val: on.val,
            split: on.model.split().to_string(),
            window_s: on.model.preprocess().window.length() as f64 * on.model.dt_s(),
            residues,
            stats,
            baseline,
            thrust_raw: raw_column(raw, &thrust, first),
            thrust_processed: on.prepared.signal_full(&thrust).ok(),
            raw_residue: raw_first_residue(unit, raw, first),
            thrust,
            floor,
            channels,
        }
    }

    /// The times of `rows`.
    pub(super) fn rows_t(&self, rows: &[usize]) -> Vec<f64> {
        rows.iter().map(|&r| self.rows_t[r]).collect()
    }

    /// Channel `k`'s validation residual after compensation.
    pub(super) fn residual(&self, k: usize) -> Vec<f64> {
        let c = &self.channels[k];
        self.val
            .iter()
            .map(|&r| c.target[r] - c.predicted[r])
            .collect()
    }
}

/// Mean and standard deviation (about the mean) of `v`.
pub(super) fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len().max(1) as f64;
    let mean = v.iter().sum::<f64>() / n;
    let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n).sqrt();
    (mean, sd)
}

pub(super) fn pick(v: &[f64], rows: &[usize]) -> Vec<f64> {
    rows.iter().map(|&r| v[r]).collect()
}

impl<S: Sensor> Evaluated<'_, S> {
    /// Channel `k`'s scores on the split's rows; with no training rows (a
    /// record the model's split does not fit), the bias-only model is the
    /// validation rows' own mean.
    fn scores(&self, k: usize) -> ChannelScores {
        let train = if self.train.is_empty() {
            self.val
        } else {
            self.train
        };
        sysid::score(self.prepared.target(k), &self.predicted[k], train, self.val)
    }
}

fn effect_views<C: Clone, E: Effect>(c: &sysid::ChannelModel<C, E>) -> Vec<EffectView> {
    let values = c.effect_coefficients();
    c.effects()
        .iter()
        .enumerate()
        .map(|(j, e)| EffectView {
            id: e.id(),
            unit: e.unit(),
            value: values.get(j).copied(),
            coefficient: c.coefficients().and_then(|k| k.get(j).cloned()),
        })
        .collect()
}

/// The unit's residues of the pre-processed outputs on every row, before
/// and after compensation.
fn residues_of_rows(unit: &Unit, channels: &[ChannelView<'_>]) -> Residues {
    let outputs: Vec<Vec<f64>> = channels.iter().map(|c| c.target.to_vec()).collect();
    let compensated: Vec<Vec<f64>> = channels
        .iter()
        .map(|c| {
            c.target
                .iter()
                .zip(c.predicted)
                .map(|(y, p)| y - p)
                .collect()
        })
        .collect();
    Residues {
        names: unit.residue_names().to_vec(),
        before: residues_of(unit, &outputs),
        after: residues_of(unit, &compensated),
    }
}

/// Each residue's rms (about zero) before and after over the validation rows.
fn validation_stats(r: &Residues, val: &[usize]) -> Vec<ResidueRms> {
    let rms = |s: &[f64]| {
        (val.iter().map(|&i| s[i] * s[i]).sum::<f64>() / val.len().max(1) as f64).sqrt()
    };
    r.names
        .iter()
        .zip(r.before.iter().zip(&r.after))
        .map(|(name, (b, a))| ResidueRms {
            name: name.clone(),
            before: rms(b),
            after: Some(rms(a)),
        })
        .collect()
}

/// The channel whose validation residual fell most against a bias-only model:
/// the one the paper's single-channel figures show.
fn showcase(channels: &[ChannelView<'_>]) -> usize {
    channels
        .iter()
        .enumerate()
        .max_by(|(_, a), (_, b)| {
            let g = |s: &ChannelScores| s.val_rms_bias_only / s.val_rms;
            g(&a.scores).total_cmp(&g(&b.scores))
        })
        .map_or(0, |(k, _)| k)
}

/// A column of the record(s) as given (an accelerometer or an extra
/// column), end to end as the preparation lays them (each later record
/// without its first `first` samples), if every record has it.
fn raw_column(raw: &[&Record], name: &str, first: usize) -> Option<Vec<f64>> {
    let mut out = Vec::new();
    for (i, r) in raw.iter().enumerate() {
        let v = r.accel_named(name).or_else(|| r.extra(name))?;
        out.extend_from_slice(&v[if i == 0 { 0 } else { first }..]);
    }
    Some(out)
}

/// The unit's first residue of the record(s) as given, end to end.
fn raw_first_residue(unit: &Unit, raw: &[&Record], first: usize) -> Option<(String, Vec<f64>)> {
    let name = unit.residue_names().first()?.clone();
    let mut out = Vec::new();
    for (i, r) in raw.iter().enumerate() {
        let gyros: Vec<Vec<f64>> = (0..unit.gyros().len())
            .map(|k| r.gyro_at(k)[if i == 0 { 0 } else { first }..].to_vec())
            .collect();
        out.extend(residues_of(unit, &gyros).swap_remove(0));
    }
    Some((name, out))
}

/// Each channel's noise floor as the model's target sees it: the per-sample
/// floor through the model's pre-filter, standard deviation on the
/// validation rows, deg/h. `None` when it cannot be filtered like the
/// targets (not one value per sample of one record).
fn floor_sd<S: Sensor>(
    on: &Evaluated<'_, S>,
    floor: &NoiseFloor<'_>,
    channels: usize,
) -> Option<Vec<f64>> {
    let samples = on.prepared.calibrated().len();
    if floor.per_sample.len() != channels
        || on.prepared.record_rows().len() != 1
        || floor.per_sample.iter().any(|s| s.len() != samples)
    {
        return None;
    }
    let first = on.prepared.first_sample();
    floor
        .per_sample
        .iter()
        .map(|series| {
            let filtered = on.prepared.filter_like_targets(series).ok()?;
            let v: Vec<f64> = on.val.iter().map(|&r| filtered[first + r]).collect();
            Some(mean_sd(&v).1)
        })
        .collect()
}
