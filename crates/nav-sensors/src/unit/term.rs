//! A unit channel's error terms: the DTG's IEEE Std 813 terms in its own
//! (I, O, S) axes for a `dtg` gyro, the rate gyro's IEEE Std 952 / 1431
//! terms in the unit frame for a `rate` gyro. One regressor definition per
//! term ([`crate::dtg::DtgTerm::regressor`], [`crate::rate::RateTerm::regressor`]),
//! reached through [`Gyro::regressor`] by the simulator's truth and the
//! diagnosis's candidates alike.

use std::fmt;

use nalgebra::{Matrix3, Vector3};
use serde::{Serialize, Serializer};

use super::{Gyro, GyroModel, Unit};
use crate::dtg::{DtgInput, DtgTerm};
use crate::geometry::ParseNameError;
use crate::rate::{RateInput, RateTerm};

/// One deterministic term of a unit channel's model. Its id is the user
/// contract (`--add-effect G2=g_y`, `Y1=gg_IS`); which ids a channel takes
/// depends on its model.
///
/// ```
/// use nav_sensors::unit::{GyroTerm, Unit};
/// let tetra = Unit::builtin("tetra").unwrap();
/// let t = tetra.parse_term(1, "g_y").unwrap();
/// assert_eq!((t.id(), t.unit()), ("g_y", "deg/h/g"));
/// let err = tetra.parse_term(1, "gg_IS").unwrap_err();
/// assert!(err.to_string().starts_with("unknown rate-gyro term 'gg_IS'"));
/// let paper = Unit::paper();
/// assert_eq!(paper.parse_term(3, "gg_IS").unwrap(), GyroTerm::Dtg(nav_sensors::dtg::DtgTerm::GgIS));
/// assert_eq!(serde_json::to_string(&t).unwrap(), "\"g_y\"");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum GyroTerm {
    /// A DTG term (IEEE Std 813).
    Dtg(DtgTerm),
    /// A rate-gyro term (IEEE Std 952 / 1431).
    Rate(RateTerm),
}

impl GyroTerm {
    /// The stable id.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::GyroTerm::Rate(nav_sensors::rate::RateTerm::GgXx).id(), "gg_xx");
    /// ```
    pub fn id(self) -> &'static str {
        match self {
            GyroTerm::Dtg(t) => t.id(),
            GyroTerm::Rate(t) => t.id(),
        }
    }

    /// The coefficient's unit.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::GyroTerm::Dtg(nav_sensors::dtg::DtgTerm::AiIO).unit(), "deg/h/(deg/s)²");
    /// ```
    pub fn unit(self) -> &'static str {
        match self {
            GyroTerm::Dtg(t) => t.unit(),
            GyroTerm::Rate(t) => t.unit(),
        }
    }

    /// The physical name (IEEE vocabulary of the channel's model).
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::GyroTerm::Rate(nav_sensors::rate::RateTerm::Bias).ieee_name(), "bias (g-insensitive drift)");
    /// ```
    pub fn ieee_name(self) -> &'static str {
        match self {
            GyroTerm::Dtg(t) => t.ieee_name(),
            GyroTerm::Rate(t) => t.ieee_name(),
        }
    }

    /// Whether ground calibration determines this term.
    ///
    /// ```
    /// assert!(!nav_sensors::unit::GyroTerm::Rate(nav_sensors::rate::RateTerm::Temp).is_calibrated());
    /// ```
    pub fn is_calibrated(self) -> bool {
        match self {
            GyroTerm::Dtg(t) => t.is_calibrated(),
            GyroTerm::Rate(t) => t.is_calibrated(),
        }
    }
}

impl fmt::Display for GyroTerm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.id())
    }
}

impl Serialize for GyroTerm {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.id())
    }
}

/// What any gyro of a unit senses over one sample, in the unit frame: the
/// rate (deg/h), the specific force (g) and its within-interval covariance
/// (g²), the temperature about the reference (°C), and for a DTG the
/// mean-square 2N rate ((deg/s)², zero where unknown).
///
/// ```
/// use nav_sensors::unit::{Sensed, Unit};
/// let s = Sensed { specific_force_g: nalgebra::Vector3::new(0.0, 0.3, 1.0), ..Sensed::default() };
/// let tetra = Unit::builtin("tetra").unwrap();
/// let g_y = tetra.parse_term(0, "g_y").unwrap();
/// assert_eq!(tetra.gyros()[0].regressor(g_y, &s), 0.3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sensed {
    /// Angular rate in the unit frame, deg/h.
    pub rate_deg_h: Vector3<f64>,
    /// Specific force in the unit frame, g.
    pub specific_force_g: Vector3<f64>,
    /// Within-interval covariance of the specific force, unit frame, g².
    pub specific_force_cov_g2: Matrix3<f64>,
    /// Temperature minus the reference temperature, °C.
    pub temperature_delta_c: f64,
    /// A DTG's mean-square rate about I in the 2N band, (deg/s)².
    pub rate_2n_mean_square_deg2_s2: f64,
}

impl Gyro {
    /// The terms of this gyro's model, in its coefficient-table order.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::paper();
    /// assert_eq!(u.gyros()[0].terms().len(), 18);
    /// assert_eq!(nav_sensors::unit::Unit::builtin("triad").unwrap().gyros()[0].terms().len(), 12);
    /// ```
    pub fn terms(&self) -> Vec<GyroTerm> {
        match self.model {
            GyroModel::Dtg { .. } => DtgTerm::ALL.into_iter().map(GyroTerm::Dtg).collect(),
            GyroModel::Rate => RateTerm::ALL.into_iter().map(GyroTerm::Rate).collect(),
        }
    }

    /// Parses a term id of this gyro's model.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// assert_eq!(u.gyros()[0].parse_term("gg_yz").unwrap().id(), "gg_yz");
    /// assert!(u.gyros()[0].parse_term("g_S").is_err());
    /// ```
    pub fn parse_term(&self, id: &str) -> Result<GyroTerm, ParseNameError> {
        Ok(match self.model {
            GyroModel::Dtg { .. } => GyroTerm::Dtg(id.parse()?),
            GyroModel::Rate => GyroTerm::Rate(id.parse()?),
        })
    }

    /// The DTG input of this gyro for what it senses (`None` for a rate gyro).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::paper();
    /// let s = nav_sensors::unit::Sensed { specific_force_g: nalgebra::Vector3::z(), ..Default::default() };
    /// assert_eq!(u.gyros()[4].dtg_input(&s).unwrap().specific_force_g.i, 1.0); // Z
    /// ```
    pub fn dtg_input(&self, s: &Sensed) -> Option<DtgInput> {
        let axes = self.dtg_axes()?;
        let mut x = DtgInput {
            rate_deg_h: axes.resolve(&s.rate_deg_h),
            specific_force_g: axes.resolve(&s.specific_force_g),
            temperature_delta_c: s.temperature_delta_c,
            rate_2n_mean_square_deg2_s2: s.rate_2n_mean_square_deg2_s2,
            ..DtgInput::default()
        };
        x.specific_force_cov_g2 = crate::dtg::resolve_covariance(&axes, &s.specific_force_cov_g2);
        Some(x)
    }

    /// The rate-gyro input of this gyro for what it senses (`None` for a DTG).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// let s = nav_sensors::unit::Sensed { rate_deg_h: nalgebra::Vector3::new(0.0, 4.0, 0.0), ..Default::default() };
    /// assert_eq!(u.gyros()[1].rate_input(&s).unwrap().rate_i_deg_h, 4.0);
    /// ```
    pub fn rate_input(&self, s: &Sensed) -> Option<RateInput> {
        match self.model {
            GyroModel::Dtg { .. } => None,
            GyroModel::Rate => {
                let mut x = RateInput::sensed(&self.input, &s.rate_deg_h, &s.specific_force_g)
                    .with_covariance(&s.specific_force_cov_g2);
                x.temperature_delta_c = s.temperature_delta_c;
                Some(x)
            }
        }
    }

    /// A term's regressor for what this gyro senses, deg/h per coefficient
    /// unit. A term of the other model (which [`Gyro::parse_term`] never
    /// gives) has none: 0.
    ///
    /// ```
    /// use nav_sensors::unit::{Sensed, Unit};
    /// let paper = Unit::paper();
    /// let s = Sensed { specific_force_g: nalgebra::Vector3::new(0.0, 0.0, 2.0), ..Default::default() };
    /// let gg_ii = paper.parse_term(4, "gg_II").unwrap();
    /// assert_eq!(paper.gyros()[4].regressor(gg_ii, &s), 4.0);
    /// ```
    pub fn regressor(&self, term: GyroTerm, s: &Sensed) -> f64 {
        match (term, self.dtg_input(s), self.rate_input(s)) {
            (GyroTerm::Dtg(t), Some(x), _) => t.regressor(&x),
            (GyroTerm::Rate(t), _, Some(x)) => t.regressor(&x),
            _ => 0.0,
        }
    }
}

impl Unit {
    /// Parses a term id for gyro `channel` (index in file order).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("dual-triad").unwrap();
    /// assert_eq!(u.parse_term(3, "g_x").unwrap().unit(), "deg/h/g");
    /// ```
    #[track_caller]
    pub fn parse_term(&self, channel: usize, id: &str) -> Result<GyroTerm, ParseNameError> {
        self.gyros[channel].parse_term(id)
    }
}
