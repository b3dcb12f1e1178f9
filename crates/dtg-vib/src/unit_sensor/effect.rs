//! The effects of any unit's channel, by id: a `dtg` channel's IEEE Std 813
//! terms in its own (I, O, S) axes (`g_I`, `gg_IS`, `ai_OS`, …), a
//! `rate` channel's IEEE Std 952 / 1431 g- and g²-sensitivities in the unit
//! frame (`g_x` … `gg_yz`), and `col:NAME` for the record's extra columns.
//! The ids of the two models are disjoint (upper-case axes for a DTG,
//! lower-case for the unit frame), so an id alone says which term it is.
//! Any channel also takes the dynamic effects ([`Dynamic`]: `sf`, `ma_x`,
//! `acc:NAME`, each with an optional `@LAG`).

use super::dynamic::{Dynamic, DynamicError};
use nav_sensors::dtg::DtgTerm;
use nav_sensors::rate::RateTerm;
use nav_sensors::unit::{GyroModel, GyroTerm};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;

/// One effect of a unit's channel.
///
/// ```
/// use dtg_vib::unit_sensor::UnitEffect;
/// let e: UnitEffect = "g_y".parse().unwrap();
/// assert_eq!((e.id(), e.unit()), ("g_y".to_string(), "deg/h/g".to_string()));
/// let d: UnitEffect = "gg_IS".parse().unwrap();
/// assert_eq!(d.unit(), "deg/h/g²");
/// assert_eq!("col:temp".parse::<UnitEffect>().unwrap().unit(), "deg/h/°C");
/// assert!("g_q".parse::<UnitEffect>().is_err());
/// assert_eq!(serde_json::to_string(&e).unwrap(), "\"g_y\"");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum UnitEffect {
    /// A term of the channel's model.
    Term(GyroTerm),
    /// An extra numeric column of the record, taken as is, in whatever
    /// unit it is logged.
    Column(String),
    /// The unit's temperature column (`columns.temperature`, °C whatever
    /// it is called; `temp` for a unit that names none), taken as is.
    Temperature(String),
    /// A response to the rate or to an accelerometer, at a lag.
    Dynamic(Dynamic),
}

/// The DTG terms that can be effects: those a vibration test excites through
/// specific force or rate. Scale factor and misalignment need a varying rate
/// reference, temperature enters as `col:temp`, and 2N rectification needs
/// angular vibration the 50-Hz record does not carry.
pub const TERM_EFFECTS: [DtgTerm; 12] = {
    let mut out = [DtgTerm::Bias; 12];
    let mut i = 0;
    while i < 9 {
        out[i] = DtgTerm::SPECIFIC_FORCE[i];
        i += 1;
    }
    while i < 12 {
        out[i] = DtgTerm::ANISOINERTIA[i - 9];
        i += 1;
    }
    out
};

/// Prefix of the ids of extra-column effects.
pub const COLUMN_PREFIX: &str = "col:";

/// Anisoinertia (rate-product) effects are observable only when the angular
/// rate varies by more than this (deg/s, standard deviation of any axis): in
/// a stationary vibration test the rate is Earth rate plus gyro noise and
/// drift, and a product of those would only fit the gyros' own errors.
pub const ANISOINERTIA_MIN_RATE_DEG_S: f64 = 0.1;

/// The rate-gyro terms that can be effects: those a vibration test excites
/// through specific force (the bias is every model's; scale factor needs a
/// varying rate reference; temperature enters as `col:NAME`).
pub const RATE_EFFECTS: [RateTerm; 9] = RateTerm::SPECIFIC_FORCE;

/// An effect id that could not be understood, or one of the other model.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum UnitEffectError {
    /// Not a known id.
    #[error("unknown effect '{given}' (rate gyros: {}; dtg channels: {}; any channel: sf, ma_x, ma_y, ma_z, delay, acc:ACCEL, each with an optional @LAG; col:NAME for an extra record column)", rate_ids().join(", "), dtg_ids().join(", "))]
    Unknown {
        /// What was given.
        given: String,
    },
    /// A dynamic effect's lag out of range.
    #[error(transparent)]
    Dynamic(#[from] DynamicError),
    /// `col:` with no name.
    #[error("effect '{given}' names no column: write col:NAME, e.g. col:temp")]
    EmptyColumn {
        /// What was given.
        given: String,
    },
    /// A term of the other gyro model.
    #[error("effect '{id}' is not a term of channel {channel}, a \"{model}\" gyro: its terms are {}, or col:NAME", valid.join(", "))]
    WrongModel {
        /// The channel.
        channel: String,
        /// Its model (`rate`, `dtg`).
        model: &'static str,
        /// The id given.
        id: String,
        /// The ids it takes.
        valid: Vec<&'static str>,
    },
    /// A dynamic effect the channel cannot take.
    #[error("effect '{id}' does not apply to channel {channel}: take one of {}", valid.join(", "))]
    WrongDynamic {
        /// The channel.
        channel: String,
        /// The id given.
        id: String,
        /// What it takes instead.
        valid: Vec<String>,
    },
    /// A `CHANNEL=ID` whose channel the unit has not.
    #[error("'{given}': unknown channel '{channel}' (the unit's channels: {})", valid.join(", "))]
    UnknownChannel {
        /// The argument.
        given: String,
        /// The channel named.
        channel: String,
        /// The unit's channels.
        valid: Vec<String>,
    },
    /// A `CHANNEL=ID` argument without `=`.
    #[error("'{given}' is not CHANNEL=ID (e.g. g2=g_y)")]
    NotAPair {
        /// The argument.
        given: String,
    },
    /// `col:NAME` where the record has no such extra column.
    #[error("effect 'col:{name}': the record has no extra column '{name}' (extra columns: {})", if available.is_empty() { "none".to_string() } else { available.join(", ") })]
    MissingColumn {
        /// The column.
        name: String,
        /// The record's extra columns.
        available: Vec<String>,
    },
}

fn rate_ids() -> Vec<&'static str> {
    RATE_EFFECTS.iter().map(|t| t.id()).collect()
}

fn dtg_ids() -> Vec<&'static str> {
    TERM_EFFECTS.iter().map(|t| t.id()).collect()
}

impl UnitEffect {
    /// The stable id.
    pub fn id(&self) -> String {
        match self {
            UnitEffect::Term(t) => t.id().to_string(),
            UnitEffect::Column(c) | UnitEffect::Temperature(c) => format!("{COLUMN_PREFIX}{c}"),
            UnitEffect::Dynamic(d) => d.to_string(),
        }
    }

    /// The physical name (IEEE vocabulary of the channel's model).
    pub fn description(&self) -> String {
        match self {
            UnitEffect::Term(t) => t.ieee_name().to_string(),
            UnitEffect::Column(c) => format!("sensitivity to the record's '{c}' column"),
            UnitEffect::Temperature(c) => {
                format!("thermal sensitivity to column '{c}', the unit's temperature")
            }
            UnitEffect::Dynamic(d) => d.description(),
        }
    }

    /// The coefficient's unit (deg/h per regressor unit).
    pub fn unit(&self) -> String {
        match self {
            UnitEffect::Term(t) => t.unit().to_string(),
            UnitEffect::Temperature(_) => "deg/h/°C".to_string(),
            UnitEffect::Column(c) => format!("deg/h per unit of {c}"),
            UnitEffect::Dynamic(d) => d.unit().to_string(),
        }
    }

    /// The effect of an extra column `name`: the temperature effect when it
    /// is `unit`'s temperature column (`Unit::column_unit` says °C), a
    /// plain column otherwise. Without a unit (an id read alone), `temp` is
    /// the temperature, as in a unit that names no temperature column.
    ///
    /// ```
    /// use dtg_vib::unit_sensor::UnitEffect;
    /// use nav_sensors::unit::Unit;
    /// let toml = Unit::builtin_toml("triad").unwrap().replace("time = \"t\"", "time = \"t\"\ntemperature = \"board_temp\"");
    /// let unit = Unit::from_toml(&toml, "u.toml").unwrap();
    /// assert_eq!(UnitEffect::column("board_temp", Some(&unit)).unit(), "deg/h/°C");
    /// assert_eq!(UnitEffect::column("temp", Some(&unit)).unit(), "deg/h per unit of temp");
    /// assert_eq!(UnitEffect::column("temp", None).unit(), "deg/h/°C");
    /// ```
    pub fn column(name: &str, unit: Option<&nav_sensors::unit::Unit>) -> UnitEffect {
        let celsius = match unit {
            Some(u) => u.column_unit(name) == Some("°C"),
            None => name == "temp",
        };
        match celsius {
            true => UnitEffect::Temperature(name.to_string()),
            false => UnitEffect::Column(name.to_string()),
        }
    }

    /// The effect as `unit` reads it: a column's role from the unit file
    /// ([`UnitEffect::column`]); every other effect as it is. An id read
    /// alone (a model file, a flag) is resolved so before use.
    pub fn resolved(self, unit: &nav_sensors::unit::Unit) -> UnitEffect {
        match self {
            UnitEffect::Column(c) | UnitEffect::Temperature(c) => {
                UnitEffect::column(&c, Some(unit))
            }
            e => e,
        }
    }

    /// The record column the effect reads, if it is a column's.
    pub fn column_name(&self) -> Option<&str> {
        match self {
            UnitEffect::Column(c) | UnitEffect::Temperature(c) => Some(c),
            UnitEffect::Term(_) | UnitEffect::Dynamic(_) => None,
        }
    }

    /// The term effects a gyro of this model takes, in ranking order.
    ///
    /// ```
    /// use nav_sensors::unit::GyroModel;
    /// assert_eq!(dtg_vib::unit_sensor::UnitEffect::terms_of(&GyroModel::Rate).len(), 9);
    /// ```
    pub fn terms_of(model: &GyroModel) -> Vec<UnitEffect> {
        match model {
            GyroModel::Rate => RATE_EFFECTS
                .iter()
                .map(|&t| UnitEffect::Term(GyroTerm::Rate(t)))
                .collect(),
            GyroModel::Dtg { .. } => TERM_EFFECTS
                .iter()
                .map(|&t| UnitEffect::Term(GyroTerm::Dtg(t)))
                .collect(),
        }
    }

    /// Whether a gyro of this model takes the effect.
    pub fn fits(&self, model: &GyroModel) -> bool {
        match self {
            UnitEffect::Column(_) | UnitEffect::Temperature(_) | UnitEffect::Dynamic(_) => true,
            UnitEffect::Term(GyroTerm::Rate(_)) => matches!(model, GyroModel::Rate),
            UnitEffect::Term(GyroTerm::Dtg(_)) => matches!(model, GyroModel::Dtg { .. }),
        }
    }

    /// Parses a comma-separated list; `bias` is accepted and ignored (every
    /// model has one), duplicates are dropped, order is kept.
    ///
    /// ```
    /// let e = dtg_vib::unit_sensor::UnitEffect::parse_list("bias,g_x, g_x,col:temp").unwrap();
    /// assert_eq!(e.len(), 2);
    /// ```
    pub fn parse_list(list: &str) -> Result<Vec<UnitEffect>, UnitEffectError> {
        let mut out: Vec<UnitEffect> = Vec::new();
        for item in list
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty() && *s != "bias")
        {
            let e: UnitEffect = item.parse()?;
            if !out.contains(&e) {
                out.push(e);
            }
        }
        Ok(out)
    }
}

impl fmt::Display for UnitEffect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.id())
    }
}

impl std::str::FromStr for UnitEffect {
    type Err = UnitEffectError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        if let Some(name) = s.strip_prefix(COLUMN_PREFIX) {
            if name.trim().is_empty() {
                return Err(UnitEffectError::EmptyColumn { given: s.into() });
            }
            return Ok(UnitEffect::column(name.trim(), None));
        }
        if let Some(t) = TERM_EFFECTS.iter().find(|t| t.id() == s) {
            return Ok(UnitEffect::Term(GyroTerm::Dtg(*t)));
        }
        if let Some(t) = RATE_EFFECTS.iter().find(|t| t.id() == s) {
            return Ok(UnitEffect::Term(GyroTerm::Rate(*t)));
        }
        match s.parse::<Dynamic>() {
            Ok(d) => Ok(UnitEffect::Dynamic(d)),
            Err(DynamicError::Unknown(_)) => Err(UnitEffectError::Unknown { given: s.into() }),
            Err(e) => Err(e.into()),
        }
    }
}

impl Serialize for UnitEffect {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.id())
    }
}

impl<'de> Deserialize<'de> for UnitEffect {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

impl sysid::Effect for UnitEffect {
    fn id(&self) -> String {
        UnitEffect::id(self)
    }
    fn unit(&self) -> String {
        UnitEffect::unit(self)
    }
    fn description(&self) -> String {
        UnitEffect::description(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_id_round_trips_and_the_models_do_not_share_one() {
        for model in [
            GyroModel::Rate,
            nav_sensors::unit::Unit::paper().gyros()[0].model,
        ] {
            for e in UnitEffect::terms_of(&model) {
                assert_eq!(e.id().parse::<UnitEffect>().unwrap(), e);
                assert!(e.fits(&model));
            }
        }
        assert!(rate_ids().iter().all(|r| !dtg_ids().contains(r)));
        let msg = "gg_q".parse::<UnitEffect>().unwrap_err().to_string();
        assert!(msg.contains("g_x") && msg.contains("gg_IS") && msg.contains("col:NAME"));
    }
}
