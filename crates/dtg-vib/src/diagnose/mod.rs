//! The diagnosis loop: compare the model with the measurements, see where it
//! fails, and learn which physical effect is missing.
//!
//! Everything is computed on the validation rows of the model's own split,
//! because a residual on training rows has already been fitted away.
//!
//! The diagnosis only reads predictions: the model's, and its mirror's (the
//! same recipe trained on the other rows), which the loop layer fits and
//! hands in ([`crate::fit::mirror`], [`crate::explain::diagnose_records`]);
//! so does a trial with a longer window ([`Diagnosis::note_window_trial`]).

mod candidates;
mod checks;
mod context;
mod crossfit;
mod findings;
mod locate;
mod rank;
mod records;
mod separate;

pub use findings::p_text;
pub use locate::{Band, Regime, RegimeBin, ResidualSpectrum, Segment, regime, segments};
pub use rank::{Candidate, RankOptions, Ranking, Unexcited, rank};
pub use records::{MIN_ENERGY_SHARE, RecordCorrelation, RecordSeparation, record_separations};
pub use separate::{Response, Separation, response, separation};

use crate::effects::Effect;
use crate::error::DtgVibError;
use crate::model::{ChannelModel, ChannelScores, CompensationModel};
use crate::pipeline::Prepared;
use crate::residuals::CorrelationCheck;
use context::Context;
use crossfit::{CrossFit, Half};
use nav_sensors::geometry::{Axis, Channel};
use serde::Serialize;

/// Anisoinertia (rate-product) candidates are offered only when the angular
/// rate varies by more than this: see [`crate::effects::ANISOINERTIA_MIN_RATE_DEG_S`].
pub use crate::effects::ANISOINERTIA_MIN_RATE_DEG_S;

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
    /// Where the residual stays correlated beyond the model's window, refit
    /// with a three times longer window and report the validation rms it gives.
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
    /// Pre-processed output minus the rate reference, deg/h.
    pub measured: Vec<f64>,
    /// Model prediction, deg/h.
    pub predicted: Vec<f64>,
    /// `measured − predicted`, deg/h.
    pub residual: Vec<f64>,
    /// The candidate columns (filtered, less their training mean) on the validation rows, by id.
    pub candidates: Vec<(String, Vec<f64>)>,
    /// The residual's spectrum and its white floor, if the residual is long enough.
    pub spectrum: Option<ResidualSpectrum>,
}

/// Everything found about one channel.
#[derive(Debug, Clone, Serialize)]
pub struct ChannelDiagnosis {
    /// The channel.
    pub channel: Channel,
    /// Effects the model already has.
    pub effects: Vec<String>,
    /// RMS of the validation residual, deg/h.
    pub rms: f64,
    /// Measured against predicted, as MATLAB's `compare` reports it (rms,
    /// fit percentage, on training and validation rows).
    pub compare: ChannelScores,
    /// Residual by time segment.
    pub segments: Vec<Segment>,
    /// Residual power by frequency band.
    pub bands: Vec<Band>,
    /// Residual by acceleration regime.
    pub regimes: Vec<Regime>,
    /// Correlation tests.
    pub checks: Vec<NamedCheck>,
    /// Names of the correlation tests that fail.
    pub failing: Vec<String>,
    /// Candidate effects, sorted by ERR descending.
    pub candidates: Vec<Candidate>,
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

/// The diagnosis of all six channels.
#[derive(Debug, Clone, Serialize)]
pub struct Diagnosis {
    /// The records diagnosed together, by name (absent for one record).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub records: Vec<String>,
    /// Per channel, in X, X1, Y, Y1, Z, Z1 order.
    pub channels: Vec<ChannelDiagnosis>,
}

/// Diagnoses `model` on the record(s) it was fitted on, `prepared` by
/// [`CompensationModel::prepare_many`], reading its predictions and those
/// of its `mirror` ([`crate::fit::mirror`]): every candidate ranked on the
/// rows of all the records. A pair of candidates that one record cannot
/// tell apart is separated by another that excites them differently, and
/// [`Candidate::record_separations`] says which.
///
/// ```no_run
/// use dtg_vib::diagnose::diagnose_prepared;
/// use dtg_vib::model::CompensationModel;
/// use nav_sensors::record::Record;
/// let model = CompensationModel::load("xyz.json")?;
/// let (x, z) = (Record::read_csv("x.csv")?, Record::read_csv("z.csv")?);
/// let prepared = model.prepare_many(&[("x.csv".to_string(), &x), ("z.csv".to_string(), &z)])?;
/// let mirror = dtg_vib::fit::mirror(&model, &prepared)?;
/// let d = diagnose_prepared(&model, &prepared, &mirror, &Default::default())?;
/// for c in &d.channels { println!("{}: {:?}", c.channel, c.suggested); }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn diagnose_prepared(
    model: &CompensationModel,
    prepared: &Prepared,
    mirror: &CompensationModel,
    options: &DiagnoseOptions,
) -> Result<Diagnosis, DtgVibError> {
    let predictions = model.predict(prepared)?;
    let (train, val) = model.rows(prepared)?;
    let mirror_predictions = mirror.predict(prepared)?;
    let x = prepared.window_matrix();
    let context = Context::new(prepared, &val)?;
    let channels = model
        .channels()
        .iter()
        .map(|c| {
            let i = c.channel().index();
            let halves = CrossFit {
                x: &x,
                ridge: model.fit_settings().ridge,
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
                &context,
                options,
            )
        })
        .collect::<Result<Vec<ChannelDiagnosis>, _>>()?;
    let records = match prepared.record_rows() {
        parts if parts.len() > 1 => parts.into_iter().map(|(n, _)| n.to_string()).collect(),
        _ => Vec::new(),
    };
    Ok(Diagnosis { records, channels })
}

impl Diagnosis {
    /// The channels whose residual stays correlated beyond the model's
    /// window (the whiteness test fails): where a longer window is the
    /// setting to try.
    pub fn slow_channels(&self) -> Vec<Channel> {
        self.channels
            .iter()
            .filter(|c| c.failing.iter().any(|f| f == "whiteness"))
            .map(|c| c.channel)
            .collect()
    }

    /// Adds to each [`Diagnosis::slow_channels`] finding the validation rms
    /// that `trial`, the model's recipe refitted on the same records with
    /// windows of `length` samples ([`crate::fit::refit_with_window`]),
    /// gave: the advice to refit with that window is given only with what it
    /// gained, before and after.
    pub fn note_window_trial(&mut self, length: usize, trial: &CompensationModel) {
        let on = if self.records.len() > 1 {
            "these records"
        } else {
            "this record"
        };
        let slow = self.slow_channels();
        for c in self
            .channels
            .iter_mut()
            .filter(|c| slow.contains(&c.channel))
        {
            let before = c.rms;
            let after = trial.channel(c.channel).scores().val_rms;
            c.findings.push(if after < 0.95 * before {
                format!(
                    "tried --window {length} on {on}: validation rms {before:.4} → {after:.4} deg/h ({:+.0}%): refit with --window {length}",
                    100.0 * (after / before - 1.0)
                )
            } else {
                format!(
                    "tried --window {length} on {on}: validation rms {before:.4} → {after:.4} deg/h, no better: the slow error is not the window's"
                )
            });
        }
    }
}

/// One channel's diagnosis: compare, rank the candidates, test the
/// residual, and see where it fails.
fn diagnose_channel(
    model: &ChannelModel,
    prepared: &Prepared,
    predicted: &[f64],
    (train, val): (&[usize], &[usize]),
    cross: &CrossFit<'_>,
    ctx: &Context,
    opts: &DiagnoseOptions,
) -> Result<ChannelDiagnosis, DtgVibError> {
    let ch = model.channel();
    let y = prepared.target(ch);
    let residual: Vec<f64> = val.iter().map(|&r| y[r] - predicted[r]).collect();
    let compare = crate::fit::score(y, predicted, train, val);
    let candidates::Ranked { ranking, series } =
        candidates::rank_candidates(model, prepared, (train, val), cross, ctx, opts)?;
    let (checks, failing) = checks::correlation_checks(&residual, ctx, opts);

    // Where it fails.
    let segs = segments(&ctx.t, &residual, &ctx.accel, opts.segments);
    let spectrum = ResidualSpectrum::new(&residual, ctx.fs, &*ctx.shape);
    let bnds = spectrum
        .as_ref()
        .map_or_else(Vec::new, |sp| sp.bands(&ctx.band_edges));
    let regs: Vec<Regime> = Axis::ALL
        .iter()
        .map(|a| {
            regime(
                a.column(),
                &ctx.accel[a.index()],
                &residual,
                opts.regime_bins,
                ranking.effective_samples,
            )
        })
        .collect();

    let findings = findings::findings(&ranking, &failing, &segs, &bnds, &regs);
    let series = ChannelSeries {
        t: ctx.t.clone(),
        measured: val.iter().map(|&r| y[r]).collect(),
        predicted: val.iter().map(|&r| predicted[r]).collect(),
        residual,
        spectrum,
        candidates: series,
    };
    Ok(ChannelDiagnosis {
        channel: ch,
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
