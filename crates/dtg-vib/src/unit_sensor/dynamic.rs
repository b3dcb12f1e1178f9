//! The effects that follow the unit's motion sample by sample, for any
//! gyro model: its response to the angular rate (IEEE Std 952 / 1431
//! scale-factor error, input-axis misalignment, and the frequency response
//! as a short FIR of the rate) and its linear response to each
//! accelerometer's specific force (a FIR of each accelerometer column).
//! One regressor column per effect: a FIR is one effect per tap, its id the
//! lag in samples after `@` (`sf@2`: the rate about the input axis two
//! samples earlier). The rate is the reference rate where one is given, the
//! unit's own least-squares rate H⁺m otherwise (in flight). `delay` is the
//! gyro's time offset against that rate: a gyro that reads ω(t − τ) errs by
//! −τ·ω̇ along its input axis to first order.

use nalgebra::Vector3;
use nav_sensors::geometry::Axis;
use std::fmt;

/// The largest lag a dynamic effect takes, samples.
pub const MAX_LAG: usize = 25;

/// Regressor scale of the rate effects: the rate in deg/h times 1e-6, so
/// the coefficient is in ppm (µrad for a misalignment).
const PPM: f64 = 1e-6;

/// What a dynamic effect responds to.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stimulus {
    /// The rate about the gyro's input axis (`sf`).
    InputRate,
    /// Minus the rate's derivative about the input axis (`delay`): the
    /// coefficient is the gyro's delay, ms.
    InputRateDelay,
    /// The rate about a unit axis (`ma_x`, `ma_y`, `ma_z`).
    AxisRate(Axis),
    /// The specific force an accelerometer of the unit reads (`acc:NAME`).
    Accel(String),
}

/// A dynamic effect: its stimulus `lag` samples earlier.
///
/// ```
/// use dtg_vib::unit_sensor::Dynamic;
/// let d: Dynamic = "ma_y@3".parse().unwrap();
/// assert_eq!((d.to_string(), d.lag), ("ma_y@3".to_string(), 3));
/// assert_eq!("sf".parse::<Dynamic>().unwrap().unit(), "ppm");
/// assert_eq!("ma_z".parse::<Dynamic>().unwrap().unit(), "µrad");
/// assert_eq!("acc:a2y@5".parse::<Dynamic>().unwrap().unit(), "deg/h/g");
/// assert_eq!("delay".parse::<Dynamic>().unwrap().unit(), "ms");
/// assert!("sf@99".parse::<Dynamic>().is_err());
/// assert!("g_x".parse::<Dynamic>().is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Dynamic {
    /// What it responds to.
    pub stimulus: Stimulus,
    /// Samples earlier, 0..=[`MAX_LAG`].
    pub lag: usize,
}

/// Prefix of the accelerometer-response ids.
pub const ACCEL_PREFIX: &str = "acc:";

impl Stimulus {
    /// The unit of a tap of this stimulus's FIR, and of the family's gain
    /// per band: a misalignment's µrad (its lag 0) and a tap's ppm are one
    /// scale (10⁻⁶ of the rate), so a family's gain sums them in ppm.
    pub fn tap_unit(&self) -> &'static str {
        match self {
            Stimulus::InputRateDelay => "ms",
            Stimulus::InputRate | Stimulus::AxisRate(_) => "ppm",
            Stimulus::Accel(_) => "deg/h/g",
        }
    }
}

impl Dynamic {
    /// The coefficient's unit: its stimulus's tap unit, but µrad for a
    /// misalignment (the lag-0 term about another axis).
    pub fn unit(&self) -> &'static str {
        match (&self.stimulus, self.lag) {
            (Stimulus::AxisRate(_), 0) => "µrad",
            (s, _) => s.tap_unit(),
        }
    }

    /// The physical name (IEEE Std 952 / 1431 vocabulary).
    pub fn description(&self) -> String {
        let tap = |what: String| match self.lag {
            0 => what,
            k => format!("frequency response: {what}, FIR tap {k} sample(s) earlier"),
        };
        match &self.stimulus {
            Stimulus::InputRateDelay => tap(
                "time delay (latency) of the output against the unit's rate about the input axis"
                    .to_string(),
            ),
            Stimulus::InputRate => match self.lag {
                0 => "scale-factor error (rate about the input axis)".to_string(),
                _ => tap("rate about the input axis".to_string()),
            },
            Stimulus::AxisRate(a) => match self.lag {
                0 => format!(
                    "input-axis misalignment (cross-axis sensitivity to the rate about unit {a})"
                ),
                _ => tap(format!("rate about unit {a}")),
            },
            Stimulus::Accel(name) => format!(
                "vibration response to the specific force of accelerometer {name}{}",
                match self.lag {
                    0 => String::new(),
                    k => format!(", FIR tap {k} sample(s) earlier"),
                }
            ),
        }
    }

    /// Whether the effect reads the rate (else an accelerometer).
    pub fn reads_rate(&self) -> bool {
        !matches!(self.stimulus, Stimulus::Accel(_))
    }

    /// The regressor column: the stimulus `lag` samples earlier (the first
    /// sample's value before the record starts). `rate` is the rate per
    /// sample, deg/h, unit frame; `accel` the accelerometer's column, g;
    /// `input` the gyro's input axis; `dt_s` the sampling interval.
    pub fn column(
        &self,
        input: &Vector3<f64>,
        rate: &[Vector3<f64>],
        accel: &[f64],
        dt_s: f64,
    ) -> Vec<f64> {
        let now: Vec<f64> = match &self.stimulus {
            Stimulus::InputRate => rate.iter().map(|w| input.dot(w) * PPM).collect(),
            // −dω/dt in deg/h per ms (backward difference; 0 at the start).
            Stimulus::InputRateDelay => (0..rate.len())
                .map(|i| match i {
                    0 => 0.0,
                    i => -input.dot(&(rate[i] - rate[i - 1])) / (dt_s * 1e3),
                })
                .collect(),
            Stimulus::AxisRate(a) => rate.iter().map(|w| w[a.index()] * PPM).collect(),
            Stimulus::Accel(_) => accel.to_vec(),
        };
        (0..now.len())
            .map(|i| now[i.saturating_sub(self.lag)])
            .collect()
    }
}

/// A dynamic-effect id that could not be understood.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DynamicError {
    /// Not a dynamic id at all.
    #[error(
        "'{0}' is not a dynamic effect (sf, ma_x, ma_y, ma_z, delay, acc:NAME, each with an optional @LAG)"
    )]
    Unknown(String),
    /// A lag out of range.
    #[error("'{given}': the lag after @ must be a whole number of samples from 0 to {MAX_LAG}")]
    Lag {
        /// What was given.
        given: String,
    },
}

impl std::str::FromStr for Dynamic {
    type Err = DynamicError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        let (base, lag) = match s.rsplit_once('@') {
            Some((b, l)) => (
                b,
                l.trim()
                    .parse::<usize>()
                    .ok()
                    .filter(|&k| k <= MAX_LAG)
                    .ok_or_else(|| DynamicError::Lag { given: s.into() })?,
            ),
            None => (s, 0),
        };
        let stimulus = match base {
            "sf" => Stimulus::InputRate,
            "delay" => Stimulus::InputRateDelay,
            "ma_x" => Stimulus::AxisRate(Axis::X),
            "ma_y" => Stimulus::AxisRate(Axis::Y),
            "ma_z" => Stimulus::AxisRate(Axis::Z),
            b => match b.strip_prefix(ACCEL_PREFIX).map(str::trim) {
                Some(name) if !name.is_empty() && name != "*" => Stimulus::Accel(name.to_string()),
                _ => return Err(DynamicError::Unknown(s.into())),
            },
        };
        Ok(Dynamic { stimulus, lag })
    }
}

impl fmt::Display for Dynamic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.stimulus {
            Stimulus::InputRate => f.write_str("sf")?,
            Stimulus::InputRateDelay => f.write_str("delay")?,
            Stimulus::AxisRate(a) => write!(f, "ma_{a}")?,
            Stimulus::Accel(n) => write!(f, "{ACCEL_PREFIX}{n}")?,
        }
        match self.lag {
            0 => Ok(()),
            k => write!(f, "@{k}"),
        }
    }
}

/// The ids one `--effects` item stands for on a gyro of input axis
/// `input` in a unit of accelerometers `accels`: `ma_*` is the misalignment
/// about each unit axis other than the input's, `acc:*` every
/// accelerometer, and `@A..B` the lags A to B (`sf@0..4`: five taps).
///
/// ```
/// let ids = dtg_vib::unit_sensor::expand_dynamic("ma_*@0..1", &nalgebra::Vector3::x(), &["ax"]).unwrap();
/// assert_eq!(ids, ["ma_y", "ma_y@1", "ma_z", "ma_z@1"]);
/// let acc = dtg_vib::unit_sensor::expand_dynamic("acc:*@2", &nalgebra::Vector3::x(), &["ax", "a2x"]).unwrap();
/// assert_eq!(acc, ["acc:ax@2", "acc:a2x@2"]);
/// assert_eq!(dtg_vib::unit_sensor::expand_dynamic("g_x", &nalgebra::Vector3::x(), &[]).unwrap(), ["g_x"]);
/// ```
pub fn expand_dynamic(
    item: &str,
    input: &Vector3<f64>,
    accels: &[&str],
) -> Result<Vec<String>, DynamicError> {
    let item = item.trim();
    let Some((base, lags)) = item.rsplit_once('@').filter(|_| !item.starts_with("col:")) else {
        return Ok(match item {
            "ma_*" | "acc:*" => expand_dynamic(&format!("{item}@0"), input, accels)?,
            _ => vec![item.to_string()],
        });
    };
    let lag = |x: &str| {
        x.trim()
            .parse::<usize>()
            .ok()
            .filter(|&k| k <= MAX_LAG)
            .ok_or_else(|| DynamicError::Lag { given: item.into() })
    };
    let (first, last) = match lags.split_once("..") {
        Some((a, z)) => (lag(a)?, lag(z)?),
        None => (lag(lags)?, lag(lags)?),
    };
    if first > last {
        return Err(DynamicError::Lag { given: item.into() });
    }
    let bases: Vec<String> = match base {
        "ma_*" => Axis::ALL
            .iter()
            .filter(|a| !is_input_axis(input, **a))
            .map(|a| format!("ma_{a}"))
            .collect(),
        "acc:*" => accels
            .iter()
            .map(|n| format!("{ACCEL_PREFIX}{n}"))
            .collect(),
        b => vec![b.to_string()],
    };
    Ok(bases
        .iter()
        .flat_map(|b| {
            (first..=last).map(move |k| match k {
                0 => b.clone(),
                k => format!("{b}@{k}"),
            })
        })
        .collect())
}

/// Whether a unit axis is (nearly) the gyro's input axis, so the rate about
/// it is the scale factor's, not a misalignment's.
pub fn is_input_axis(input: &Vector3<f64>, axis: Axis) -> bool {
    input[axis.index()].abs() > 0.9
}
