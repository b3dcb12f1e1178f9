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

use super::engine::HighRate;
use super::output::Components;
use super::predictable;
use super::scenario::Scenario;

pub(crate) use stats::{correlation, std_dev};

/// What the ground calibration's errors leave on a channel: the terms
/// `counted` (calibrated, not hidden), at the regressors the record shows.
/// Any model: `c`, `cal` and `counted` in its term order.
fn calibration_error(pred: &[Vec<f64>], c: &[f64], cal: &[f64], counted: &[bool]) -> Vec<f64> {
    pred.iter()
        .map(|pred| {
            let mut v = 0.0;
            for k in 0..c.len() {
                if counted[k] {
                    v += (c[k] - cal[k]) * pred[k];
                }
            }
            v
        })
        .collect()
}

/// The level-only expectation of format version 1: each term's `d_k`
/// fitted through the origin on g² (`k_k`), their sum over the record and
/// the `k_k` worth writing (|k_k| ≥ 1e-4 deg/h at full level) as (term
/// index, k_k). Any model.
fn level_only_expectation(
    d: &[Vec<f64>],
    g2: &[f64],
    n_out: usize,
) -> (Vec<f64>, Vec<(usize, f64)>) {
    let g2_energy: f64 = g2.iter().map(|v| v * v).sum();
    let mut expected = vec![0.0; n_out];
    let mut at_full = Vec::new();
    for (k, dk) in d.iter().enumerate() {
        let kk = if g2_energy > 0.0 {
            dk.iter().zip(g2).map(|(a, b)| a * b).sum::<f64>() / g2_energy
        } else {
            0.0
        };
        if kk.abs() >= 1e-4 {
            at_full.push((k, kk));
        }
        for (e, g) in expected.iter_mut().zip(g2) {
            *e += kk * g;
        }
    }
    (expected, at_full)
}

/// Candidates (term indices, in the order given) whose regressors move
/// together on this record, as (i, j, correlation) with i before j
/// (gravity-only constants excluded: a constant regressor has no
/// correlation). Any model.
fn collinear_pairs(pred: &[Vec<f64>], candidates: &[usize]) -> Vec<(usize, usize, f64)> {
    let series: Vec<Vec<f64>> = candidates
        .iter()
        .map(|&k| pred.iter().map(|p| p[k]).collect())
        .collect();
    let mut collinear = Vec::new();
    for i in 0..candidates.len() {
        for j in i + 1..candidates.len() {
            let r = correlation(&series[i], &series[j]);
            if r.abs() > 0.95 {
                collinear.push((candidates[i], candidates[j], r));
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

/// What a channel's truth adds to its budget (any model): the level-only
/// expectation (series, the floor without it, `k_k` at full level as
/// (term index, value)), what the calibration errors leave, and the
/// candidate pairs nearly collinear on the record.
pub(crate) struct Extras {
    pub expected: Vec<f64>,
    pub level_only_floor_deg_h: f64,
    pub at_full: Vec<(usize, f64)>,
    pub calibration_error_deg_h: f64,
    pub collinear: Vec<(usize, usize, f64)>,
}

impl ChannelBudget {
    /// The [`Extras`] of this budget: `g2` the level, `c` and `cal` the
    /// true and calibrated coefficients, `counted` the terms the
    /// calibration error counts (calibrated, not hidden), `candidates` the
    /// terms checked for collinearity, in order.
    pub(crate) fn extras(
        &self,
        g2: &[f64],
        c: &[f64],
        cal: &[f64],
        counted: &[bool],
        candidates: &[usize],
    ) -> Extras {
        let n_out = self.noise.len();
        let (expected, at_full) = level_only_expectation(&self.d, g2, n_out);
        let level_only_floor: Vec<f64> = (0..n_out)
            .map(|n| self.noise[n] + self.motion[n] + self.unmodelled[n] - expected[n])
            .collect();
        Extras {
            level_only_floor_deg_h: std_dev(&level_only_floor),
            expected,
            at_full,
            calibration_error_deg_h: std_dev(&calibration_error(&self.pred, c, cal, counted)),
            collinear: collinear_pairs(&self.pred, candidates),
        }
    }

    /// Pushes the channel's components `{name}_noise`, `_motion`,
    /// `_unmodelled`, `_expected`, `_predictable`, `_floor` (in that
    /// order) and gives back the floor and after-compensation series.
    pub(crate) fn push_components(
        self,
        components: &mut Components,
        name: &str,
        expected: Vec<f64>,
    ) -> (Vec<f64>, Vec<f64>) {
        components.push(&format!("{name}_noise"), self.noise);
        components.push(&format!("{name}_motion"), self.motion);
        components.push(&format!("{name}_unmodelled"), self.unmodelled);
        components.push(&format!("{name}_expected"), expected);
        components.push(&format!("{name}_predictable"), self.predicted);
        components.push(&format!("{name}_floor"), self.floor.clone());
        (self.floor, self.after)
    }
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
