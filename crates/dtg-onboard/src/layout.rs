//! The tables' layout: the magic, the versions, the sizes an evaluator
//! holds, the header's flags and codes, and the numbers each part takes.

/// The first four bytes of the tables.
pub const MAGIC: [u8; 4] = *b"DTGO";
/// The layout `dtg-vib export` writes for a model of any unit: n channels
/// ([`MAX_CHANNELS`] at most), each a DTG or a rate gyro with its own
/// calibration table and its network on its own window signals, the unit's
/// least-squares rate and specific-force operators, and the log's units
/// (docs/formats.md, "Onboard tables").
pub const VERSION: u32 = 4;
/// The layout written for the paper's unit before [`VERSION`]: six DTG
/// channels X … Z1, the paper's geometry and calibration (read as it was).
pub const LAYOUT_2: u32 = 2;
/// The layout written for any other unit before [`VERSION`]: every
/// channel's network on the one list of window signals (read as it was).
pub const LAYOUT_3: u32 = 3;

/// Most channels (gyros) tables may have; the evaluator's arrays are this
/// long, so a step needs no heap.
pub const MAX_CHANNELS: usize = 16;
/// Most accelerometers tables may have.
pub const MAX_ACCELS: usize = 16;
/// Most window signals tables may have (a channel's signals are a 32-bit
/// mask).
pub const MAX_SIGNALS: usize = 32;

/// Fixed header words of layouts [`LAYOUT_3`] and [`VERSION`] before their
/// per-channel lists (see docs/formats.md).
pub const FIXED_HEADER_WORDS: usize = 11;
/// Fixed header words of layout [`LAYOUT_2`] before its signal codes.
pub const LAYOUT_2_HEADER_WORDS: usize = 21;

/// Flag bit: the tables hold a ground calibration.
pub const FLAG_CALIBRATION: u32 = 1;

/// Flag bit: the tables end with a fade block ([`fade_floats`] numbers):
/// outside the model's per-axis training range the network part holds
/// (sysid::operating::fade).
pub const FLAG_FADE: u32 = 2;

/// Flag bit (layouts [`LAYOUT_3`] and [`VERSION`]): the accelerometers are
/// the unit's x, y, z axes and the tables hold their triad calibration
/// (3 × 8 numbers in x, y, z order); without it they pass through as
/// given. Layout [`LAYOUT_2`] always calibrates its triad with the ground
/// calibration.
pub const FLAG_ACCEL_TRIAD: u32 = 4;

/// Flag bit (with [`FLAG_FADE`]): the fade block ends with the vibration
/// shape's range (sysid::operating::shape) and the weight's fall gain: a
/// window's distance counts its shape's excess too; without it the fade
/// judges mean and level alone and its weight falls as it rises (tables
/// written before).
pub const FLAG_FADE_SHAPE: u32 = 8;

/// `f64` numbers of the fade block of `n_accels` operating signals and
/// `n_channels` channels: per accelerometer the window mean's smallest and
/// largest and the window level's smallest and largest (g); the scale (g),
/// the tolerance and the width (in scales), the smoother's gain α; each
/// channel's network at rest, where a record's hold starts (deg/h); with
/// `shape` ([`FLAG_FADE_SHAPE`]), per accelerometer the smallest and
/// largest vibration shape, then the shape's scale and the smoother's gain
/// toward a lower weight (without, the weight falls by α as it rises).
pub const fn fade_floats(n_accels: usize, n_channels: usize, shape: bool) -> usize {
    4 * n_accels + 4 + n_channels + if shape { 2 * n_accels + 2 } else { 0 }
}

/// Network input kinds of the tables (the word after the effect pairs).
pub mod input {
    /// The window itself: L samples per signal, oldest first.
    pub const RAW: u32 = 0;
    /// Per signal: current sample, window mean, window rms about the mean.
    pub const STATISTICS: u32 = 1;
}

/// Gyro models (one header word per channel; layout [`crate::LAYOUT_2`]'s
/// are all DTGs).
pub mod gyro {
    /// One input axis of a two-axis DTG (IEEE Std 813): 19 calibration
    /// numbers (the 18 terms of `DtgTerm::ALL`, the scale-factor nonlinearity).
    pub const DTG: u32 = 0;
    /// A single-axis rate gyro (IEEE Std 952 / 1431): 12 calibration numbers
    /// (`RateTerm::ALL`: bias, scale factor, g_x … gg_yz, temp).
    pub const RATE: u32 = 1;
}

/// Effect kinds of the tables.
pub mod kind {
    /// An extra column, as given: `z = extra[index]`.
    pub const COLUMN: u32 = 0;
    /// Linear in specific force: `z = p·f` (3 parameters).
    pub const LINEAR_G: u32 = 1;
    /// Quadratic in specific force: `z = (p·f)(q·f) + pᵀ C q` (6 parameters).
    pub const QUADRATIC_G: u32 = 2;
    /// Product of rates: `z = (r·m)(s·m)` over the calibrated outputs
    /// (2 × the channels' parameters).
    pub const RATE_PRODUCT: u32 = 3;
}

/// Number of `f64` parameters of an effect kind in tables of `n_channels`
/// channels.
pub const fn kind_params_of(k: u32, n_channels: usize) -> Option<usize> {
    match k {
        kind::COLUMN => Some(0),
        kind::LINEAR_G => Some(3),
        kind::QUADRATIC_G => Some(6),
        kind::RATE_PRODUCT => Some(2 * n_channels),
        _ => None,
    }
}

/// `f64` numbers of a gyro model's calibration table.
pub const fn gyro_cal_len(model: u32) -> Option<usize> {
    match model {
        gyro::DTG => Some(GYRO_CAL),
        gyro::RATE => Some(RATE_CAL),
        _ => None,
    }
}

/// `f64` numbers of a gyro's calibration: the 18 DTG terms, then the
/// scale-factor nonlinearity.
pub(crate) const GYRO_CAL: usize = 19;
/// `f64` numbers of a rate gyro's calibration.
pub(crate) const RATE_CAL: usize = 12;
/// `f64` numbers of an accelerometer's calibration.
pub(crate) const ACCEL_CAL: usize = 8;

/// Centres whose kernel arguments are summed side by side and whose
/// weighted terms keep one partial sum each (the exported C's `DTG_LANES`):
/// a centre set's numbers are laid out in blocks of this many
/// (`Model::kernel_lanes`).
pub const LANES: usize = 8;
