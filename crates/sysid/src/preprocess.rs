//! How a record is prepared for the models: the low-pass of the targets
//! and regressors, the low-pass of the windowed signals, the windows, and
//! zero-phase or causal filtering.

use crate::input::ModelInput;
use crate::smoother::Smoother;
use crate::window::WindowSpec;
use serde::{Deserialize, Serialize};

/// A Butterworth low-pass: `order` and −3 dB `cutoff_hz` of one pass (the
/// forward–backward pass is −6 dB there).
///
/// ```
/// let f = sysid::FilterSpec::default();
/// assert_eq!((f.order, f.cutoff_hz), (4, 5.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilterSpec {
    /// Filter order (1 to 12).
    pub order: usize,
    /// Cut-off, Hz.
    pub cutoff_hz: f64,
}

impl Default for FilterSpec {
    /// 4th order at 5 Hz on 50-Hz data. The DTG paper names a low-pass but
    /// not its corner; 5 Hz keeps the level-dependent (rectified) error,
    /// which moves on the scale of seconds, and the part of the
    /// vibration-proportional error below 5 Hz, and removes four fifths of
    /// the band of the white sensor noise. docs/dtg-vib.md has the cut-off
    /// sweep that chose it.
    fn default() -> Self {
        Self {
            order: 4,
            cutoff_hz: 5.0,
        }
    }
}

/// Samples in a window by default: the DTG paper's 50 (1 s at 50 Hz).
const DEFAULT_WINDOW: usize = 50;

/// How a record is prepared for the models.
///
/// ```
/// let p = sysid::Preprocess::default();
/// assert_eq!(p.window.length(), 50);
/// assert!(p.window.is_auto()); // the records choose among the sensor's operating signals
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Preprocess {
    /// Low-pass of the targets and effect regressors, or none.
    pub filter: Option<FilterSpec>,
    /// Low-pass of the windowed input signals, or none. None by default:
    /// the vibration level a rectified error follows is carried by the
    /// input's energy across its whole band, and a low-pass on the window
    /// throws most of it away (measured on the DTG paper's test: residue
    /// reduction 3.7× with a 5-Hz input filter against 4.2× without).
    pub input_filter: Option<FilterSpec>,
    /// Input windows of the RBF: their length and signals, named or chosen
    /// from the records ([`crate::window::WindowSignals::Auto`]).
    pub window: WindowSpec,
    /// Causal mode: the model runs on-line. The low-passes are one forward
    /// pass started in the steady state of the first sample instead of
    /// forward–backward. Absent in files written before it: zero-phase.
    #[serde(default)]
    pub causal: bool,
    /// What the network reads of the windows: the window itself or per
    /// signal its current sample, mean and rms ([`ModelInput`]). Absent in
    /// files written before the choice: the raw window.
    #[serde(default, skip_serializing_if = "ModelInput::is_raw")]
    pub input: ModelInput,
    /// Low-pass of the network part of each prediction ([`Smoother`]), or
    /// none (absent in files written before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub smoother: Option<Smoother>,
}

impl Default for Preprocess {
    /// Low-pass of the targets, unfiltered 50-sample windows (the DTG
    /// paper's length) of the operating signals that vibrate in the
    /// training records ([`crate::window::signal_choice`]).
    fn default() -> Self {
        Self {
            filter: Some(FilterSpec::default()),
            input_filter: None,
            window: WindowSpec::auto(DEFAULT_WINDOW).expect("a window of 50 samples"),
            causal: false,
            input: ModelInput::Raw,
            smoother: None,
        }
    }
}
