//! The diagnosis loop: compare the model with the measurements, see where it
//! fails, and learn which physical effect is missing.
//!
//! Everything is computed on the validation rows of the model's own split,
//! because a residual on training rows has already been fitted away.
//!
//! The diagnosis fits no model: it reads predictions, the model's and its
//! mirror's (the same recipe trained on the other rows), which the loop
//! layer fits and hands in ([`crate::fit::mirror`],
//! [`crate::explain::diagnose_records`]); so does a trial with a longer
//! window ([`Diagnosis::note_window_trial`]). The one estimate it makes
//! with the fit layer is a suggestion's coefficient, stated by the fit's
//! own cross-fitted estimator so that it is what the refit stores
//! (`estimate`).
//! What is physical in it (the candidate effects, what separates two of
//! them, the words of a finding) is the sensor's.

mod candidates;
mod checks;
mod context;
mod estimate;
mod findings;
mod locate;
mod model_and_mirror;
mod rank;
mod records;

pub use crate::sensor::{Response, Separation};
pub use findings::p_text;
pub use locate::{Band, Regime, RegimeBin, ResidualSpectrum, Segment, regime, segments};
pub use rank::{Candidate, RankOptions, Ranking, Unexcited, rank};
pub use records::{MIN_ENERGY_SHARE, RecordCorrelation, RecordSeparation, record_separations};

use crate::error::SysidError;
use crate::model::{ChannelModelOf, ChannelScores, Model};
use crate::prepared::Prepared;
use crate::residuals::CorrelationCheck;
use crate::sensor::{Effect, Sensor};
use context::Context;
use model_and_mirror::{CrossFit, Half};
use rayon::prelude::*;
use serde::Serialize;

/// Diagnosis settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DiagnoseOptions {
    /// Candidate ranking and suggestion thresholds.
    pub rank: RankOptions,
    /// Confidence of the correlation tests' per-lag bands (MATLAB's `resid` uses 0.99).
    pub confidence: f64,
    /// Largest lag of the correlation tests, samples (MATLAB's default is 25).
    pub max_lag: usize,
    /// Time segments of the validation part.
    pub segments: usize,
    /// Quantile bins per acceleration axis.
    pub regime_bins: usize,
    /// Where the residual stays correlated beyond the model's window, the
    /// loop refits with a three times longer window and the diagnosis
    /// reports the validation rms it gives
    /// ([`crate::explain::diagnose_records`]).
    pub try_settings: bool,
}

impl Default for DiagnoseOptions {
    fn default() -> Self {
        Self {
            rank: RankOptions::default(),
            confidence: 0.99,
            max_lag: 25,
            segments: 10,
            regime_bins: 5,
            try_settings: true,
        }
    }
}

/// A correlation test with the name of what it tested against.
#[derive(Debug, Clone, Serialize)]
pub struct NamedCheck {
    /// `whiteness`, `independence:az`, `billings_voon_u2_e:ax`, …
    pub name: String,
    /// The curve, bands and verdict.
    pub check: CorrelationCheck,
}

/// Per-row series of a channel on the validation rows, for figures.
#[derive(Debug, Clone, Default)]
pub struct ChannelSeries {
    /// Time, s.
    pub t: Vec<f64>,
    /// The pre-processed target, in its unit.
    pub measured: Vec<f64>,
    /// Model prediction.
    pub predicted: Vec<f64>,
    /// `measured − predicted`.
    pub residual: Vec<f64>,
    /// The candidate columns (filtered, less their training mean) on the validation rows, by id.
    pub candidates: Vec<(String, Vec<f64>)>,
    /// The residual's spectrum and its white floor, if the residual is long enough.
    pub spectrum: Option<ResidualSpectrum>,
}

/// Everything found about one channel `C` (the sensor's channel type; `A`
/// its axis, as separation advice names it).
#[derive(Debug, Clone, Serialize)]
pub struct ChannelDiagnosis<C, A = String> {
    /// The channel.
    pub channel: C,
    /// Effects the model already has.
    pub effects: Vec<String>,
    /// RMS of the validation residual, in the target's unit.
    pub rms: f64,
    /// Measured against predicted, as MATLAB's `compare` reports it (rms,
    /// fit percentage, on training and validation rows).
    pub compare: ChannelScores,
    /// Residual by time segment.
    pub segments: Vec<Segment>,
    /// Residual power by frequency band.
    pub bands: Vec<Band>,
    /// Residual by operating regime (bins of each operating signal).
    pub regimes: Vec<Regime>,
    /// Correlation tests.
    pub checks: Vec<NamedCheck>,
    /// Names of the correlation tests that fail.
    pub failing: Vec<String>,
    /// Candidate effects, sorted by ERR descending.
    pub candidates: Vec<Candidate<A>>,
    /// Candidates the record does not excite.
    pub unexcited: Vec<Unexcited>,
    /// Suggested effect ids (significant only; empty when nothing is).
    pub suggested: Vec<String>,
    /// The p-value a suggestion must fall below: α / (channels · candidates).
    pub p_threshold: f64,
    /// Plain-language findings, most important first.
    pub findings: Vec<String>,
    /// Series for figures (not serialised).
    #[serde(skip)]
    pub series: ChannelSeries,
}

/// The diagnosis of every channel.
#[derive(Debug, Clone, Serialize)]
pub struct Diagnosis<C, A = String> {
    /// The records diagnosed together, by name (absent for one record).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub records: Vec<String>,
    /// Per channel, in the sensor's channel order.
    pub channels: Vec<ChannelDiagnosis<C, A>>,
    /// What the records can observe of each effect family, one line per
    /// family ([`Sensor::observable`]; absent when the sensor says nothing).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub observable: Vec<String>,
}

/// Diagnoses `model` on the record(s) it was fitted on, `prepared` by
/// [`Model::prepare_many`], reading its predictions and those of its
/// `mirror` ([`crate::fit::mirror`]): every candidate ranked on the rows of
/// all the records. A pair of candidates that one record cannot tell apart
/// is separated by another that excites them differently, and
/// [`Candidate::record_separations`] says which.
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let rec = line_record(3000, 2.0, 5);
/// let mut options = sysid::FitOptions::new(1);
/// options.recipe.preprocess = Line::preprocess();
/// options.recipe.settings.max_centres = 5;
/// let (model, _) = sysid::fit_records(&Line, &[("r".into(), &rec)], &options, &|_| {})?;
/// let prepared = model.prepare(&rec)?;
/// let mirror = sysid::fit::mirror(&model, &prepared)?;
/// let d = sysid::diagnose::diagnose_prepared(&model, &prepared, &mirror, &Default::default())?;
/// assert_eq!(d.channels[0].channel, "y");
/// # Ok::<(), sysid::SysidError>(())
/// ```
pub fn diagnose_prepared<S: Sensor>(
    model: &Model<S>,
    prepared: &Prepared<S>,
    mirror: &Model<S>,
    options: &DiagnoseOptions,
) -> Result<Diagnosis<S::Channel, S::Axis>, SysidError> {
    let predictions = model.predict(prepared)?;
    let (train, val) = model.rows(prepared)?;
    let mirror_predictions = mirror.predict(prepared)?;
    // Each group of channels' windows, copied once.
    let windows: Vec<(Vec<usize>, faer::Mat<f64>)> = prepared
        .window_groups()
        .into_iter()
        .map(|(members, x)| (members, x.to_owned()))
        .collect();
    let x_of = |k: usize| {
        let (_, x) = windows
            .iter()
            .find(|(m, _)| m.contains(&k))
            .expect("every channel reads a group's windows");
        x
    };
    let context = Context::new(prepared, &val)?;
    let raw = crate::fit::raw_windows(prepared)?;
    let theta_rows = crate::fit::theta_rows(&train, &val);
    let estimator = |k: usize| estimate::Estimator {
        x: raw
            .as_ref()
            .map_or(prepared.window_view(k), |p| p.window_view(k)),
        settings: model.settings(),
        rows: &theta_rows,
        gap: crate::split::leakage_gap(prepared),
    };
    // The suggestion threshold is shared over the model's channels.
    let options = DiagnoseOptions {
        rank: RankOptions {
            channels: model.channels().len(),
            ..options.rank
        },
        ..*options
    };
    // The channels are independent: in parallel (the mirror's fit before
    // this keeps both cores busy, this part did not).
    let channels = model
        .channels()
        .par_iter()
        .enumerate()
        .map(|(i, c)| {
            let halves = CrossFit {
                x: x_of(i),
                ridge: model.settings().ridge,
                channel: i,
                halves: [
                    Half {
                        model: c,
                        predicted: &predictions[i],
                        fit_rows: &train,
                        test_rows: &val,
                    },
                    Half {
                        model: &mirror.channels()[i],
                        predicted: &mirror_predictions[i],
                        fit_rows: &val,
                        test_rows: &train,
                    },
                ],
            };
            let rows = (train.as_slice(), val.as_slice());
            diagnose_channel(
                c,
                prepared,
                &predictions[i],
                rows,
                &halves,
                (&context, &estimator(i)),
                &options,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let records = match prepared.record_rows() {
        parts if parts.len() > 1 => parts.into_iter().map(|(n, _)| n.to_string()).collect(),
        _ => Vec::new(),
    };
    Ok(Diagnosis {
        records,
        channels,
        observable: prepared.sensor().observable(),
    })
}

impl<C: Clone + PartialEq, A> Diagnosis<C, A> {
    /// The channels whose residual stays correlated beyond the model's
    /// window (the whiteness test fails): where a longer window is the
    /// setting to try.
    pub fn slow_channels(&self) -> Vec<C> {
        self.channels
            .iter()
            .filter(|c| c.failing.iter().any(|f| f == "whiteness"))
            .map(|c| c.channel.clone())
            .collect()
    }

    /// Adds to each [`Diagnosis::slow_channels`] finding the validation rms
    /// that `trial`, the model's recipe refitted on the same records with
    /// windows of `length` samples ([`crate::fit::refit_with_window`]),
    /// gave: the advice to refit with that window is given only with what it
    /// gained, before and after.
    pub fn note_window_trial<S: Sensor<Channel = C>>(&mut self, length: usize, trial: &Model<S>) {
        let on = if self.records.len() > 1 {
            "these records"
        } else {
            "this record"
        };
        let unit = trial.sensor().wording().target_unit;
        for (k, c) in self.channels.iter_mut().enumerate() {
            if !c.failing.iter().any(|f| f == "whiteness") {
                continue;
            }
            let before = c.rms;
            let after = trial.channel(k).scores().val_rms;
            c.findings.push(if after < 0.95 * before {
                format!(
                    "tried --window {length} on {on}: validation rms {before:.4} → {after:.4} {unit} ({:+.0}%): refit with --window {length}",
                    100.0 * (after / before - 1.0)
                )
            } else {
                format!(
                    "tried --window {length} on {on}: validation rms {before:.4} → {after:.4} {unit}, no better: the slow error is not the window's"
                )
            });
        }
    }
}

/// One channel's diagnosis: compare, rank the candidates, test the
/// residual, and see where it fails.
fn diagnose_channel<S: Sensor>(
    model: &ChannelModelOf<S>,
    prepared: &Prepared<S>,
    predicted: &[f64],
    (train, val): (&[usize], &[usize]),
    cross: &CrossFit<'_, S>,
    (ctx, est): (&Context, &estimate::Estimator<'_>),
    opts: &DiagnoseOptions,
) -> Result<ChannelDiagnosis<S::Channel, S::Axis>, SysidError> {
    let y = prepared.target(cross.channel);
    let residual: Vec<f64> = val.iter().map(|&r| y[r] - predicted[r]).collect();
    let compare = crate::model::score(y, predicted, train, val);
    let candidates::Ranked { ranking, series } =
        candidates::rank_candidates(model, prepared, (train, val), cross, (ctx, est), opts)?;
    let (checks, failing) = checks::correlation_checks(&residual, ctx, opts);

    // Where it fails.
    let operating: Vec<Vec<f64>> = ctx.operating.iter().map(|(_, v)| v.clone()).collect();
    let segs = segments(&ctx.t, &residual, &operating, opts.segments);
    let spectrum = ResidualSpectrum::new(&residual, ctx.fs, &*ctx.shape);
    let bnds = spectrum
        .as_ref()
        .map_or_else(Vec::new, |sp| sp.bands(&ctx.band_edges));
    let regs: Vec<Regime> = ctx
        .operating
        .iter()
        .map(|(name, v)| {
            regime(
                name,
                v,
                &residual,
                opts.regime_bins,
                ranking.effective_samples,
            )
        })
        .collect();

    let wording = prepared.sensor().wording();
    let findings = findings::findings(&ranking, &failing, (&segs, &bnds, &regs), &wording);
    let series = ChannelSeries {
        t: ctx.t.clone(),
        measured: val.iter().map(|&r| y[r]).collect(),
        predicted: val.iter().map(|&r| predicted[r]).collect(),
        residual,
        spectrum,
        candidates: series,
    };
    Ok(ChannelDiagnosis {
        channel: model.channel(),
        effects: model.effects().iter().map(Effect::id).collect(),
        rms: compare.val_rms,
        compare,
        segments: segs,
        bands: bnds,
        regimes: regs,
        checks,
        failing,
        candidates: ranking.candidates,
        unexcited: ranking.unexcited,
        suggested: ranking.suggested,
        p_threshold: ranking.p_threshold,
        findings,
        series,
    })
}
