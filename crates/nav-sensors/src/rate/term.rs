//! The deterministic terms of the rate-gyro model, with stable string ids.
//!
//! The ids are a user contract (`--add-effect G2=g_y`, JSON keys, reports):
//! never rename one.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::input::RateInput;
use crate::geometry::ParseNameError;

/// One deterministic term of a rate gyro's model (IEEE Std 952 / 1431
/// vocabulary), acceleration terms in the unit frame.
///
/// Every term is linear in its coefficient: its drift is `coefficient ×
/// regressor` ([`RateTerm::regressor`]), so the coefficient's unit is deg/h
/// divided by the regressor's.
///
/// ```
/// use nav_sensors::rate::RateTerm;
/// let t: RateTerm = "g_y".parse().unwrap();
/// assert_eq!(t, RateTerm::GY);
/// assert_eq!((t.id(), t.unit()), ("g_y", "deg/h/g"));
/// assert_eq!(RateTerm::GgXz.unit(), "deg/h/g²");
/// assert_eq!(serde_json::to_string(&RateTerm::GgXz).unwrap(), "\"gg_xz\"");
/// let err = "g_I".parse::<RateTerm>().unwrap_err();
/// assert!(err.to_string().starts_with("unknown rate-gyro term 'g_I'"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum RateTerm {
    /// `bias`: g-insensitive drift, deg/h.
    #[serde(rename = "bias")]
    Bias,
    /// `scale_factor`: scale-factor error, ppm of ω_I.
    #[serde(rename = "scale_factor")]
    ScaleFactor,
    /// `g_x`: acceleration-sensitive drift, specific force along x, deg/h/g.
    #[serde(rename = "g_x")]
    GX,
    /// `g_y`: acceleration-sensitive drift along y, deg/h/g.
    #[serde(rename = "g_y")]
    GY,
    /// `g_z`: acceleration-sensitive drift along z, deg/h/g.
    #[serde(rename = "g_z")]
    GZ,
    /// `gg_xx`: vibration rectification, f_x², deg/h/g².
    #[serde(rename = "gg_xx")]
    GgXx,
    /// `gg_yy`: vibration rectification, f_y², deg/h/g².
    #[serde(rename = "gg_yy")]
    GgYy,
    /// `gg_zz`: vibration rectification, f_z², deg/h/g².
    #[serde(rename = "gg_zz")]
    GgZz,
    /// `gg_xy`: vibration rectification, f_x·f_y, deg/h/g².
    #[serde(rename = "gg_xy")]
    GgXy,
    /// `gg_xz`: vibration rectification, f_x·f_z, deg/h/g².
    #[serde(rename = "gg_xz")]
    GgXz,
    /// `gg_yz`: vibration rectification, f_y·f_z, deg/h/g².
    #[serde(rename = "gg_yz")]
    GgYz,
    /// `temp`: drift temperature sensitivity, deg/h/°C about the reference.
    #[serde(rename = "temp")]
    Temp,
}

impl RateTerm {
    /// All terms, in the order of the coefficient table.
    ///
    /// ```
    /// assert_eq!(nav_sensors::rate::RateTerm::ALL.len(), 12);
    /// ```
    pub const ALL: [RateTerm; 12] = [
        RateTerm::Bias,
        RateTerm::ScaleFactor,
        RateTerm::GX,
        RateTerm::GY,
        RateTerm::GZ,
        RateTerm::GgXx,
        RateTerm::GgYy,
        RateTerm::GgZz,
        RateTerm::GgXy,
        RateTerm::GgXz,
        RateTerm::GgYz,
        RateTerm::Temp,
    ];

    /// The terms driven by specific force (what a vibration test excites),
    /// in the order of the DTG's [`crate::dtg::DtgTerm::SPECIFIC_FORCE`]:
    /// the three linear terms, then the six products.
    ///
    /// ```
    /// use nav_sensors::rate::RateTerm;
    /// assert!(RateTerm::SPECIFIC_FORCE.iter().all(|t| t.unit().starts_with("deg/h/g")));
    /// ```
    pub const SPECIFIC_FORCE: [RateTerm; 9] = [
        RateTerm::GX,
        RateTerm::GY,
        RateTerm::GZ,
        RateTerm::GgXx,
        RateTerm::GgYy,
        RateTerm::GgZz,
        RateTerm::GgXy,
        RateTerm::GgXz,
        RateTerm::GgYz,
    ];

    /// Position in [`RateTerm::ALL`].
    ///
    /// ```
    /// assert_eq!(nav_sensors::rate::RateTerm::Temp.index(), 11);
    /// ```
    pub fn index(self) -> usize {
        self as usize
    }

    /// The stable string id.
    ///
    /// ```
    /// assert_eq!(nav_sensors::rate::RateTerm::GgYz.id(), "gg_yz");
    /// ```
    pub fn id(self) -> &'static str {
        match self {
            RateTerm::Bias => "bias",
            RateTerm::ScaleFactor => "scale_factor",
            RateTerm::GX => "g_x",
            RateTerm::GY => "g_y",
            RateTerm::GZ => "g_z",
            RateTerm::GgXx => "gg_xx",
            RateTerm::GgYy => "gg_yy",
            RateTerm::GgZz => "gg_zz",
            RateTerm::GgXy => "gg_xy",
            RateTerm::GgXz => "gg_xz",
            RateTerm::GgYz => "gg_yz",
            RateTerm::Temp => "temp",
        }
    }

    /// The physical name (IEEE Std 952 / 1431 vocabulary).
    ///
    /// ```
    /// assert_eq!(nav_sensors::rate::RateTerm::GX.ieee_name(), "acceleration-sensitive drift, specific force along the unit's x axis");
    /// ```
    pub fn ieee_name(self) -> &'static str {
        match self {
            RateTerm::Bias => "bias (g-insensitive drift)",
            RateTerm::ScaleFactor => "scale-factor error",
            RateTerm::GX => "acceleration-sensitive drift, specific force along the unit's x axis",
            RateTerm::GY => "acceleration-sensitive drift, specific force along the unit's y axis",
            RateTerm::GZ => "acceleration-sensitive drift, specific force along the unit's z axis",
            RateTerm::GgXx => "vibration rectification (g²-sensitive drift), x squared",
            RateTerm::GgYy => "vibration rectification (g²-sensitive drift), y squared",
            RateTerm::GgZz => "vibration rectification (g²-sensitive drift), z squared",
            RateTerm::GgXy => "vibration rectification (g²-sensitive drift), x × y",
            RateTerm::GgXz => "vibration rectification (g²-sensitive drift), x × z",
            RateTerm::GgYz => "vibration rectification (g²-sensitive drift), y × z",
            RateTerm::Temp => "drift temperature sensitivity",
        }
    }

    /// The coefficient's unit.
    ///
    /// ```
    /// assert_eq!(nav_sensors::rate::RateTerm::ScaleFactor.unit(), "ppm");
    /// ```
    pub fn unit(self) -> &'static str {
        match self {
            RateTerm::Bias => "deg/h",
            RateTerm::ScaleFactor => "ppm",
            RateTerm::GX | RateTerm::GY | RateTerm::GZ => "deg/h/g",
            RateTerm::GgXx
            | RateTerm::GgYy
            | RateTerm::GgZz
            | RateTerm::GgXy
            | RateTerm::GgXz
            | RateTerm::GgYz => "deg/h/g²",
            RateTerm::Temp => "deg/h/°C",
        }
    }

    /// Whether ground calibration determines this term (all but `temp`, as
    /// for the DTG).
    ///
    /// ```
    /// use nav_sensors::rate::RateTerm;
    /// assert!(RateTerm::GgXx.is_calibrated() && !RateTerm::Temp.is_calibrated());
    /// ```
    pub fn is_calibrated(self) -> bool {
        self != RateTerm::Temp
    }

    /// Whether the term is quadratic in specific force (vibration rectifies
    /// through it).
    ///
    /// ```
    /// use nav_sensors::rate::RateTerm;
    /// assert!(RateTerm::GgXy.is_quadratic() && !RateTerm::GY.is_quadratic());
    /// ```
    pub fn is_quadratic(self) -> bool {
        RateTerm::SPECIFIC_FORCE[3..].contains(&self)
    }

    /// The regressor: the term's drift per unit coefficient, deg/h per
    /// coefficient unit. The one definition the simulator's truth and the
    /// diagnosis's candidates share.
    ///
    /// ```
    /// use nav_sensors::rate::{RateInput, RateTerm};
    /// let x = RateInput {
    ///     rate_i_deg_h: 3600.0,
    ///     specific_force_g: nalgebra::Vector3::new(0.5, 0.0, 2.0),
    ///     specific_force_cov_g2: [0.0, 0.0, 0.0, 0.0, 0.25, 0.0],
    ///     ..RateInput::default()
    /// };
    /// assert_eq!(RateTerm::GgXz.regressor(&x), 1.25); // f_x·f_z + cov(f_x, f_z)
    /// assert_eq!(RateTerm::GZ.regressor(&x), 2.0);
    /// assert_eq!(RateTerm::ScaleFactor.regressor(&x), 3600.0e-6);
    /// ```
    #[inline]
    pub fn regressor(self, x: &RateInput) -> f64 {
        let f = &x.specific_force_g;
        let c = &x.specific_force_cov_g2;
        match self {
            RateTerm::Bias => 1.0,
            RateTerm::ScaleFactor => 1e-6 * x.rate_i_deg_h,
            RateTerm::GX => f.x,
            RateTerm::GY => f.y,
            RateTerm::GZ => f.z,
            RateTerm::GgXx => f.x * f.x + c[0],
            RateTerm::GgYy => f.y * f.y + c[1],
            RateTerm::GgZz => f.z * f.z + c[2],
            RateTerm::GgXy => f.x * f.y + c[3],
            RateTerm::GgXz => f.x * f.z + c[4],
            RateTerm::GgYz => f.y * f.z + c[5],
            RateTerm::Temp => x.temperature_delta_c,
        }
    }

    /// All twelve regressors at once, in [`RateTerm::ALL`] order.
    ///
    /// ```
    /// use nav_sensors::rate::{RateInput, RateTerm};
    /// let r = RateTerm::regressors(&RateInput::default());
    /// assert_eq!(r.iter().sum::<f64>(), 1.0); // the bias alone
    /// ```
    #[inline]
    pub fn regressors(x: &RateInput) -> [f64; 12] {
        RateTerm::ALL.map(|t| t.regressor(x))
    }
}

impl fmt::Display for RateTerm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.id())
    }
}

impl FromStr for RateTerm {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ParseNameError::lookup("rate-gyro term", &RateTerm::ALL, RateTerm::id, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_the_contract() {
        let ids: Vec<&str> = RateTerm::ALL.iter().map(|t| t.id()).collect();
        assert_eq!(
            ids,
            [
                "bias",
                "scale_factor",
                "g_x",
                "g_y",
                "g_z",
                "gg_xx",
                "gg_yy",
                "gg_zz",
                "gg_xy",
                "gg_xz",
                "gg_yz",
                "temp"
            ]
        );
        for t in RateTerm::ALL {
            assert_eq!(t.id().parse::<RateTerm>().unwrap(), t);
            assert_eq!(RateTerm::ALL[t.index()], t);
            let json = serde_json::to_string(&t).unwrap();
            assert_eq!(json, format!("\"{}\"", t.id()));
        }
    }
}
