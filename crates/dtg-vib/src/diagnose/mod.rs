//! The diagnosis loop: compare the model with the measurements, see where it
//! fails, and learn which physical effect is missing.
//!
//! Everything is computed on the validation rows of the model's own split,
//! because a residual on training rows has already been fitted away.

mod locate;
mod rank;
mod records;
mod separate;

pub use locate::{Band, Regime, RegimeBin, ResidualSpectrum, Segment, regime, segments};
pub use rank::{Candidate, RankOptions, Ranking, Unexcited, rank};
pub use records::{MIN_ENERGY_SHARE, RecordCorrelation, RecordSeparation, record_separations};
pub use separate::{Response, Separation, response, separation};

use crate::effects::{Effect, TERM_EFFECTS};
use crate::error::DtgVibError;
use crate::fit::FitOptions;
use crate::model::{ChannelModel, ChannelScores, CompensationModel};
use crate::pipeline::Prepared;
use crate::residuals::{CorrelationCheck, billings_voon, independence, whiteness_beyond};
use faer::Mat;
use nav_sensors::dtg::DtgTerm;
use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::record::Record;
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

/// Diagnoses a fitted model on a record (normally the one it was fitted on:
/// the validation rows of the model's split are used).
pub fn diagnose(
    model: &CompensationModel,
    record: &Record,
    options: &DiagnoseOptions,
) -> Result<Diagnosis, DtgVibError> {
    diagnose_records(model, &[(String::new(), record)], options)
}

/// Diagnoses a fitted model on several records at once (normally those it
/// was fitted on, named by their files as at the fit): each record prepared
/// on its own, the model's split applied as at fit time, and every
/// candidate ranked on the rows of all of them. A pair of candidates that
/// one record cannot tell apart is separated by another that excites them
/// differently, and [`Candidate::record_separations`] says which. One record gives
/// exactly [`diagnose`].
///
/// ```no_run
/// use dtg_vib::diagnose::diagnose_records;
/// use dtg_vib::model::CompensationModel;
/// use nav_sensors::record::Record;
/// let model = CompensationModel::load("xyz.json")?;
/// let (x, z) = (Record::read_csv("x.csv")?, Record::read_csv("z.csv")?);
/// let recs = [("x.csv".to_string(), &x), ("z.csv".to_string(), &z)];
/// let d = diagnose_records(&model, &recs, &Default::default())?;
/// for c in &d.channels { println!("{}: {:?}", c.channel, c.suggested); }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn diagnose_records(
    model: &CompensationModel,
    records: &[(String, &Record)],
    options: &DiagnoseOptions,
) -> Result<Diagnosis, DtgVibError> {
    let prepared = model.prepare_many(records)?;
    let predictions = model.predict(&prepared)?;
    let (train, val) = model.rows(&prepared)?;
    // The mirror of the model: the same settings trained on its validation
    // rows, so every row of the record has an out-of-sample residual.
    let mirror = crate::fit::fit_rows(
        &prepared,
        model.calibration(),
        &FitOptions::of_model(model),
        &val,
        &train,
        &|_| {},
    )?;
    let mirror_predictions = mirror.predict(&prepared)?;
    let x = prepared.window_matrix();
    let context = Context::new(&prepared, &val)?;
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
            diagnose_channel(
                c,
                &prepared,
                &predictions[i],
                &train,
                &val,
                &halves,
                &context,
                options,
            )
        })
        .collect::<Result<Vec<ChannelDiagnosis>, _>>()?;
    let mut channels = channels;
    if options.try_settings {
        try_longer_window(model, records, &mut channels);
    }
    Ok(Diagnosis {
        records: match records.len() {
            1 => Vec::new(),
            _ => records.iter().map(|(n, _)| n.clone()).collect(),
        },
        channels,
    })
}

/// Where a residual stays correlated beyond the model's window, a longer
/// window is the setting to try; the advice is given only with the
/// validation rms it gave on this record, before and after.
fn try_longer_window(
    model: &CompensationModel,
    records: &[(String, &Record)],
    channels: &mut [ChannelDiagnosis],
) {
    let slow: Vec<usize> = channels
        .iter()
        .enumerate()
        .filter(|(_, c)| c.failing.iter().any(|f| f == "whiteness"))
        .map(|(i, _)| i)
        .collect();
    if slow.is_empty() {
        return;
    }
    let mut options = FitOptions::of_model(model);
    let w = &options.preprocess.window;
    let longer = w.length() * 3;
    let Ok(window) = crate::window::WindowSpec::new(w.signals().to_vec(), longer) else {
        return;
    };
    options.preprocess.window = window;
    // A record too short for the longer window has nothing to say about it.
    let Ok((trial, _)) = crate::fit::fit_records(records, model.calibration(), &options, &|_| {})
    else {
        return;
    };
    let on = if records.len() > 1 {
        "these records"
    } else {
        "this record"
    };
    for i in slow {
        let c = &mut channels[i];
        let before = c.rms;
        let after = trial.channels()[c.channel.index()].scores().val_rms;
        c.findings.push(if after < 0.95 * before {
            format!(
                "tried --window {longer} on {on}: validation rms {before:.4} → {after:.4} deg/h ({:+.0}%): refit with --window {longer}",
                100.0 * (after / before - 1.0)
            )
        } else {
            format!(
                "tried --window {longer} on {on}: validation rms {before:.4} → {after:.4} deg/h, no better: the slow error is not the window's"
            )
        });
    }
}

/// One half of a cross-fit: a channel model, its predictions, the rows it
/// was fitted on and the rows it predicts out of sample.
struct Half<'a> {
    model: &'a ChannelModel,
    predicted: &'a [f64],
    fit_rows: &'a [usize],
    test_rows: &'a [usize],
}

/// The model and its mirror: between them every analysed row is predicted
/// by a model that did not see it.
struct CrossFit<'a> {
    x: &'a Mat<f64>,
    /// The fit's ridge on network weights.
    ridge: f64,
    halves: [Half<'a>; 2],
}

impl CrossFit<'_> {
    /// The analysed rows, in time order.
    fn rows(&self) -> Vec<usize> {
        let mut r: Vec<usize> = self
            .halves
            .iter()
            .flat_map(|h| h.test_rows.iter().copied())
            .collect();
        r.sort_unstable();
        r
    }

    /// Out-of-sample residual `y − ŷ` on [`CrossFit::rows`].
    fn residual(&self, y: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; y.len()];
        for h in &self.halves {
            for &r in h.test_rows {
                out[r] = y[r] - h.predicted[r];
            }
        }
        self.rows().iter().map(|&r| out[r]).collect()
    }

    /// `columns` (rows × m, all prepared rows) with each half's function space
    /// (bias, the model's effects, its network basis) fitted on its fitting
    /// rows and projected out of its test rows; on [`CrossFit::rows`].
    fn partial_out(
        &self,
        prepared: &Prepared,
        columns: &Mat<f64>,
    ) -> Result<Mat<f64>, DtgVibError> {
        let m = columns.ncols();
        let mut out = Mat::<f64>::zeros(columns.nrows(), m);
        for h in &self.halves {
            let z = prepared.effect_matrix(h.model.channel(), h.model.effects())?;
            let p = z.ncols();
            let basis = |rows: &[usize]| {
                let xr = Mat::from_fn(rows.len(), self.x.ncols(), |i, j| self.x[(rows[i], j)]);
                let f = h.model.rbf().features(xr.as_ref());
                // [bias, effects, network]: the unpenalised columns first.
                Mat::from_fn(rows.len(), f.ncols() + p, |i, j| match j {
                    0 => f[(i, 0)],
                    j if j <= p => z[(rows[i], j - 1)],
                    j => f[(i, j - p)],
                })
            };
            let pick = |rows: &[usize]| Mat::from_fn(rows.len(), m, |i, j| columns[(rows[i], j)]);
            let r = crate::inference::residualise(
                basis(h.fit_rows).as_ref(),
                pick(h.fit_rows).as_ref(),
                basis(h.test_rows).as_ref(),
                pick(h.test_rows).as_ref(),
                1 + p,
                self.ridge,
            )
            .map_err(|e| DtgVibError::Fit {
                channel: h.model.channel(),
                source: e.into(),
            })?;
            for (i, &row) in h.test_rows.iter().enumerate() {
                for j in 0..m {
                    out[(row, j)] = r[(i, j)];
                }
            }
        }
        let rows = self.rows();
        Ok(Mat::from_fn(rows.len(), m, |i, j| out[(rows[i], j)]))
    }
}

/// What every channel's diagnosis shares: inputs on the validation rows.
struct Context {
    t: Vec<f64>,
    /// Filtered accelerations (ax, ay, az) on the validation rows.
    accel: [Vec<f64>; 3],
    /// Filtered extra columns on the validation rows.
    extras: Vec<(String, Vec<f64>)>,
    /// Largest standard deviation of the least-squares rate, deg/s.
    rate_std_deg_s: f64,
    /// Mean filtered specific force on the validation rows (cluster frame), g.
    gravity_g: nalgebra::Vector3<f64>,
    /// RMS of the filtered specific force about its mean, g.
    vibration_g: f64,
    /// The axis along which the filtered specific force varies most.
    vibration_axis: Axis,
    fs: f64,
    /// The model's memory in decimated samples: a window plus the filter's
    /// reach. The whiteness test looks beyond it.
    memory: usize,
    /// Decimation of the whiteness test: to about twice the filter's cut-off
    /// (the lags in between carry no information).
    decimation: usize,
    /// Positions of the validation rows the correlation tests use: those
    /// whose window lies beyond the filter's reach of the record's ends. At
    /// an end the zero-phase filter's reflected extension makes the filtered
    /// input (and the residual with it) several times its usual size, and
    /// the fourth-power Billings–Voon products of one such row can decide a
    /// test on their own. With several records, the ends of each record.
    steady: Vec<usize>,
    band_edges: Vec<f64>,
    shape: Box<dyn Fn(f64) -> f64>,
}

impl Context {
    fn new(prepared: &Prepared, val: &[usize]) -> Result<Self, DtgVibError> {
        let first = prepared.first_sample();
        let on_val = |x: &[f64]| -> Vec<f64> { val.iter().map(|&r| x[first + r]).collect() };
        let rec = prepared.calibrated();
        let accel = [
            on_val(&prepared.signal_full(Axis::X.column())?),
            on_val(&prepared.signal_full(Axis::Y.column())?),
            on_val(&prepared.signal_full(Axis::Z.column())?),
        ];
        let extras = rec
            .extra_names()
            .iter()
            .map(|n| Ok((n.to_string(), on_val(&prepared.signal_full(n)?))))
            .collect::<Result<Vec<_>, DtgVibError>>()?;
        let rate_std_deg_s =
            crate::effects::rate_variation_deg_s(rec, val.iter().map(|&r| first + r));
        // The validation series' own rate: alternate rows (an interleaved
        // split) are two samples apart.
        let spacing = crate::split::row_spacing(val);
        let fs = 1.0 / (rec.dt() * spacing as f64);
        let nyquist = fs / 2.0;
        let (decimation, cutoff) = match prepared.filter() {
            // Decimation in validation rows.
            Some(f) => (
                ((fs / (2.0 * f.cutoff_hz())).floor() as usize).max(1),
                f.cutoff_hz().min(nyquist),
            ),
            None => (1, nyquist),
        };
        let mut band_edges: Vec<f64> = vec![0.0, 0.1, 0.5, 2.0];
        band_edges.retain(|&e| e < cutoff);
        band_edges.push(cutoff);
        if cutoff < nyquist {
            band_edges.push(nyquist);
        }
        let shape: Box<dyn Fn(f64) -> f64> = match prepared.filter() {
            Some(f) => {
                let f = f.clone();
                Box::new(move |hz| f.gain_at(hz).powi(4))
            }
            None => Box::new(|_| 1.0),
        };
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        let var = |v: &[f64]| {
            let m = mean(v);
            v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len().max(1) as f64
        };
        let gravity_g = nalgebra::Vector3::new(mean(&accel[0]), mean(&accel[1]), mean(&accel[2]));
        let variances = [var(&accel[0]), var(&accel[1]), var(&accel[2])];
        let vibration_axis = Axis::ALL
            .into_iter()
            .max_by(|a, b| variances[a.index()].total_cmp(&variances[b.index()]))
            .expect("three axes");
        let fm = prepared.filter_memory();
        // A row's window starts `first` samples before the sample it ends at.
        let steady: Vec<usize> = val
            .iter()
            .enumerate()
            .filter(|&(_, &r)| {
                let (record, sample) = prepared.locate(r);
                sample >= first + fm && sample + fm < record.len()
            })
            .map(|(i, _)| i)
            .collect();
        // Too little left (a record barely longer than the filter): test all rows.
        let steady = if steady.len() >= val.len() / 2 {
            steady
        } else {
            (0..val.len()).collect()
        };
        let reach = prepared.first_sample() + 1 + prepared.filter_memory();
        let memory = reach.div_ceil(spacing * decimation);
        Ok(Self {
            t: on_val(rec.t()),
            memory,
            gravity_g,
            vibration_g: variances.iter().sum::<f64>().sqrt(),
            vibration_axis,
            accel,
            extras,
            rate_std_deg_s,
            fs,
            decimation,
            steady,
            band_edges,
            shape,
        })
    }
}

#[allow(clippy::too_many_arguments)]
fn diagnose_channel(
    model: &ChannelModel,
    prepared: &Prepared,
    predicted: &[f64],
    train: &[usize],
    val: &[usize],
    cross: &CrossFit<'_>,
    ctx: &Context,
    opts: &DiagnoseOptions,
) -> Result<ChannelDiagnosis, DtgVibError> {
    let ch = model.channel();
    let y = prepared.target(ch);
    let residual: Vec<f64> = val.iter().map(|&r| y[r] - predicted[r]).collect();
    let compare = crate::fit::score(y, predicted, train, val);

    // Candidates: every effect the model lacks; rate products only where rates vary.
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
    let full = prepared.effect_columns_full(ch, &wanted)?;
    let first = prepared.first_sample();
    let columns: Vec<(Effect, Vec<f64>, f64)> = wanted
        .iter()
        .cloned()
        .zip(&full)
        .map(|(e, c)| {
            let train_mean =
                train.iter().map(|&r| c[first + r]).sum::<f64>() / train.len().max(1) as f64;
            (e, val.iter().map(|&r| c[first + r]).collect(), train_mean)
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
            ch,
            &group,
            &kappa,
            &ctx.gravity_g,
            ctx.vibration_g,
            ctx.vibration_axis,
        ));
    }
    // Several records: which candidates a suggestion was collinear with on
    // some record alone, and which records told them apart.
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
    ranking.unexcited.extend(unexcited_ai);

    // Correlation tests.
    let mut checks = Vec::new();
    let steady = |x: &[f64]| -> Vec<f64> { ctx.steady.iter().map(|&i| x[i]).collect() };
    let e = steady(&residual);
    let dec: Vec<f64> = e.iter().step_by(ctx.decimation).copied().collect();
    let lag = opts
        .max_lag
        .min(dec.len().saturating_sub(ctx.memory + 2) / 4)
        .max(1);
    if dec.len() > ctx.memory + lag + 2 {
        checks.push(NamedCheck {
            name: "whiteness".into(),
            check: whiteness_beyond(&dec, ctx.memory, lag, opts.confidence),
        });
    }
    let lag = opts.max_lag.min(e.len() / 4).max(1);
    let inputs = Axis::ALL
        .iter()
        .map(|a| (a.column().to_string(), steady(&ctx.accel[a.index()])))
        .chain(
            ctx.extras
                .iter()
                .map(|(n, v)| (format!("col:{n}"), steady(v))),
        );
    for (name, u) in inputs {
        checks.push(NamedCheck {
            name: format!("independence:{name}"),
            check: independence(&e, &u, lag, opts.confidence),
        });
        if name.starts_with('a') {
            for c in billings_voon(&e, &u, lag.min(10), opts.confidence) {
                checks.push(NamedCheck {
                    name: format!("{}:{name}", c.kind.name()),
                    check: c,
                });
            }
        }
    }
    let failing: Vec<String> = checks
        .iter()
        .filter(|c| !c.check.passed)
        .map(|c| c.name.clone())
        .collect();

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

    let findings = findings(&ranking, &failing, &segs, &bnds, &regs);
    let series = ChannelSeries {
        t: ctx.t.clone(),
        measured: val.iter().map(|&r| y[r]).collect(),
        predicted: val.iter().map(|&r| predicted[r]).collect(),
        residual,
        spectrum,
        candidates: columns
            .into_iter()
            .map(|(e, c, m)| (e.id(), c.iter().map(|v| v - m).collect()))
            .collect(),
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

/// A p-value as text: below double precision's resolution of 1 − cdf it
/// is a bound, not a number.
///
/// ```
/// assert_eq!(dtg_vib::diagnose::p_text(0.0), "< 1e-15");
/// assert_eq!(dtg_vib::diagnose::p_text(0.0123), "= 1.2e-2");
/// ```
pub fn p_text(p: f64) -> String {
    if p < 1e-15 {
        "< 1e-15".into()
    } else {
        format!("= {p:.1e}")
    }
}

/// Plain-language findings, most actionable first.
fn findings(
    ranking: &Ranking,
    failing: &[String],
    segs: &[Segment],
    bands: &[Band],
    regimes: &[Regime],
) -> Vec<String> {
    let mut out = Vec::new();
    for id in &ranking.suggested {
        if let Some(c) = ranking.candidates.iter().find(|c| &c.effect == id) {
            let mut s = format!(
                "missing effect {id} ({}): explains {:.0}% of the cross-fitted residual, coefficient {:.4} ± {:.4} {} (95% CI {:.4} to {:.4}; p {})",
                c.description,
                100.0 * c.conditional_err.unwrap_or(c.err),
                c.coef,
                c.coef_se,
                c.unit,
                c.coef_ci95[0],
                c.coef_ci95[1],
                c.p_value.map_or("n/a".into(), p_text)
            );
            match &c.separation {
                Some(sep) => s.push_str(&format!(
                    "; cannot be told apart here from {}: {}",
                    c.alternatives.join(", "),
                    sep.advice
                )),
                None if !c.collinear_with.is_empty() => s.push_str(&format!(
                    "; nearly collinear on this record with {}: cannot be told apart here",
                    c.collinear_with.join(", ")
                )),
                None => {}
            }
            for r in &c.record_separations {
                let on = |names: &[String]| {
                    names
                        .iter()
                        .filter_map(|n| r.records.iter().find(|x| &x.file == n))
                        .map(|x| format!("{} (|r| {:.2})", x.file, x.correlation.abs()))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                s.push_str(&format!(
                    "; told apart from {} only by the records together: collinear on {} alone{}",
                    r.effect,
                    on(&r.collinear_on),
                    if r.separated_by.is_empty() {
                        String::new()
                    } else {
                        format!(", separated by {}", on(&r.separated_by))
                    }
                ));
            }
            out.push(s);
        }
    }
    if ranking.suggested.is_empty() {
        out.push(
            "no candidate effect explains a significant part of the validation residual".into(),
        );
    }
    // What this record cannot reveal matters as much as what it does: a
    // stationary test never excites anisoinertia, a held chamber never temperature.
    if !ranking.unexcited.is_empty() {
        let ids: Vec<&str> = ranking
            .unexcited
            .iter()
            .map(|u| u.effect.as_str())
            .collect();
        out.push(format!(
            "not ranked, this record does not excite them: {}",
            ids.join(", ")
        ));
    }
    // Excess slow power alone is expected of any model (its errors are
    // correlated over its window); "something slow is left" needs the
    // residual to be correlated beyond that memory as well.
    let slow_left = failing.iter().any(|f| f == "whiteness");
    for b in bands
        .iter()
        .filter(|b| b.ratio_to_floor > 3.0 && b.share > 0.1)
        .filter(|b| slow_left || b.f_hi_hz > 0.5)
    {
        out.push(format!(
            "{:.0}% of the residual power lies in {}–{} Hz, {:.1}× a white floor there{}",
            100.0 * b.share,
            b.f_lo_hz,
            b.f_hi_hz,
            b.ratio_to_floor,
            if b.f_hi_hz <= 0.5 {
                ": something slow is not modelled and the residual stays correlated beyond the model's window (a temperature or a drift: add its column as col:NAME)"
            } else {
                ""
            }
        ));
    }
    for r in regimes.iter().filter(|r| r.mean_spread_sigma > 5.0) {
        out.push(format!("the residual's mean changes with {} across its range ({:.0}σ): a g- or g²-sensitive term along it may be missing", r.axis, r.mean_spread_sigma));
    }
    if !segs.is_empty() {
        let mut rms: Vec<f64> = segs.iter().map(|s| s.residual_rms).collect();
        rms.sort_by(f64::total_cmp);
        let median = rms[rms.len() / 2];
        for s in segs.iter().filter(|s| s.residual_rms > 2.0 * median) {
            out.push(format!("{:.1}–{:.1} s: residual rms {:.3} deg/h, {:.1}× the median segment (low-passed specific force, rms about its record mean: {:.2} g)", s.t_start, s.t_end, s.residual_rms, s.residual_rms / median, s.vibration_rms_g));
        }
    }
    if !failing.is_empty() {
        out.push(format!("failing correlation tests: {}", failing.join(", ")));
    }
    out
}
