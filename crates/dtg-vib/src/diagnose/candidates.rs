//! A channel's candidate effects: every effect its model lacks that the
//! record excites, ranked on the cross-fitted residual, with the experiment
//! that separates a collinear group and, of several records, the records
//! that told a suggestion apart from its look-alikes.

use super::context::Context;
use super::crossfit::CrossFit;
use super::{Ranking, Unexcited, rank, record_separations, separation};
use crate::effects::{ANISOINERTIA_MIN_RATE_DEG_S, Effect, TERM_EFFECTS};
use crate::error::DtgVibError;
use crate::model::ChannelModel;
use crate::pipeline::Prepared;
use faer::Mat;
use nav_sensors::dtg::DtgTerm;

/// A channel's ranking, and each candidate's column (filtered, less its
/// training mean) on the validation rows by id, for figures.
pub(super) struct Ranked {
    pub(super) ranking: Ranking,
    pub(super) series: Vec<(String, Vec<f64>)>,
}

/// Ranks the candidates of one channel model on `prepared` (see the module).
pub(super) fn rank_candidates(
    model: &ChannelModel,
    prepared: &Prepared,
    (train, val): (&[usize], &[usize]),
    cross: &CrossFit<'_>,
    ctx: &Context,
    opts: &super::DiagnoseOptions,
) -> Result<Ranked, DtgVibError> {
    let ch = model.channel();
    let y = prepared.target(ch);
    let (wanted, unexcited_ai) = wanted(model, ctx);
    let full = prepared.effect_columns_full(ch, &wanted)?;
    let first = prepared.first_sample();
    let series: Vec<(String, Vec<f64>)> = wanted
        .iter()
        .zip(&full)
        .map(|(e, c)| {
            let train_mean =
                train.iter().map(|&r| c[first + r]).sum::<f64>() / train.len().max(1) as f64;
            (
                e.id(),
                val.iter().map(|&r| c[first + r] - train_mean).collect(),
            )
        })
        .collect();
    // The ranking's evidence: the whole record, cross-fitted and partialled out.
    let all = Mat::from_fn(prepared.rows(), full.len(), |i, j| full[j][first + i]);
    let partialled = cross.partial_out(prepared, &all)?;
    let ranked: Vec<(Effect, Vec<f64>)> = wanted
        .iter()
        .enumerate()
        .map(|(j, e)| {
            (
                e.clone(),
                (0..partialled.nrows())
                    .map(|i| partialled[(i, j)])
                    .collect(),
            )
        })
        .collect();
    let mut ranking = rank(&cross.residual(y), &ranked, opts.rank);
    separate_groups(model, &mut ranking, &ranked, ctx);
    separate_by_record(prepared, cross, &mut ranking, &ranked, opts);
    ranking.unexcited.extend(unexcited_ai);
    Ok(Ranked { ranking, series })
}

/// Every effect the model lacks, and the anisoinertia candidates left out
/// (with why) where the rate does not vary.
fn wanted(model: &ChannelModel, ctx: &Context) -> (Vec<Effect>, Vec<Unexcited>) {
    let extra_names: Vec<&str> = ctx.extras.iter().map(|(n, _)| n.as_str()).collect();
    let mut unexcited_ai = Vec::new();
    let wanted: Vec<Effect> = Effect::candidates(&extra_names)
        .into_iter()
        .filter(|e| !model.effects().contains(e))
        .filter(|e| {
            let ai = matches!(e, Effect::Term(t) if DtgTerm::ANISOINERTIA.contains(t));
            if ai && ctx.rate_std_deg_s < ANISOINERTIA_MIN_RATE_DEG_S {
                unexcited_ai.push(Unexcited {
                    effect: e.id(),
                    reason: format!(
                        "the angular rate does not vary (largest std {:.3} deg/s < {ANISOINERTIA_MIN_RATE_DEG_S} deg/s): anisoinertia is not observable",
                        ctx.rate_std_deg_s
                    ),
                });
                return false;
            }
            true
        })
        .collect();
    debug_assert!(TERM_EFFECTS.len() + extra_names.len() >= wanted.len());
    (wanted, unexcited_ai)
}

/// For each significant candidate with alternatives: the combination the
/// record identifies and the run that would separate the group.
fn separate_groups(
    model: &ChannelModel,
    ranking: &mut Ranking,
    ranked: &[(Effect, Vec<f64>)],
    ctx: &Context,
) {
    for c in ranking
        .candidates
        .iter_mut()
        .filter(|c| c.significant && !c.alternatives.is_empty())
    {
        let column = |id: &str| ranked.iter().find(|(e, _)| e.id() == id);
        let Some((rep, r)) = column(&c.effect) else {
            continue;
        };
        let rr: f64 = r.iter().map(|v| v * v).sum();
        let mut group = vec![rep.clone()];
        let mut kappa = Vec::new();
        for alt in &c.alternatives {
            if let Some((e, a)) = column(alt) {
                group.push(e.clone());
                kappa.push(r.iter().zip(a).map(|(p, q)| p * q).sum::<f64>() / rr);
            }
        }
        c.separation = Some(separation(
            model.channel(),
            &group,
            &kappa,
            &ctx.gravity_g,
            ctx.vibration_g,
            ctx.vibration_axis,
        ));
    }
}

/// Several records: which candidates a suggestion was collinear with on
/// some record alone, and which records told them apart.
fn separate_by_record(
    prepared: &Prepared,
    cross: &CrossFit<'_>,
    ranking: &mut Ranking,
    ranked: &[(Effect, Vec<f64>)],
    opts: &super::DiagnoseOptions,
) {
    let rows = cross.rows();
    let positions: Vec<(String, Vec<usize>)> = prepared
        .record_rows()
        .into_iter()
        .map(|(name, range)| {
            let at = rows
                .iter()
                .enumerate()
                .filter(|(_, r)| range.contains(r))
                .map(|(i, _)| i);
            (name.to_string(), at.collect())
        })
        .collect();
    for c in ranking.candidates.iter_mut().filter(|c| c.significant) {
        let Some((_, column)) = ranked.iter().find(|(e, _)| e.id() == c.effect) else {
            continue;
        };
        let others: Vec<(String, &[f64])> = ranked
            .iter()
            .filter(|(e, _)| e.id() != c.effect)
            .map(|(e, v)| (e.id(), v.as_slice()))
            .collect();
        c.record_separations =
            record_separations(column, &others, &positions, opts.rank.collinearity);
    }
}
