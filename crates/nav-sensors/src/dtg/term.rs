//! The deterministic terms of the DTG error model, with stable string ids.
//!
//! The ids are a contract shared with the application (`dtg-vib` uses them
//! for effect columns and diagnosis): never rename one.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::input::DtgInput;
use crate::geometry::ParseNameError;

/// One deterministic term of the DTG model (IEEE Std 813 naming).
///
/// Every term is linear in its coefficient: its drift contribution is
/// `coefficient × regressor`, with [`DtgTerm::regressor`] computed from the
/// rate, specific force and temperature resolved into the channel's (I, O, S)
/// frame, so the coefficient's unit is `deg/h` divided by the regressor's.
///
/// ```
/// use nav_sensors::dtg::DtgTerm;
/// let t: DtgTerm = "gg_IS".parse().unwrap();
/// assert_eq!(t, DtgTerm::GgIS);
/// assert_eq!(t.id(), "gg_IS");
/// assert_eq!(t.unit(), "deg/h/g²");
/// assert_eq!(serde_json::to_string(&t).unwrap(), "\"gg_IS\"");
/// assert!(DtgTerm::Temp.to_string() == "temp" && !DtgTerm::Temp.is_calibrated());
/// let err = "gg_XY".parse::<DtgTerm>().unwrap_err();
/// assert!(err.to_string().contains("gg_OS"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum DtgTerm {
    /// `bias`: g-insensitive drift, deg/h.
    #[serde(rename = "bias")]
    Bias,
    /// `scale_factor`: scale-factor error, ppm of ω_I.
    #[serde(rename = "scale_factor")]
    ScaleFactor,
    /// `misalignment_O`: input axis tilted toward O (rotation about S), µrad; couples ω_O.
    #[serde(rename = "misalignment_O")]
    MisalignmentO,
    /// `misalignment_S`: input axis tilted toward S (rotation about O), µrad; couples ω_S.
    #[serde(rename = "misalignment_S")]
    MisalignmentS,
    /// `g_I`: g-sensitive drift (mass unbalance / quadrature) along I, deg/h/g.
    #[serde(rename = "g_I")]
    GI,
    /// `g_O`: g-sensitive drift along O, deg/h/g.
    #[serde(rename = "g_O")]
    GO,
    /// `g_S`: g-sensitive drift along S (spin-axis mass unbalance), deg/h/g.
    #[serde(rename = "g_S")]
    GS,
    /// `gg_II`: anisoelastic (g²-sensitive) drift, f_I², deg/h/g².
    #[serde(rename = "gg_II")]
    GgII,
    /// `gg_OO`: anisoelastic drift, f_O², deg/h/g².
    #[serde(rename = "gg_OO")]
    GgOO,
    /// `gg_SS`: anisoelastic drift, f_S², deg/h/g².
    #[serde(rename = "gg_SS")]
    GgSS,
    /// `gg_IO`: anisoelastic drift, f_I·f_O, deg/h/g².
    #[serde(rename = "gg_IO")]
    GgIO,
    /// `gg_IS`: anisoelastic drift, f_I·f_S, deg/h/g².
    #[serde(rename = "gg_IS")]
    GgIS,
    /// `gg_OS`: anisoelastic drift, f_O·f_S, deg/h/g².
    #[serde(rename = "gg_OS")]
    GgOS,
    /// `ai_IO`: anisoinertia, ω_I·ω_O, deg/h/(deg/s)².
    #[serde(rename = "ai_IO")]
    AiIO,
    /// `ai_IS`: anisoinertia, ω_I·ω_S, deg/h/(deg/s)².
    #[serde(rename = "ai_IS")]
    AiIS,
    /// `ai_OS`: anisoinertia, ω_O·ω_S, deg/h/(deg/s)².
    #[serde(rename = "ai_OS")]
    AiOS,
    /// `temp`: drift temperature sensitivity, deg/h/°C about the reference temperature.
    #[serde(rename = "temp")]
    Temp,
    /// `rect_2n`: rectification of angular vibration at twice the spin
    /// frequency, deg/h/(deg/s)² of band-passed mean-square rate about I.
    #[serde(rename = "rect_2n")]
    Rect2N,
}

impl DtgTerm {
    /// All terms, in the order of the coefficient table.
    ///
    /// ```
    /// assert_eq!(nav_sensors::dtg::DtgTerm::ALL.len(), 18);
    /// ```
    pub const ALL: [DtgTerm; 18] = [
        DtgTerm::Bias,
        DtgTerm::ScaleFactor,
        DtgTerm::MisalignmentO,
        DtgTerm::MisalignmentS,
        DtgTerm::GI,
        DtgTerm::GO,
        DtgTerm::GS,
        DtgTerm::GgII,
        DtgTerm::GgOO,
        DtgTerm::GgSS,
        DtgTerm::GgIO,
        DtgTerm::GgIS,
        DtgTerm::GgOS,
        DtgTerm::AiIO,
        DtgTerm::AiIS,
        DtgTerm::AiOS,
        DtgTerm::Temp,
        DtgTerm::Rect2N,
    ];

    /// The terms driven by specific force: g-sensitive drift (mass
    /// unbalance, quadrature) along I, O, S and the six anisoelastic
    /// (g²-sensitive) products — what a vibration test excites.
    ///
    /// ```
    /// use nav_sensors::dtg::DtgTerm;
    /// assert!(DtgTerm::SPECIFIC_FORCE.iter().all(|t| t.unit().starts_with("deg/h/g")));
    /// ```
    pub const SPECIFIC_FORCE: [DtgTerm; 9] = [
        DtgTerm::GI,
        DtgTerm::GO,
        DtgTerm::GS,
        DtgTerm::GgII,
        DtgTerm::GgOO,
        DtgTerm::GgSS,
        DtgTerm::GgIO,
        DtgTerm::GgIS,
        DtgTerm::GgOS,
    ];

    /// The anisoinertia terms (products of rates about I, O, S).
    ///
    /// ```
    /// use nav_sensors::dtg::DtgTerm;
    /// assert!(DtgTerm::ANISOINERTIA.iter().all(|t| t.id().starts_with("ai_")));
    /// ```
    pub const ANISOINERTIA: [DtgTerm; 3] = [DtgTerm::AiIO, DtgTerm::AiIS, DtgTerm::AiOS];

    /// Position in [`DtgTerm::ALL`].
    ///
    /// ```
    /// assert_eq!(nav_sensors::dtg::DtgTerm::Rect2N.index(), 17);
    /// ```
    pub fn index(self) -> usize {
        self as usize
    }

    /// The stable string id.
    ///
    /// ```
    /// assert_eq!(nav_sensors::dtg::DtgTerm::MisalignmentO.id(), "misalignment_O");
    /// ```
    pub fn id(self) -> &'static str {
        match self {
            DtgTerm::Bias => "bias",
            DtgTerm::ScaleFactor => "scale_factor",
            DtgTerm::MisalignmentO => "misalignment_O",
            DtgTerm::MisalignmentS => "misalignment_S",
            DtgTerm::GI => "g_I",
            DtgTerm::GO => "g_O",
            DtgTerm::GS => "g_S",
            DtgTerm::GgII => "gg_II",
            DtgTerm::GgOO => "gg_OO",
            DtgTerm::GgSS => "gg_SS",
            DtgTerm::GgIO => "gg_IO",
            DtgTerm::GgIS => "gg_IS",
            DtgTerm::GgOS => "gg_OS",
            DtgTerm::AiIO => "ai_IO",
            DtgTerm::AiIS => "ai_IS",
            DtgTerm::AiOS => "ai_OS",
            DtgTerm::Temp => "temp",
            DtgTerm::Rect2N => "rect_2n",
        }
    }

    /// The physical name (IEEE Std 813 vocabulary).
    ///
    /// ```
    /// assert_eq!(nav_sensors::dtg::DtgTerm::GS.ieee_name(), "g-sensitive drift along the spin axis (mass unbalance)");
    /// ```
    pub fn ieee_name(self) -> &'static str {
        match self {
            DtgTerm::Bias => "bias (g-insensitive drift)",
            DtgTerm::ScaleFactor => "scale-factor error",
            DtgTerm::MisalignmentO => "input-axis misalignment toward the other input axis",
            DtgTerm::MisalignmentS => "input-axis misalignment toward the spin axis",
            DtgTerm::GI => "g-sensitive drift along the input axis (mass unbalance / quadrature)",
            DtgTerm::GO => "g-sensitive drift along the other input axis (quadrature)",
            DtgTerm::GS => "g-sensitive drift along the spin axis (mass unbalance)",
            DtgTerm::GgII => "anisoelastic (g²-sensitive) drift, input axis squared",
            DtgTerm::GgOO => "anisoelastic (g²-sensitive) drift, other input axis squared",
            DtgTerm::GgSS => "anisoelastic (g²-sensitive) drift, spin axis squared",
            DtgTerm::GgIO => "anisoelastic (g²-sensitive) drift, input × other input axis",
            DtgTerm::GgIS => "anisoelastic (g²-sensitive) drift, input × spin axis",
            DtgTerm::GgOS => "anisoelastic (g²-sensitive) drift, other input × spin axis",
            DtgTerm::AiIO => "anisoinertia drift, input × other input rate",
            DtgTerm::AiIS => "anisoinertia drift, input × spin-axis rate",
            DtgTerm::AiOS => "anisoinertia drift, other input × spin-axis rate",
            DtgTerm::Temp => "drift temperature sensitivity",
            DtgTerm::Rect2N => {
                "rectification of angular vibration at twice the spin frequency (2N)"
            }
        }
    }

    /// The coefficient's unit.
    ///
    /// ```
    /// assert_eq!(nav_sensors::dtg::DtgTerm::AiIO.unit(), "deg/h/(deg/s)²");
    /// ```
    pub fn unit(self) -> &'static str {
        match self {
            DtgTerm::Bias => "deg/h",
            DtgTerm::ScaleFactor => "ppm",
            DtgTerm::MisalignmentO | DtgTerm::MisalignmentS => "µrad",
            DtgTerm::GI | DtgTerm::GO | DtgTerm::GS => "deg/h/g",
            DtgTerm::GgII
            | DtgTerm::GgOO
            | DtgTerm::GgSS
            | DtgTerm::GgIO
            | DtgTerm::GgIS
            | DtgTerm::GgOS => "deg/h/g²",
            DtgTerm::AiIO | DtgTerm::AiIS | DtgTerm::AiOS | DtgTerm::Rect2N => "deg/h/(deg/s)²",
            DtgTerm::Temp => "deg/h/°C",
        }
    }

    /// Whether ground calibration determines this term. `temp` and `rect_2n`
    /// are modelled in the truth but never part of a calibration file.
    ///
    /// ```
    /// use nav_sensors::dtg::DtgTerm;
    /// assert!(DtgTerm::GgIS.is_calibrated() && !DtgTerm::Rect2N.is_calibrated());
    /// ```
    pub fn is_calibrated(self) -> bool {
        !matches!(self, DtgTerm::Temp | DtgTerm::Rect2N)
    }

    /// Whether the term is quadratic in specific force or rate (so that, at a
    /// high rate, vibration rectifies through it).
    ///
    /// ```
    /// use nav_sensors::dtg::DtgTerm;
    /// assert!(DtgTerm::GgOO.is_quadratic() && !DtgTerm::GO.is_quadratic());
    /// ```
    pub fn is_quadratic(self) -> bool {
        matches!(
            self,
            DtgTerm::GgII
                | DtgTerm::GgOO
                | DtgTerm::GgSS
                | DtgTerm::GgIO
                | DtgTerm::GgIS
                | DtgTerm::GgOS
                | DtgTerm::AiIO
                | DtgTerm::AiIS
                | DtgTerm::AiOS
                | DtgTerm::Rect2N
        )
    }

    /// The regressor: the term's drift per unit coefficient, in deg/h per
    /// coefficient unit.
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgInput, DtgTerm};
    /// use nav_sensors::geometry::Ios;
    /// let x = DtgInput {
    ///     rate_deg_h: Ios { i: 3600.0, o: 7200.0, s: 0.0 },
    ///     specific_force_g: Ios { i: 0.5, o: 0.0, s: 2.0 },
    ///     ..DtgInput::default()
    /// };
    /// assert_eq!(DtgTerm::GgIS.regressor(&x), 1.0);        // g_I·g_S
    /// assert_eq!(DtgTerm::AiIO.regressor(&x), 2.0);        // (1 deg/s)·(2 deg/s)
    /// assert_eq!(DtgTerm::ScaleFactor.regressor(&x), 3600.0e-6);
    /// ```
    #[inline]
    pub fn regressor(self, x: &DtgInput) -> f64 {
        let w = &x.rate_deg_h;
        let f = &x.specific_force_g;
        const PER_S: f64 = 1.0 / 3600.0;
        match self {
            DtgTerm::Bias => 1.0,
            DtgTerm::ScaleFactor => 1e-6 * w.i,
            DtgTerm::MisalignmentO => 1e-6 * w.o,
            DtgTerm::MisalignmentS => 1e-6 * w.s,
            DtgTerm::GI => f.i,
            DtgTerm::GO => f.o,
            DtgTerm::GS => f.s,
            DtgTerm::GgII => f.i * f.i + x.specific_force_cov_g2[0],
            DtgTerm::GgOO => f.o * f.o + x.specific_force_cov_g2[1],
            DtgTerm::GgSS => f.s * f.s + x.specific_force_cov_g2[2],
            DtgTerm::GgIO => f.i * f.o + x.specific_force_cov_g2[3],
            DtgTerm::GgIS => f.i * f.s + x.specific_force_cov_g2[4],
            DtgTerm::GgOS => f.o * f.s + x.specific_force_cov_g2[5],
            DtgTerm::AiIO => (w.i * PER_S) * (w.o * PER_S),
            DtgTerm::AiIS => (w.i * PER_S) * (w.s * PER_S),
            DtgTerm::AiOS => (w.o * PER_S) * (w.s * PER_S),
            DtgTerm::Temp => x.temperature_delta_c,
            DtgTerm::Rect2N => x.rate_2n_mean_square_deg2_s2,
        }
    }

    /// All eighteen regressors at once, in [`DtgTerm::ALL`] order.
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgInput, DtgTerm};
    /// let r = DtgTerm::regressors(&DtgInput::default());
    /// assert_eq!(r[DtgTerm::Bias.index()], 1.0);
    /// assert_eq!(r.iter().sum::<f64>(), 1.0);
    /// ```
    #[inline]
    pub fn regressors(x: &DtgInput) -> [f64; 18] {
        DtgTerm::ALL.map(|t| t.regressor(x))
    }
}

impl fmt::Display for DtgTerm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.id())
    }
}

impl FromStr for DtgTerm {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ParseNameError::lookup("DTG term", &DtgTerm::ALL, DtgTerm::id, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_the_contract() {
        let ids: Vec<&str> = DtgTerm::ALL.iter().map(|t| t.id()).collect();
        assert_eq!(
            ids,
            [
                "bias",
                "scale_factor",
                "misalignment_O",
                "misalignment_S",
                "g_I",
                "g_O",
                "g_S",
                "gg_II",
                "gg_OO",
                "gg_SS",
                "gg_IO",
                "gg_IS",
                "gg_OS",
                "ai_IO",
                "ai_IS",
                "ai_OS",
                "temp",
                "rect_2n"
            ]
        );
        for t in DtgTerm::ALL {
            assert_eq!(t.id().parse::<DtgTerm>().unwrap(), t);
            assert_eq!(DtgTerm::ALL[t.index()], t);
            let json = serde_json::to_string(&t).unwrap();
            assert_eq!(json, format!("\"{}\"", t.id()));
            assert_eq!(serde_json::from_str::<DtgTerm>(&json).unwrap(), t);
        }
    }
}
