//! The error budget of a simulated record: what a model of the 50-Hz record
//! can and cannot predict, per channel, and the noise floor.
//!
//! For every term k of channel c with true coefficient c_k, the record holds
//! `c_k · mean(r_k)` over each interval (the high-rate truth), while a model
//! of the record can at best form `c_k · r_k(x̄)`: the regressor evaluated on
//! what the record shows — the interval's accelerations through an
//! error-free accelerometer of the same bandwidth, Earth rate as the
//! reference rate, the `temp` column. The difference
//!
//! ```text
//! d_k[n] = c_k · (mean(r_k)[n] − r_k(x̄[n]))
//! ```
//!
//! is the unmodelled part (for a g² term, `c_k` times the within-interval
//! covariance of the vibration: the rectification). What a model of the
//! record can predict of it is its conditional expectation given the
//! vibration level g² **and** the observed 50-Hz accelerations: for
//! band-limited vibration the neighbouring samples reveal the motion's
//! local slope and curvature, hence much of the within-interval covariance.
//! [`super::predictable`] estimates it by least squares on local linear
//! and quadratic features of x̄ (lags −3..=3); the noise floor is the rms
//! about the mean of
//!
//! ```text
//! floor[n] = noise[n] + motion[n] + Σ_k d_k[n] − Ê[Σ_k d_k | g², x̄][n]
//! ```
//!
//! with `noise` the sensor noise (ARW, bias instability, quantisation) and
//! `motion` the true angular motion (rocking) about I averaged per interval.
//! The level-only expectation of format version 1, `k_k · g²[n]` (g the
//! schedule's amplitude gain, `k_k` fitted through the origin), is kept as
//! `{ch}_expected`, `k_k` at full level and `level_only_noise_floor_deg_h`.

use std::collections::BTreeMap;

use super::engine::HighRate;
use super::output::Components;
use super::predictable;
use super::scenario::Scenario;
use super::truth::{ChannelTruth, Collinear, HiddenTruth, Truth};
use crate::dtg::{DtgCoefficients, DtgInput, DtgTerm};
use crate::files::calibration::Calibration;
use crate::geometry::{Channel, ChannelFrame, Ios, Residue};

/// The candidate pairs checked for collinearity: the specific-force terms.
const CANDIDATES: [DtgTerm; 9] = DtgTerm::SPECIFIC_FORCE;

pub(crate) use stats::{correlation, rms, std_dev};

/// Computes the truth file and the component series.
#[allow(clippy::too_many_arguments)]
pub(crate) fn budget(
    s: &Scenario,
    hr: &HighRate,
    noise: &[Vec<f64>],
    temp_meas: &[f64],
    calibration: &Calibration,
    t: &[f64],
) -> (Truth, Components) {
    let n_out = t.len();
    let Reference {
        earth,
        gravity,
        static_rate,
        elementary,
    } = Reference::of(s, hr);
    let static_rate = |n: usize| static_rate[n];
    let g2 = &hr.level_squared;
    let mut components = Components::new(t.to_vec());
    components.push("level_squared", g2.clone());
    let mut channels = BTreeMap::new();
    let mut hidden = Vec::new();
    let mut floor_series: [Vec<f64>; 6] = Default::default();
    let mut after_true: [Vec<f64>; 6] = Default::default();
    for (ch, frame) in ChannelFrame::all().iter().enumerate() {
        let channel = frame.channel;
        let truth = s.gyro(channel);
        let c = truth.to_array();
        let cal = calibration.gyro(channel).to_array();
        let hidden_here = s.hidden_terms(channel);
        let ChannelBudget {
            d,
            pred: pred_all,
            unmodelled,
            motion,
            predicted,
            floor,
            after,
            noise: noise_ch,
        } = channel_budget(
            hr,
            ch,
            &c,
            &noise[ch],
            &elementary,
            &predictable::weights(&frame.input, &frame.other, &frame.spin, &c),
            |n| {
                at_record(
                    frame,
                    &truth,
                    static_rate(n),
                    hr.accel_ideal_g[n],
                    temp_meas[n] - s.thermal.reference_c,
                )
            },
        );
        let cal_err = calibration_error(&pred_all, &c, &cal, &hidden_here);
        let (expected, at_full) = level_only_expectation(&d, g2, n_out);
        let level_only_floor: Vec<f64> = (0..n_out)
            .map(|n| noise_ch[n] + motion[n] + unmodelled[n] - expected[n])
            .collect();
        let noise_floor = std_dev(&floor);
        for &term in &hidden_here {
            let (truth, visible) = hidden_truth(channel, term, &c, &pred_all, noise_floor);
            hidden.push(truth);
            components.push(&format!("hidden_{channel}_{term}"), visible);
        }
        let collinear = collinear(&pred_all);
        channels.insert(
            channel,
            ChannelTruth {
                coefficients: truth,
                noise_floor_deg_h: noise_floor,
                level_only_noise_floor_deg_h: std_dev(&level_only_floor),
                noise_rms_deg_h: std_dev(&noise_ch),
                motion_rms_deg_h: rms(&motion),
                unmodelled_rms_deg_h: rms(&unmodelled),
                rectification_expected_rms_deg_h: rms(&expected),
                predictable_rms_deg_h: rms(&predicted),
                rectification_at_full_level_deg_h: at_full,
                calibration_error_rms_deg_h: std_dev(&cal_err),
                after_true_compensation_rms_deg_h: rms(&after),
                collinear,
            },
        );
        components.push(&format!("{channel}_noise"), noise_ch);
        components.push(&format!("{channel}_motion"), motion);
        components.push(&format!("{channel}_unmodelled"), unmodelled);
        components.push(&format!("{channel}_expected"), expected);
        components.push(&format!("{channel}_predictable"), predicted);
        components.push(&format!("{channel}_floor"), floor.clone());
        floor_series[ch] = floor;
        after_true[ch] = after;
    }
    let combine = |series: &[Vec<f64>; 6], r: Residue| residue_series(series, r, n_out);
    let residue_noise_floor_deg_h = Residue::ALL
        .iter()
        .map(|&r| (r, std_dev(&combine(&floor_series, r))))
        .collect();
    let residue_after_true_compensation_rms_deg_h = Residue::ALL
        .iter()
        .map(|&r| (r, rms(&combine(&after_true, r))))
        .collect();
    let truth = Truth {
        format_version: Truth::FORMAT_VERSION,
        scenario: s.clone(),
        earth_rate_cluster_deg_h: [earth.x, earth.y, earth.z],
        gravity_cluster_g: [gravity.x, gravity.y, gravity.z],
        hidden,
        channels,
        residue_noise_floor_deg_h,
        residue_after_true_compensation_rms_deg_h,
    };
    (truth, components)
}

/// The regressors of a paper channel at what the record shows (the product
/// of interval means: `d_k` is defined against it), the rate about I a
/// model takes as the reference, and the nonlinearity's drift there.
fn at_record(
    frame: &ChannelFrame,
    truth: &DtgCoefficients,
    static_rate: nalgebra::Vector3<f64>,
    accel_g: [f64; 3],
    temperature_delta_c: f64,
) -> (Vec<f64>, f64, f64) {
    let e: Ios = frame.resolve(&static_rate);
    let x = DtgInput {
        rate_deg_h: e,
        specific_force_g: frame
            .resolve(&nalgebra::Vector3::new(accel_g[0], accel_g[1], accel_g[2])),
        temperature_delta_c,
        rate_2n_mean_square_deg2_s2: 0.0,
        specific_force_cov_g2: [0.0; 6],
    };
    (
        DtgTerm::regressors(&x).to_vec(),
        e.i,
        truth.nonlinearity_deg_h(e.i),
    )
}

/// A hidden term's truth: what it adds to the record as a model of the
/// record sees it (`c_k · r_k(x̄)`, also written as a component), its rms
/// and its ratio to the channel's noise floor.
fn hidden_truth(
    channel: Channel,
    term: DtgTerm,
    c: &[f64],
    pred: &[Vec<f64>],
    noise_floor: f64,
) -> (HiddenTruth, Vec<f64>) {
    let k = term.index();
    let visible: Vec<f64> = pred.iter().map(|p| c[k] * p[k]).collect();
    let rms_deg_h = std_dev(&visible);
    let truth = HiddenTruth {
        channel,
        term,
        coefficient: c[k],
        unit: term.unit().to_string(),
        description: term.ieee_name().to_string(),
        rms_deg_h,
        ratio_to_noise_floor: rms_deg_h / noise_floor,
    };
    (truth, visible)
}

/// A residue (eq. 6) of six channel series.
fn residue_series(series: &[Vec<f64>; 6], r: Residue, n_out: usize) -> Vec<f64> {
    let w = r.coefficients();
    (0..n_out)
        .map(|n| (0..6).map(|k| w[k] * series[k][n]).sum())
        .collect()
}

/// What the ground calibration's errors leave on a channel: the calibrated
/// terms, hidden ones excepted, at the regressors the record shows.
fn calibration_error(pred: &[Vec<f64>], c: &[f64], cal: &[f64], hidden: &[DtgTerm]) -> Vec<f64> {
    pred.iter()
        .map(|pred| {
            let mut v = 0.0;
            for k in 0..18 {
                let term = DtgTerm::ALL[k];
                if term.is_calibrated() && !hidden.contains(&term) {
                    v += (c[k] - cal[k]) * pred[k];
                }
            }
            v
        })
        .collect()
}

/// The level-only expectation of format version 1: each term's `d_k`
/// fitted through the origin on g² (`k_k`), their sum over the record and
/// the `k_k` worth writing (|k_k| ≥ 1e-4 deg/h at full level).
fn level_only_expectation(
    d: &[Vec<f64>],
    g2: &[f64],
    n_out: usize,
) -> (Vec<f64>, BTreeMap<DtgTerm, f64>) {
    let g2_energy: f64 = g2.iter().map(|v| v * v).sum();
    let mut expected = vec![0.0; n_out];
    let mut at_full = BTreeMap::new();
    for (k, dk) in d.iter().enumerate() {
        let kk = if g2_energy > 0.0 {
            dk.iter().zip(g2).map(|(a, b)| a * b).sum::<f64>() / g2_energy
        } else {
            0.0
        };
        if kk.abs() >= 1e-4 {
            at_full.insert(DtgTerm::ALL[k], kk);
        }
        for (e, g) in expected.iter_mut().zip(g2) {
            *e += kk * g;
        }
    }
    (expected, at_full)
}

/// Candidates that move together on this record (gravity-only constants
/// excluded: a constant regressor has no correlation).
fn collinear(pred: &[Vec<f64>]) -> Vec<Collinear> {
    let series: Vec<Vec<f64>> = CANDIDATES
        .iter()
        .map(|t| pred.iter().map(|p| p[t.index()]).collect())
        .collect();
    let mut collinear = Vec::new();
    for i in 0..CANDIDATES.len() {
        for j in i + 1..CANDIDATES.len() {
            let r = correlation(&series[i], &series[j]);
            if r.abs() > 0.95 {
                collinear.push(Collinear {
                    a: CANDIDATES[i],
                    b: CANDIDATES[j],
                    correlation: r,
                });
            }
        }
    }
    collinear
}

/// One channel's budget series: per term the unmodelled part `d_k`, the
/// regressors at what the record shows (`pred[n][k]`), their sum with the
/// nonlinearity's mismatch (`unmodelled`), the rocking about I (`motion`),
/// the part a model given the level and the 50-Hz accelerations predicts,
/// the floor series and what true-coefficient compensation leaves.
pub(crate) struct ChannelBudget {
    pub d: Vec<Vec<f64>>,
    pub pred: Vec<Vec<f64>>,
    pub unmodelled: Vec<f64>,
    pub motion: Vec<f64>,
    pub predicted: Vec<f64>,
    pub floor: Vec<f64>,
    pub after: Vec<f64>,
    pub noise: Vec<f64>,
}

/// The budget of channel `ch` with true coefficients `c` (term order),
/// g/g² weights `w` on the elementary series, and `at_record(n)` giving the
/// regressors at what the record shows, the rate about I a model would
/// take as the reference, and the nonlinearity's drift there. Any model,
/// any unit: the paper's DTG channels and a unit's DTG or rate channels
/// share it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn channel_budget(
    hr: &HighRate,
    ch: usize,
    c: &[f64],
    noise: &[f64],
    elementary: &predictable::Elementary,
    w: &[f64; 9],
    at_record: impl Fn(usize) -> (Vec<f64>, f64, f64),
) -> ChannelBudget {
    let n_out = noise.len();
    let g2 = &hr.level_squared;
    let mut d = vec![vec![0.0; n_out]; c.len()];
    let mut pred_all = Vec::with_capacity(n_out);
    let mut unmodelled = vec![0.0; n_out];
    let mut motion = vec![0.0; n_out];
    for n in 0..n_out {
        let (pred, rate_i, nl) = at_record(n);
        let regs = hr.regs(ch, n);
        for k in 0..c.len() {
            d[k][n] = c[k] * (regs[k] - pred[k]);
        }
        pred_all.push(pred);
        unmodelled[n] = d.iter().map(|dk| dk[n]).sum::<f64>() + hr.nonlinearity_deg_h[ch][n] - nl;
        motion[n] = hr.rate_i_deg_h[ch][n] - rate_i;
    }
    // What a model given the level and the 50-Hz accelerations can
    // predict: the g and g² terms through the elementary series, the
    // rest (temperature lag, rates, 2N, nonlinearity) through the level.
    let rest: Vec<f64> = (0..n_out)
        .map(|n| unmodelled[n] - predictable::combine(w, &elementary.actual, n))
        .collect();
    let rest_predicted = predictable::level_only(g2, &[&rest]).pop().expect("one");
    let predicted: Vec<f64> = (0..n_out)
        .map(|n| predictable::combine(w, &elementary.predicted, n) + rest_predicted[n])
        .collect();
    let floor: Vec<f64> = (0..n_out)
        .map(|n| noise[n] + motion[n] + unmodelled[n] - predicted[n])
        .collect();
    let after: Vec<f64> = (0..n_out)
        .map(|n| noise[n] + motion[n] + unmodelled[n])
        .collect();
    ChannelBudget {
        d,
        pred: pred_all,
        unmodelled,
        motion,
        predicted,
        floor,
        after,
        noise: noise.to_vec(),
    }
}

/// What a model of the record takes as the unit's own motion: Earth rate
/// and gravity at t = 0, and per interval the reference rate (deg/h: the
/// site's Earth rate at rest, the motion's interval mean in flight), with
/// the elementary series of the g and g² terms ([`predictable`]).
pub(crate) struct Reference {
    pub earth: nalgebra::Vector3<f64>,
    pub gravity: nalgebra::Vector3<f64>,
    pub static_rate: Vec<nalgebra::Vector3<f64>>,
    pub elementary: predictable::Elementary,
}

impl Reference {
    pub(crate) fn of(s: &Scenario, hr: &HighRate) -> Self {
        let n_out = hr.level_squared.len();
        let earth = s.site.earth_rate_cluster_deg_h().expect("validated");
        let gravity = s.site.gravity_cluster_g().expect("validated");
        // The unit's own specific force and rate per interval: the site's
        // constants at rest, the motion's interval means in flight.
        let (static_force, static_rate): (Vec<[f64; 3]>, _) = match &hr.motion_means {
            None => (
                vec![[gravity.x, gravity.y, gravity.z]; n_out],
                vec![earth; n_out],
            ),
            Some(m) => (
                m.force_g.clone(),
                m.rate_deg_h
                    .iter()
                    .map(|w| nalgebra::Vector3::from(*w))
                    .collect(),
            ),
        };
        let elementary = predictable::elementary(
            &hr.force_moments,
            &hr.accel_ideal_g,
            &static_force,
            &hr.level_squared,
        );
        Self {
            earth,
            gravity,
            static_rate,
            elementary,
        }
    }
}
