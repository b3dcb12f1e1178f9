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
}

impl FadeSettings {
    /// The default for a model of `length`-sample windows at `dt_s`: width
    /// [`FADE_WIDTH`], time constant one window (the statistics' own span).
    ///
    /// ```
    /// let f = sysid::operating::fade::FadeSettings::for_window(50, 0.02);
    /// assert_eq!((f.width, f.time_constant_s), (2.0, 1.0));
    /// ```
    pub fn for_window(length: usize, dt_s: f64) -> Self {
        Self {
            width: FADE_WIDTH,
            time_constant_s: length as f64 * dt_s,
        }
    }

    /// The one-pole smoother's gain per sample of `dt_s`.
    pub fn alpha(&self, dt_s: f64) -> f64 {
        if self.time_constant_s > 0.0 {
            1.0 - (-dt_s / self.time_constant_s).exp()
        } else {
            1.0
        }
    }
}
