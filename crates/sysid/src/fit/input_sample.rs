//! A large record's network input chosen on a sample of it.
//!
//! The choice fits the recipe once per input and judges every smoother on
//! each. On a record of a million rows each input's fit is a full fit
//! (cross-validation on the selection rows, the weights on every training
//! row, predictions on every row), and the inputs run one after the other
//! to stay within memory: the choice cost two fits. Which input wins is a
//! property of the signals, not of the record's length, so on a large
//! record the choice is first made on a few chunks of it spread over its
//! length, each prepared as a record of its own, and only the winning input
//! is fitted on the whole record, where its smoothers are judged again.
//!
//! The sample also decides whether the channels share one centre
//! selection: it is fitted again with one, and where that costs at most
//! [`SHARED_CENTRES_TOLERANCE`] of the mean validation rms the record is
//! fitted so (one selection instead of one per channel halves the fit's
//! time, and the onboard step computes the kernels once).

use super::fixed::Coef;
use super::input_choice::{PARALLEL_INPUTS_MAX_ROWS, fit_choosing};
use crate::error::SysidError;
use crate::model::choice_report::{InputSample, SharedCentresTrial};
use crate::prepared::Prepared;
use crate::recipe::{ModelChoice, Recipe};
use crate::sensor::Sensor;
use crate::split::split_rows;

/// Chunks of the sample, spread evenly over the record's rows.
pub const SAMPLE_CHUNKS: usize = 4;

/// Rows of each chunk: half the demo's record (50 s at 50 Hz), so the
/// sample's cross-validation (on its 5,000 training rows) costs a fifth of
/// the whole record's (on its 25,000 selection rows), and each chunk's
/// validation half is a run of 1,250 rows, long enough for the Allan
/// deviation to a tenth of it.
pub const SAMPLE_CHUNK_ROWS: usize = 2_500;

/// How much higher (relatively) the sample's mean validation rms may be
/// with one centre selection for every channel than with one per channel
/// for the record to be fitted with one: 1%.
pub const SHARED_CENTRES_TOLERANCE: f64 = 0.01;

/// On a record of more than [`PARALLEL_INPUTS_MAX_ROWS`] rows with more
/// than one input to choose from: the choice narrowed to the input chosen
/// on [`SAMPLE_CHUNKS`] chunks of [`SAMPLE_CHUNK_ROWS`] rows (every
/// smoother kept), with what the sample showed. `None` otherwise, and when
/// the record is too short for the chunks.
pub(super) fn choose_input<S: Sensor>(
    prepared: &Prepared<S>,
    recipe: &Recipe<S::Effect>,
    choice: &ModelChoice,
) -> Result<Option<(ModelChoice, InputSample)>, SysidError> {
    if choice.inputs.len() < 2 || prepared.rows() <= PARALLEL_INPUTS_MAX_ROWS {
        return Ok(None);
    }
    let Some(sample) = prepared.sample(SAMPLE_CHUNKS, SAMPLE_CHUNK_ROWS)? else {
        return Ok(None);
    };
    let (train, val) = split_rows(&sample, recipe.split)?;
    let model = fit_choosing(
        &sample,
        recipe,
        choice,
        (&train, &val),
        Coef::AllRows,
        &|_| {},
    )?;
    let Some(report) = model.choice() else {
        return Ok(None);
    };
    let narrowed = ModelChoice {
        inputs: vec![report.chosen().input],
        smoothers: choice.smoothers.clone(),
        try_shared_centres: false,
    };
    let shared_centres = match recipe.settings.shared_centres || !choice.try_shared_centres {
        true => None,
        false => {
            let mut shared = recipe.clone();
            shared.settings.shared_centres = true;
            let one = fit_choosing(
                &sample,
                &shared,
                &narrowed,
                (&train, &val),
                Coef::AllRows,
                &|_| {},
            )?;
            one.choice().map(|r| {
                let (own, one) = (report.chosen(), r.chosen());
                SharedCentresTrial {
                    per_channel_mean_val_rms: own.mean_val_rms,
                    shared_mean_val_rms: one.mean_val_rms,
                    taken: one.mean_val_rms <= own.mean_val_rms * (1.0 + SHARED_CENTRES_TOLERANCE)
                        && (one.passes || !own.passes),
                }
            })
        }
    };
    Ok(Some((
        narrowed,
        InputSample {
            rows: sample.rows(),
            chunks: SAMPLE_CHUNKS,
            candidates: report.candidates.clone(),
            chosen: report.chosen,
            shared_centres,
        },
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::example::{Line, line_record};
    use crate::recipe::FitOptions;

    /// The sample's windows are the record's own at the same samples (no
    /// input filter here), chunk by chunk, spread over the record.
    #[test]
    fn a_sample_is_chunks_of_the_records_own_windows() {
        let rec = line_record(40_000, 2.0, 5);
        let prepared = Prepared::new(&Line, &rec, &Line::preprocess()).unwrap();
        let sample = prepared.sample(4, 2_500).unwrap().unwrap();
        let rows = sample.record_rows();
        assert_eq!(rows.len(), 4);
        let span = prepared.rows() / 4;
        for (c, (name, r)) in rows.iter().enumerate() {
            assert_eq!(*name, format!("sample {}", c + 1));
            assert_eq!(r.len(), 2_500, "{name}");
            let start = c * span + (span - 2_500) / 2;
            for i in [0, 1_000, 2_499] {
                assert_eq!(
                    sample.windows(0).row(r.start + i),
                    prepared.windows(0).row(start + i),
                    "{name} row {i}"
                );
            }
        }
        // Too short for four chunks of 2,500 rows: none.
        let short = Prepared::new(&Line, &line_record(9_000, 2.0, 5), &Line::preprocess()).unwrap();
        assert!(short.sample(4, 2_500).unwrap().is_none());
    }

    /// Above 100,000 rows the choice fits only the input chosen on the
    /// sample, and the report keeps every candidate of the sample and the
    /// shared-centre trial; below, every input is fitted on the record.
    #[test]
    fn a_large_records_input_is_chosen_on_a_sample() {
        let mut options = FitOptions::new(1);
        options.recipe.preprocess = Line::preprocess();
        options.recipe.settings.max_centres = 4;
        options.recipe.settings.candidates = 40;
        options.recipe.settings.width_scales = vec![1.0];
        options.recipe.settings.choice = Some(ModelChoice::default());
        let fit = |n| crate::fit(&Line, &line_record(n, 2.0, 7), &options, &|_| {}).unwrap();
        let large = fit(PARALLEL_INPUTS_MAX_ROWS + 20_000);
        let report = large.choice().unwrap();
        let sample = report.input_sample.as_ref().expect("chosen on a sample");
        assert_eq!(sample.rows, SAMPLE_CHUNKS * SAMPLE_CHUNK_ROWS);
        let inputs = ModelChoice::default().inputs.len();
        let smoothers = ModelChoice::default().smoothers.len();
        assert_eq!(sample.candidates.len(), inputs * smoothers);
        assert_eq!(report.candidates.len(), smoothers);
        assert!(
            report
                .candidates
                .iter()
                .all(|c| c.input == sample.candidates[sample.chosen].input)
        );
        assert_eq!(large.preprocess().input, report.chosen().input);
        // The sample also tried one centre selection for every channel, and
        // the record was fitted as it decided.
        let trial = sample.shared_centres.as_ref().expect("a shared trial");
        assert_eq!(
            trial.taken,
            trial.shared_mean_val_rms
                <= trial.per_channel_mean_val_rms * (1.0 + SHARED_CENTRES_TOLERANCE)
        );
        assert_eq!(large.settings().shared_centres, trial.taken);
        let small = fit(20_000);
        let report = small.choice().unwrap();
        assert!(report.input_sample.is_none());
        assert_eq!(report.candidates.len(), inputs * smoothers);
    }
}
