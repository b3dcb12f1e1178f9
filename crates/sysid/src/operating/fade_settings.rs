//! How the network part fades outside the training range: the settings a
//! model stores ([`FadeSettings`]), apart from the fade itself
//! ([`super::fade`]) so the training range can hold them without importing
//! the model that the fade reads.

use serde::{Deserialize, Serialize};

/// Width of the fade beyond the tolerance, in the range's scales: with an
/// inertial unit's 0.05 g, the network is gone 0.1 g beyond what it saw.
pub const FADE_WIDTH: f64 = 2.0;

/// How the network part fades outside the training range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FadeSettings {
    /// Distance beyond the tolerance (in the range's scales) over which the
    /// weight falls from 1 to 0.
    pub width: f64,
    /// Time constant of the one-pole smoother of the weight, s.
    pub time_constant_s: f64,
    /// Time constant of the weight's fall, s: 0 falls at once to a lower
    /// weight (a window outside the range fades the network from its own
    /// sample on), and the weight comes back by `time_constant_s`. Absent
    /// in files written before: the weight falls as it rises.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fall_time_constant_s: Option<f64>,
}

impl FadeSettings {
    /// The default for a model of `length`-sample windows at `dt_s`: width
    /// [`FADE_WIDTH`], the weight back by a time constant of one window (the
    /// statistics' own span) and down at once. A weight that fell by the
    /// same one-pole kept a second of the network's extrapolation each time
    /// a record went from rest to a vibration the model never saw (2.5% of
    /// spread on the 2–12 Hz run of tests/dtg_vib_fade_shape.rs).
    ///
    /// ```
    /// let f = sysid::operating::fade::FadeSettings::for_window(50, 0.02);
    /// assert_eq!((f.width, f.time_constant_s, f.fall_time_constant_s), (2.0, 1.0, Some(0.0)));
    /// assert_eq!(f.fall_alpha(0.02), 1.0);
    /// ```
    pub fn for_window(length: usize, dt_s: f64) -> Self {
        Self {
            width: FADE_WIDTH,
            time_constant_s: length as f64 * dt_s,
            fall_time_constant_s: Some(0.0),
        }
    }

    /// The one-pole smoother's gain per sample of `dt_s`.
    pub fn alpha(&self, dt_s: f64) -> f64 {
        gain(self.time_constant_s, dt_s)
    }

    /// The smoother's gain per sample of `dt_s` toward a lower weight
    /// ([`FadeSettings::alpha`] for a file written before the fall had its
    /// own time constant).
    pub fn fall_alpha(&self, dt_s: f64) -> f64 {
        gain(
            self.fall_time_constant_s.unwrap_or(self.time_constant_s),
            dt_s,
        )
    }
}

/// A one-pole's gain per sample of `dt_s` for time constant `tau_s` (1 at 0).
fn gain(tau_s: f64, dt_s: f64) -> f64 {
    if tau_s > 0.0 {
        1.0 - (-dt_s / tau_s).exp()
    } else {
        1.0
    }
}
