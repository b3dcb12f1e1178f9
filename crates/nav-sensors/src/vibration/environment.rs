//! The shaker environment: drives on axes, cross-axis motion, a level
//! schedule and the rocking (angular) vibration that comes with them.

use std::collections::BTreeMap;

use rand::Rng;
use serde::{Deserialize, Serialize};

use super::psd::PsdTable;
use super::schedule::LevelSchedule;
use super::sine::{sine, sweep};
use super::synth::{Motion, synthesize_random};
use crate::geometry::Axis;

/// One shaker drive: a signal along an axis plus transverse (cross-axis)
/// motion as fractions of it. Independent drives on several axes make a
/// multi-axis test.
///
/// ```
/// use nav_sensors::vibration::Drive;
/// let d: Drive = toml::from_str(r#"
///     kind = "random"
///     axis = "z"
///     psd = [[20.0, 0.01], [80.0, 0.04], [350.0, 0.04], [2000.0, 0.007]]
///     transverse = { x = 0.05 }
/// "#).unwrap();
/// assert_eq!(d.axis(), nav_sensors::geometry::Axis::Z);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Drive {
    /// Random vibration with a PSD table, scaled by `gain_db`.
    Random {
        /// Drive axis.
        axis: Axis,
        /// Single-sided PSD, `[Hz, g²/Hz]` breakpoints.
        psd: PsdTable,
        /// Level offset applied to the table, dB.
        #[serde(default)]
        gain_db: f64,
        /// Cross-axis motion: fraction of the drive signal on other axes.
        #[serde(default)]
        transverse: BTreeMap<Axis, f64>,
    },
    /// A sine of constant frequency.
    Sine {
        /// Drive axis.
        axis: Axis,
        /// Frequency, Hz.
        frequency_hz: f64,
        /// Peak amplitude, g.
        amplitude_g: f64,
        /// Phase at t = 0, degrees.
        #[serde(default)]
        phase_deg: f64,
        /// Cross-axis motion: fraction of the drive signal on other axes.
        #[serde(default)]
        transverse: BTreeMap<Axis, f64>,
    },
    /// A logarithmic sine sweep over the whole test.
    Sweep {
        /// Drive axis.
        axis: Axis,
        /// Start frequency, Hz.
        start_hz: f64,
        /// End frequency, Hz.
        end_hz: f64,
        /// Peak amplitude, g.
        amplitude_g: f64,
        /// Cross-axis motion: fraction of the drive signal on other axes.
        #[serde(default)]
        transverse: BTreeMap<Axis, f64>,
    },
}

impl Drive {
    /// The drive axis.
    ///
    /// ```
    /// use nav_sensors::vibration::{Drive, PsdTable};
    /// use nav_sensors::geometry::Axis;
    /// let d = Drive::Random { axis: Axis::Y, psd: PsdTable::navmat_p9492(), gain_db: -3.0,
    ///     transverse: [(Axis::X, 0.1)].into_iter().collect() };
    /// assert_eq!(d.axis(), Axis::Y);
    /// ```
    pub fn axis(&self) -> Axis {
        match self {
            Drive::Random { axis, .. } | Drive::Sine { axis, .. } | Drive::Sweep { axis, .. } => {
                *axis
            }
        }
    }

    /// The cross-axis fractions.
    ///
    /// ```
    /// use nav_sensors::vibration::{Drive, PsdTable};
    /// use nav_sensors::geometry::Axis;
    /// let d = Drive::Random { axis: Axis::Y, psd: PsdTable::navmat_p9492(), gain_db: -3.0,
    ///     transverse: [(Axis::X, 0.1)].into_iter().collect() };
    /// assert_eq!(d.transverse()[&Axis::X], 0.1);
    /// ```
    pub fn transverse(&self) -> &BTreeMap<Axis, f64> {
        match self {
            Drive::Random { transverse, .. }
            | Drive::Sine { transverse, .. }
            | Drive::Sweep { transverse, .. } => transverse,
        }
    }

    /// The direction the drive moves the cluster in: its axis plus the
    /// transverse fractions.
    ///
    /// ```
    /// use nav_sensors::vibration::Drive;
    /// use nav_sensors::geometry::Axis;
    /// let d = Drive::Sine { axis: Axis::Z, frequency_hz: 100.0, amplitude_g: 1.0, phase_deg: 0.0,
    ///     transverse: [(Axis::X, 0.1)].into_iter().collect() };
    /// assert_eq!(d.direction(), nalgebra::Vector3::new(0.1, 0.0, 1.0));
    /// ```
    pub fn direction(&self) -> nalgebra::Vector3<f64> {
        let mut d = self.axis().unit_vector();
        for (a, f) in self.transverse() {
            if *a != self.axis() {
                d[a.index()] += f;
            }
        }
        d
    }

    /// Highest frequency the drive excites, Hz.
    ///
    /// ```
    /// use nav_sensors::vibration::{Drive, PsdTable};
    /// use nav_sensors::geometry::Axis;
    /// let d = Drive::Random { axis: Axis::Y, psd: PsdTable::navmat_p9492(), gain_db: -3.0,
    ///     transverse: [(Axis::X, 0.1)].into_iter().collect() };
    /// assert_eq!(d.max_frequency_hz(), 2000.0);
    /// ```
    pub fn max_frequency_hz(&self) -> f64 {
        match self {
            Drive::Random { psd, .. } => psd.band_hz().1,
            Drive::Sine { frequency_hz, .. } => *frequency_hz,
            Drive::Sweep {
                start_hz, end_hz, ..
            } => start_hz.max(*end_hz),
        }
    }

    /// The drive's scalar signal at full level: `n` samples at `fs`.
    ///
    /// ```
    /// use nav_sensors::vibration::{Drive, PsdTable};
    /// use nav_sensors::geometry::Axis;
    /// let d = Drive::Random { axis: Axis::Y, psd: PsdTable::navmat_p9492(), gain_db: -3.0,
    ///     transverse: [(Axis::X, 0.1)].into_iter().collect() };
    /// use rand::SeedableRng;
    /// let m = d.signal(4000, 4000.0, &mut rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1));
    /// let rms = (m.accel_g.iter().map(|a| a * a).sum::<f64>() / 4000.0).sqrt();
    /// assert!((rms / (PsdTable::navmat_p9492().grms() * 10f64.powf(-3.0 / 20.0)) - 1.0).abs() < 0.02);
    /// ```
    pub fn signal(&self, n: usize, fs: f64, rng: &mut impl Rng) -> Motion {
        match self {
            Drive::Random { psd, gain_db, .. } => {
                synthesize_random(&psd.scaled_db(*gain_db), n, fs, rng)
            }
            Drive::Sine {
                frequency_hz,
                amplitude_g,
                phase_deg,
                ..
            } => sine(*frequency_hz, *amplitude_g, *phase_deg, n, fs),
            Drive::Sweep {
                start_hz,
                end_hz,
                amplitude_g,
                ..
            } => sweep(*start_hz, *end_hz, *amplitude_g, n, fs),
        }
    }
}

/// Rocking of the fixture: angular rate about the cluster axes as a linear
/// map of the linear vibration velocity,
///
/// ```text
/// ω_rock (rad/s) = R · v (m/s),   R in rad/s per m/s = 1/m
/// ```
///
/// Row i is the rotation about cluster axis i, column j the velocity along
/// axis j. A fixture whose table tilts by θ = x/L when it moves by x has
/// R = 1/L; real fixtures rock by a small fraction of that. The rocking
/// angle follows the displacement, so the gyros see an oscillating rate of
/// zero mean: it rectifies only through anisoinertia and the 2N term.
///
/// ```
/// use nav_sensors::vibration::Rocking;
/// let r = Rocking { rad_s_per_m_s: [[0.0, 0.0, 1e-3], [0.0; 3], [0.0; 3]] };
/// let w = r.rate_rad_s(&nalgebra::Vector3::new(0.0, 0.0, 0.1));
/// assert_eq!(w.x, 1e-4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rocking {
    /// R, rad/s per m/s (rows: about x, y, z; columns: velocity along x, y, z).
    pub rad_s_per_m_s: [[f64; 3]; 3],
}

impl Rocking {
    /// The rocking rate for a linear velocity, rad/s.
    ///
    /// ```
    /// let r = nav_sensors::vibration::Rocking::default();
    /// assert_eq!(r.rate_rad_s(&nalgebra::Vector3::new(1.0, 1.0, 1.0)), nalgebra::Vector3::zeros());
    /// ```
    pub fn rate_rad_s(&self, v_m_s: &nalgebra::Vector3<f64>) -> nalgebra::Vector3<f64> {
        let r = &self.rad_s_per_m_s;
        nalgebra::Vector3::from_fn(|i, _| r[i][0] * v_m_s.x + r[i][1] * v_m_s.y + r[i][2] * v_m_s.z)
    }
}

/// What is wrong with a vibration description.
///
/// ```
/// use nav_sensors::vibration::{Drive, VibrationConfig, VibrationError};
/// let v = VibrationConfig { drives: vec![Drive::Sine { axis: nav_sensors::geometry::Axis::Z,
///     frequency_hz: -5.0, amplitude_g: 1.0, phase_deg: 0.0, transverse: Default::default() }], ..Default::default() };
/// assert!(matches!(v.validate(4000.0), Err(VibrationError::NotPositive { what: "frequency_hz", .. })));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VibrationError {
    /// A drive excites frequencies at or above the Nyquist frequency of the internal rate.
    #[error(
        "drive {index} reaches {frequency_hz} Hz, at or above the internal Nyquist frequency {nyquist_hz} Hz"
    )]
    AboveNyquist {
        /// Drive index (0-based).
        index: usize,
        /// Highest frequency of the drive, Hz.
        frequency_hz: f64,
        /// Half the internal rate, Hz.
        nyquist_hz: f64,
    },
    /// A frequency or amplitude that is not finite and positive.
    #[error("drive {index}: {what} must be finite and positive, got {value}")]
    NotPositive {
        /// Drive index (0-based).
        index: usize,
        /// Which parameter.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// A level beyond what a vibration test produces; such values only
    /// overflow the simulation into infinities and NaN.
    #[error("drive {index}: {what} = {value:e} is out of range: {requirement}")]
    OutOfRange {
        /// Drive (or schedule segment) index (0-based).
        index: usize,
        /// Which parameter.
        what: &'static str,
        /// The value.
        value: f64,
        /// The valid range, in words.
        requirement: &'static str,
    },
    /// A schedule segment with a negative or non-finite duration or ramp.
    #[error(
        "schedule segment {index}: duration {duration_s} s and ramp {ramp_s} s must be finite, ramp ≤ duration, both ≥ 0"
    )]
    BadSegment {
        /// Segment index (0-based).
        index: usize,
        /// Its duration, s.
        duration_s: f64,
        /// Its ramp, s.
        ramp_s: f64,
    },
}

/// The strongest vibration a scenario may ask for, g (rms for random, peak
/// for sine): far beyond any shaker or flight, far below where squares of
/// the simulated signals overflow.
pub const MAX_LEVEL_G: f64 = 1000.0;
/// The largest gain or level change in dB, either way (a factor of 1000 in g).
const MAX_DB: f64 = 60.0;
const DB_RANGE: &str = "finite, from -60 to +60 dB";

/// The vibration part of a scenario.
///
/// ```
/// use nav_sensors::vibration::VibrationConfig;
/// use rand::SeedableRng;
/// let v = VibrationConfig::default(); // no drive: a quiet table
/// let h = v.generate(100, 4000.0, &mut rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(0)).unwrap();
/// assert!(h.accel_g[2].iter().all(|a| *a == 0.0));
/// ```
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VibrationConfig {
    /// The drives, summed.
    #[serde(default)]
    pub drives: Vec<Drive>,
    /// Level schedule applied to every drive (empty: full level throughout).
    #[serde(default)]
    pub schedule: LevelSchedule,
    /// Rocking coupling from linear velocity to angular rate.
    #[serde(default)]
    pub rocking: Rocking,
}

/// A generated vibration time history at the internal rate.
///
/// ```
/// use rand::SeedableRng;
/// let v = nav_sensors::sim::Scenario::default().vibration;
/// let h = v.generate(4000, 4000.0, &mut rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(0)).unwrap();
/// assert_eq!(h.accel_g[2].len(), 4000);
/// assert_eq!(h.envelope[0], 0.0); // the default schedule starts with the shaker off
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct VibrationHistory {
    /// Linear vibration acceleration along x, y, z, g.
    pub accel_g: [Vec<f64>; 3],
    /// Rocking rate about x, y, z, deg/s.
    pub angular_rate_deg_s: [Vec<f64>; 3],
    /// Amplitude gain of the level schedule at each sample (0 = off, 1 = 0 dB).
    pub envelope: Vec<f64>,
}

impl VibrationConfig {
    /// Checks the description against the internal rate.
    ///
    /// ```
    /// assert!(nav_sensors::sim::Scenario::default().vibration.validate(4000.0).is_ok());
    /// assert!(nav_sensors::sim::Scenario::default().vibration.validate(3000.0).is_err());
    /// ```
    pub fn validate(&self, fs: f64) -> Result<(), VibrationError> {
        let nyquist_hz = 0.5 * fs;
        let out_of_range = |index, what, value: f64, ok: bool, requirement| {
            if ok && value.is_finite() {
                Ok(())
            } else {
                Err(VibrationError::OutOfRange {
                    index,
                    what,
                    value,
                    requirement,
                })
            }
        };
        for (index, d) in self.drives.iter().enumerate() {
            let (amplitude, transverse) = match d {
                Drive::Random {
                    psd,
                    gain_db,
                    transverse,
                    ..
                } => {
                    out_of_range(
                        index,
                        "gain_db",
                        *gain_db,
                        gain_db.abs() <= MAX_DB,
                        DB_RANGE,
                    )?;
                    (psd.scaled_db(*gain_db).grms(), transverse)
                }
                Drive::Sine {
                    amplitude_g,
                    transverse,
                    ..
                }
                | Drive::Sweep {
                    amplitude_g,
                    transverse,
                    ..
                } => (*amplitude_g, transverse),
            };
            out_of_range(
                index,
                "level (g rms, or g amplitude)",
                amplitude,
                amplitude <= MAX_LEVEL_G,
                "at most 1000 g (shakers reach tens of g)",
            )?;
            for &c in transverse.values() {
                out_of_range(
                    index,
                    "transverse",
                    c,
                    c.abs() <= 10.0,
                    "a fraction of the drive, at most 10 in magnitude",
                )?;
            }
            let checks: Vec<(&'static str, f64)> = match d {
                Drive::Random { .. } => vec![],
                Drive::Sine {
                    frequency_hz,
                    amplitude_g,
                    ..
                } => vec![
                    ("frequency_hz", *frequency_hz),
                    ("amplitude_g", *amplitude_g),
                ],
                Drive::Sweep {
                    start_hz,
                    end_hz,
                    amplitude_g,
                    ..
                } => vec![
                    ("start_hz", *start_hz),
                    ("end_hz", *end_hz),
                    ("amplitude_g", *amplitude_g),
                ],
            };
            for (what, value) in checks {
                if !(value.is_finite() && value > 0.0) {
                    return Err(VibrationError::NotPositive { index, what, value });
                }
            }
            // A random table may end exactly at Nyquist (the NAVMAT table at
            // 4 kHz): synthesis leaves the Nyquist bin empty. A sine must be below.
            let frequency_hz = d.max_frequency_hz();
            let above = match d {
                Drive::Random { .. } => frequency_hz > nyquist_hz,
                _ => frequency_hz >= nyquist_hz,
            };
            if above {
                return Err(VibrationError::AboveNyquist {
                    index,
                    frequency_hz,
                    nyquist_hz,
                });
            }
        }
        for (index, s) in self.schedule.segments().iter().enumerate() {
            if let Some(db) = s.level_db {
                out_of_range(index, "schedule level_db", db, db.abs() <= MAX_DB, DB_RANGE)?;
            }
            let ok = s.duration_s.is_finite()
                && s.ramp_s.is_finite()
                && s.duration_s >= 0.0
                && s.ramp_s >= 0.0
                && s.ramp_s <= s.duration_s;
            if !ok {
                return Err(VibrationError::BadSegment {
                    index,
                    duration_s: s.duration_s,
                    ramp_s: s.ramp_s,
                });
            }
        }
        Ok(())
    }

    /// Generates `n` samples at `fs` Hz: every drive's signal (random drives
    /// draw from `rng` in drive order) along its direction, times the level
    /// envelope, and the rocking rate from the enveloped velocity.
    ///
    /// ```
    /// use rand::SeedableRng;
    /// use nav_sensors::vibration::{Drive, VibrationConfig};
    /// let v = VibrationConfig { drives: vec![Drive::Sine { axis: nav_sensors::geometry::Axis::X,
    ///     frequency_hz: 100.0, amplitude_g: 2.0, phase_deg: 90.0, transverse: Default::default() }], ..Default::default() };
    /// let h = v.generate(40, 4000.0, &mut rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(0)).unwrap();
    /// assert!((h.accel_g[0][0] - 2.0).abs() < 1e-12);
    /// ```
    pub fn generate(
        &self,
        n: usize,
        fs: f64,
        rng: &mut impl Rng,
    ) -> Result<VibrationHistory, VibrationError> {
        self.validate(fs)?;
        let envelope = self.schedule.envelope(n, fs);
        let mut accel_g: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; n]);
        let mut vel: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; n]);
        for d in &self.drives {
            let m = d.signal(n, fs, rng);
            let dir = d.direction();
            for axis in 0..3 {
                let k = dir[axis];
                if k == 0.0 {
                    continue;
                }
                for t in 0..n {
                    accel_g[axis][t] += k * envelope[t] * m.accel_g[t];
                    vel[axis][t] += k * envelope[t] * m.velocity_m_s[t];
                }
            }
        }
        let r = &self.rocking.rad_s_per_m_s;
        let angular_rate_deg_s = std::array::from_fn(|i| {
            (0..n)
                .map(|t| {
                    (r[i][0] * vel[0][t] + r[i][1] * vel[1][t] + r[i][2] * vel[2][t]).to_degrees()
                })
                .collect()
        });
        Ok(VibrationHistory {
            accel_g,
            angular_rate_deg_s,
            envelope,
        })
    }
}
