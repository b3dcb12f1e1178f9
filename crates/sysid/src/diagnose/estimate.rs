//! A suggested effect's coefficient as the refit will store it.
//!
//! The ranking decides what to suggest on one cut of the record (the model
//! and its mirror), and its test holds the false-alarm rate; but one cut's
//! standard error leaves out how much the partialling networks themselves
//! move with the rows they were fitted on, and its 95% interval covered the
//! truth only 73% (temperature) and 85% (g²) of the time over 78 seeds. A
//! suggestion's coefficient and interval are therefore stated with the
//! fit's own estimator ([`crate::fit::cross_fitted_theta`]: every row, the
//! raw windows, 4, 6 and 8 alternating spans, the spread between cuts in
//! the interval), on the rows and settings the refit uses, with the model's
//! effects and every suggestion of the channel in the order the refit adds
//! them: the diagnosis and the refit's model then say the same.

use super::rank::Ranking;
use crate::error::SysidError;
use crate::model::ChannelModelOf;
use crate::prepared::Prepared;
use crate::recipe::FitSettings;
use crate::sensor::{Effect, Sensor};
use faer::MatRef;

/// What the fit's estimator needs for one channel of a diagnosis.
pub(super) struct Estimator<'a> {
    /// The channel's raw windows (what the partialling networks read).
    pub(super) x: MatRef<'a, f64>,
    /// The model's settings (the networks' grid, seed, ridge).
    pub(super) settings: &'a FitSettings,
    /// The rows the refit estimates on ([`crate::fit::theta_rows`]).
    pub(super) rows: &'a [usize],
    /// The leakage gap between blocks, rows.
    pub(super) gap: usize,
}

/// Restates each suggestion of `ranking` (channel `channel`, of `model`)
/// with the fit's estimate: `coef`, `coef_se` and `coef_ci95` become what
/// the refit will store. The suggestion itself and its p-value stay the
/// ranking's. A suggestion whose estimate's interval holds zero, or that
/// the estimator cannot state, keeps a caveat saying so.
pub(super) fn restate<S: Sensor>(
    est: &Estimator<'_>,
    prepared: &Prepared<S>,
    channel: usize,
    model: &ChannelModelOf<S>,
    ranked: &[(S::Effect, Vec<f64>)],
    ranking: &mut Ranking<S::Axis>,
) -> Result<(), SysidError> {
    if ranking.suggested.is_empty() {
        return Ok(());
    }
    let suggested: Vec<S::Effect> = ranking
        .suggested
        .iter()
        .filter_map(|id| ranked.iter().find(|(e, _)| &e.id() == id))
        .map(|(e, _)| e.clone())
        .collect();
    let mut effects = model.effects().to_vec();
    effects.extend(suggested.iter().cloned());
    let z = prepared.effect_matrix(channel, &effects)?;
    let y = prepared.target(channel);
    let estimate = crate::fit::cross_fitted_theta(est.x, &z, y, est.rows, est.settings, est.gap);
    let first = model.effects().len();
    for (i, e) in suggested.iter().enumerate() {
        let id = e.id();
        let Some(c) = ranking.candidates.iter_mut().find(|c| c.effect == id) else {
            continue;
        };
        let j = first + i;
        match &estimate {
            Ok(Some(f)) => {
                c.coef = f.coef[j];
                c.coef_se = f.se[j];
                c.coef_ci95 = f.interval(j, 0.95);
                if c.coef_ci95[0] <= 0.0 && 0.0 <= c.coef_ci95[1] {
                    c.caveats.push(format!(
                        "its coefficient as the refit estimates it, {:.4} ± {:.4} {}, has a 95% interval that holds zero: the refit may store an effect it cannot tell from none",
                        c.coef, c.coef_se, c.unit
                    ));
                }
            }
            Ok(None) => c.caveats.push(
                "the record is too short for the fit's cross-fitting cuts: the coefficient shown is this diagnosis's one-cut estimate, and the refit's will be a joint fit's".into(),
            ),
            Err(e) => c.caveats.push(format!(
                "the fit's estimate of its coefficient failed ({e}): the coefficient shown is this diagnosis's one-cut estimate"
            )),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::example::{Line, Slope, line_record};
    use crate::input::ModelInput;
    use crate::{FitOptions, Model};

    fn fit_line(
        effects: Vec<Slope>,
        input: ModelInput,
        shared: bool,
    ) -> (Model<Line>, Prepared<Line>) {
        let rec = line_record(3000, 2.0, 7);
        let mut options = FitOptions::new(1);
        options.recipe.preprocess = Line::preprocess();
        options.recipe.preprocess.input = input;
        options.recipe.effects[0] = effects;
        options.recipe.settings.max_centres = 5;
        options.recipe.settings.shared_centres = shared;
        let (model, _) = crate::fit_records(&Line, &[("r".into(), &rec)], &options, &|_| {})
            .expect("the line fits");
        let prepared = model.prepare(&rec).expect("the record prepares");
        (model, prepared)
    }

    /// One estimate: a suggestion restated by the diagnosis of a model
    /// without it is the coefficient, standard error and interval the refit
    /// with it stores, whatever input the network reads, per channel or
    /// with the shared selection (`--shared-centres`).
    #[test]
    fn a_suggestion_is_stated_as_the_refit_stores_it() {
        for (input, shared) in [
            (ModelInput::Raw, false),
            (ModelInput::Statistics, false),
            (ModelInput::Raw, true),
            (ModelInput::Statistics, true),
        ] {
            let (base, prepared) = fit_line(Vec::new(), input, shared);
            let (train, val) = base.rows(&prepared).unwrap();
            let raw = crate::fit::raw_windows(&prepared).unwrap();
            assert_eq!(raw.is_some(), input == ModelInput::Statistics);
            let est = Estimator {
                x: raw
                    .as_ref()
                    .map_or(prepared.window_view(0), |p| p.window_view(0)),
                settings: base.settings(),
                rows: &crate::fit::theta_rows(&train, &val),
                gap: crate::split::leakage_gap(&prepared),
            };
            let column: Vec<f64> = (0..100).map(|i| f64::from(i % 7)).collect();
            let residual: Vec<f64> = column.iter().map(|v| v + 0.1).collect();
            let ranked = vec![(Slope, column)];
            let mut ranking: Ranking<String> =
                super::super::rank(&residual, &ranked, Default::default());
            ranking.suggested = vec!["u".into()];
            restate(&est, &prepared, 0, base.channel(0), &ranked, &mut ranking).unwrap();
            let stated = &ranking.candidates[0];

            let (refit, _) = fit_line(vec![Slope], input, shared);
            assert_eq!(refit.settings().shared_centres, shared);
            let stored = &refit.channel(0).coefficients().unwrap()[0];
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-12);
            assert!(
                close(stated.coef, stored.value),
                "{stated:?} against {stored:?}"
            );
            assert!(
                close(stated.coef_se, stored.se),
                "{stated:?} against {stored:?}"
            );
            assert!(close(stated.coef_ci95[0], stored.ci95[0]));
            assert!(close(stated.coef_ci95[1], stored.ci95[1]));
        }
    }
}
