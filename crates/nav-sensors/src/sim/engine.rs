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

use super::budget::budget;
use super::calibrate::ground_calibration;
use super::error::SimError;
use super::motion::MotionProfile;
use super::output::Simulation;
use super::scenario::Scenario;
use crate::dtg::{DtgInput, DtgTerm, Rect2nDetector};
use crate::geometry::{Axis, Channel, ChannelFrame};
use crate::record::Record;
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

/// Per-interval means from the high-rate loop.
pub(crate) struct HighRate {
    /// Mean regressor of every term, per channel (the `temp` slot is zero:
    /// temperature enters at the output rate).
    pub regressors: Vec<[[f64; 18]; 6]>,
    /// Mean true rate about each channel's input axis, deg/h.
    pub rate_i_deg_h: Vec<[f64; 6]>,
    /// Mean scale-factor-nonlinearity drift per channel (true coefficients), deg/h.
    pub nonlinearity_deg_h: Vec<[f64; 6]>,
    /// Mean accelerometer output (error model, then servo loop), g.
    pub accel_output_g: Vec<[f64; 3]>,
    /// Mean of the true specific force through the servo loop alone (an
    /// error-free accelerometer of the same bandwidth), g.
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

fn high_rate(s: &Scenario, vib: &VibrationHistory, kin: &Kinematics) -> HighRate {
    let fs = s.internal_rate_hz;
    let m = s.oversampling();
    let n_out = s.output_samples();
    let frames = ChannelFrame::all();
    let coefficients = Channel::ALL.map(|c| s.gyro(c));
    let accel = Axis::ALL.map(|a| s.accel(a));
    let mut servo_out = Axis::ALL.map(|_| s.accels.servo.filter(fs));
    let mut servo_ideal = servo_out;
    let (gravity, _) = kin.at(0);
    let gravity = &gravity;
    for a in Axis::ALL {
        // Start settled on the stationary unit's outputs (no start-up transient).
        servo_out[a.index()].settle(accel[a.index()].output_g(a, gravity));
        servo_ideal[a.index()].settle(gravity[a.index()]);
    }
    let mut detectors =
        Channel::ALL.map(|_| Rect2nDetector::new(s.gyros.spin_hz, s.gyros.rect_2n_q, fs));
    let inv_m = 1.0 / m as f64;
    let mut out = HighRate {
        regressors: Vec::with_capacity(n_out),
        rate_i_deg_h: Vec::with_capacity(n_out),
        nonlinearity_deg_h: Vec::with_capacity(n_out),
        accel_output_g: Vec::with_capacity(n_out),
        accel_ideal_g: Vec::with_capacity(n_out),
        level_squared: Vec::with_capacity(n_out),
        force_moments: Vec::with_capacity(n_out),
        motion_means: kin.motion.map(|_| MotionMeans {
            force_g: Vec::with_capacity(n_out),
            rate_deg_h: Vec::with_capacity(n_out),
        }),
    };
    for j in 0..n_out {
        let mut static_f = Vector3::zeros();
        let mut static_w = Vector3::zeros();
        let mut reg = [[0.0; 18]; 6];
        let mut rate_i = [0.0; 6];
        let mut nl = [0.0; 6];
        let mut acc_out = [0.0; 3];
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
            for a in Axis::ALL {
                let k = a.index();
                acc_out[k] += servo_out[k].step(accel[k].output_g(a, &f));
                acc_ideal[k] += servo_ideal[k].step(f[k]);
            }
            for (ch, frame) in frames.iter().enumerate() {
                let rate = frame.resolve(&w);
                let x = DtgInput {
                    rate_deg_h: rate,
                    specific_force_g: frame.resolve(&f),
                    temperature_delta_c: 0.0,
                    rate_2n_mean_square_deg2_s2: detectors[ch].step(rate.i / 3600.0),
                    // An instant: no interval to average over.
                    specific_force_cov_g2: [0.0; 6],
                };
                let r = DtgTerm::regressors(&x);
                for (acc, v) in reg[ch].iter_mut().zip(r) {
                    *acc += v;
                }
                rate_i[ch] += rate.i;
                nl[ch] += coefficients[ch].nonlinearity_deg_h(rate.i);
            }
            g2 += vib.envelope[idx] * vib.envelope[idx];
        }
        for row in &mut reg {
            for v in row.iter_mut() {
                *v *= inv_m;
            }
        }
        out.regressors.push(reg);
        out.rate_i_deg_h.push(rate_i.map(|v| v * inv_m));
        out.nonlinearity_deg_h.push(nl.map(|v| v * inv_m));
        out.accel_output_g.push(acc_out.map(|v| v * inv_m));
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

/// Sensor noise per output sample and channel: white (ARW) plus a
/// first-order Gauss–Markov bias, deg/h, plus the rate random walk.
fn gyro_noise(s: &Scenario, n_out: usize, rng: &mut Xoshiro256PlusPlus) -> Vec<[f64; 6]> {
    let mut noise = white_and_markov(s, n_out, rng);
    add_rate_random_walk(s, &mut noise);
    noise
}

/// Adds the rate random walk's interval means, deg/h: over each interval
/// the walk moves by W = q·z₁ (q = K·√dt) and its mean over the interval is
/// b + W/2 + q·z₂/√12 (a Brownian bridge's mean has variance dt/12 and is
/// independent of the end point), so the Allan deviation is K·√(τ/3) at
/// every τ, the shortest included. Nothing is drawn when K is zero.
fn add_rate_random_walk(s: &Scenario, noise: &mut [[f64; 6]]) {
    let q = s.gyros.noise.rrw_step_deg_h(1.0 / s.output_rate_hz);
    if q == 0.0 {
        return;
    }
    let mut rng = stream(s.seed, Stream::GyroRateWalk);
    let mut walk = [0.0; 6];
    for sample in noise.iter_mut() {
        for (e, b) in sample.iter_mut().zip(walk.iter_mut()) {
            let z1: f64 = StandardNormal.sample(&mut rng);
            let z2: f64 = StandardNormal.sample(&mut rng);
            *e += *b + q * (0.5 * z1 + z2 / 12f64.sqrt());
            *b += q * z1;
        }
    }
}

fn white_and_markov(s: &Scenario, n_out: usize, rng: &mut Xoshiro256PlusPlus) -> Vec<[f64; 6]> {
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
    let mut bias: [f64; 6] = std::array::from_fn(|_| p.bias_instability_deg_h * normal());
    (0..n_out)
        .map(|_| {
            std::array::from_fn(|ch| {
                let e = white * normal() + bias[ch];
                bias[ch] = phi * bias[ch] + drive * normal();
                e
            })
        })
        .collect()
}

/// Simulates a scenario: the record, the calibration a user would have and
/// the truth (with the per-channel noise floor), plus per-channel component
/// series. The same scenario (seed included) always gives identical results.
///
/// ```
/// use nav_sensors::sim::{simulate, Scenario};
/// use nav_sensors::geometry::Channel;
/// let s = Scenario { duration_s: 1.0, ..Scenario::default() };
/// let sim = simulate(&s).unwrap();
/// assert_eq!(sim.record.len(), 50);
/// assert!((sim.record.dt() - 0.02).abs() < 1e-12);
/// // Shaker off at first: Z reads Earth rate plus its drift, az reads 1 g.
/// assert!((sim.record.accel(nav_sensors::record::Axis::Z)[0] - 1.0).abs() < 1e-3);
/// ```
pub fn simulate(s: &Scenario) -> Result<Simulation, SimError> {
    s.validate()?;
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
    let hr = high_rate(s, &vib, &kin);
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
    let coefficients = Channel::ALL.map(|c| s.gyro(c).to_array());
    let mut noise = gyro_noise(s, n_out, &mut stream(s.seed, Stream::GyroNoise));
    let mut gyro: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(n_out));
    let mut regressors = hr.regressors.clone();
    let mut remainder_deg = [0.0; 6];
    for n in 0..n_out {
        for ch in 0..6 {
            let r = &mut regressors[n][ch];
            r[DtgTerm::Temp.index()] = t_mean[n] - s.thermal.reference_c;
            let drift: f64 = coefficients[ch]
                .iter()
                .zip(r.iter())
                .map(|(c, r)| c * r)
                .sum();
            let exact =
                hr.rate_i_deg_h[n][ch] + drift + hr.nonlinearity_deg_h[n][ch] + noise[n][ch];
            let out = match s.gyros.pulse_arcsec {
                None => exact,
                Some(q_arcsec) => {
                    let q = q_arcsec / 3600.0;
                    let angle = remainder_deg[ch] + exact * dt / 3600.0;
                    let pulses = (angle / q).floor();
                    remainder_deg[ch] = angle - pulses * q;
                    let out = pulses * q * 3600.0 / dt;
                    noise[n][ch] += out - exact;
                    out
                }
            };
            gyro[ch].push(out);
        }
    }

    let mut rng_accel = stream(s.seed, Stream::AccelNoise);
    let accel_sigma = s.accels.noise.averaged_sigma_g(dt);
    let accel: [Vec<f64>; 3] = std::array::from_fn(|k| {
        hr.accel_output_g
            .iter()
            .map(|a| {
                let e: f64 = StandardNormal.sample(&mut rng_accel);
                a[k] + accel_sigma * e
            })
            .collect()
    });

    let t: Vec<f64> = (1..=n_out).map(|n| n as f64 * dt).collect();
    let record = Record::new(
        t,
        gyro,
        accel,
        vec![("temp".to_string(), temp_meas.clone())],
    )?;
    let calibration = ground_calibration(s, &mut stream(s.seed, Stream::Calibration));
    let (truth, components) = budget(
        s,
        &hr,
        &regressors,
        &noise,
        &temp_meas,
        &calibration,
        record.t(),
    );
    Ok(Simulation {
        record,
        calibration,
        truth,
        components,
    })
}
