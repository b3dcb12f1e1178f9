//! A channel's candidate effects: every effect its model lacks that the
//! record excites, ranked on the cross-fitted residual, with the experiment
//! that separates a collinear group and, of several records, the records
//! that told a suggestion apart from its look-alikes.

use super::context::Context;
use super::estimate::{Estimator, restate};
use super::model_and_mirror::CrossFit;
use super::rank::{Ranking, Unexcited, rank, rank_suggestions};
use super::records::record_separations;
use crate::error::SysidError;
use crate::model::ChannelModelOf;
use crate::prepared::Prepared;
use crate::sensor::{Candidacy, Effect, Sensor};
use faer::Mat;

/// A channel's ranking, and each candidate's column (filtered, less its
/// training mean) on the validation rows by id, for figures.
pub(super) struct Ranked<A> {
    pub(super) ranking: Ranking<A>,
    pub(super) series: Vec<(String, Vec<f64>)>,
}

/// Ranks the candidates of one channel model on `prepared` (see the module).
pub(super) fn rank_candidates<S: Sensor>(
    model: &ChannelModelOf<S>,
    prepared: &Prepared<S>,
    (train, val): (&[usize], &[usize]),
    cross: &CrossFit<'_, S>,
    (ctx, est): (&Context, &Estimator<'_>),
    opts: &super::DiagnoseOptions,
) -> Result<Ranked<S::Axis>, SysidError> {
    let ch = cross.channel;
    let y = prepared.target(ch);
    let (wanted, not_excited) = wanted(prepared, ch, model, ctx);
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
    let ranked: Vec<(S::Effect, Vec<f64>)> = wanted
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
    let screened = screen(prepared, model, cross, y, &all)?;
    add_screened(&mut ranking, &wanted, &screened, opts);
    separate_groups(prepared.sensor(), ch, &mut ranking, &ranked, ctx);
    separate_by_record(prepared, cross, &mut ranking, &ranked, opts);
    add_caveats(prepared, ch, &mut ranking, &ranked, cross);
    restate(est, prepared, ch, model, &ranked, &mut ranking)?;
    ranking.unexcited.extend(not_excited);
    Ok(Ranked { ranking, series })
}

/// Every candidate the model lacks that the record excites (the sensor
/// judges on the validation rows), and those it does not excite, with why.
fn wanted<S: Sensor>(
    prepared: &Prepared<S>,
    channel: usize,
    model: &ChannelModelOf<S>,
    ctx: &Context,
) -> (Vec<S::Effect>, Vec<Unexcited>) {
    let mut wanted = Vec::new();
    let mut not_excited = Vec::new();
    let offered = prepared
        .sensor()
        .candidates(prepared.calibrated(), &ctx.samples, channel);
    for c in offered {
        match c {
            Candidacy::Excited(e) if !model.effects().contains(&e) => wanted.push(e),
            Candidacy::NotExcited { effect, reason } if !model.effects().contains(&effect) => {
                not_excited.push(Unexcited {
                    effect: effect.id(),
                    reason,
                });
            }
            _ => {}
        }
    }
    (wanted, not_excited)
}

/// For each significant candidate with alternatives: the combination the
/// record identifies and the run that would separate the group.
fn separate_groups<S: Sensor>(
    sensor: &S,
    channel: usize,
    ranking: &mut Ranking<S::Axis>,
    ranked: &[(S::Effect, Vec<f64>)],
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
        c.separation = Some(sensor.separation(channel, &group, &kappa, &ctx.stats));
    }
}

/// Several records: which candidates a suggestion was collinear with on
/// some record alone, and which records told them apart.
fn separate_by_record<S: Sensor>(
    prepared: &Prepared<S>,
    cross: &CrossFit<'_, S>,
    ranking: &mut Ranking<S::Axis>,
    ranked: &[(S::Effect, Vec<f64>)],
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

/// Each suggestion's caveats (the sensor's), from every diagnosed record
/// and the samples of its analysed rows.
fn add_caveats<S: Sensor>(
    prepared: &Prepared<S>,
    channel: usize,
    ranking: &mut Ranking<S::Axis>,
    ranked: &[(S::Effect, Vec<f64>)],
    cross: &CrossFit<'_, S>,
) {
    if ranking.suggested.is_empty() {
        return;
    }
    let rows = cross.rows();
    let records: Vec<(&crate::signals::Signals, Vec<usize>)> = prepared
        .record_rows()
        .into_iter()
        .filter_map(|(_, range)| {
            let (record, _) = prepared.locate(range.start);
            let samples: Vec<usize> = rows
                .iter()
                .filter(|r| range.contains(r))
                .map(|&r| prepared.locate(r).1)
                .collect();
            (!samples.is_empty()).then_some((record, samples))
        })
        .collect();
    for c in ranking.candidates.iter_mut() {
        if !ranking.suggested.contains(&c.effect) {
            continue;
        }
        if let Some((e, _)) = ranked.iter().find(|(e, _)| e.id() == c.effect) {
            c.caveats = prepared.sensor().caveats(&records, channel, e);
        }
    }
}

/// Adds the screen's suggestions to the model's: a term the network could
/// absorb (a linear g-sensitivity along an axis the window reads) is named
/// all the same, its coefficient and interval then stated by the estimator
/// like any other suggestion's.
fn add_screened<E: Effect, A>(
    ranking: &mut Ranking<A>,
    wanted: &[E],
    (target, columns): &(Vec<f64>, Mat<f64>),
    opts: &super::DiagnoseOptions,
) {
    let candidates: Vec<(E, Vec<f64>)> = wanted
        .iter()
        .enumerate()
        .map(|(j, e)| {
            (
                e.clone(),
                (0..columns.nrows()).map(|i| columns[(i, j)]).collect(),
            )
        })
        .collect();
    let screened: Ranking<A> = rank_suggestions(target, &candidates, opts.rank);
    for id in screened.suggested.clone() {
        if !ranking.suggested.contains(&id) && !collinear_with_suggested(ranking, &screened, &id) {
            if let Some(c) = ranking.candidates.iter_mut().find(|c| c.effect == id) {
                c.significant = true;
            }
            ranking.suggested.push(id);
        }
    }
}

/// Whether `id` is nearly collinear, on this record, with a suggestion
/// `ranking` already makes: it is then that suggestion's alternative, not a
/// second effect (the pair would be fitted as two coefficients the record
/// cannot separate).
fn collinear_with_suggested<A>(ranking: &Ranking<A>, screened: &Ranking<A>, id: &str) -> bool {
    ranking
        .candidates
        .iter()
        .chain(&screened.candidates)
        .filter(|c| c.effect == id)
        .any(|c| {
            c.collinear_with
                .iter()
                .any(|o| ranking.suggested.contains(o))
        })
}

/// The screen: what the network absorbed put back into the cross-fitted
/// residual (each half's network part on its test rows), and the candidate
/// columns; both with the physics the model states and the network's
/// level-only reach projected out over the analysed rows — a constant per
/// half, the model's effects, and a quadratic in the window rms of the
/// operating signals (vibration level changes a DTG's drift without any
/// instantaneous g-term). What remains correlating with a candidate is a
/// term the network read through the window's axes instead of naming.
fn screen<S: Sensor>(
    prepared: &Prepared<S>,
    model: &ChannelModelOf<S>,
    cross: &CrossFit<'_, S>,
    y: &[f64],
    all: &Mat<f64>,
) -> Result<(Vec<f64>, Mat<f64>), SysidError> {
    let rows = cross.rows();
    let e = cross.residual(y);
    let net = cross.network_part(prepared)?;
    let t: Vec<f64> = e.iter().zip(&net).map(|(a, b)| a + b).collect();
    let length = prepared.preprocess().window.length();
    let stats = crate::operating::range::statistics(prepared, length, &rows)?;
    let k = prepared.sensor().operating_signals().len();
    let z = prepared.effect_matrix(cross.channel, model.effects())?;
    let p = z.ncols();
    let mut cols: Vec<Vec<f64>> = cross
        .halves
        .iter()
        .map(|h| {
            let mut on = vec![false; prepared.rows()];
            h.test_rows.iter().for_each(|&r| on[r] = true);
            rows.iter().map(|&r| f64::from(u8::from(on[r]))).collect()
        })
        .collect();
    for j in 0..p {
        cols.push(rows.iter().map(|&r| z[(r, j)]).collect());
    }
    for a in 0..k {
        cols.push(stats.iter().map(|s| s[k + a]).collect());
    }
    for a in 0..k {
        for b in a..k {
            cols.push(stats.iter().map(|s| s[k + a] * s[k + b]).collect());
        }
    }
    let basis = Mat::from_fn(rows.len(), cols.len(), |i, j| cols[j][i]);
    let m = all.ncols();
    let targets = Mat::from_fn(rows.len(), m + 1, |i, j| match j {
        0 => t[i],
        j => all[(rows[i], j - 1)],
    });
    let r = crate::inference::residualise(
        basis.as_ref(),
        targets.as_ref(),
        basis.as_ref(),
        targets.as_ref(),
        cols.len(),
        0.0,
    )
    .map_err(|e| SysidError::Fit {
        channel: model.channel().to_string(),
        source: e.into(),
    })?;
    let t = (0..rows.len()).map(|i| r[(i, 0)]).collect();
    Ok((t, Mat::from_fn(rows.len(), m, |i, j| r[(i, j + 1)])))
}
