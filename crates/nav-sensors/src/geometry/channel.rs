//! Names of the six gyro channels, the three DTGs and the three cluster axes.
//!
//! The string names are a user contract: they are the record's column names
//! (`X,X1,Y,Y1,Z,Z1`, `ax,ay,az`) and the ids other tools put on their command
//! lines, so they never change.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// One of the six rate channels of the three two-axis DTGs (paper eq. 4).
///
/// `X`, `Y`, `Z` sense along a cluster axis; `X1`, `Y1`, `Z1` are the second
/// input axes of the same DTGs, skewed by 45°.
///
/// ```
/// use nav_sensors::geometry::{Channel, Dtg};
/// let names: Vec<&str> = Channel::ALL.iter().map(|c| c.name()).collect();
/// assert_eq!(names, ["X", "X1", "Y", "Y1", "Z", "Z1"]);
/// assert_eq!("Y1".parse::<Channel>().unwrap(), Channel::Y1);
/// assert_eq!(Channel::Z1.dtg(), Dtg::Z);
/// let err = "Q".parse::<Channel>().unwrap_err();
/// assert_eq!(err.to_string(), "unknown channel 'Q' (valid: X, X1, Y, Y1, Z, Z1)");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Channel {
    X,
    X1,
    Y,
    Y1,
    Z,
    Z1,
}

impl Channel {
    /// All channels in the record's column order (and the row order of eq. 4).
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Channel::ALL[4], nav_sensors::geometry::Channel::Z);
    /// ```
    pub const ALL: [Channel; 6] = [
        Channel::X,
        Channel::X1,
        Channel::Y,
        Channel::Y1,
        Channel::Z,
        Channel::Z1,
    ];

    /// The stable name, also the record's column name.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Channel::X1.name(), "X1");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Channel::X => "X",
            Channel::X1 => "X1",
            Channel::Y => "Y",
            Channel::Y1 => "Y1",
            Channel::Z => "Z",
            Channel::Z1 => "Z1",
        }
    }

    /// Position in [`Channel::ALL`] (0..6), the row of eq. 4.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Channel::Y1.index(), 3);
    /// ```
    pub fn index(self) -> usize {
        self as usize
    }

    /// The DTG this channel belongs to.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Dtg};
    /// assert_eq!(Channel::X1.dtg(), Dtg::X);
    /// ```
    pub fn dtg(self) -> Dtg {
        match self {
            Channel::X | Channel::X1 => Dtg::X,
            Channel::Y | Channel::Y1 => Dtg::Y,
            Channel::Z | Channel::Z1 => Dtg::Z,
        }
    }

    /// The other channel of the same DTG (its input axis is this channel's O axis).
    ///
    /// ```
    /// use nav_sensors::geometry::Channel;
    /// assert_eq!(Channel::Z.partner(), Channel::Z1);
    /// ```
    pub fn partner(self) -> Channel {
        match self {
            Channel::X => Channel::X1,
            Channel::X1 => Channel::X,
            Channel::Y => Channel::Y1,
            Channel::Y1 => Channel::Y,
            Channel::Z => Channel::Z1,
            Channel::Z1 => Channel::Z,
        }
    }
}

impl fmt::Display for Channel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A channel or axis name that is not one of the valid ones.
///
/// ```
/// let err = "x2".parse::<nav_sensors::geometry::Channel>().unwrap_err();
/// assert_eq!(err.given, "x2");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {kind} '{given}' (valid: {})", valid.join(", "))]
pub struct ParseNameError {
    /// What was being parsed ("channel", "axis", "DTG").
    pub kind: &'static str,
    /// The text given.
    pub given: String,
    /// The valid names.
    pub valid: Vec<&'static str>,
}

impl ParseNameError {
    /// The one of `all` whose `name` is `given` (trimmed), or the error that
    /// lists every valid name: the parser of every name set that matches
    /// exactly (channels, DTG and rate-gyro terms).
    pub(crate) fn lookup<T: Copy>(
        kind: &'static str,
        all: &[T],
        name: fn(T) -> &'static str,
        given: &str,
    ) -> Result<T, Self> {
        all.iter()
            .copied()
            .find(|&t| name(t) == given.trim())
            .ok_or_else(|| ParseNameError {
                kind,
                given: given.to_string(),
                valid: all.iter().map(|&t| name(t)).collect(),
            })
    }
}

impl FromStr for Channel {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ParseNameError::lookup("channel", &Channel::ALL, Channel::name, s)
    }
}

/// One of the three two-axis DTGs, named after its principal input axis.
///
/// ```
/// use nav_sensors::geometry::{Channel, Dtg};
/// assert_eq!(Dtg::Y.channels(), [Channel::Y, Channel::Y1]);
/// assert_eq!(Dtg::Z.to_string(), "Z");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Dtg {
    X,
    Y,
    Z,
}

impl Dtg {
    /// The three DTGs.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Dtg::ALL.len(), 3);
    /// ```
    pub const ALL: [Dtg; 3] = [Dtg::X, Dtg::Y, Dtg::Z];

    /// The principal channel and the skewed channel of this DTG.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Dtg};
    /// assert_eq!(Dtg::X.channels(), [Channel::X, Channel::X1]);
    /// ```
    pub fn channels(self) -> [Channel; 2] {
        match self {
            Dtg::X => [Channel::X, Channel::X1],
            Dtg::Y => [Channel::Y, Channel::Y1],
            Dtg::Z => [Channel::Z, Channel::Z1],
        }
    }

    /// The stable name ("X", "Y", "Z").
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Dtg::X.name(), "X");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Dtg::X => "X",
            Dtg::Y => "Y",
            Dtg::Z => "Z",
        }
    }
}

impl fmt::Display for Dtg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A cluster axis (also an accelerometer's input axis).
///
/// Names are lower case (`x`, `y`, `z`); the record's column is `ax`, `ay`, `az`.
///
/// ```
/// use nav_sensors::geometry::Axis;
/// assert_eq!(Axis::Z.column(), "az");
/// assert_eq!("y".parse::<Axis>().unwrap(), Axis::Y);
/// assert_eq!("az".parse::<Axis>().unwrap(), Axis::Z);
/// assert_eq!(Axis::X.unit_vector(), nalgebra::Vector3::new(1.0, 0.0, 0.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    X,
    Y,
    Z,
}

impl Axis {
    /// The three axes in record column order.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Axis::ALL[2].column(), "az");
    /// ```
    pub const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    /// Stable lower-case name.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Axis::Y.name(), "y");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Axis::X => "x",
            Axis::Y => "y",
            Axis::Z => "z",
        }
    }

    /// The record's column name for this accelerometer (`ax`, `ay`, `az`).
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Axis::X.column(), "ax");
    /// ```
    pub fn column(self) -> &'static str {
        match self {
            Axis::X => "ax",
            Axis::Y => "ay",
            Axis::Z => "az",
        }
    }

    /// Position 0..3.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Axis::Z.index(), 2);
    /// ```
    pub fn index(self) -> usize {
        self as usize
    }

    /// The unit vector of this axis in the cluster frame.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Axis::Y.unit_vector(), nalgebra::Vector3::new(0.0, 1.0, 0.0));
    /// ```
    pub fn unit_vector(self) -> nalgebra::Vector3<f64> {
        let mut v = nalgebra::Vector3::zeros();
        v[self.index()] = 1.0;
        v
    }
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Axis {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s.trim();
        Axis::ALL
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(t) || a.column() == t)
            .ok_or_else(|| ParseNameError {
                kind: "axis",
                given: s.to_string(),
                valid: Axis::ALL.iter().map(|a| a.name()).collect(),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_through_from_str() {
        for c in Channel::ALL {
            assert_eq!(c.name().parse::<Channel>().unwrap(), c);
            assert_eq!(Channel::ALL[c.index()], c);
            assert_eq!(c.partner().partner(), c);
            assert_eq!(c.partner().dtg(), c.dtg());
        }
        for a in Axis::ALL {
            assert_eq!(a.to_string().parse::<Axis>().unwrap(), a);
        }
    }

    #[test]
    fn serde_uses_the_stable_names() {
        assert_eq!(serde_json::to_string(&Channel::Y1).unwrap(), "\"Y1\"");
        assert_eq!(serde_json::to_string(&Axis::Z).unwrap(), "\"z\"");
    }
}
