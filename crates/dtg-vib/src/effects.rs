//! Physical effects: the linear-in-parameters columns of a channel model and
//! the candidates the diagnosis ranks.
//!
//! An effect is either a DTG term of `nav-sensors` (g-sensitive drift,
//! anisoelastic g²-drift, anisoinertia; IEEE Std 813 names) evaluated on the
//! measured specific force and rate resolved into the channel's (I, O, S)
//! frame, or an extra numeric column of the record (`col:NAME`, e.g.
//! `col:temp`). The regressor formulas are `nav_sensors::dtg::DtgTerm`'s own,
//! so the simulator's truth and the application's candidates are one
//! definition.
//!
//! The bias is not an effect: every channel model has one (λ0 of eq. 7).

use nav_sensors::dtg::{DtgInput, DtgTerm, within_interval_covariance};
use nav_sensors::geometry::{Axis, Channel, ChannelFrame, least_squares_rate, measurement_matrix};
use nav_sensors::record::Record;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::str::FromStr;

pub use crate::unit_sensor::{COLUMN_PREFIX, TERM_EFFECTS};

/// One physical effect, by stable id (`g_I`, `gg_IS`, `ai_OS`, `col:temp`, …).
///
/// ```
/// use dtg_vib::effects::Effect;
/// let e: Effect = "gg_IS".parse().unwrap();
/// assert_eq!(e.id(), "gg_IS");
/// assert_eq!(e.unit(), "deg/h/g²");
/// let t: Effect = "col:temp".parse().unwrap();
/// assert_eq!(t.to_string(), "col:temp");
/// assert!("gg_XY".parse::<Effect>().unwrap_err().to_string().contains("col:NAME"));
/// assert_eq!(serde_json::to_string(&e).unwrap(), "\"gg_IS\"");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Effect {
    /// A DTG term from [`TERM_EFFECTS`], in the channel's frame.
    Term(DtgTerm),
    /// An extra numeric column of the record, taken as is.
    Column(String),
}

/// An effect id or `CHANNEL=ID` pair that could not be understood.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EffectError {
    /// Not a known effect id.
    #[error("unknown effect '{given}' (valid: {}, col:NAME for an extra record column)", valid_ids().join(", "))]
    Unknown { given: String },
    /// `col:` with no name.
    #[error("effect '{given}' names no column: write col:NAME, e.g. col:temp")]
    EmptyColumn { given: String },
    /// `col:NAME` where the record has no such extra column.
    #[error("effect 'col:{name}': the record has no extra column '{name}' (extra columns: {})", if available.is_empty() { "none".to_string() } else { available.join(", ") })]
    MissingColumn {
        name: String,
        available: Vec<String>,
    },
    /// A `CHANNEL=ID` argument without `=`.
    #[error("'{given}' is not CHANNEL=ID (e.g. Y1=gg_IS)")]
    NotAPair { given: String },
    /// The channel of a `CHANNEL=ID` argument is unknown.
    #[error("{0}")]
    Channel(#[from] nav_sensors::geometry::ParseNameError),
}

fn valid_ids() -> Vec<&'static str> {
    TERM_EFFECTS.iter().map(|t| t.id()).collect()
}

impl Effect {
    /// The stable id.
    pub fn id(&self) -> String {
        match self {
            Effect::Term(t) => t.id().to_string(),
            Effect::Column(c) => format!("{COLUMN_PREFIX}{c}"),
        }
    }

    /// The physical name (IEEE Std 813 for DTG terms).
    pub fn description(&self) -> String {
        match self {
            Effect::Term(t) => t.ieee_name().to_string(),
            Effect::Column(c) => format!("sensitivity to the record's '{c}' column"),
        }
    }

    /// The unit of the effect's coefficient (deg/h per regressor unit).
    pub fn unit(&self) -> String {
        match self {
            Effect::Term(t) => t.unit().to_string(),
            Effect::Column(c) if c == "temp" => "deg/h/°C".to_string(),
            Effect::Column(c) => format!("deg/h per unit of {c}"),
        }
    }

    /// Every candidate effect for a record with these extra columns: the
    /// twelve frame-resolved DTG terms, then `col:NAME` for each column.
    ///
    /// ```
    /// let all = dtg_vib::effects::Effect::candidates(&["temp"]);
    /// assert_eq!(all.len(), 13);
    /// assert_eq!(all.last().unwrap().id(), "col:temp");
    /// ```
    pub fn candidates(extra_columns: &[&str]) -> Vec<Effect> {
        TERM_EFFECTS
            .iter()
            .map(|&t| Effect::Term(t))
            .chain(extra_columns.iter().map(|c| Effect::Column(c.to_string())))
            .collect()
    }

    /// Parses a comma-separated list; `bias` is accepted and ignored (every
    /// model has one), duplicates are dropped, order is kept.
    ///
    /// ```
    /// let e = dtg_vib::effects::Effect::parse_list("bias, g_S,gg_II,g_S").unwrap();
    /// assert_eq!(e.iter().map(|e| e.id()).collect::<Vec<_>>(), ["g_S", "gg_II"]);
    /// ```
    pub fn parse_list(list: &str) -> Result<Vec<Effect>, EffectError> {
        let mut out: Vec<Effect> = Vec::new();
        for item in list
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty() && *s != "bias")
        {
            let e: Effect = item.parse()?;
            if !out.contains(&e) {
                out.push(e);
            }
        }
        Ok(out)
    }
}

impl fmt::Display for Effect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.id())
    }
}

impl FromStr for Effect {
    type Err = EffectError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        if let Some(name) = s.strip_prefix(COLUMN_PREFIX) {
            if name.trim().is_empty() {
                return Err(EffectError::EmptyColumn {
                    given: s.to_string(),
                });
            }
            return Ok(Effect::Column(name.trim().to_string()));
        }
        TERM_EFFECTS
            .iter()
            .find(|t| t.id() == s)
            .map(|&t| Effect::Term(t))
            .ok_or_else(|| EffectError::Unknown {
                given: s.to_string(),
            })
    }
}

impl Serialize for Effect {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.id())
    }
}

impl<'de> Deserialize<'de> for Effect {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// An effect added to one channel: the `CHANNEL=ID` of `--add-effect`.
///
/// ```
/// use dtg_vib::effects::ChannelEffect;
/// use nav_sensors::geometry::Channel;
/// let a: ChannelEffect = "Y1=gg_IS".parse().unwrap();
/// assert_eq!(a.channel, Channel::Y1);
/// assert_eq!(a.effect.id(), "gg_IS");
/// assert!("Q=gg_IS".parse::<ChannelEffect>().unwrap_err().to_string().contains("X1"));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ChannelEffect {
    /// The channel it applies to.
    pub channel: Channel,
    /// The effect.
    pub effect: Effect,
}

impl FromStr for ChannelEffect {
    type Err = EffectError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (c, e) = s.split_once('=').ok_or_else(|| EffectError::NotAPair {
            given: s.to_string(),
        })?;
        Ok(Self {
            channel: c.parse()?,
            effect: e.parse()?,
        })
    }
}

/// A unit's record as the effects read it: its columns, borrowed (from a
/// [`Record`], or from the loop's [`sysid::Signals`] of one).
///
/// ```
/// use dtg_vib::effects::UnitColumns;
/// let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n0,1,0,0,0,0,0,0,0,1,20\n0.02,1,0,0,0,0,0,0,0,1,21\n";
/// let rec = nav_sensors::record::Record::from_reader(csv.as_bytes(), "doc.csv").unwrap();
/// let u = UnitColumns::from(&rec);
/// assert_eq!((u.len(), u.gyro_sample(1)[0], u.extra("temp")), (2, 1.0, Some(&[20.0, 21.0][..])));
/// ```
#[derive(Debug, Clone)]
pub struct UnitColumns<'a> {
    gyro: [&'a [f64]; 6],
    accel: [&'a [f64]; 3],
    extra: Vec<(&'a str, &'a [f64])>,
}

impl<'a> UnitColumns<'a> {
    /// The columns of a record of the paper's unit held as named signals:
    /// `None` when one of the unit's columns is missing.
    pub fn of_signals(s: &'a sysid::Signals) -> Option<Self> {
        let gyro = Channel::ALL.map(|c| s.column(c.name()));
        let accel = Axis::ALL.map(|a| s.column(a.column()));
        let extra = s
            .columns()
            .iter()
            .filter(|(n, _)| !is_unit_column(n))
            .map(|(n, v)| (n.as_str(), v.as_slice()))
            .collect();
        Some(Self {
            gyro: [gyro[0]?, gyro[1]?, gyro[2]?, gyro[3]?, gyro[4]?, gyro[5]?],
            accel: [accel[0]?, accel[1]?, accel[2]?],
            extra,
        })
    }

    /// Samples.
    pub fn len(&self) -> usize {
        self.gyro[0].len()
    }

    /// True for a record without samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Gyro channel `k`'s outputs (X, X1, Y, Y1, Z, Z1 order), deg/h.
    pub fn gyro_column(&self, k: usize) -> &'a [f64] {
        self.gyro[k]
    }

    /// Accelerometer axis `k`'s specific force (x, y, z order), g.
    pub fn accel_column(&self, k: usize) -> &'a [f64] {
        self.accel[k]
    }

    /// The six gyro outputs of sample `i`, deg/h.
    pub fn gyro_sample(&self, i: usize) -> [f64; 6] {
        self.gyro.map(|g| g[i])
    }

    /// The specific force of sample `i`, g (cluster frame).
    pub fn accel_sample(&self, i: usize) -> nalgebra::Vector3<f64> {
        nalgebra::Vector3::new(self.accel[0][i], self.accel[1][i], self.accel[2][i])
    }

    /// An extra column by name.
    pub fn extra(&self, name: &str) -> Option<&'a [f64]> {
        self.extra.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
    }

    /// The extra columns' names, in order.
    pub fn extra_names(&self) -> Vec<&'a str> {
        self.extra.iter().map(|(n, _)| *n).collect()
    }
}

impl<'a> From<&'a Record> for UnitColumns<'a> {
    fn from(r: &'a Record) -> Self {
        Self {
            gyro: Channel::ALL.map(|c| r.gyro(c)),
            accel: Axis::ALL.map(|a| r.accel(a)),
            extra: r
                .extra_names()
                .into_iter()
                .map(|n| (n, r.extra(n).unwrap_or(&[])))
                .collect(),
        }
    }
}

/// True for a column of the paper's unit itself (a gyro output or an
/// accelerometer axis), false for an extra column.
pub fn is_unit_column(name: &str) -> bool {
    Channel::ALL.iter().any(|c| c.name() == name) || Axis::ALL.iter().any(|a| a.column() == name)
}

/// Evaluates effect regressors on a record for one channel.
///
/// Specific force comes from the record's accelerometers (g, cluster frame);
/// rate from the least-squares combination of the five gyro outputs other
/// than the channel's own (deg/h), both resolved into the channel's (I, O, S)
/// frame. A channel's own output never enters its regressors: its noise and
/// its vibration error would make the rate products fit the target itself. The g² regressors are
/// interval means of products (product of means plus the within-interval
/// covariance estimated from neighbouring samples), as the gyro output is.
///
/// ```
/// use dtg_vib::effects::{Effect, EffectColumns};
/// use nav_sensors::geometry::Channel;
/// use nav_sensors::record::Record;
/// let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n0,0,0,0,0,0,0,0,0,1,20\n0.02,0,0,0,0,0,0,0,0,2,21\n";
/// let rec = Record::from_reader(csv.as_bytes(), "doc.csv").unwrap();
/// let cols = EffectColumns::new(&rec);
/// // Channel Z: I is the cluster Z axis, so g_I is az and gg_II is az².
/// let e = ["g_I".parse::<Effect>().unwrap(), "gg_II".parse().unwrap(), "col:temp".parse().unwrap()];
/// let m = cols.evaluate(Channel::Z, &e).unwrap();
/// assert_eq!(m, vec![vec![1.0, 2.0], vec![1.0, 4.0], vec![20.0, 21.0]]);
/// ```
pub struct EffectColumns<'a> {
    record: UnitColumns<'a>,
    /// Per sample, the rate seen without each channel (index = `Channel::index`).
    rate_deg_h: Vec<[nalgebra::Vector3<f64>; 6]>,
    /// Within-interval covariance of the specific force (cluster frame), g².
    covariance: Vec<nalgebra::Matrix3<f64>>,
}

impl<'a> EffectColumns<'a> {
    /// Prepares the record (computes the least-squares rates once).
    pub fn new(record: impl Into<UnitColumns<'a>>) -> Self {
        let record = record.into();
        let ops = rate_without_each_channel();
        let rate_deg_h = (0..record.len())
            .map(|i| {
                let m = nalgebra::SVector::<f64, 6>::from(record.gyro_sample(i));
                std::array::from_fn(|j| ops[j] * m)
            })
            .collect();
        let means: Vec<nalgebra::Vector3<f64>> =
            (0..record.len()).map(|i| record.accel_sample(i)).collect();
        let covariance = within_interval_covariance(&means);
        Self {
            record,
            rate_deg_h,
            covariance,
        }
    }

    /// One column per effect, each of the record's length.
    pub fn evaluate(
        &self,
        channel: Channel,
        effects: &[Effect],
    ) -> Result<Vec<Vec<f64>>, EffectError> {
        let frame = ChannelFrame::of(channel);
        let n = self.record.len();
        let inputs: Vec<DtgInput> = (0..n)
            .map(|i| {
                let rate = &self.rate_deg_h[i][channel.index()];
                DtgInput::resolved(&frame, rate, &self.record.accel_sample(i))
                    .with_covariance(&frame, &self.covariance[i])
            })
            .collect();
        effects
            .iter()
            .map(|e| match e {
                Effect::Term(t) => Ok(inputs.iter().map(|x| t.regressor(x)).collect()),
                Effect::Column(c) => self.record.extra(c).map(<[f64]>::to_vec).ok_or_else(|| {
                    EffectError::MissingColumn {
                        name: c.clone(),
                        available: self
                            .record
                            .extra_names()
                            .iter()
                            .map(|s| s.to_string())
                            .collect(),
                    }
                }),
            })
            .collect()
    }
}

pub use crate::unit_sensor::ANISOINERTIA_MIN_RATE_DEG_S;

/// How much the angular rate varies over the given samples of a record: the
/// largest standard deviation of the least-squares rate's three axes, deg/s.
///
/// ```
/// use dtg_vib::effects::rate_variation_deg_s;
/// use nav_sensors::geometry::ideal_outputs;
/// use nav_sensors::record::Record;
/// // A table turning about x at +1 and −1 deg/s (3600 deg/h) in turn.
/// let mut csv = String::from("t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n");
/// for i in 0..10 {
///     let w = if i % 2 == 0 { 3600.0 } else { -3600.0 };
///     let m = ideal_outputs(&nalgebra::Vector3::new(w, 0.0, 0.0));
///     let cells: Vec<String> = m.iter().map(|v| v.to_string()).collect();
///     csv += &format!("{},{},0,0,1\n", i as f64 * 0.02, cells.join(","));
/// }
/// let rec = Record::from_reader(csv.as_bytes(), "doc.csv").unwrap();
/// assert!((rate_variation_deg_s(&rec, 0..10) - 1.0).abs() < 1e-9);
/// ```
pub fn rate_variation_deg_s<'a>(
    record: impl Into<UnitColumns<'a>>,
    samples: impl IntoIterator<Item = usize>,
) -> f64 {
    let record = record.into();
    let rates: Vec<nalgebra::Vector3<f64>> = samples
        .into_iter()
        .map(|i| least_squares_rate(&record.gyro_sample(i)) / 3600.0)
        .collect();
    crate::unit_sensor::largest_axis_std(&rates)
}

/// For each channel j, the 3×6 least-squares operator of eq. 4 with row j
/// left out (its column is zero). Any five rows of eq. 4 have rank 3: the
/// skewed geometry tolerates one failed channel.
pub(crate) fn rate_without_each_channel() -> [nalgebra::SMatrix<f64, 3, 6>; 6] {
    let h = measurement_matrix();
    std::array::from_fn(|j| {
        let mut ht = h.transpose();
        ht.column_mut(j).fill(0.0);
        let inv = (ht * h)
            .try_inverse()
            .expect("any five rows of eq. 4 have rank 3 (constant matrix)");
        inv * ht
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_channels_own_output_never_enters_its_rate() {
        use nav_sensors::geometry::ideal_outputs;
        let w = nalgebra::Vector3::new(15.0, -4.0, 7.5);
        let ideal = ideal_outputs(&w);
        let ops = rate_without_each_channel();
        for (j, op) in ops.iter().enumerate() {
            // Exact on ideal outputs …
            assert!((op * nalgebra::SVector::<f64, 6>::from(ideal) - w).norm() < 1e-12);
            // … and blind to a fault on the left-out channel.
            let mut m = ideal;
            m[j] += 1e3;
            assert!(
                (op * nalgebra::SVector::<f64, 6>::from(m) - w).norm() < 1e-9,
                "{j}"
            );
        }
    }

    #[test]
    fn every_term_effect_round_trips_through_its_id() {
        for e in Effect::candidates(&["temp", "humidity"]) {
            assert_eq!(e.id().parse::<Effect>().unwrap(), e);
            let json = serde_json::to_string(&e).unwrap();
            assert_eq!(serde_json::from_str::<Effect>(&json).unwrap(), e);
        }
    }

    #[test]
    fn unknown_effect_lists_the_valid_ids() {
        let msg = "gg_XY".parse::<Effect>().unwrap_err().to_string();
        for t in TERM_EFFECTS {
            assert!(msg.contains(t.id()), "{msg}");
        }
        assert!(matches!(
            "col:".parse::<Effect>(),
            Err(EffectError::EmptyColumn { .. })
        ));
        // Terms outside the effect set (e.g. the bias or scale factor) are not effects.
        assert!("scale_factor".parse::<Effect>().is_err());
    }

    #[test]
    fn channel_effect_errors_name_what_is_wrong() {
        assert!(matches!(
            "Y1gg_IS".parse::<ChannelEffect>(),
            Err(EffectError::NotAPair { .. })
        ));
        assert!(matches!(
            "Y1=nope".parse::<ChannelEffect>(),
            Err(EffectError::Unknown { .. })
        ));
        assert!(matches!(
            "W=g_I".parse::<ChannelEffect>(),
            Err(EffectError::Channel(_))
        ));
    }

    #[test]
    fn frame_resolution_follows_eq_2_for_the_x_channel() {
        // X channel: I = Xc, O = X1 = (Yc − Zc)/√2, S = −(Yc + Zc)/√2.
        let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0,0,0,0,0,0,0,0.5,0.3,0.7\n0.02,0,0,0,0,0,0,0,0,0\n";
        let rec = Record::from_reader(csv.as_bytes(), "x.csv").unwrap();
        let e: Vec<Effect> = ["g_I", "g_O", "g_S", "gg_OS"]
            .iter()
            .map(|s| s.parse().unwrap())
            .collect();
        let m = EffectColumns::new(&rec).evaluate(Channel::X, &e).unwrap();
        let h = 0.5f64.sqrt();
        let (fo, fs) = ((0.3 - 0.7) * h, -(0.3 + 0.7) * h);
        assert!((m[0][0] - 0.5).abs() < 1e-15);
        assert!((m[1][0] - fo).abs() < 1e-15);
        assert!((m[2][0] - fs).abs() < 1e-15);
        assert!((m[3][0] - fo * fs).abs() < 1e-15);
    }

    #[test]
    fn missing_extra_column_is_reported_with_the_available_ones() {
        let csv =
            "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n0,0,0,0,0,0,0,0,0,1,20\n0.02,0,0,0,0,0,0,0,0,2,21\n";
        let rec = Record::from_reader(csv.as_bytes(), "m.csv").unwrap();
        let err = EffectColumns::new(&rec)
            .evaluate(Channel::X, &[Effect::Column("pressure".into())])
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "effect 'col:pressure': the record has no extra column 'pressure' (extra columns: temp)"
        );
    }
}
