//! The noise-aware choice of the network's input and prediction smoother.
//!
//! A compensator is switched on only if it never makes the sensor worse, and
//! validation rms alone prefers a model whose prediction carries its own
//! estimation noise (a window's level estimate) into the compensated
//! output. So each candidate (input, smoother) is judged on the validation
//! rows twice: its validation rms, and the Allan deviation of the output
//! after compensation against before. A candidate passes when, at every τ
//! from one sample to a tenth of each validation run and on every channel,
//! ADEV after ≤ ADEV before × (1 + the relative half-width of before's 68%
//! interval); the passing candidate with the lowest validation rms (mean
//! over channels) wins. When none passes, the one that exceeds its bound
//! least wins, and the report says so.
//!
//! The network is fitted once per input; the smoothers only post-process
//! its predictions, so the ladder costs no fit.

use super::fixed::{Coef, fit_rows_predicting};
use super::progress::Progress;
use crate::error::SysidError;
use crate::input::ModelInput;
use crate::model::{Model, score};
use crate::prepared::Prepared;
use crate::recipe::Recipe;
use crate::sensor::Sensor;
use crate::smoother::{Smoother, smoothed};
use rayon::prelude::*;
use std::borrow::Cow;

pub use crate::recipe::ModelChoice;

/// Confidence of the interval of ADEV before that bounds ADEV after.
pub const ADEV_CONFIDENCE: f64 = 0.683;

/// Fewest rows of a contiguous validation run whose Allan deviation is
/// checked (shorter runs, as an interleaved split's, say nothing at τ).
pub const MIN_ADEV_ROWS: usize = 200;

pub use crate::model::choice_report::{Candidate, ChoiceReport, InputSample, SharedCentresTrial};

/// The recipe fitted once per candidate input, every smoother judged, the
/// winner returned with its smoother set, scored with it, and the report.
pub(super) fn fit_choosing<S: Sensor>(
    prepared: &Prepared<S>,
    recipe: &Recipe<S::Effect>,
    choice: &ModelChoice,
    (train, val): (&[usize], &[usize]),
    coef: Coef<'_>,
    progress: Progress<'_, S::Channel>,
) -> Result<Model<S>, SysidError> {
    // A large record's input is chosen on a sample of it, then fitted alone.
    let sampled = super::input_sample::choose_input(prepared, recipe, choice)?;
    let choice = sampled.as_ref().map_or(choice, |(c, _)| c);
    let shared_taken = sampled
        .as_ref()
        .and_then(|(_, s)| s.shared_centres.as_ref())
        .is_some_and(|t| t.taken);
    let judge = Judge::new(prepared, val)?;
    let records: Vec<_> = prepared.record_rows().into_iter().map(|(_, r)| r).collect();
    // Per input: its candidates, and the model with its unsmoothed
    // predictions and effect columns (the winner is smoothed and scored
    // from them, without predicting again).
    let try_input = |i: usize, input: ModelInput| -> Result<_, SysidError> {
        // The records as they are for their own input, not a copy of them;
        // another input's are dropped once judged.
        let p = if input == prepared.preprocess().input {
            Cow::Borrowed(prepared)
        } else {
            Cow::Owned(prepared.with_input(input)?)
        };
        let mut r = recipe.clone();
        r.settings.shared_centres |= shared_taken;
        r.preprocess.input = input;
        r.preprocess.smoother = None;
        // Each channel is reported done once: by the first input's fit.
        let quiet: Progress<'_, S::Channel> = &|_| {};
        let (model, unsmoothed) = fit_rows_predicting(
            &p,
            &r,
            (train, val),
            coef,
            if i == 0 { progress } else { quiet },
        )?;
        let z: Vec<_> = model
            .channels()
            .iter()
            .enumerate()
            .map(|(k, c)| p.effect_matrix(k, c.effects()))
            .collect::<Result<_, _>>()?;
        let candidates = choice
            .smoothers
            .iter()
            .map(|&smoother| {
                let predicted = smoothed_all(&model, smoother, &records, &z, &unsmoothed)?;
                judge.candidate(&p, input, smoother, &predicted, train, val)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok((candidates, (model, unsmoothed, z)))
    };
    // A small record's inputs are fitted side by side (each fit alone keeps
    // two cores only partly busy); a large one's one after the other, so
    // its fit never holds both inputs' records and predictions.
    let inputs: Vec<(usize, ModelInput)> = choice.inputs.iter().copied().enumerate().collect();
    let results: Vec<_> = if prepared.rows() <= PARALLEL_INPUTS_MAX_ROWS {
        inputs
            .into_par_iter()
            .map(|(i, input)| try_input(i, input))
            .collect::<Result<_, _>>()?
    } else {
        inputs
            .into_iter()
            .map(|(i, input)| try_input(i, input))
            .collect::<Result<_, _>>()?
    };
    let (candidates, mut tried): (Vec<Vec<Candidate>>, Vec<_>) = results.into_iter().unzip();
    let candidates: Vec<Candidate> = candidates.into_iter().flatten().collect();
    let chosen = pick(&candidates);
    let winner = &candidates[chosen];
    let (mut model, unsmoothed, z) = tried.swap_remove(
        choice
            .inputs
            .iter()
            .position(|&i| i == winner.input)
            .expect("the winner's input was tried"),
    );
    model.set_smoother(winner.smoother);
    let predicted = smoothed_all(&model, winner.smoother, &records, &z, &unsmoothed)?;
    for (k, c) in model.channels_mut().iter_mut().enumerate() {
        c.set_scores(score(prepared.target(k), &predicted[k], train, val));
    }
    model.set_choice(ChoiceReport {
        candidates,
        chosen,
        adev_runs: judge.runs.len(),
        networks_shrunk: Vec::new(),
        input_sample: sampled.map(|(_, s)| s),
        bias_instability_raised: Vec::new(),
        window_signals: Vec::new(),
    });
    Ok(model)
}

/// Rows up to which a choice fits its inputs in parallel: the demo's record
/// (about 5,000) is far below, a 1M-row record (whose fit must stay within
/// 1 GiB) far above.
pub const PARALLEL_INPUTS_MAX_ROWS: usize = 100_000;

/// Every channel's prediction of `model` with `smoother` applied to its
/// unsmoothed predictions (effect columns `z`).
fn smoothed_all<S: Sensor>(
    model: &Model<S>,
    smoother: Option<Smoother>,
    records: &[std::ops::Range<usize>],
    z: &[faer::Mat<f64>],
    unsmoothed: &[Vec<f64>],
) -> Result<Vec<Vec<f64>>, SysidError> {
    model
        .channels()
        .par_iter()
        .enumerate()
        .map(|(k, c)| {
            smoothed(
                smoother.as_ref(),
                model.preprocess().causal,
                model.dt_s(),
                records,
                (c.bias(), &c.effect_coefficients()),
                &z[k],
                unsmoothed[k].clone(),
            )
        })
        .collect()
}

/// Relative validation rms a smaller input may cost and still be chosen
/// over the raw window: 3 numbers a signal instead of a window's samples
/// make the onboard step several times cheaper and give the network fewer
/// directions to extrapolate in (issue 25 asks for the rms within 2%).
pub const SMALLER_INPUT_TOLERANCE: f64 = 0.02;

/// The passing candidate with the lowest mean validation rms (the
/// statistics input's best when within [`SMALLER_INPUT_TOLERANCE`] of it),
/// or, when none passes, the one that exceeds its bound least.
fn pick(candidates: &[Candidate]) -> usize {
    let by = |key: &dyn Fn(&Candidate) -> f64, keep: &dyn Fn(&Candidate) -> bool| {
        candidates
            .iter()
            .enumerate()
            .filter(|(_, c)| keep(c))
            .min_by(|a, b| key(a.1).total_cmp(&key(b.1)))
            .map(|(i, _)| i)
    };
    let rms = |c: &Candidate| c.mean_val_rms;
    let Some(best) = by(&rms, &|c| c.passes) else {
        return by(&|c| c.worst_excess, &|_| true).unwrap_or(0);
    };
    let limit = candidates[best].mean_val_rms * (1.0 + SMALLER_INPUT_TOLERANCE);
    by(&rms, &|c| {
        c.passes && c.input == ModelInput::Statistics && c.mean_val_rms <= limit
    })
    .unwrap_or(best)
}

/// Each channel's scores from the model's own (smoothed) predictions.
pub(super) fn rescore<S: Sensor>(
    model: &mut Model<S>,
    prepared: &Prepared<S>,
    train: &[usize],
    val: &[usize],
) -> Result<(), SysidError> {
    let predicted = model.predict(prepared)?;
    for (k, c) in model.channels_mut().iter_mut().enumerate() {
        c.set_scores(score(prepared.target(k), &predicted[k], train, val));
    }
    Ok(())
}

/// The validation runs and, per run and channel, the output before
/// compensation with its Allan curve.
struct Judge {
    dt_s: f64,
    names: Vec<String>,
    runs: Vec<Run>,
}

struct Run {
    rows: std::ops::Range<usize>,
    factors: Vec<usize>,
    /// Per channel: the unfiltered target on the run, ADEV before and its bound.
    before: Vec<(Vec<f64>, Vec<f64>, Vec<f64>)>,
}

impl Judge {
    fn new<S: Sensor>(prepared: &Prepared<S>, val: &[usize]) -> Result<Self, SysidError> {
        let dt_s = prepared.calibrated().dt();
        let targets = prepared
            .sensor()
            .targets(prepared.calibrated())
            .map_err(SysidError::Sensor)?;
        let first = prepared.first_sample();
        let mut runs = Vec::new();
        for rows in contiguous(val) {
            if rows.len() < MIN_ADEV_ROWS {
                continue;
            }
            let factors = allan::octave_factors(rows.len());
            let before = targets
                .iter()
                .map(|t| {
                    let y = t[first + rows.start..first + rows.end].to_vec();
                    let curve = allan::AllanCurve::new(&y, dt_s, &factors, ADEV_CONFIDENCE)
                        .map_err(|e| adev_error(&e))?;
                    let adev = curve.adev();
                    let bound = curve
                        .points
                        .iter()
                        .map(|p| p.adev * (1.0 + (p.high - p.low) / (2.0 * p.adev)))
                        .collect();
                    Ok((y, adev, bound))
                })
                .collect::<Result<Vec<_>, SysidError>>()?;
            runs.push(Run {
                rows,
                factors,
                before,
            });
        }
        let names = prepared
            .sensor()
            .channels()
            .iter()
            .map(ToString::to_string)
            .collect();
        Ok(Self { dt_s, names, runs })
    }

    fn candidate<S: Sensor>(
        &self,
        prepared: &Prepared<S>,
        input: ModelInput,
        smoother: Option<Smoother>,
        predicted: &[Vec<f64>],
        train: &[usize],
        val: &[usize],
    ) -> Result<Candidate, SysidError> {
        let val_rms: Vec<f64> = predicted
            .iter()
            .enumerate()
            .map(|(k, p)| score(prepared.target(k), p, train, val).val_rms)
            .collect();
        let mut c = Candidate::unjudged(input, smoother, val_rms);
        for run in &self.runs {
            for (k, (y, before, bound)) in run.before.iter().enumerate() {
                let after: Vec<f64> = y
                    .iter()
                    .zip(&predicted[k][run.rows.clone()])
                    .map(|(y, p)| y - p)
                    .collect();
                let adev = allan::overlapping_adev(&after, self.dt_s, &run.factors)
                    .map_err(|e| adev_error(&e))?;
                for (i, a) in adev.iter().enumerate() {
                    let ratio = a / before[i];
                    // The first ratio replaces the NaN start.
                    if c.worst_adev_ratio.is_nan() || ratio > c.worst_adev_ratio {
                        c.worst_adev_ratio = ratio;
                        c.worst_channel = self.names[k].clone();
                        c.worst_tau_s = run.factors[i] as f64 * self.dt_s;
                    }
                    c.worst_excess = c.worst_excess.max(a / bound[i]);
                }
            }
        }
        c.passes = c.worst_excess <= 1.0;
        Ok(c)
    }
}

fn adev_error(e: &allan::AllanError) -> SysidError {
    SysidError::InvalidOption {
        name: "model choice",
        value: e.to_string(),
        reason: "the validation rows' Allan deviation could not be computed",
    }
}

/// Sorted row indices as runs of consecutive rows.
fn contiguous(rows: &[usize]) -> Vec<std::ops::Range<usize>> {
    let mut out: Vec<std::ops::Range<usize>> = Vec::new();
    for &r in rows {
        match out.last_mut() {
            Some(run) if run.end == r => run.end += 1,
            _ => out.push(r..r + 1),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_consecutive_rows() {
        assert_eq!(contiguous(&[1, 2, 3, 7, 8, 10]), vec![1..4, 7..9, 10..11]);
        assert!(contiguous(&[]).is_empty());
    }

    fn candidate(rms: f64, excess: f64) -> Candidate {
        Candidate {
            input: ModelInput::Raw,
            smoother: None,
            val_rms: vec![rms],
            mean_val_rms: rms,
            worst_adev_ratio: excess,
            worst_channel: "x".into(),
            worst_tau_s: 1.0,
            worst_excess: excess,
            passes: excess <= 1.0,
        }
    }

    /// A lower rms loses to a candidate that keeps the Allan deviation
    /// within its interval; with none passing, the least excess wins.
    #[test]
    fn the_lowest_rms_among_those_that_pass() {
        let c = [
            candidate(1.0, 1.5),
            candidate(1.2, 0.99),
            candidate(1.1, 1.0),
        ];
        assert_eq!(pick(&c), 2);
        assert_eq!(pick(&[candidate(1.0, 1.5), candidate(2.0, 1.2)]), 1);
        // The statistics input within 2% of the best raw one is taken.
        let mut s = candidate(1.11, 0.9);
        s.input = ModelInput::Statistics;
        assert_eq!(
            pick(&[candidate(1.0, 1.5), candidate(1.1, 0.9), s.clone()]),
            2
        );
        s.mean_val_rms = 1.13;
        assert_eq!(pick(&[candidate(1.1, 0.9), s]), 0);
    }
}
