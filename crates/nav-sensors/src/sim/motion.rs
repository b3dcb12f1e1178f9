//! A flight-like motion of the unit: attitude, turn rate and speed by phase,
//! giving the specific force (gravity and manoeuvre accelerations) and the
//! angular rate (Earth rate and body rates) in the cluster (body) frame.
//!
//! Frames. The rest frame L is the cluster frame at t = 0 as the site puts
//! it (z up and x north by default). The body (cluster) attitude is
//! `R = Rz(ψ)·Ry(−θ)·Rx(φ)` from body to L: heading ψ about L's z
//! (positive turns x toward y, a left turn with z up), pitch θ positive
//! nose (x) up, roll φ about x positive y (the left side) up. The velocity
//! points along the body x axis at speed V (no angle of attack or
//! sideslip), so a turn at rate ψ̇ and speed V pulls `V·ψ̇` toward the
//! centre and a pitch change `V·θ̇` normal to the path; a bank of
//! `atan(V·ψ̇/g)` makes the turn coordinated (no side force).
//!
//! At time t: specific force `f_b = Rᵀ·(g_L + a_L/g₀)` (g), with `g_L` the
//! site's +1 g up in L and `a_L = d(V·x_b)/dt`; angular rate `ω_b =
//! Rᵀ·Ω_L + ω_attitude` (deg/h), with Ω_L the Earth rate in L and
//! ω_attitude from `R(t−h)ᵀ·R(t+h)`. The transport rate (the motion over
//! the curved Earth, V/R ≈ 8 deg/h at 250 m/s) is left out: the test
//! needs rates that vary, not a navigation solution.
//!
//! Each phase moves from the previous phase's roll, pitch, turn rate,
//! oscillation amplitudes and oscillation frequency to its own over
//! `transition_s` (a raised cosine, so attitude and rates are continuous),
//! then holds them; its speed changes linearly
//! over the whole phase (a constant longitudinal acceleration). Past the
//! last phase everything holds.

use nalgebra::{Rotation3, Vector3};
use serde::{Deserialize, Serialize};

use super::scenario::{ScenarioError, check_range};
use crate::vibration::STANDARD_GRAVITY_M_S2;

/// One phase of a motion profile.
///
/// ```
/// let p: nav_sensors::sim::Phase = toml::from_str(r#"
///     name = "turn left"
///     duration_s = 60.0
///     roll_deg = -25.0
///     turn_rate_deg_s = 3.0
///     speed_m_s = 200.0
/// "#).unwrap();
/// assert_eq!(p.transition_s, 5.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Phase {
    /// What the phase is (`taxi`, `take-off`, …), for the reader.
    #[serde(default)]
    pub name: String,
    /// Length, s.
    pub duration_s: f64,
    /// Roll reached at the end of the transition, deg (positive: left side up).
    #[serde(default)]
    pub roll_deg: f64,
    /// Pitch reached at the end of the transition, deg (positive: nose up).
    #[serde(default)]
    pub pitch_deg: f64,
    /// Heading rate reached at the end of the transition, deg/s (positive:
    /// x turns toward y).
    #[serde(default)]
    pub turn_rate_deg_s: f64,
    /// Speed at the end of the phase, m/s (linear from the previous phase's).
    #[serde(default)]
    pub speed_m_s: f64,
    /// Time to move from the previous phase's values to these, s.
    #[serde(default = "default_transition_s")]
    pub transition_s: f64,
    /// Peak of a sinusoidal roll oscillation on top of `roll_deg` (S-turns,
    /// turbulence), deg.
    #[serde(default)]
    pub roll_oscillation_deg: f64,
    /// Peak of a sinusoidal pitch oscillation on top of `pitch_deg`, deg.
    #[serde(default)]
    pub pitch_oscillation_deg: f64,
    /// Period of both oscillations, s.
    #[serde(default = "default_oscillation_period_s")]
    pub oscillation_period_s: f64,
}

fn default_transition_s() -> f64 {
    5.0
}

fn default_oscillation_period_s() -> f64 {
    20.0
}

/// A motion profile: phases one after the other from t = 0, starting at
/// rest (level, heading 0, speed 0).
///
/// ```
/// use nav_sensors::sim::{MotionProfile, Phase};
/// let m = MotionProfile { phases: vec![Phase {
///     name: "bank".into(), duration_s: 10.0, roll_deg: 90.0, pitch_deg: 0.0,
///     turn_rate_deg_s: 0.0, speed_m_s: 0.0, transition_s: 5.0,
///     roll_oscillation_deg: 0.0, pitch_oscillation_deg: 0.0, oscillation_period_s: 20.0 }] };
/// let up = nalgebra::Vector3::new(0.0, 0.0, 1.0);
/// let (f0, _) = m.at(0.0, &up, &nalgebra::Vector3::zeros());
/// let (f1, w1) = m.at(8.0, &up, &nalgebra::Vector3::zeros());
/// assert!((f0 - up).norm() < 1e-12);
/// // Rolled 90°, left side up: gravity's reaction is now on +y.
/// assert!((f1 - nalgebra::Vector3::new(0.0, 1.0, 0.0)).norm() < 1e-9);
/// assert!(w1.norm() < 1e-6);
/// let (_, w) = m.at(2.5, &up, &nalgebra::Vector3::zeros());
/// assert!(w.x > 0.0); // rolling at mid-transition, deg/h
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionProfile {
    /// The phases, in order.
    pub phases: Vec<Phase>,
}

/// The profile's state at an instant (angles rad, rates rad/s, speed m/s).
#[derive(Debug, Clone, Copy)]
struct State {
    roll: f64,
    pitch: f64,
    heading: f64,
    speed: f64,
}

/// Half-step of the central differences, s: small against every phase's
/// time scale (≥ 0.5 s), large against rounding.
const H_S: f64 = 1e-3;

/// A raised-cosine step from 0 to 1 over `tau` in [0, 1], and its integral
/// over [0, tau] (in units of the transition time).
fn blend(tau: f64) -> (f64, f64) {
    let pi = std::f64::consts::PI;
    if tau >= 1.0 {
        (1.0, tau - 0.5)
    } else {
        let s = 0.5 * (1.0 - (pi * tau).cos());
        (s, 0.5 * tau - (pi * tau).sin() / (2.0 * pi))
    }
}

impl MotionProfile {
    /// Total length of the phases, s.
    ///
    /// ```
    /// let m: nav_sensors::sim::MotionProfile = toml::from_str(
    ///     "phases = [{ duration_s = 60.0 }, { duration_s = 30.0, speed_m_s = 10.0 }]").unwrap();
    /// assert_eq!(m.duration_s(), 90.0);
    /// ```
    pub fn duration_s(&self) -> f64 {
        self.phases.iter().map(|p| p.duration_s).sum()
    }

    /// Checks every phase: positive finite durations, transitions within
    /// their phase, roll within ±180°, pitch within ±80°, speeds not
    /// negative, oscillation periods of at least 1 s.
    pub(crate) fn validate(&self) -> Result<(), ScenarioError> {
        let range = check_range;
        if self.phases.is_empty() {
            return Err(ScenarioError::OutOfRange {
                field: "motion.phases",
                value: 0.0,
                requirement: "a motion profile needs at least one phase",
            });
        }
        for p in &self.phases {
            range(
                "motion.phases.duration_s",
                p.duration_s,
                p.duration_s > 0.0,
                "must be positive",
            )?;
            range(
                "motion.phases.transition_s",
                p.transition_s,
                p.transition_s >= 0.5 && p.transition_s <= p.duration_s,
                "must be from 0.5 s to the phase's duration",
            )?;
            range(
                "motion.phases.roll_deg",
                p.roll_deg,
                p.roll_deg.abs() <= 180.0,
                "must be from -180 to 180 degrees",
            )?;
            range(
                "motion.phases.pitch_deg",
                p.pitch_deg + p.pitch_oscillation_deg.abs(),
                p.pitch_deg.abs() + p.pitch_oscillation_deg.abs() <= 80.0,
                "pitch plus its oscillation must stay within ±80 degrees",
            )?;
            range(
                "motion.phases.roll_oscillation_deg",
                p.roll_oscillation_deg,
                p.roll_oscillation_deg.abs() <= 90.0,
                "must be within ±90 degrees",
            )?;
            range(
                "motion.phases.turn_rate_deg_s",
                p.turn_rate_deg_s,
                p.turn_rate_deg_s.abs() <= 90.0,
                "must be within ±90 deg/s",
            )?;
            range(
                "motion.phases.speed_m_s",
                p.speed_m_s,
                (0.0..=1000.0).contains(&p.speed_m_s),
                "must be from 0 to 1000 m/s",
            )?;
            range(
                "motion.phases.oscillation_period_s",
                p.oscillation_period_s,
                p.oscillation_period_s >= 1.0,
                "must be at least 1 s",
            )?;
        }
        Ok(())
    }

    /// Roll, pitch, heading (rad) and speed (m/s) at `t` s.
    fn state(&self, t: f64) -> State {
        let tau_2pi = std::f64::consts::TAU;
        // Values at the start of the current phase: the previous phase's
        // targets, from rest for the first.
        let (mut roll0, mut pitch0, mut rate0, mut speed0) = (0.0, 0.0, 0.0, 0.0);
        let (mut roll_osc0, mut pitch_osc0) = (0.0, 0.0);
        // The oscillations' phase angle at the start of the phase, rad:
        // accumulated, so a change of period between phases is no jump.
        let mut osc_angle0 = 0.0;
        // Their angular frequency, rad/s, blended like the turn rate, so
        // that a change of period is no step in the roll or pitch rate.
        let mut omega0 = tau_2pi / self.phases[0].oscillation_period_s;
        let mut heading0 = 0.0;
        let mut start = 0.0;
        let last = self.phases.len() - 1;
        for (k, p) in self.phases.iter().enumerate() {
            let end = start + p.duration_s;
            if t < end || k == last {
                let dt = (t - start).max(0.0);
                let tr = p.transition_s;
                let (s, integral) = blend(dt / tr);
                let lerp = |a: f64, b: f64| a + (b - a) * s;
                let roll_osc = lerp(roll_osc0, p.roll_oscillation_deg);
                let pitch_osc = lerp(pitch_osc0, p.pitch_oscillation_deg);
                let omega = tau_2pi / p.oscillation_period_s;
                let phase = osc_angle0 + omega0 * dt + (omega - omega0) * tr * integral;
                let roll = lerp(roll0, p.roll_deg) + roll_osc * phase.sin();
                let pitch = lerp(pitch0, p.pitch_deg) + pitch_osc * phase.sin();
                // ∫ rate = rate0·dt + (rate − rate0)·tr·∫blend
                let heading = heading0 + rate0 * dt + (p.turn_rate_deg_s - rate0) * tr * integral;
                let frac = (dt / p.duration_s).min(1.0);
                let speed = speed0 + (p.speed_m_s - speed0) * frac;
                return State {
                    roll: roll.to_radians(),
                    pitch: pitch.to_radians(),
                    heading: heading.to_radians(),
                    speed,
                };
            }
            let (_, integral) = blend(p.duration_s / p.transition_s);
            heading0 +=
                rate0 * p.duration_s + (p.turn_rate_deg_s - rate0) * p.transition_s * integral;
            roll0 = p.roll_deg;
            pitch0 = p.pitch_deg;
            rate0 = p.turn_rate_deg_s;
            speed0 = p.speed_m_s;
            roll_osc0 = p.roll_oscillation_deg;
            pitch_osc0 = p.pitch_oscillation_deg;
            let omega = tau_2pi / p.oscillation_period_s;
            osc_angle0 += omega0 * p.duration_s + (omega - omega0) * p.transition_s * integral;
            omega0 = omega;
            start = end;
        }
        unreachable!("the last phase returns")
    }

    fn attitude(st: &State) -> Rotation3<f64> {
        Rotation3::from_euler_angles(st.roll, -st.pitch, st.heading)
    }

    fn velocity(st: &State) -> Vector3<f64> {
        Self::attitude(st) * Vector3::new(st.speed, 0.0, 0.0)
    }

    /// The specific force (g) and angular rate (deg/h) in the cluster
    /// frame at `t` s, given the site's specific force at rest (g) and
    /// Earth rate (deg/h) in the rest frame.
    pub fn at(
        &self,
        t: f64,
        gravity_rest_g: &Vector3<f64>,
        earth_rest_deg_h: &Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let (before, now, after) = (self.state(t - H_S), self.state(t), self.state(t + H_S));
        let r = Self::attitude(&now);
        let accel_m_s2 = (Self::velocity(&after) - Self::velocity(&before)) / (2.0 * H_S);
        let f = r.inverse() * (gravity_rest_g + accel_m_s2 / STANDARD_GRAVITY_M_S2);
        let turn = Self::attitude(&before).inverse() * Self::attitude(&after);
        let body_rate_deg_h = turn.scaled_axis() / (2.0 * H_S) * (3600.0f64.to_degrees());
        let w = r.inverse() * earth_rest_deg_h + body_rate_deg_h;
        (f, w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn phase(duration_s: f64) -> Phase {
        Phase {
            name: String::new(),
            duration_s,
            roll_deg: 0.0,
            pitch_deg: 0.0,
            turn_rate_deg_s: 0.0,
            speed_m_s: 0.0,
            transition_s: 5.0,
            roll_oscillation_deg: 0.0,
            pitch_oscillation_deg: 0.0,
            oscillation_period_s: 20.0,
        }
    }

    const UP: Vector3<f64> = Vector3::new(0.0, 0.0, 1.0);

    #[test]
    fn a_steady_turn_reads_its_rate_and_a_coordinated_bank_has_no_side_force() {
        // 3 deg/s at 100 m/s: centripetal 5.24 m/s², bank atan(0.534) = 28.1°.
        let (v, rate) = (100.0f64, 3.0f64);
        let bank = (v * rate.to_radians() / STANDARD_GRAVITY_M_S2)
            .atan()
            .to_degrees();
        let m = MotionProfile {
            phases: vec![
                Phase {
                    speed_m_s: v,
                    ..phase(30.0)
                },
                Phase {
                    speed_m_s: v,
                    roll_deg: -bank,
                    turn_rate_deg_s: rate,
                    ..phase(60.0)
                },
            ],
        };
        let (f, w) = m.at(60.0, &UP, &Vector3::zeros());
        assert!(f.y.abs() < 1e-6, "no side force: {f}");
        // Load factor 1/cos(bank) on body z.
        assert!((f.z - 1.0 / bank.to_radians().cos()).abs() < 1e-6, "{f}");
        // The turn rate, about L's z, shows on body y and z.
        assert!((w.norm() - rate * 3600.0).abs() < 1e-3, "{w}");
        assert!(w.y.abs() > 0.4 * w.norm() && w.z > 0.8 * w.norm(), "{w}");
        // Heading keeps accumulating: 60 s after a 5-s transition.
        let s = m.state(90.0);
        let expected = rate * (60.0 - 2.5);
        assert!((s.heading.to_degrees() - expected).abs() < 1e-9);
    }

    #[test]
    fn acceleration_along_the_path_is_specific_force_on_x() {
        let m = MotionProfile {
            phases: vec![Phase {
                speed_m_s: 60.0,
                ..phase(30.0)
            }],
        };
        let (f, w) = m.at(10.0, &UP, &Vector3::zeros());
        assert!((f.x - 2.0 / STANDARD_GRAVITY_M_S2).abs() < 1e-9, "{f}");
        assert!((f.z - 1.0).abs() < 1e-12 && w.norm() < 1e-9);
    }

    #[test]
    fn earth_rate_turns_with_the_body() {
        let m = MotionProfile {
            phases: vec![Phase {
                pitch_deg: 30.0,
                ..phase(30.0)
            }],
        };
        let earth = Vector3::new(14.87, 0.0, 2.22);
        let (f, w) = m.at(20.0, &UP, &earth);
        // Nose up 30°: +1 g up reads sin 30° on x, cos 30° on z.
        assert!((f.x - 0.5).abs() < 1e-12 && (f.z - 0.75f64.sqrt()).abs() < 1e-12);
        assert!((w.norm() - earth.norm()).abs() < 1e-9);
    }

    #[test]
    fn attitude_and_rates_are_continuous_across_phases() {
        // An oscillation whose period changes between phases, a turn that
        // starts and stops: no step in attitude (gravity's direction) or
        // rate anywhere (a step would ring the 2N detector with a huge
        // rate; one did, before the oscillation's phase was carried across
        // phases). At zero speed, so the force is gravity alone: a speed
        // ramp's constant acceleration steps at its ends by design.
        let m = MotionProfile {
            phases: vec![
                Phase {
                    roll_oscillation_deg: 30.0,
                    pitch_oscillation_deg: 5.0,
                    oscillation_period_s: 7.0,
                    ..phase(23.0)
                },
                Phase {
                    roll_oscillation_deg: 10.0,
                    oscillation_period_s: 13.0,
                    turn_rate_deg_s: 2.0,
                    pitch_deg: 10.0,
                    ..phase(17.0)
                },
                phase(20.0),
            ],
        };
        let dt = 2.5e-4;
        let mut prev = m.at(0.0, &UP, &Vector3::zeros());
        let mut moved = 0.0f64;
        let mut k = 1;
        while (k as f64) * dt < 60.0 {
            let now = m.at(k as f64 * dt, &UP, &Vector3::zeros());
            // Per 0.25-ms step: under 1e-3 g of force and 100 deg/h of rate.
            let t = k as f64 * dt;
            assert!((now.0 - prev.0).norm() < 1e-3, "force jumps at {t} s");
            assert!((now.1 - prev.1).norm() < 100.0, "rate jumps at {t} s");
            moved = moved.max((now.0 - UP).norm());
            prev = now;
            k += 1;
        }
        assert!(moved > 0.4, "the attitude did move: {moved}");
    }

    #[test]
    fn validation_names_the_field() {
        let bad = MotionProfile {
            phases: vec![Phase {
                transition_s: 40.0,
                ..phase(30.0)
            }],
        };
        assert!(matches!(
            bad.validate(),
            Err(ScenarioError::OutOfRange {
                field: "motion.phases.transition_s",
                ..
            })
        ));
        assert!(MotionProfile { phases: vec![] }.validate().is_err());
    }
}
