//! The vibration-test simulator: physics and error models at the internal
//! rate, outputs as the instruments deliver them.
//!
//! At every internal sample (default 4 kHz) the specific force is gravity
//! plus the shaker's vibration and the rate is Earth rate plus the fixture's
//! rocking, both in the cluster frame; a scenario with a motion profile
//! (flight) turns gravity and Earth rate with the unit's attitude and adds
//! its manoeuvre accelerations and body rates. Each gyro channel resolves them into
//! its (I, O, S) frame and evaluates every DTG term's regressor there, the
//! 2N detector runs on the rate about I, and each accelerometer applies its
//! static error model and then its servo loop. Over each output interval
//! (default 20 ms) the simulator averages: a gyro output is its incremental
//! angle over the interval divided by the interval (deg/h), an accelerometer
//! output is its velocity increment over the interval divided by the
//! interval (g). So a g² term's 50-Hz output is `D·mean(a_I·a_S)` over the
//! interval, which is not `D·mean(a_I)·mean(a_S)`: vibration rectifies as it
//! physically does. Temperature is slow and enters at the output rate, as do
//! the white and Gauss–Markov noises (averaging white noise over an interval
//! gives white noise of the averaged variance).

use nalgebra::Vector3;
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;

use super::error::SimError;
use super::motion::MotionProfile;
use super::scenario::Scenario;
use crate::accel::AccelCoefficients;
use crate::dtg::{DtgCoefficients, DtgInput, DtgTerm, Rect2nDetector};
use crate::geometry::{Axis, DtgAxes};
use crate::rate::{RateCoefficients, RateInput, RateTerm};
use crate::vibration::VibrationHistory;

/// Independent random streams derived from the scenario's seed, one per
/// purpose, so that changing (say) the noise level does not change the
/// vibration realisation.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Stream {
    Vibration = 0,
    GyroNoise = 1,
    AccelNoise = 2,
    TemperatureNoise = 3,
    Calibration = 4,
    /// The rate random walk has its own stream: adding it leaves every
    /// other draw, hence the ARW and bias-instability realisation, as it was.
    GyroRateWalk = 5,
}

pub(crate) fn stream(seed: u64, which: Stream) -> Xoshiro256PlusPlus {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    for _ in 0..which as usize {
        rng.jump(); // 2^128 steps apart: non-overlapping streams
    }
    rng
}

/// One gyro channel's physics at the internal rate: its model, axes and
/// true coefficients (and a DTG's 2N detector).
pub(crate) enum GyroPhysics {
    /// One input axis of a two-axis DTG (IEEE Std 813 terms in its I, O, S).
    Dtg {
        axes: DtgAxes,
        coefficients: DtgCoefficients,
        detector: Rect2nDetector,
    },
    /// A single-axis rate gyro (IEEE Std 952 / 1431 terms in the unit frame).
    Rate {
        input: Vector3<f64>,
        coefficients: RateCoefficients,
    },
}

impl GyroPhysics {
    /// A DTG channel with the scenario's spin and 2N resonance.
    pub(crate) fn dtg(s: &Scenario, axes: DtgAxes, coefficients: DtgCoefficients) -> Self {
        GyroPhysics::Dtg {
            axes,
            coefficients,
            detector: Rect2nDetector::new(s.gyros.spin_hz, s.gyros.rect_2n_q, s.internal_rate_hz),
        }
    }

    /// Number of terms (regressors) of the model.
    pub(crate) fn terms(&self) -> usize {
        match self {
            GyroPhysics::Dtg { .. } => DtgTerm::ALL.len(),
            GyroPhysics::Rate { .. } => RateTerm::ALL.len(),
        }
    }

    /// Position of the temperature term among the regressors (temperature
    /// enters at the output rate, not in the high-rate loop).
    pub(crate) fn temp_index(&self) -> usize {
        match self {
            GyroPhysics::Dtg { .. } => DtgTerm::Temp.index(),
            GyroPhysics::Rate { .. } => RateTerm::Temp.index(),
        }
    }

    /// The true coefficients in term order.
    pub(crate) fn coefficients(&self) -> Vec<f64> {
        match self {
            GyroPhysics::Dtg { coefficients, .. } => coefficients.to_array().to_vec(),
            GyroPhysics::Rate { coefficients, .. } => coefficients.to_array().to_vec(),
        }
    }

    /// One internal sample: adds the regressors to `acc` and returns the
    /// true rate about the input axis (deg/h) and the scale-factor
    /// nonlinearity's drift (deg/h).
    #[inline]
    fn step(&mut self, w: &Vector3<f64>, f: &Vector3<f64>, acc: &mut [f64]) -> (f64, f64) {
        match self {
            GyroPhysics::Dtg {
                axes,
                coefficients,
                detector,
            } => {
                let rate = axes.resolve(w);
                let x = DtgInput {
                    rate_deg_h: rate,
                    specific_force_g: axes.resolve(f),
                    temperature_delta_c: 0.0,
                    rate_2n_mean_square_deg2_s2: detector.step(rate.i / 3600.0),
                    // An instant: no interval to average over.
                    specific_force_cov_g2: [0.0; 6],
                };
                for (a, v) in acc.iter_mut().zip(DtgTerm::regressors(&x)) {
                    *a += v;
                }
                (rate.i, coefficients.nonlinearity_deg_h(rate.i))
            }
            GyroPhysics::Rate { input, .. } => {
                let x = RateInput::sensed(input, w, f);
                for (a, v) in acc.iter_mut().zip(RateTerm::regressors(&x)) {
                    *a += v;
                }
                (x.rate_i_deg_h, 0.0)
            }
        }
    }
}

/// One accelerometer's physics: the pendulous servo model (IEEE Std 1293)
/// when it lies on a unit axis and the scenario gives that axis's
/// coefficients, else an error-free accelerometer along its input axis
/// (noise and servo loop still apply).
#[derive(Debug, Clone, Copy)]
pub(crate) enum AccelPhysics {
    Modelled {
        axis: Axis,
        coefficients: AccelCoefficients,
    },
    Ideal {
        input: Vector3<f64>,
    },
}

impl AccelPhysics {
    #[inline]
    fn output_g(&self, f: &Vector3<f64>) -> f64 {
        match self {
            AccelPhysics::Modelled { axis, coefficients } => coefficients.output_g(*axis, f),
            AccelPhysics::Ideal { input } => input.dot(f),
        }
    }
}

/// Per-interval means from the high-rate loop.
pub(crate) struct HighRate {
    /// Regressors per term of each channel (`temp` zero until the output
    /// rate sets it), `[channel][n·terms + k]`.
    regressors: Vec<Vec<f64>>,
    /// Terms per channel.
    terms: Vec<usize>,
    /// Mean true rate about each channel's input axis, deg/h, `[channel][n]`.
    pub rate_i_deg_h: Vec<Vec<f64>>,
    /// Mean scale-factor-nonlinearity drift per channel (true coefficients),
    /// deg/h, `[channel][n]`.
    pub nonlinearity_deg_h: Vec<Vec<f64>>,
    /// Mean accelerometer output (error model, then servo loop), g,
    /// `[accelerometer][n]`.
    pub accel_output_g: Vec<Vec<f64>>,
    /// Mean of the true specific force through the servo loop alone (an
    /// error-free accelerometer of the same bandwidth) along the unit axes, g.
    pub accel_ideal_g: Vec<[f64; 3]>,
    /// Mean squared level gain of the schedule.
    pub level_squared: Vec<f64>,
    /// Moments of the true specific force in the cluster frame over the
    /// interval, g and g²: mean f_x, f_y, f_z, then mean f_x², f_y², f_z²,
    /// f_x·f_y, f_x·f_z, f_y·f_z (every channel's g and g² regressor means
    /// are linear combinations of these).
    pub force_moments: Vec<[f64; 9]>,
    /// With a motion profile only: the interval means of the specific
    /// force without the vibration (gravity and manoeuvres), g, and of the
    /// angular rate without the rocking (Earth and body rates), deg/h, in
    /// the cluster frame. `None` at rest, where the site's constants hold.
    pub motion_means: Option<MotionMeans>,
}

impl HighRate {
    /// Channel `ch`'s mean regressors over interval `n`.
    #[inline]
    pub fn regs(&self, ch: usize, n: usize) -> &[f64] {
        let k = self.terms[ch];
        &self.regressors[ch][n * k..(n + 1) * k]
    }

    #[inline]
    fn regs_mut(&mut self, ch: usize, n: usize) -> &mut [f64] {
        let k = self.terms[ch];
        &mut self.regressors[ch][n * k..(n + 1) * k]
    }
}

/// Interval means of a moving unit's specific force (g) and rate (deg/h).
pub(crate) struct MotionMeans {
    pub force_g: Vec<[f64; 3]>,
    pub rate_deg_h: Vec<[f64; 3]>,
}

/// The specific force (g) and angular rate (deg/h) of the unit itself,
/// before the shaker's vibration and rocking, at each internal sample: the
/// site's constants at rest, the motion profile's values in motion.
struct Kinematics<'a> {
    gravity: Vector3<f64>,
    earth: Vector3<f64>,
    motion: Option<&'a MotionProfile>,
    internal_rate_hz: f64,
}

impl Kinematics<'_> {
    fn at(&self, idx: usize) -> (Vector3<f64>, Vector3<f64>) {
        match self.motion {
            None => (self.gravity, self.earth),
            // Sample idx ends at (idx + 1)/fs, as output n ends at (n + 1)·dt.
            Some(m) => m.at(
                (idx + 1) as f64 / self.internal_rate_hz,
                &self.gravity,
                &self.earth,
            ),
        }
    }
}

fn high_rate(
    s: &Scenario,
    vib: &VibrationHistory,
    kin: &Kinematics,
    gyros: &mut [GyroPhysics],
    accels: &[AccelPhysics],
) -> HighRate {
    let fs = s.internal_rate_hz;
    let m = s.oversampling();
    let n_out = s.output_samples();
    let mut servo_out: Vec<_> = accels.iter().map(|_| s.accels.servo.filter(fs)).collect();
    let mut servo_ideal = Axis::ALL.map(|_| s.accels.servo.filter(fs));
    let (gravity, _) = kin.at(0);
    let gravity = &gravity;
    // Start settled on the stationary unit's outputs (no start-up transient).
    for (servo, a) in servo_out.iter_mut().zip(accels) {
        servo.settle(a.output_g(gravity));
    }
    for a in Axis::ALL {
        servo_ideal[a.index()].settle(gravity[a.index()]);
    }
    let inv_m = 1.0 / m as f64;
    let terms: Vec<usize> = gyros.iter().map(GyroPhysics::terms).collect();
    let mut out = HighRate {
        regressors: terms
            .iter()
            .map(|k| Vec::with_capacity(n_out * k))
            .collect(),
        terms: terms.clone(),
        rate_i_deg_h: gyros.iter().map(|_| Vec::with_capacity(n_out)).collect(),
        nonlinearity_deg_h: gyros.iter().map(|_| Vec::with_capacity(n_out)).collect(),
        accel_output_g: accels.iter().map(|_| Vec::with_capacity(n_out)).collect(),
        accel_ideal_g: Vec::with_capacity(n_out),
        level_squared: Vec::with_capacity(n_out),
        force_moments: Vec::with_capacity(n_out),
        motion_means: kin.motion.map(|_| MotionMeans {
            force_g: Vec::with_capacity(n_out),
            rate_deg_h: Vec::with_capacity(n_out),
        }),
    };
    let mut reg: Vec<Vec<f64>> = terms.iter().map(|&k| vec![0.0; k]).collect();
    let mut rate_i = vec![0.0; gyros.len()];
    let mut nl = vec![0.0; gyros.len()];
    let mut acc_out = vec![0.0; accels.len()];
    for j in 0..n_out {
        let mut static_f = Vector3::zeros();
        let mut static_w = Vector3::zeros();
        for r in &mut reg {
            r.fill(0.0);
        }
        rate_i.fill(0.0);
        nl.fill(0.0);
        acc_out.fill(0.0);
        let mut acc_ideal = [0.0; 3];
        let mut g2 = 0.0;
        let mut moments = [0.0; 9];
        for idx in j * m..(j + 1) * m {
            let (gravity, earth) = kin.at(idx);
            if kin.motion.is_some() {
                static_f += gravity;
                static_w += earth;
            }
            let f = Vector3::new(
                gravity.x + vib.accel_g[0][idx],
                gravity.y + vib.accel_g[1][idx],
                gravity.z + vib.accel_g[2][idx],
            );
            let w = Vector3::new(
                earth.x + 3600.0 * vib.angular_rate_deg_s[0][idx],
                earth.y + 3600.0 * vib.angular_rate_deg_s[1][idx],
                earth.z + 3600.0 * vib.angular_rate_deg_s[2][idx],
            );
            for (acc, v) in moments
                .iter_mut()
                .zip(super::predictable::elementary_moments(&f))
            {
                *acc += v;
            }
            for (k, a) in accels.iter().enumerate() {
                acc_out[k] += servo_out[k].step(a.output_g(&f));
            }
            for (k, servo) in servo_ideal.iter_mut().enumerate() {
                acc_ideal[k] += servo.step(f[k]);
            }
            for (ch, gyro) in gyros.iter_mut().enumerate() {
                let (r, n) = gyro.step(&w, &f, &mut reg[ch]);
                rate_i[ch] += r;
                nl[ch] += n;
            }
            g2 += vib.envelope[idx] * vib.envelope[idx];
        }
        for (ch, r) in reg.iter().enumerate() {
            out.regressors[ch].extend(r.iter().map(|v| v * inv_m));
            out.rate_i_deg_h[ch].push(rate_i[ch] * inv_m);
            out.nonlinearity_deg_h[ch].push(nl[ch] * inv_m);
        }
        for (k, v) in acc_out.iter().enumerate() {
            out.accel_output_g[k].push(v * inv_m);
        }
        out.accel_ideal_g.push(acc_ideal.map(|v| v * inv_m));
        out.level_squared.push(g2 * inv_m);
        out.force_moments.push(moments.map(|v| v * inv_m));
        if let Some(mm) = &mut out.motion_means {
            mm.force_g.push((static_f * inv_m).into());
            mm.rate_deg_h.push((static_w * inv_m).into());
        }
    }
    out
}

/// Sensor noise per channel and output sample (`[channel][n]`): white (ARW)
/// plus a first-order Gauss–Markov bias, deg/h, plus the rate random walk.
fn gyro_noise(
    s: &Scenario,
    channels: usize,
    n_out: usize,
    rng: &mut Xoshiro256PlusPlus,
) -> Vec<Vec<f64>> {
    let mut noise = white_and_markov(s, channels, n_out, rng);
    add_rate_random_walk(s, &mut noise);
    noise
}

/// Adds the rate random walk's interval means, deg/h: over each interval
/// the walk moves by W = q·z₁ (q = K·√dt) and its mean over the interval is
/// b + W/2 + q·z₂/√12 (a Brownian bridge's mean has variance dt/12 and is
/// independent of the end point), so the Allan deviation is K·√(τ/3) at
/// every τ, the shortest included. Nothing is drawn when K is zero.
fn add_rate_random_walk(s: &Scenario, noise: &mut [Vec<f64>]) {
    let q = s.gyros.noise.rrw_step_deg_h(1.0 / s.output_rate_hz);
    if q == 0.0 {
        return;
    }
    let mut rng = stream(s.seed, Stream::GyroRateWalk);
    let mut walk = vec![0.0; noise.len()];
    let n_out = noise.first().map_or(0, Vec::len);
    // Sample by sample, channel by channel: the draw order of every unit
    // (n indexes every channel's series at once).
    #[allow(clippy::needless_range_loop)]
    for n in 0..n_out {
        for (ch, b) in walk.iter_mut().enumerate() {
            let z1: f64 = StandardNormal.sample(&mut rng);
            let z2: f64 = StandardNormal.sample(&mut rng);
            noise[ch][n] += *b + q * (0.5 * z1 + z2 / 12f64.sqrt());
            *b += q * z1;
        }
    }
}

fn white_and_markov(
    s: &Scenario,
    channels: usize,
    n_out: usize,
    rng: &mut Xoshiro256PlusPlus,
) -> Vec<Vec<f64>> {
    let dt = 1.0 / s.output_rate_hz;
    let p = &s.gyros.noise;
    let white = p.white_sigma_deg_h(dt);
    let (phi, drive) = if p.bias_instability_deg_h > 0.0 {
        let phi = (-dt / p.bias_instability_tau_s).exp();
        (phi, p.bias_instability_deg_h * (1.0 - phi * phi).sqrt())
    } else {
        (0.0, 0.0)
    };
    let mut normal = || -> f64 { StandardNormal.sample(rng) };
    // Start the Gauss–Markov state in its stationary distribution.
    let mut bias: Vec<f64> = (0..channels)
        .map(|_| p.bias_instability_deg_h * normal())
        .collect();
    let mut out: Vec<Vec<f64>> = (0..channels).map(|_| Vec::with_capacity(n_out)).collect();
    for _ in 0..n_out {
        for (ch, b) in bias.iter_mut().enumerate() {
            out[ch].push(white * normal() + *b);
            *b = phi * *b + drive * normal();
        }
    }
    out
}

/// What every simulation produces before its calibration and truth: the
/// high-rate means (with the temperature regressor set), the time base, the
/// gyro and accelerometer outputs (`[sensor][n]`, deg/h and g), the sensor
/// noise per channel (quantisation included) and the measured temperature.
pub(crate) struct Run {
    pub hr: HighRate,
    pub t: Vec<f64>,
    pub gyro: Vec<Vec<f64>>,
    pub accel: Vec<Vec<f64>>,
    pub noise: Vec<Vec<f64>>,
    pub temp_meas: Vec<f64>,
}

/// Simulates a validated scenario for any set of gyro and accelerometer
/// physics (the paper's unit or any other).
pub(crate) fn run(
    s: &Scenario,
    mut gyros: Vec<GyroPhysics>,
    accels: &[AccelPhysics],
) -> Result<Run, SimError> {
    let n_out = s.output_samples();
    let m = s.oversampling();
    let dt = 1.0 / s.output_rate_hz;
    let gravity = s.site.gravity_cluster_g().expect("validated orientation");
    let earth = s
        .site
        .earth_rate_cluster_deg_h()
        .expect("validated orientation");

    let vib = s.vibration.generate(
        n_out * m,
        s.internal_rate_hz,
        &mut stream(s.seed, Stream::Vibration),
    )?;
    let kin = Kinematics {
        gravity,
        earth,
        motion: s.motion.as_ref(),
        internal_rate_hz: s.internal_rate_hz,
    };
    let mut hr = high_rate(s, &vib, &kin, &mut gyros, accels);
    drop(vib);

    // Temperature: end-of-interval values for the record, the interval's
    // mean (trapezoid) for the drift.
    let t_end = s.thermal.temperatures(&hr.level_squared, dt);
    let t_mean: Vec<f64> = (0..n_out)
        .map(|n| {
            0.5 * (if n == 0 {
                s.thermal.initial_c
            } else {
                t_end[n - 1]
            } + t_end[n])
        })
        .collect();
    let mut rng_temp = stream(s.seed, Stream::TemperatureNoise);
    let temp_meas: Vec<f64> = t_end
        .iter()
        .map(|t| {
            let e: f64 = StandardNormal.sample(&mut rng_temp);
            t + s.thermal.sensor_noise_c * e
        })
        .collect();

    // Gyros: deterministic model from the interval means, then noise, then
    // optional pulse quantisation of the incremental angle.
    let coefficients: Vec<Vec<f64>> = gyros.iter().map(GyroPhysics::coefficients).collect();
    let temp_index: Vec<usize> = gyros.iter().map(GyroPhysics::temp_index).collect();
    let channels = gyros.len();
    let mut noise = gyro_noise(s, channels, n_out, &mut stream(s.seed, Stream::GyroNoise));
    let mut gyro: Vec<Vec<f64>> = (0..channels).map(|_| Vec::with_capacity(n_out)).collect();
    let mut remainder_deg = vec![0.0; channels];
    for n in 0..n_out {
        for ch in 0..channels {
            let r = hr.regs_mut(ch, n);
            r[temp_index[ch]] = t_mean[n] - s.thermal.reference_c;
            let drift: f64 = coefficients[ch]
                .iter()
                .zip(r.iter())
                .map(|(c, r)| c * r)
                .sum();
            let exact =
                hr.rate_i_deg_h[ch][n] + drift + hr.nonlinearity_deg_h[ch][n] + noise[ch][n];
            let out = match s.gyros.pulse_arcsec {
                None => exact,
                Some(q_arcsec) => {
                    let q = q_arcsec / 3600.0;
                    let angle = remainder_deg[ch] + exact * dt / 3600.0;
                    let pulses = (angle / q).floor();
                    remainder_deg[ch] = angle - pulses * q;
                    let out = pulses * q * 3600.0 / dt;
                    noise[ch][n] += out - exact;
                    out
                }
            };
            gyro[ch].push(out);
        }
    }

    let mut rng_accel = stream(s.seed, Stream::AccelNoise);
    let accel_sigma = s.accels.noise.averaged_sigma_g(dt);
    let accel: Vec<Vec<f64>> = hr
        .accel_output_g
        .iter()
        .map(|a| {
            a.iter()
                .map(|a| {
                    let e: f64 = StandardNormal.sample(&mut rng_accel);
                    a + accel_sigma * e
                })
                .collect()
        })
        .collect();

    let t: Vec<f64> = (1..=n_out).map(|n| n as f64 * dt).collect();
    Ok(Run {
        hr,
        t,
        gyro,
        accel,
        noise,
        temp_meas,
    })
}
