//! Fitting the six channel models: physical effects and an RBF on the
//! acceleration window, fitted together, with the width and the number of
//! centres chosen by blocked cross-validation inside the training rows.
//!
//! Together, not in stages: the effect columns (e.g. g_I ∝ a_z) and the RBF
//! features (functions of the a_z window) are correlated, and a staged fit
//! would hand the shared part to whichever stage runs first. The OLS engine
//! takes the effects as forced columns (always in, orthogonalised first), so
//! the centres explain only what the physics does not, and the final weights
//! and effect coefficients come from one QR solve.

use crate::effects::{ANISOINERTIA_MIN_RATE_DEG_S, ChannelEffect, Effect, rate_variation_deg_s};
use crate::error::DtgVibError;
use crate::inference::{Blocks, Coefficient, HacFit, hac_regression, residualise};
pub use crate::model::{CentreMethod, FitSettings, Recipe};
use crate::model::{ChannelModel, ChannelScores, CompensationModel};
use crate::pipeline::{Prepared, Preprocess};
use crate::split::{Holdout, by_record_rows, leakage_gap, split_rows};
use faer::{Mat, MatRef, Par};
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use rayon::prelude::*;
use rbf::ParamGuard;
use rbf::{Candidates, CentreSelection, Grid, KMeansSettings, RbfParams, Sizes, Split, WidthRule};
use serde::Serialize;

/// Everything a fit can be told: the recipe in the command line's words
/// (effects of every channel, additions to one channel) and, of several
/// records, the one that only validates.
///
/// ```
/// let o = dtg_vib::fit::FitOptions::default();
/// assert_eq!(o.settings.max_centres, 60);
/// assert!(o.effects.is_empty());
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FitOptions {
    /// Pre-processing (filter, window, rate reference).
    pub preprocess: Preprocess,
    /// Effects of every channel's linear part.
    pub effects: Vec<Effect>,
    /// Effects added to one channel each.
    pub add: Vec<ChannelEffect>,
    /// Training/validation split (within each record of several).
    pub split: Holdout,
    /// Of several records, the one that only validates (the others only
    /// train); `None`: [`FitOptions::split`] within each record.
    pub validate_on: Option<String>,
    /// How the networks are chosen (what the model keeps).
    pub settings: FitSettings,
}

impl FitOptions {
    /// The recipe these options describe: each channel's effects resolved
    /// (the common ones, then its additions, each once).
    pub fn recipe(&self) -> Recipe {
        Recipe {
            preprocess: self.preprocess.clone(),
            split: self.split,
            effects: std::array::from_fn(|k| self.effects_of(Channel::ALL[k])),
            settings: self.settings.clone(),
        }
    }

    /// The effects of one channel: the common ones, then its additions.
    pub fn effects_of(&self, channel: Channel) -> Vec<Effect> {
        let mut e = self.effects.clone();
        for a in self.add.iter().filter(|a| a.channel == channel) {
            if !e.contains(&a.effect) {
                e.push(a.effect.clone());
            }
        }
        e
    }
}

impl FitSettings {
    /// Refuses settings no fit can use, naming the setting.
    fn check(&self) -> Result<(), DtgVibError> {
        let bad = |name, value: String, reason| {
            Err(DtgVibError::InvalidOption {
                name,
                value,
                reason,
            })
        };
        if self.max_centres == 0 {
            return bad("max centres", "0".into(), "need at least one centre");
        }
        if self.width_scales.is_empty()
            || self
                .width_scales
                .iter()
                .any(|s| !(s.is_finite() && *s > 0.0))
        {
            return bad(
                "width scales",
                format!("{:?}", self.width_scales),
                "need positive finite multiples",
            );
        }
        if !(self.ridge.is_finite() && self.ridge >= 0.0) {
            return bad(
                "ridge",
                self.ridge.to_string(),
                "must be a finite number ≥ 0",
            );
        }
        if self.inner_folds < 2 {
            return bad(
                "inner folds",
                self.inner_folds.to_string(),
                "cross-validation needs at least 2 folds",
            );
        }
        Ok(())
    }
}

/// Numbers of centres tried: a roughly geometric ladder up to `max`.
fn size_ladder(max: usize) -> Vec<usize> {
    let mut v: Vec<usize> = [2, 5, 10, 15, 20, 30, 40, 60, 80, 100, 150, 200, 300]
        .into_iter()
        .filter(|&k| k < max)
        .collect();
    v.push(max);
    v
}

/// Which stage of a fit is running, for progress display.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitStage {
    /// Reading and pre-processing the record.
    Preparing,
    /// One channel's cross-validation and fit finished.
    ChannelDone(Channel),
}

/// Fits the six channel models on a record.
///
/// ```no_run
/// use dtg_vib::fit::{fit, FitOptions};
/// let rec = nav_sensors::record::Record::read_csv("record.csv")?;
/// let model = fit(&rec, None, &FitOptions::default(), &|_| {})?;
/// println!("{}", model.channel(nav_sensors::geometry::Channel::Z).scores().val_rms);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit(
    record: &Record,
    calibration: Option<&Calibration>,
    options: &FitOptions,
    progress: &(dyn Fn(FitStage) + Sync),
) -> Result<CompensationModel, DtgVibError> {
    options.settings.check()?;
    progress(FitStage::Preparing);
    let prepared = Prepared::new(record, calibration, &options.preprocess)?;
    fit_prepared(&prepared, options, progress)
}

/// [`fit`] on data already prepared (with `options.preprocess`, after the
/// calibration the model is to keep: both come from `prepared`).
pub fn fit_prepared(
    prepared: &Prepared,
    options: &FitOptions,
    progress: &(dyn Fn(FitStage) + Sync),
) -> Result<CompensationModel, DtgVibError> {
    options.settings.check()?;
    let (train, val) = match &options.validate_on {
        Some(name) => by_record_rows(prepared, name)?,
        None => split_rows(prepared, options.split)?,
    };
    let mut model = fit_rows(prepared, &options.recipe(), &train, &val, progress)?;
    model.validated_on = options.validate_on.clone();
    Ok(model)
}

/// [`fit`] on several records, each prepared on its own (filters and
/// windows never cross a boundary) and named for errors and scores.
///
/// ```no_run
/// use dtg_vib::fit::{fit_records, FitOptions};
/// use nav_sensors::record::Record;
/// let (x, z) = (Record::read_csv("x.csv")?, Record::read_csv("z.csv")?);
/// let recs = [("x.csv".to_string(), &x), ("z.csv".to_string(), &z)];
/// let (model, prepared) = fit_records(&recs, None, &FitOptions::default(), &|_| {})?;
/// let per_record = dtg_vib::fit::record_scores(&model, &prepared)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_records(
    records: &[(String, &Record)],
    calibration: Option<&Calibration>,
    options: &FitOptions,
    progress: &(dyn Fn(FitStage) + Sync),
) -> Result<(CompensationModel, Prepared), DtgVibError> {
    options.settings.check()?;
    progress(FitStage::Preparing);
    let prepared = Prepared::new_many(records, calibration, &options.preprocess)?;
    let mut model = fit_prepared(&prepared, options, progress)?;
    model.records = record_names(records);
    Ok((model, prepared))
}

/// The names a model or diagnosis keeps of its records: none for one
/// record (its file is said where it is given), every one of several.
pub(crate) fn record_names(records: &[(String, &Record)]) -> Vec<String> {
    match records.len() {
        1 => Vec::new(),
        _ => records.iter().map(|(n, _)| n.clone()).collect(),
    }
}

/// The model's mirror, which the diagnosis's cross-fit reads: its recipe
/// trained on its validation rows of `prepared` (the record(s) it was
/// fitted on, prepared by [`CompensationModel::prepare_many`]) and
/// validated on its training rows, so that between the model and its
/// mirror every row has a prediction from a model that did not see it.
pub fn mirror(
    model: &CompensationModel,
    prepared: &Prepared,
) -> Result<CompensationModel, DtgVibError> {
    let (train, val) = model.rows(prepared)?;
    fit_rows(prepared, &model.recipe(), &val, &train, &|_| {})
}

/// `model`'s recipe fitted again on `records` with windows of `length`
/// samples, split within each record: the trial the diagnosis's advice on a
/// slow residual rests on.
pub fn refit_with_window(
    model: &CompensationModel,
    records: &[(String, &Record)],
    length: usize,
) -> Result<CompensationModel, DtgVibError> {
    let mut recipe = model.recipe();
    let signals = recipe.preprocess.window.signals().to_vec();
    recipe.preprocess.window = crate::window::WindowSpec::new(signals, length)?;
    let prepared = Prepared::new_many(records, model.calibration(), &recipe.preprocess)?;
    let (train, val) = split_rows(&prepared, recipe.split)?;
    let mut trial = fit_rows(&prepared, &recipe, &train, &val, &|_| {})?;
    trial.records = record_names(records);
    Ok(trial)
}

/// One record's validation rms of one channel, deg/h.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordScore {
    /// The record's name (its file).
    pub file: String,
    /// Rms of target − model on the record's validation rows, deg/h.
    pub val_rms: f64,
}

/// Each channel's validation rms on each record of `prepared`, for the
/// validation rows the model was fitted with (X, X1, Y, Y1, Z, Z1 order); a
/// record without validation rows (it only trained) is left out.
pub fn record_scores(
    model: &CompensationModel,
    prepared: &Prepared,
) -> Result<[Vec<RecordScore>; 6], DtgVibError> {
    let val = match &model.validated_on {
        // A by-record fit validated on one whole record: asked of data without
        // it, that is an error naming the record, not another split.
        Some(name) => by_record_rows(prepared, name)?.1,
        None => model.rows(prepared)?.1,
    };
    let predicted = model.predict(prepared)?;
    Ok(std::array::from_fn(|k| {
        let y = prepared.target(Channel::ALL[k]);
        prepared
            .record_rows()
            .into_iter()
            .filter_map(|(name, range)| {
                let rows: Vec<usize> = val.iter().copied().filter(|r| range.contains(r)).collect();
                (!rows.is_empty()).then(|| RecordScore {
                    file: name.to_string(),
                    val_rms: rms(rows.iter().map(|&r| y[r] - predicted[k][r])),
                })
            })
            .collect()
    }))
}

/// Leave one record out (`fit --cv records`): each record validated, whole,
/// by a model fitted on the others; each channel's rms per record.
pub fn leave_one_record_out(
    prepared: &Prepared,
    options: &FitOptions,
) -> Result<[Vec<RecordScore>; 6], DtgVibError> {
    let recipe = options.recipe();
    let mut out: [Vec<RecordScore>; 6] = Default::default();
    for (name, _) in prepared.record_rows() {
        let (train, val) = by_record_rows(prepared, name)?;
        let m = fit_rows(prepared, &recipe, &train, &val, &|_| {}).map_err(|e| {
            DtgVibError::InRecord {
                record: format!("leaving out {name}"),
                source: Box::new(e),
            }
        })?;
        for (k, c) in m.channels().iter().enumerate() {
            out[k].push(RecordScore {
                file: name.to_string(),
                val_rms: c.scores().val_rms,
            });
        }
    }
    Ok(out)
}

/// A recipe fitted on explicit training and validation rows of data
/// prepared with its pre-processing (the mirror trains on a model's
/// validation rows; leaving a record out trains on the others).
fn fit_rows(
    prepared: &Prepared,
    recipe: &Recipe,
    train: &[usize],
    val: &[usize],
    progress: &(dyn Fn(FitStage) + Sync),
) -> Result<CompensationModel, DtgVibError> {
    debug_assert_eq!(prepared.preprocess(), &recipe.preprocess);
    let settings = &recipe.settings;
    let (train, val) = (train.to_vec(), val.to_vec());
    // A view of the prepared windows, not a copy: only the rows a fit works
    // on are gathered (all training rows, or the selection subsample).
    let x = prepared.window_view();
    windows_vary(x, &train, recipe.preprocess.window.signals())?;
    let stride = selection_stride(train.len());
    let sel: Vec<usize> = train.iter().step_by(stride).copied().collect();
    inner_folds_fit(prepared, sel.len(), settings.inner_folds)?;
    let fit_on = if stride > 1 { &sel } else { &train };
    let x_fit = gather(x, fit_on);
    let fits: Vec<ChannelFit> = Channel::ALL
        .par_iter()
        .map(|&ch| {
            let effects = recipe.effects_of(ch);
            let m = fit_channel(prepared, x, &x_fit, fit_on, ch, effects, settings);
            progress(FitStage::ChannelDone(ch));
            m
        })
        .collect::<Result<_, _>>()?;
    drop(x_fit);
    // On a subsample, the weights are solved again on every training row,
    // over row blocks (memory independent of the number of rows), before
    // the channel is scored.
    let channels: Vec<ChannelModel> = fits
        .into_par_iter()
        .map(|f| match stride {
            1 => scored(prepared, x, &train, &val, f),
            _ => refit_weights(prepared, x, &train, f, settings)
                .and_then(|f| scored(prepared, x, &train, &val, f)),
        })
        .collect::<Result<_, _>>()?;
    Ok(CompensationModel {
        preprocess: recipe.preprocess.clone(),
        calibration: prepared.calibration().cloned(),
        dt_s: prepared.calibrated().dt(),
        split: recipe.split,
        channels,
        fit: settings.clone(),
        records: Vec::new(),
        validated_on: None,
        operating_points: Some(crate::operating::OperatingPoints::from_training(
            prepared,
            recipe.preprocess.window.length(),
            &train,
            &val,
        )?),
    })
}

/// Training windows above which cross-validation and centre selection run on
/// every `selection_stride`-th of them; the weights are still solved on all.
/// Their cost is rows × candidates per fold and channel: 1.6 GB a channel at
/// 500,000 rows, where a 1M-row record needed 6 GB and over 5 minutes.
pub const MAX_SELECTION_ROWS: usize = 50_000;

/// The stride of the training windows that choose centres and width: 1 up to
/// [`MAX_SELECTION_ROWS`]. A stride keeps time order, so the blocked folds'
/// leakage gap of g rows spans g·stride samples, never fewer than needed.
///
/// ```
/// assert_eq!(dtg_vib::fit::selection_stride(50_000), 1);
/// assert_eq!(dtg_vib::fit::selection_stride(500_000), 10);
/// ```
pub fn selection_stride(n_train: usize) -> usize {
    n_train.div_ceil(MAX_SELECTION_ROWS).max(1)
}

/// One channel's fitted network and effect coefficients, not yet scored.
#[derive(Debug, Clone)]
struct ChannelFit {
    channel: Channel,
    effects: Vec<Effect>,
    /// The effects' columns on every row (worked out once per channel).
    z: Mat<f64>,
    width: f64,
    model: rbf::RbfModel,
    coefficients: Vec<Coefficient>,
}

impl ChannelFit {
    /// True when the effects' coefficients were estimated (by partialling
    /// out) and stay fixed in the network's refit; as
    /// [`ChannelModel::coefficients`] tells.
    fn theta_fixed(&self) -> bool {
        self.coefficients.len() == self.effects.len() && !self.effects.is_empty()
    }
}

/// The channel model of a fit, scored on the training and validation rows.
fn scored(
    prepared: &Prepared,
    x: MatRef<'_, f64>,
    train: &[usize],
    val: &[usize],
    f: ChannelFit,
) -> Result<ChannelModel, DtgVibError> {
    let y = prepared.target(f.channel);
    let yhat = f.model.predict_with_linear(x, f.z.as_ref());
    let yhat: Vec<f64> = (0..yhat.nrows()).map(|i| yhat[(i, 0)]).collect();
    let scores = score(y, &yhat, train, val);
    Ok(
        ChannelModel::new(f.channel, f.effects, f.width, f.model, scores)
            .with_coefficients(f.coefficients),
    )
}

/// A channel fit whose centres and width were chosen on a subsample, with
/// its bias, effect coefficients and weights solved again on every training
/// row by a row-block QR ([`rbf::RbfValidParams::fit_given_streaming`]: the
/// rows are copied from the prepared windows block by block, so neither the
/// training windows nor their n × (1 + effects + K) design are ever held).
fn refit_weights(
    prepared: &Prepared,
    x: MatRef<'_, f64>,
    train: &[usize],
    f: ChannelFit,
    settings: &FitSettings,
) -> Result<ChannelFit, DtgVibError> {
    let (channel, z) = (f.channel, &f.z);
    let y = prepared.target(channel);
    let fail = |source| DtgVibError::Fit { channel, source };
    let params = RbfParams::new()
        .kernel(settings.kernel)
        .centres(CentreSelection::Given(f.model.centres()))
        .width(WidthRule::Fixed(f.width))
        .ridge(settings.ridge)
        .seed(settings.seed)
        .parallelism(Par::Seq)
        .check()
        .map_err(|e| fail(e.into()))?;
    // Effect coefficients estimated by partialling out stay as they are
    // (with their intervals); the network is solved on what they leave.
    let theta = f
        .theta_fixed()
        .then(|| f.model.linear_coefficients().to_owned());
    let r = if theta.is_some() { 0 } else { z.ncols() };
    let (n, d) = (train.len(), x.ncols());
    let model = params
        .fit_given_streaming(n, d, r, 1, |start, mut xb, mut zb, mut yb| {
            for i in 0..xb.nrows() {
                let row = train[start + i];
                for j in 0..d {
                    xb[(i, j)] = x[(row, j)];
                }
                for j in 0..r {
                    zb[(i, j)] = z[(row, j)];
                }
                yb[(i, 0)] = match &theta {
                    Some(t) => {
                        y[row] - (0..t.nrows()).map(|j| z[(row, j)] * t[(j, 0)]).sum::<f64>()
                    }
                    None => y[row],
                };
            }
        })
        .map_err(fail)?;
    let model = match &theta {
        Some(t) => model.with_linear(t.as_ref()),
        None => model,
    };
    Ok(ChannelFit { model, ..f })
}

/// Windows that are all the same point leave the network nothing to tell
/// apart, and the library's width rule would say "use a fixed width", which
/// no flag here sets: say which signals do not vary instead.
fn windows_vary(
    x: MatRef<'_, f64>,
    train: &[usize],
    signals: &[String],
) -> Result<(), DtgVibError> {
    let Some(&first) = train.first() else {
        return Ok(());
    };
    let same = (0..x.ncols()).all(|j| {
        let v = x[(first, j)];
        train.iter().all(|&i| x[(i, j)] == v)
    });
    if same {
        return Err(DtgVibError::WindowsConstant {
            signals: signals.to_vec(),
        });
    }
    Ok(())
}

/// The inner cross-validation keeps its blocked folds a leakage gap apart;
/// on a short record the gap can leave a fold no training rows, which the
/// library reports as "fold 1 of 226 samples has 0 training rows" without
/// the settings behind it: say them here, before any channel is fitted.
fn inner_folds_fit(prepared: &Prepared, n_train: usize, folds: usize) -> Result<(), DtgVibError> {
    let gap = leakage_gap(prepared);
    match (Split::Blocked { k: folds, gap }).folds(n_train) {
        Ok(_) => Ok(()),
        Err(_) => Err(DtgVibError::InnerFoldsEmpty {
            folds,
            n_train,
            gap,
            window: prepared.first_sample() + 1,
            filter_memory: prepared.filter_memory(),
        }),
    }
}

/// One channel's network and effects, chosen and fitted on the windows
/// `x_train` (rows `train` of the prepared windows `x`).
fn fit_channel(
    prepared: &Prepared,
    x: MatRef<'_, f64>,
    x_train: &Mat<f64>,
    train: &[usize],
    channel: Channel,
    effects: &[Effect],
    settings: &FitSettings,
) -> Result<ChannelFit, DtgVibError> {
    let effects = effects.to_vec();
    let z = prepared.effect_matrix(channel, &effects)?;
    let y = prepared.target(channel);
    let z_train = gather(z.as_ref(), train);
    let y_train = Mat::from_fn(train.len(), 1, |i, _| y[train[i]]);
    let fail = |source| DtgVibError::Fit { channel, source };
    // A constant effect (a temperature column held by a thermal chamber, say)
    // would surface as an anonymous collinear forced column deep in OLS: name it.
    if let Some(ai) = effects.iter().find(
        |e| matches!(e, Effect::Term(t) if nav_sensors::dtg::DtgTerm::ANISOINERTIA.contains(t)),
    ) {
        let first = prepared.first_sample();
        let v = rate_variation_deg_s(prepared.calibrated(), train.iter().map(|&r| first + r));
        if v < ANISOINERTIA_MIN_RATE_DEG_S {
            return Err(DtgVibError::EffectNotObservable {
                channel,
                effect: ai.id(),
                rate_std_deg_s: v,
                min_deg_s: ANISOINERTIA_MIN_RATE_DEG_S,
            });
        }
    }
    for (j, effect) in effects.iter().enumerate() {
        let col = (0..z_train.nrows()).map(|i| z_train[(i, j)]);
        let (lo, hi) = col.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        if hi - lo <= 1e-12 * lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE) {
            return Err(DtgVibError::EffectConstant {
                channel,
                effect: effect.id(),
                value: lo,
            });
        }
    }

    if let Some((j, kept)) = first_collinear_effect(z_train.as_ref()) {
        return Err(DtgVibError::EffectsCollinear {
            channel,
            effect: effects[j].id(),
            earlier: effects[..j].iter().map(Effect::id).collect(),
            kept,
        });
    }
    let gap = leakage_gap(prepared);
    let (model, coefficients) = if effects.is_empty() {
        let net = fit_network(
            settings,
            x_train.as_ref(),
            z_train.as_ref(),
            y_train.as_ref(),
            gap,
        )
        .map_err(fail)?;
        (net, Vec::new())
    } else {
        fit_partially_linear(x, &z, y, train, &effects, settings, gap).map_err(fail)?
    };
    let width = model.widths().get(0);
    Ok(ChannelFit {
        channel,
        effects,
        z,
        width,
        model,
        coefficients,
    })
}

/// How the training rows are cut for cross-fitting: into this many spans of
/// time, alternately assigned to the two blocks, so that both blocks see the
/// whole test (every level step, the whole temperature range). Each count
/// gives an estimate; their spread is part of the uncertainty, because the
/// networks that partial the effects out are themselves estimates and shift
/// with the rows they were fitted on.
const CROSS_FIT_CHUNKS: [usize; 3] = [4, 6, 8];

/// Several cross-fits' estimates as one (Chernozhukov et al. 2018, §3.4):
/// θ the mean, σ² the mean of σ_s² + (θ_s − θ)², the fewest degrees of freedom.
fn combine_splits(fits: &[HacFit]) -> Option<HacFit> {
    let first = fits.first()?;
    let s = fits.len() as f64;
    let p = first.coef.len();
    let mut out = first.clone();
    for j in 0..p {
        let mean = fits.iter().map(|f| f.coef[j]).sum::<f64>() / s;
        let var = fits
            .iter()
            .map(|f| f.se[j].powi(2) + (f.coef[j] - mean).powi(2))
            .sum::<f64>()
            / s;
        out.coef[j] = mean;
        out.se[j] = var.sqrt();
    }
    out.dof = fits.iter().map(|f| f.dof).fold(f64::INFINITY, f64::min);
    Some(out)
}

/// Fewest rows in each cross-fitting block: each block's network is chosen
/// by its own cross-validation, which needs a few hundred windows.
pub const MIN_BLOCK_ROWS: usize = 200;

/// The effects' coefficients by cross-fitted partialling out, then the network
/// on what the effects leave.
///
/// The training rows are cut in two blocks (with the leakage gap between).
/// On each block a network alone (no effects) is fitted to y by
/// cross-validation; its basis (bias and kernel columns) is fitted by least
/// squares to y and to every effect column on that block, and the residuals
/// are taken on the other block. θ is the regression of y's residual on the
/// effects' residuals over both blocks, with Newey–West standard errors.
/// The final network is fitted to y − Zθ on all training rows.
///
/// With blocks too short for their own cross-validation the fit is joint (θ
/// and the network in one solve) and θ's standard errors come from the same
/// regression in-sample (Frisch–Waugh–Lovell), which is optimistic.
fn fit_partially_linear(
    x: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    train: &[usize],
    effects: &[Effect],
    settings: &FitSettings,
    gap: usize,
) -> Result<(rbf::RbfModel, Vec<Coefficient>), rbf::RbfError> {
    let p = effects.len();
    let cuts: Vec<Blocks> = CROSS_FIT_CHUNKS
        .iter()
        .filter_map(|&k| Blocks::alternating(train, gap, k))
        .filter(|b| b.first.len().min(b.second.len()) >= MIN_BLOCK_ROWS)
        .collect();
    let mut fits = Vec::with_capacity(cuts.len());
    for b in &cuts {
        if let Some(f) = cross_fit(x, z, y, b, settings, gap)? {
            fits.push(f);
        }
    }
    let inference = combine_splits(&fits);
    let x_train = gather(x, train);
    let z_train = gather(z.as_ref(), train);
    let y_train = Mat::from_fn(train.len(), 1, |i, _| y[train[i]]);
    let (model, fit) = match inference {
        Some(f) => {
            let theta = Mat::from_fn(p, 1, |j, _| f.coef[j]);
            let y_adj = &y_train - &z_train * &theta;
            let net = fit_network(
                settings,
                x_train.as_ref(),
                Mat::<f64>::zeros(train.len(), 0).as_ref(),
                y_adj.as_ref(),
                gap,
            )?;
            (net.with_linear(theta.as_ref()), Some(f))
        }
        None => joint_fit(x, z, y, train, settings, gap)?,
    };
    let theta = model.linear_coefficients();
    // No interval rather than a made-up one when the regression of the
    // residuals failed (the model file then carries none).
    let coefficients = match &fit {
        Some(f) => effects
            .iter()
            .enumerate()
            .map(|(j, e)| {
                // Centred on the stored value (θ itself, or the joint fit's in the fallback).
                let half = f.interval(j, 0.95).map(|b| b - f.coef[j]);
                let v = theta[(j, 0)];
                Coefficient::new(v, f.se[j], [v + half[0], v + half[1]], e.unit())
            })
            .collect(),
        None => Vec::new(),
    };
    Ok((model, coefficients))
}

/// `[y, Z]` on `rows`: the targets whose residuals on a network's basis
/// the partialling out regresses.
fn y_and_z(y: &[f64], z: &Mat<f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), 1 + z.ncols(), |i, j| {
        if j == 0 {
            y[rows[i]]
        } else {
            z[(rows[i], j - 1)]
        }
    })
}

/// One cross-fit: residuals of `[y, Z]` on each block from the other
/// block's basis (a network alone fitted there), put back in time order,
/// and θ with its HAC errors.
fn cross_fit(
    x: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    b: &Blocks,
    settings: &FitSettings,
    gap: usize,
) -> Result<Option<HacFit>, rbf::RbfError> {
    let p = z.ncols();
    let mut by_row: Vec<(usize, Vec<f64>)> = Vec::with_capacity(b.first.len() + b.second.len());
    for (fit_rows, test_rows) in [(&b.second, &b.first), (&b.first, &b.second)] {
        let xf = gather(x, fit_rows);
        let yf = Mat::from_fn(fit_rows.len(), 1, |i, _| y[fit_rows[i]]);
        let no_z = Mat::<f64>::zeros(fit_rows.len(), 0);
        let net = fit_network(settings, xf.as_ref(), no_z.as_ref(), yf.as_ref(), gap)?;
        let xt = gather(x, test_rows);
        let r = residualise(
            net.features(xf.as_ref()).as_ref(),
            y_and_z(y, z, fit_rows).as_ref(),
            net.features(xt.as_ref()).as_ref(),
            y_and_z(y, z, test_rows).as_ref(),
            1,
            settings.ridge,
        )
        .map_err(rbf::RbfError::from)?;
        by_row.extend(
            test_rows
                .iter()
                .enumerate()
                .map(|(i, &row)| (row, (0..=p).map(|j| r[(i, j)]).collect())),
        );
    }
    by_row.sort_by_key(|(row, _)| *row);
    let column = |j: usize| -> Vec<f64> { by_row.iter().map(|(_, v)| v[j]).collect() };
    let rz: Vec<Vec<f64>> = (1..=p).map(column).collect();
    let cols: Vec<&[f64]> = rz.iter().map(Vec::as_slice).collect();
    Ok(hac_regression(&column(0), &cols).ok())
}

/// The joint fit of blocks too short to cross-fit: θ and the network in one
/// solve, θ's uncertainty from the same projection in-sample.
fn joint_fit(
    x: MatRef<'_, f64>,
    z: &Mat<f64>,
    y: &[f64],
    train: &[usize],
    settings: &FitSettings,
    gap: usize,
) -> Result<(rbf::RbfModel, Option<HacFit>), rbf::RbfError> {
    let p = z.ncols();
    let x_train = gather(x, train);
    let z_train = gather(z.as_ref(), train);
    let y_train = Mat::from_fn(train.len(), 1, |i, _| y[train[i]]);
    let joint = fit_network(
        settings,
        x_train.as_ref(),
        z_train.as_ref(),
        y_train.as_ref(),
        gap,
    )?;
    let phi = joint.features(x_train.as_ref());
    let targets = y_and_z(y, z, train);
    let r = residualise(
        phi.as_ref(),
        targets.as_ref(),
        phi.as_ref(),
        targets.as_ref(),
        1,
        settings.ridge,
    )
    .map_err(rbf::RbfError::from)?;
    let ry: Vec<f64> = (0..r.nrows()).map(|i| r[(i, 0)]).collect();
    let rz: Vec<Vec<f64>> = (1..=p)
        .map(|j| (0..r.nrows()).map(|i| r[(i, j)]).collect())
        .collect();
    let cols: Vec<&[f64]> = rz.iter().map(Vec::as_slice).collect();
    let f = hac_regression(&ry, &cols).ok();
    Ok((joint, f))
}

/// The network (with `z` as forced linear columns, none if it has no
/// columns) chosen by blocked cross-validation over widths and numbers of
/// centres, refitted on all the given rows.
fn fit_network(
    settings: &FitSettings,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    gap: usize,
) -> Result<rbf::RbfModel, rbf::RbfError> {
    let selection = |k: usize| match settings.centres {
        CentreMethod::Ols => CentreSelection::Ols {
            max_centres: k,
            tol: 0.0,
            regularisation: 0.0,
            candidates: Candidates::Subsample {
                size: settings.candidates,
            },
        },
        CentreMethod::KMeans => CentreSelection::KMeans(KMeansSettings::new(k)),
    };
    let params = |k: usize, width: WidthRule| {
        RbfParams::new()
            .kernel(settings.kernel)
            .centres(selection(k))
            .width(width)
            .ridge(settings.ridge)
            .seed(settings.seed)
            .parallelism(Par::Seq)
            .check()
            .map_err(rbf::RbfError::from)
    };
    let widths: Vec<WidthRule> = settings
        .width_scales
        .iter()
        .map(|&s| WidthRule::MedianPairwise { scale: s })
        .collect();
    let max_k = settings.max_centres.min(x.nrows() / 2).max(1);
    let grid = Grid {
        widths: widths.clone(),
        sizes: Sizes::Centres(size_ladder(max_k)),
        ridges: vec![],
    };
    let report = rbf::grid_search_with_linear(
        &params(max_k, widths[0].clone())?,
        x,
        z,
        y,
        &Split::Blocked {
            k: settings.inner_folds,
            gap,
        },
        &grid,
    )?;
    let best = match report.best() {
        Some(b) => b,
        None => {
            let first_error = report.points.into_iter().find_map(|p| p.result.err());
            return Err(first_error.unwrap_or(rbf::RbfError::FoldFailed {
                reason: "no grid point".into(),
            }));
        }
    };
    let k = best.n_centres.unwrap_or(max_k);
    params(k, best.width.clone())?.fit_with_linear(x, z, y)
}

/// Share of a column's variation (energy about its mean) that an effect must
/// keep once the bias and the effects before it are projected out. Stricter
/// than the OLS engine's own 1e-12, so a cross-validation fold on fewer rows
/// does not meet the collinearity first.
const EFFECT_COLLINEARITY_TOL: f64 = 1e-9;

/// The first effect column (and the share of its variation it keeps) that is
/// (nearly) a combination of the bias and the columns before it: modified
/// Gram–Schmidt on the centred columns, in order.
fn first_collinear_effect(z: MatRef<'_, f64>) -> Option<(usize, f64)> {
    let n = z.nrows();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for j in 0..z.ncols() {
        let mean = (0..n).map(|i| z[(i, j)]).sum::<f64>() / n.max(1) as f64;
        let mut v: Vec<f64> = (0..n).map(|i| z[(i, j)] - mean).collect();
        let orig: f64 = v.iter().map(|x| x * x).sum();
        for q in &basis {
            let c: f64 = q.iter().zip(&v).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(q).for_each(|(x, a)| *x -= c * a);
        }
        let kept: f64 = v.iter().map(|x| x * x).sum();
        if kept.is_nan() || kept <= EFFECT_COLLINEARITY_TOL * orig {
            return Some((j, if orig > 0.0 { kept / orig } else { 0.0 }));
        }
        let norm = kept.sqrt();
        basis.push(v.into_iter().map(|x| x / norm).collect());
    }
    None
}

/// Rows `rows` of `m`.
fn gather(m: MatRef<'_, f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), m.ncols(), |i, j| m[(rows[i], j)])
}

/// [`stats::rms`] of rows picked by an iterator (never empty here: a split
/// side has at least [`crate::split::MIN_ROWS`] rows).
fn rms(v: impl Iterator<Item = f64>) -> f64 {
    stats::rms(&v.collect::<Vec<_>>())
}

/// Scores of a prediction on training and validation rows.
pub(crate) fn score(y: &[f64], yhat: &[f64], train: &[usize], val: &[usize]) -> ChannelScores {
    let mean = |rows: &[usize]| rows.iter().map(|&i| y[i]).sum::<f64>() / rows.len() as f64;
    let fit = |rows: &[usize]| {
        let m = mean(rows);
        let num = rms(rows.iter().map(|&i| y[i] - yhat[i]));
        let den = rms(rows.iter().map(|&i| y[i] - m));
        100.0 * (1.0 - num / den)
    };
    let train_mean = mean(train);
    ChannelScores {
        n_train: train.len(),
        n_val: val.len(),
        train_rms: rms(train.iter().map(|&i| y[i] - yhat[i])),
        val_rms: rms(val.iter().map(|&i| y[i] - yhat[i])),
        val_rms_bias_only: rms(val.iter().map(|&i| y[i] - train_mean)),
        train_fit_percent: fit(train),
        val_fit_percent: fit(val),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nav_sensors::sim::{Scenario, simulate};

    /// The row-block solve of a large record's final weights gives the
    /// weights the whole-matrix QR gives on the same rows and centres, with
    /// and without effects (partialled out: θ kept, the network refitted).
    #[test]
    fn streamed_final_weights_equal_the_whole_matrix_solve() {
        let sim = simulate(&Scenario {
            duration_s: 60.0,
            ..Scenario::default()
        })
        .unwrap();
        for effects in [vec![], vec!["g_I".parse().unwrap()]] {
            let options = FitOptions {
                effects,
                settings: FitSettings {
                    max_centres: 12,
                    width_scales: vec![1.0],
                    ..FitSettings::default()
                },
                ..FitOptions::default()
            };
            let prepared =
                Prepared::new(&sim.record, Some(&sim.calibration), &options.preprocess).unwrap();
            let (train, val) = split_rows(&prepared, options.split).unwrap();
            let model = fit_rows(&prepared, &options.recipe(), &train, &val, &|_| {}).unwrap();
            for m in model.channels() {
                let f = ChannelFit {
                    channel: m.channel(),
                    effects: m.effects().to_vec(),
                    z: prepared.effect_matrix(m.channel(), m.effects()).unwrap(),
                    width: m.width(),
                    model: m.rbf().clone(),
                    coefficients: m.coefficients().map(<[_]>::to_vec).unwrap_or_default(),
                };
                let x = prepared.window_view();
                let f = refit_weights(&prepared, x, &train, f, &options.settings).unwrap();
                let again = scored(&prepared, x, &train, &val, f).unwrap();
                let (a, b) = (m.rbf(), again.rbf());
                assert_eq!(a.centres(), b.centres());
                assert_eq!(a.linear_coefficients(), b.linear_coefficients());
                let scale = a.weights().norm_max();
                assert!(
                    (a.weights() - b.weights()).norm_max() <= 1e-7 * scale,
                    "{}: weights {:?} against {:?}",
                    m.channel(),
                    a.weights(),
                    b.weights()
                );
                let (sa, sb) = (m.scores(), again.scores());
                assert!((sa.val_rms - sb.val_rms).abs() <= 1e-9 * sa.val_rms);
                assert_eq!(
                    (sa.n_train, sa.n_val),
                    (sb.n_train, sb.n_val),
                    "{}",
                    m.channel()
                );
            }
        }
    }
}
