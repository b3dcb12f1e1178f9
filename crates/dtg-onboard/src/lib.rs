//! On-line DTG vibration-error compensation, one output period per step, in
//! bounded time and memory: no standard library, no heap. It does not fit
//! or choose anything: it evaluates what `dtg-vib export` wrote.
//!
//! A model fitted by `dtg-vib fit --causal` is exported as flat tables (the
//! versioned byte layout of docs/formats.md, "Onboard tables"). [`Model`]
//! reads them from a byte slice (a file, flash, an `include_bytes!`);
//! [`Evaluator`] keeps the state (filter states, the last two accelerations,
//! the input windows) in a caller-provided `f64` buffer of
//! [`Model::state_len`] elements, and [`Evaluator::step`] turns one period's
//! raw gyro outputs (deg/h), accelerations (g) and extra columns into the
//! compensated rates (deg/h) of the period before: one period of
//! latency, because the g² terms' within-interval covariance of a sample is
//! estimated from its two neighbours. The paper's unit (six DTG channels)
//! has layout [`VERSION`]; any other unit (up to [`MAX_CHANNELS`] DTG or
//! rate-gyro channels, its own operators and calibration) layout
//! [`UNIT_VERSION`]. Channels that share their centres and widths (the
//! same numbers in the tables) take each kernel value computed once.
//!
//! Each sample goes through, in this order (the same as `dtg-vib
//! compensate` on a causal model, which runs this code):
//!
//! 1. ground calibration: the accelerometer triad's static inverse, then each
//!    gyro's inverse DTG model with the other-axis rates from the
//!    least-squares rate (two passes), the g² terms with the within-interval
//!    covariance from the sample and its two neighbours;
//! 2. per channel, the effect regressors from the calibrated accelerations,
//!    rates and extra columns, each through the tables' effect low-pass
//!    (none in the tables `dtg-vib export` writes: the effects are
//!    subtracted unfiltered, θ·z);
//! 3. the window signals through the causal input low-pass into their windows;
//! 4. once the windows are full, per channel the predicted error
//!    `bias + Σ θⱼ·zⱼ + Σₖ wₖ·exp(−‖x − cₖ‖²/βₖ²)`, subtracted from the
//!    calibrated output.
//!
//! ```
//! # fn tables() -> Vec<u8> { dtg_onboard::doc_tables().to_vec() }
//! use dtg_onboard::{Evaluator, Model};
//! let bytes = tables(); // e.g. include_bytes!("model.dtgo")
//! let model = Model::parse(&bytes).unwrap();
//! let mut state = [0.0f64; 4096];
//! let mut ev = Evaluator::new(model, &mut state).unwrap();
//! for _ in 0..model.window_len() {
//!     // Outputs lag one sample: the window_len-th sample's comes with the next.
//!     assert!(ev.step(&[0.0; 6], &[0.0, 0.0, 1.0], &[]).unwrap().is_none());
//! }
//! let out = ev.flush().expect("the record's last sample, with a full window");
//! assert!(out.rate_deg_h.iter().all(|w| w.is_finite()));
//! ```

#![no_std]
#![forbid(unsafe_code)]
// One dependency, itself no_std and dependency-free: `fastexp`, whose
// `exp_neg11` (a few ulps from the desktop's `exp_neg`, in fewer operations)
// the exported C writes out constant for constant, so Rust and C give the
// same bits. The rest needs only `+ − × ÷`, comparisons and bit operations.
use fastexp::exp_neg11;

/// The first four bytes of the tables.
pub const MAGIC: [u8; 4] = *b"DTGO";
/// The layout version of the paper's unit (six DTG channels X … Z1, the
/// paper's geometry and calibration) that `dtg-vib export` writes for its
/// models (2: the network's input kind and the prediction smoother).
pub const VERSION: u32 = 2;
/// The layout version of any other unit (`dtg-vib fit --unit …`): n
/// channels ([`MAX_CHANNELS`] at most), each a DTG or a rate gyro with its
/// own calibration table, the unit's least-squares rate and specific-force
/// operators, and the log's units (docs/formats.md, "Onboard tables").
pub const UNIT_VERSION: u32 = 3;

/// Most channels (gyros) tables may have; the evaluator's arrays are this
/// long, so a step needs no heap.
pub const MAX_CHANNELS: usize = 16;
/// Most accelerometers tables may have.
pub const MAX_ACCELS: usize = 16;

/// Fixed header words before the per-model lists of layout [`VERSION`]
/// (see docs/formats.md).
pub const FIXED_HEADER_WORDS: usize = 21;
/// Fixed header words of layout [`UNIT_VERSION`] before its three
/// per-channel lists (effects, centres, gyro model: n words each).
pub const UNIT_FIXED_HEADER_WORDS: usize = 11;

/// Flag bit: the tables hold a ground calibration.
pub const FLAG_CALIBRATION: u32 = 1;

/// Flag bit: the tables end with a fade block ([`fade_floats`] numbers):
/// outside the model's per-axis training range the network part holds
/// (sysid::operating::fade).
pub const FLAG_FADE: u32 = 2;

/// Flag bit (layout [`UNIT_VERSION`]): the accelerometers are the unit's
/// x, y, z axes and the tables hold their triad calibration (3 × 8 numbers
/// in x, y, z order); without it they pass through as given. Layout
/// [`VERSION`] always calibrates its triad with the ground calibration.
pub const FLAG_ACCEL_TRIAD: u32 = 4;

/// `f64` numbers of the paper layout's fade block: per axis x, y, z the
/// window mean's smallest and largest and the window level's smallest and
/// largest (g); the scale (g), the tolerance and the width (in scales), the
/// smoother's gain α; each channel's network at rest, where a record's
/// hold starts (deg/h).
pub const FADE_FLOATS: usize = 12 + 4 + 6;

/// `f64` numbers of the fade block of `n_accels` operating signals and
/// `n_channels` channels (the paper's: [`FADE_FLOATS`]).
pub const fn fade_floats(n_accels: usize, n_channels: usize) -> usize {
    4 * n_accels + 4 + n_channels
}

/// Network input kinds of the tables (the word after the effect pairs).
pub mod input {
    /// The window itself: L samples per signal, oldest first.
    pub const RAW: u32 = 0;
    /// Per signal: current sample, window mean, window rms about the mean.
    pub const STATISTICS: u32 = 1;
}

/// Gyro models of layout [`UNIT_VERSION`] (one header word per channel).
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
    /// (2 × the channels' parameters: 12 for the paper's six).
    pub const RATE_PRODUCT: u32 = 3;
}

/// Number of `f64` parameters of an effect kind in the paper's layout.
pub const fn kind_params(k: u32) -> Option<usize> {
    kind_params_of(k, 6)
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
const GYRO_CAL: usize = 19;
/// `f64` numbers of a rate gyro's calibration.
const RATE_CAL: usize = 12;
/// `f64` numbers of an accelerometer's calibration.
const ACCEL_CAL: usize = 8;
/// `f64` numbers of one second-order section: b0 b1 b2 a1 a2 zi1 zi2.
const SECTION: usize = 7;

/// Why tables or a step were refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Error {
    /// The bytes do not start with [`MAGIC`].
    Magic,
    /// A layout version this crate does not read.
    Version {
        /// Version in the tables.
        found: u32,
        /// The newest version read here ([`VERSION`] is read too).
        supported: u32,
    },
    /// More channels or accelerometers than the evaluator's arrays hold.
    TooMany {
        /// "channels" or "accelerometers".
        what: &'static str,
        /// How many the tables have.
        found: usize,
        /// The most read here ([`MAX_CHANNELS`], [`MAX_ACCELS`]).
        max: usize,
    },
    /// The tables end before what their header announces.
    Truncated {
        /// Bytes the header announces.
        need: usize,
        /// Bytes given.
        have: usize,
    },
    /// A header field is out of range (an unknown effect kind, a signal or
    /// column index beyond the extra columns, a zero window).
    Header {
        /// The header word, counted from 0.
        word: usize,
    },
    /// The state buffer is smaller than [`Model::state_len`].
    StateTooSmall {
        /// Elements needed.
        need: usize,
        /// Elements given.
        have: usize,
    },
    /// A step was given another number of gyro outputs or accelerations
    /// than the model has.
    Sensors {
        /// "gyro outputs" or "accelerations".
        what: &'static str,
        /// How many the model has.
        need: usize,
        /// How many were given.
        have: usize,
    },
    /// A step was given another number of extra columns than the model reads.
    Extra {
        /// Columns the model reads ([`Model::n_extra`]).
        need: usize,
        /// Columns given.
        have: usize,
    },
}

impl core::fmt::Display for Error {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::Magic => f.write_str("not onboard tables (the bytes do not start with DTGO)"),
            Error::Version { found, supported } => write!(
                f,
                "onboard tables of layout version {found}; this evaluator reads versions {VERSION} to {supported}: export the model again"
            ),
            Error::TooMany { what, found, max } => write!(
                f,
                "onboard tables of {found} {what}; this evaluator holds at most {max}"
            ),
            Error::Sensors { what, need, have } => {
                write!(f, "{have} {what} given; the model has {need}")
            }
            Error::Truncated { need, have } => write!(
                f,
                "onboard tables are {have} bytes, their header announces {need}: the file is cut short"
            ),
            Error::Header { word } => {
                write!(f, "onboard tables: header word {word} is out of range")
            }
            Error::StateTooSmall { need, have } => write!(
                f,
                "state buffer of {have} elements; the model needs {need} (Model::state_len)"
            ),
            Error::Extra { need, have } => {
                write!(f, "{have} extra columns given; the model reads {need}")
            }
        }
    }
}

/// Reads a little-endian `f64` at byte `at`.
#[inline(always)]
fn rd(b: &[u8], at: usize) -> f64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[at..at + 8]);
    f64::from_le_bytes(a)
}

fn word(b: &[u8], i: usize) -> Result<u32, Error> {
    let at = 4 * i;
    if b.len() < at + 4 {
        return Err(Error::Truncated {
            need: at + 4,
            have: b.len(),
        });
    }
    Ok(u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]))
}

/// Where one channel's numbers are.
#[derive(Debug, Clone, Copy, Default)]
struct ChannelAt {
    n_effects: usize,
    n_centres: usize,
    /// Header word of the first (kind, index) pair.
    effect_words: usize,
    /// Byte offsets.
    bias: usize,
    coefficients: usize,
    params: usize,
    widths: usize,
    weights: usize,
    centres: usize,
    /// State offset of its centre set in lane order (a leader's, with the
    /// statistics input: [`fill_lanes`]).
    lanes: usize,
    /// First output-filter state of this channel's effects.
    state: usize,
    /// The gyro's model ([`gyro`]) and the byte offset of its calibration.
    model: u32,
    cal: usize,
}

/// A model's tables, checked once; cheap to copy.
#[derive(Debug, Clone, Copy)]
pub struct Model<'a> {
    bytes: &'a [u8],
    /// Layout version ([`VERSION`] or [`UNIT_VERSION`]).
    version: u32,
    calibrated: bool,
    /// The accelerometers are calibrated as the x, y, z triad.
    accel_triad: bool,
    n_extra: usize,
    n_sections: usize,
    n_in_sections: usize,
    window_len: usize,
    n_signals: usize,
    signal_words: usize,
    /// Channels (gyros) and accelerometers.
    n_channels: usize,
    n_accels: usize,
    dt_s: f64,
    /// The log's rate unit in deg/h and specific-force unit in g (1 and 1
    /// for the paper's layout).
    rate_to_deg_h: f64,
    force_to_g: f64,
    frames: usize,
    ls: usize,
    /// Byte offset of the specific-force operator (3 × n_accels), `None`
    /// for the paper's layout (ax, ay, az are x, y, z).
    force_op: Option<usize>,
    accel_cal: usize,
    out_filter: usize,
    in_filter: usize,
    channels: [ChannelAt; MAX_CHANNELS],
    /// Per channel the first channel with the same centres and widths (its
    /// kernel values are computed once per step for all of them), and the
    /// channels that share each leader's set.
    leader: [usize; MAX_CHANNELS],
    members: [[u8; MAX_CHANNELS]; MAX_CHANNELS],
    n_members: [usize; MAX_CHANNELS],
    state_len: usize,
    /// State slots of the pending sample's calibrated accelerometers (the
    /// specific force itself in the paper's layout), raw gyro outputs and
    /// extra columns.
    st_accel: usize,
    st_gyro: usize,
    st_extra: usize,
    in_state: usize,
    rings: usize,
    /// Byte offset of the fade block, if the tables have one.
    fade: Option<usize>,
    /// State of the fade: a doubled ring of 2L per accelerometer, the held
    /// network part per channel, the smoothed weight.
    fade_state: usize,
    /// The network's input ([`input`]) and its dimension.
    input: u32,
    dim: usize,
    /// Sections of the prediction smoother (0: none), their floats, and the
    /// state: per channel two per section.
    n_smooth_sections: usize,
    smoother: usize,
    smooth_state: usize,
    /// Running sums s₁, s₂ per signal, then the statistics inputs (3 per signal).
    sums: usize,
    features: usize,
}

/// The signal words and each channel's effect pairs of the header (from
/// word `signal_words`), checked: the word after them, and each channel's
/// number of effect parameters.
fn effect_words(
    bytes: &[u8],
    channels: &mut [ChannelAt],
    signal_words: usize,
    (n_signals, n_accels, n_extra): (usize, usize, usize),
) -> Result<(usize, [usize; MAX_CHANNELS]), Error> {
    let n_channels = channels.len();
    for s in 0..n_signals {
        if word(bytes, signal_words + s)? as usize >= n_accels + n_extra {
            return Err(Error::Header {
                word: signal_words + s,
            });
        }
    }
    let mut w = signal_words + n_signals;
    let mut params_len = [0usize; MAX_CHANNELS];
    for (c, ch) in channels.iter_mut().enumerate() {
        ch.effect_words = w;
        for _ in 0..ch.n_effects {
            let k = word(bytes, w)?;
            let Some(p) = kind_params_of(k, n_channels) else {
                return Err(Error::Header { word: w });
            };
            if k == kind::COLUMN && word(bytes, w + 1)? as usize >= n_extra {
                return Err(Error::Header { word: w + 1 });
            }
            params_len[c] += p;
            w += 2;
        }
    }
    Ok((w, params_len))
}

/// The two header words after the effect pairs (at `w`): the network's
/// input kind with its dimension, and the prediction smoother's sections.
fn input_words(
    bytes: &[u8],
    w: usize,
    window_len: usize,
    n_signals: usize,
) -> Result<(u32, usize, usize), Error> {
    let input = word(bytes, w)?;
    let dim = match input {
        input::RAW => window_len * n_signals,
        input::STATISTICS => 3 * n_signals,
        _ => return Err(Error::Header { word: w }),
    };
    Ok((input, dim, word(bytes, w + 1)? as usize))
}

/// The header's sizes before the per-channel lists: channels and
/// accelerometers, and where each channel's effect count, centre count and
/// gyro model words are (`None`: all DTG, the paper's layout).
struct Counts {
    n_channels: usize,
    n_accels: usize,
    effects_at: usize,
    centres_at: usize,
    models_at: Option<usize>,
    signal_words: usize,
}

fn counts(bytes: &[u8], version: u32) -> Result<Counts, Error> {
    if version == VERSION {
        return Ok(Counts {
            n_channels: 6,
            n_accels: 3,
            effects_at: 9,
            centres_at: 15,
            models_at: None,
            signal_words: FIXED_HEADER_WORDS,
        });
    }
    let n_channels = word(bytes, 9)? as usize;
    let n_accels = word(bytes, 10)? as usize;
    if n_channels > MAX_CHANNELS {
        return Err(Error::TooMany {
            what: "channels",
            found: n_channels,
            max: MAX_CHANNELS,
        });
    }
    if n_accels > MAX_ACCELS {
        return Err(Error::TooMany {
            what: "accelerometers",
            found: n_accels,
            max: MAX_ACCELS,
        });
    }
    for (v, word) in [(n_channels, 9), (n_accels, 10)] {
        if v == 0 {
            return Err(Error::Header { word });
        }
    }
    let w = UNIT_FIXED_HEADER_WORDS;
    Ok(Counts {
        n_channels,
        n_accels,
        effects_at: w,
        centres_at: w + n_channels,
        models_at: Some(w + 2 * n_channels),
        signal_words: w + 3 * n_channels,
    })
}

/// Per channel the first channel whose centres and widths are the same
/// bytes (its leader), and each leader's members in channel order.
type Sharing = (
    [usize; MAX_CHANNELS],
    [[u8; MAX_CHANNELS]; MAX_CHANNELS],
    [usize; MAX_CHANNELS],
);

fn sharing(bytes: &[u8], channels: &[ChannelAt], dim: usize) -> Sharing {
    let mut leader = [0usize; MAX_CHANNELS];
    let mut members = [[0u8; MAX_CHANNELS]; MAX_CHANNELS];
    let mut n_members = [0usize; MAX_CHANNELS];
    let block = |ch: &ChannelAt| {
        let k = ch.n_centres;
        (
            &bytes[ch.widths..ch.widths + 8 * k],
            &bytes[ch.centres..ch.centres + 8 * k * dim],
        )
    };
    for (c, ch) in channels.iter().enumerate() {
        let l = (0..c)
            .find(|&p| {
                leader[p] == p
                    && channels[p].n_centres == ch.n_centres
                    && ch.n_centres > 0
                    && block(&channels[p]) == block(ch)
            })
            .unwrap_or(c);
        leader[c] = l;
        members[l][n_members[l]] = c as u8;
        n_members[l] += 1;
    }
    (leader, members, n_members)
}

impl<'a> Model<'a> {
    /// Checks the header and sizes of `bytes` (layout version [`VERSION`]
    /// or [`UNIT_VERSION`]).
    pub fn parse(bytes: &'a [u8]) -> Result<Self, Error> {
        if bytes.len() < 4 || bytes[..4] != MAGIC {
            return Err(Error::Magic);
        }
        let version = word(bytes, 1)?;
        if version != VERSION && version != UNIT_VERSION {
            return Err(Error::Version {
                found: version,
                supported: UNIT_VERSION,
            });
        }
        let header_words = word(bytes, 2)? as usize;
        let flags = word(bytes, 3)?;
        let n_extra = word(bytes, 4)? as usize;
        let n_sections = word(bytes, 5)? as usize;
        let n_in_sections = word(bytes, 6)? as usize;
        let window_len = word(bytes, 7)? as usize;
        let n_signals = word(bytes, 8)? as usize;
        for (v, word) in [(window_len, 7), (n_signals, 8)] {
            if v == 0 {
                return Err(Error::Header { word });
            }
        }
        let n = counts(bytes, version)?;
        let mut channels = [ChannelAt::default(); MAX_CHANNELS];
        for (c, ch) in channels[..n.n_channels].iter_mut().enumerate() {
            ch.n_effects = word(bytes, n.effects_at + c)? as usize;
            ch.n_centres = word(bytes, n.centres_at + c)? as usize;
            ch.model = match n.models_at {
                None => gyro::DTG,
                Some(at) => word(bytes, at + c)?,
            };
            if gyro_cal_len(ch.model).is_none() {
                return Err(Error::Header {
                    word: n.models_at.unwrap_or(0) + c,
                });
            }
        }
        let signal_words = n.signal_words;
        let (w, params_len) = effect_words(
            bytes,
            &mut channels[..n.n_channels],
            signal_words,
            (n_signals, n.n_accels, n_extra),
        )?;
        let (input, dim, n_smooth_sections) = input_words(bytes, w, window_len, n_signals)?;
        if header_words < w + 2 || !header_words.is_multiple_of(2) {
            return Err(Error::Header { word: 2 });
        }
        let unit = version == UNIT_VERSION;
        let calibrated = flags & FLAG_CALIBRATION != 0;
        let accel_triad = if unit {
            flags & FLAG_ACCEL_TRIAD != 0
        } else {
            calibrated
        };
        if accel_triad && n.n_accels != 3 {
            return Err(Error::Header { word: 3 });
        }
        let (nc, na) = (n.n_channels, n.n_accels);
        // Payload offsets, in bytes.
        let mut at = 4 * header_words;
        let mut take = |n: usize| {
            let here = at;
            at += 8 * n;
            here
        };
        let dt_at = take(1);
        let scales = unit.then(|| take(2));
        let frames = take(9 * nc);
        let ls = take(3 * nc);
        let force_op = unit.then(|| take(3 * na));
        if calibrated {
            for ch in channels[..nc].iter_mut() {
                ch.cal = take(gyro_cal_len(ch.model).unwrap_or(0));
            }
        }
        let accel_cal = if accel_triad { take(3 * ACCEL_CAL) } else { 0 };
        let out_filter = take(SECTION * n_sections);
        let in_filter = take(SECTION * n_in_sections);
        let smoother = take(SECTION * n_smooth_sections);
        let (st_accel, st_gyro) = if unit { (6, 6 + na) } else { (0, 6) };
        let st_extra = st_gyro + nc;
        let mut state = st_extra + n_extra;
        for (c, ch) in channels[..nc].iter_mut().enumerate() {
            ch.bias = take(1);
            ch.coefficients = take(ch.n_effects);
            ch.params = take(params_len[c]);
            ch.widths = take(ch.n_centres);
            ch.weights = take(ch.n_centres);
            ch.centres = take(ch.n_centres * dim);
            ch.state = state;
            state += 2 * n_sections * ch.n_effects;
        }
        let fade = (flags & FLAG_FADE != 0).then(|| take(fade_floats(na, nc)));
        let need = at;
        if bytes.len() < need {
            return Err(Error::Truncated {
                need,
                have: bytes.len(),
            });
        }
        let in_state = state;
        state += 2 * n_in_sections * n_signals;
        let rings = state;
        state += 2 * window_len * n_signals;
        let fade_state = state;
        if fade.is_some() {
            state += 2 * window_len * na + nc + 1;
        }
        let smooth_state = state;
        state += nc * 2 * n_smooth_sections;
        let sums = state;
        state += 2 * n_signals;
        let features = state;
        if input == input::STATISTICS {
            state += 3 * n_signals;
        }
        let (leader, members, n_members) = sharing(bytes, &channels[..nc], dim);
        if input == input::STATISTICS {
            for (c, ch) in channels[..nc].iter_mut().enumerate() {
                if leader[c] == c {
                    ch.lanes = state;
                    state += lane_blocks(ch.n_centres) * (dim + 1) * LANES;
                }
            }
        }
        Ok(Self {
            bytes: &bytes[..need],
            version,
            calibrated,
            accel_triad,
            n_extra,
            n_sections,
            n_in_sections,
            window_len,
            n_signals,
            signal_words,
            n_channels: nc,
            n_accels: na,
            dt_s: rd(bytes, dt_at),
            rate_to_deg_h: scales.map_or(1.0, |s| rd(bytes, s)),
            force_to_g: scales.map_or(1.0, |s| rd(bytes, s + 8)),
            frames,
            ls,
            force_op,
            accel_cal,
            out_filter,
            in_filter,
            channels,
            leader,
            members,
            n_members,
            state_len: state,
            st_accel,
            st_gyro,
            st_extra,
            in_state,
            rings,
            fade,
            fade_state,
            input,
            dim,
            n_smooth_sections,
            smoother,
            smooth_state,
            sums,
            features,
        })
    }

    /// Size of the tables, bytes.
    pub fn size_bytes(&self) -> usize {
        self.bytes.len()
    }

    /// `f64` elements of state an [`Evaluator`] needs.
    pub fn state_len(&self) -> usize {
        self.state_len
    }

    /// Extra columns each step takes, in the exporter's order.
    pub fn n_extra(&self) -> usize {
        self.n_extra
    }

    /// Samples per window: steps before the first output.
    pub fn window_len(&self) -> usize {
        self.window_len
    }

    /// The output period the model was fitted at, s.
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// Centres of one channel (0..6 = X, X1, Y, Y1, Z, Z1 in the paper's
    /// layout; the unit's gyros in its file's order otherwise).
    pub fn n_centres(&self, channel: usize) -> usize {
        self.channels[channel].n_centres
    }

    /// Effects of one channel.
    pub fn n_effects(&self, channel: usize) -> usize {
        self.channels[channel].n_effects
    }

    /// Channels (gyros): 6 in the paper's layout.
    pub fn n_channels(&self) -> usize {
        self.n_channels
    }

    /// Accelerometers a step takes: 3 in the paper's layout.
    pub fn n_accels(&self) -> usize {
        self.n_accels
    }

    /// The layout version of the tables ([`VERSION`] or [`UNIT_VERSION`]).
    pub fn version(&self) -> u32 {
        self.version
    }

    /// The log's rate unit in deg/h and its specific-force unit in g (what
    /// a log's gyro and accelerometer columns are multiplied by before a
    /// step; 1 and 1 in the paper's layout).
    pub fn log_units(&self) -> (f64, f64) {
        (self.rate_to_deg_h, self.force_to_g)
    }

    /// The first channel whose centres and widths channel `channel` shares
    /// (itself if none): the kernel values of a shared set are computed
    /// once per step.
    pub fn centre_set(&self, channel: usize) -> usize {
        self.leader[channel]
    }

    /// Floating-point operations of one step (a multiply-add is two; `exp`,
    /// `/` and `fabs` count one each): the RBF sums, filters and effect
    /// weights counted from the tables, the calibration's Newton steps and
    /// the regressors estimated per operation. A channel sharing another's
    /// centres costs one multiply-add per centre.
    pub fn flops_per_step(&self) -> usize {
        let dim = self.dim;
        let (nc, na) = (self.n_channels, self.n_accels);
        let mut f = 0;
        if self.calibrated {
            if self.accel_triad {
                // Triad: 3 passes × 3 axes × 4 Newton steps of ~25 flops.
                f += 3 * 3 * 4 * 25 + 3;
            }
            // Two passes: rate (3 × 2n) + n × (resolve 3×3×5 + cov 6×15 +
            // drift 2×36 + Newton 4×12).
            f += 2 * (3 * 2 * nc + nc * (45 + 90 + 72 + 48 + 4));
        }
        f += 9 * 6; // covariance
        for (c, ch) in self.channels[..nc].iter().enumerate() {
            f += 2 + 2 * ch.n_effects + 9 * self.n_sections * ch.n_effects + 20 * ch.n_effects;
            f += if self.leader[c] == c {
                ch.n_centres * (3 * dim + 6)
            } else {
                2 * ch.n_centres
            };
        }
        if self.fade.is_some() {
            // Per axis: mean and variance over the window, the excesses; the
            // smoothstep, the smoother, one hold per channel.
            f += na * (4 * self.window_len + 12) + 20 + nc * 5;
        }
        f += nc * 9 * self.n_smooth_sections;
        if self.input == input::STATISTICS {
            f += 12 * self.n_signals;
        }
        f + 9 * self.n_in_sections * self.n_signals
    }

    /// Whether the tables fade the network part outside the training range.
    pub fn fades(&self) -> bool {
        self.fade.is_some()
    }

    /// The network's input kind ([`input`]).
    pub fn input_kind(&self) -> u32 {
        self.input
    }

    /// The network's input dimension.
    pub fn input_dim(&self) -> usize {
        self.dim
    }

    /// Second-order sections of the prediction smoother (0: none).
    pub fn n_smoother_sections(&self) -> usize {
        self.n_smooth_sections
    }

    #[inline(always)]
    fn f(&self, at: usize) -> f64 {
        rd(self.bytes, at)
    }

    #[inline(always)]
    fn w(&self, i: usize) -> u32 {
        let at = 4 * i;
        let b = self.bytes;
        u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
    }
}

/// One step's result. Only the first [`Output::n_channels`] (and
/// [`Output::n_accels`]) entries are the model's; the rest are zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Output {
    /// Compensated rates (X, X1, Y, Y1, Z, Z1 in the paper's layout; the
    /// unit's gyros in its order otherwise), deg/h: the calibrated outputs
    /// minus the predicted errors.
    pub rate_deg_h: [f64; MAX_CHANNELS],
    /// The predicted vibration errors, deg/h.
    pub error_deg_h: [f64; MAX_CHANNELS],
    /// Calibrated accelerations (x, y, z; the unit's accelerometers in its
    /// order), g.
    pub accel_g: [f64; MAX_ACCELS],
    /// Channels of the model.
    pub n_channels: usize,
    /// Accelerometers of the model.
    pub n_accels: usize,
}

impl Output {
    /// The compensated rates of the model's channels, deg/h.
    pub fn rates(&self) -> &[f64] {
        &self.rate_deg_h[..self.n_channels]
    }

    /// The predicted errors of the model's channels, deg/h.
    pub fn errors(&self) -> &[f64] {
        &self.error_deg_h[..self.n_channels]
    }

    /// The calibrated accelerations of the model's accelerometers, g.
    pub fn accels(&self) -> &[f64] {
        &self.accel_g[..self.n_accels]
    }
}

/// The compensator's state over a model.
///
/// One period of latency: the call with sample n returns the output of
/// sample n − 1, because the g² terms' within-interval covariance of a
/// sample is estimated from its two neighbours. [`Evaluator::flush`] gives
/// the last sample's output at the end of a record.
#[derive(Debug)]
pub struct Evaluator<'m, 's> {
    model: Model<'m>,
    state: &'s mut [f64],
    /// Samples received since rest.
    steps: u64,
    /// Samples processed (one fewer than received, once running).
    processed: u64,
    ring_pos: usize,
}

/// State slots: the calibrated specific force (unit frame, g) of the
/// pending sample and of the one before it; the other slots (the pending
/// sample's accelerometers, raw gyro outputs, extra columns) are the
/// model's (`Model::st_*`).
const PENDING_FORCE: usize = 0;
const EARLIER_FORCE: usize = 3;

impl<'m, 's> Evaluator<'m, 's> {
    /// An evaluator at rest; `state` needs [`Model::state_len`] elements
    /// (more are left alone).
    pub fn new(model: Model<'m>, state: &'s mut [f64]) -> Result<Self, Error> {
        let need = model.state_len();
        if state.len() < need {
            return Err(Error::StateTooSmall {
                need,
                have: state.len(),
            });
        }
        let state = &mut state[..need];
        state.fill(0.0);
        fill_lanes(&model, state);
        Ok(Self {
            model,
            state,
            steps: 0,
            processed: 0,
            ring_pos: 0,
        })
    }

    /// Back to rest, as after [`Evaluator::new`].
    pub fn reset(&mut self) {
        self.state.fill(0.0);
        fill_lanes(&self.model, self.state);
        self.steps = 0;
        self.processed = 0;
        self.ring_pos = 0;
    }

    /// Samples received since rest.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// One output period: raw gyro outputs (X, X1, Y, Y1, Z, Z1 in the
    /// paper's layout; the unit's gyros in its order), deg/h, raw
    /// accelerations (x, y, z; the unit's accelerometers), g, and the
    /// model's extra columns (in the exporter's order, [`Model::n_extra`]
    /// of them) of sample n; returns the output of sample n − 1, or `None`
    /// while the windows fill (the first output, of sample
    /// [`Model::window_len`] − 1, comes with sample `window_len`). A
    /// non-finite input makes every later output non-finite (the filters
    /// keep it): reset.
    pub fn step(
        &mut self,
        gyro_deg_h: &[f64],
        accel_g: &[f64],
        extra: &[f64],
    ) -> Result<Option<Output>, Error> {
        let m = self.model;
        let (nc, na) = (m.n_channels, m.n_accels);
        if extra.len() != m.n_extra {
            return Err(Error::Extra {
                need: m.n_extra,
                have: extra.len(),
            });
        }
        for (what, need, have) in [
            ("gyro outputs", nc, gyro_deg_h.len()),
            ("accelerations", na, accel_g.len()),
        ] {
            if need != have {
                return Err(Error::Sensors { what, need, have });
            }
        }
        let mut cal = [0.0; MAX_ACCELS];
        let f = calibrated_force(&m, accel_g, &mut cal[..na]);
        let out = if self.steps >= 1 {
            // The pending sample's covariance, centred: n − 2, n − 1, n (zero
            // for the first sample, which has one neighbour, as in the batch).
            let cov = if self.steps >= 2 {
                let st = &*self.state;
                let earlier = [
                    st[EARLIER_FORCE],
                    st[EARLIER_FORCE + 1],
                    st[EARLIER_FORCE + 2],
                ];
                let pending = [
                    st[PENDING_FORCE],
                    st[PENDING_FORCE + 1],
                    st[PENDING_FORCE + 2],
                ];
                covariance(&earlier, &pending, &f)
            } else {
                [[0.0; 3]; 3]
            };
            self.process(&cov)
        } else {
            None
        };
        let st = &mut *self.state;
        st.copy_within(PENDING_FORCE..PENDING_FORCE + 3, EARLIER_FORCE);
        st[PENDING_FORCE..PENDING_FORCE + 3].copy_from_slice(&f);
        if m.st_accel != PENDING_FORCE {
            st[m.st_accel..m.st_accel + na].copy_from_slice(&cal[..na]);
        }
        st[m.st_gyro..m.st_gyro + nc].copy_from_slice(gyro_deg_h);
        st[m.st_extra..m.st_extra + m.n_extra].copy_from_slice(extra);
        self.steps += 1;
        Ok(out)
    }

    /// The end of a record: the output of the last sample received (its
    /// covariance is zero, as the batch's at a record's end), then back to
    /// rest. `None` if nothing is pending or the windows are not full.
    pub fn flush(&mut self) -> Option<Output> {
        let out = if self.steps >= 1 {
            self.process(&[[0.0; 3]; 3])
        } else {
            None
        };
        self.reset();
        out
    }

    /// Compensates the pending sample with its covariance `cov`.
    fn process(&mut self, cov: &[[f64; 3]; 3]) -> Option<Output> {
        let m = self.model;
        let (nc, na) = (m.n_channels, m.n_accels);
        let first = self.processed == 0;
        let st = &mut *self.state;
        let f = [
            st[PENDING_FORCE],
            st[PENDING_FORCE + 1],
            st[PENDING_FORCE + 2],
        ];
        let mut a = [0.0; MAX_ACCELS];
        a[..na].copy_from_slice(&st[m.st_accel..m.st_accel + na]);
        let mut gyro = [0.0; MAX_CHANNELS];
        gyro[..nc].copy_from_slice(&st[m.st_gyro..m.st_gyro + nc]);
        if m.calibrated {
            compensate_gyros(&m, &mut gyro[..nc], &f, cov);
        }

        // Effects, filtered, weighted: the linear part of each prediction.
        let linear = linear_parts(&m, st, (&f, &gyro[..nc], cov), first);

        // Window signals, filtered, into their windows.
        let l = m.window_len;
        for s in 0..m.n_signals {
            let code = m.w(m.signal_words + s) as usize;
            let v = if code < na {
                a[code]
            } else {
                st[m.st_extra + code - na]
            };
            let s0 = m.in_state + 2 * m.n_in_sections * s;
            let v = cascade(&m, m.in_filter, m.n_in_sections, &mut st[s0..], v, first);
            let r = m.rings + 2 * l * s;
            // The running sums: the sample L steps back (0 while the
            // window fills) leaves as this one enters (sysid::input).
            let old = st[r + self.ring_pos];
            let sum = m.sums + 2 * s;
            st[sum] = (st[sum] + v) - old;
            st[sum + 1] = (st[sum + 1] + v * v) - old * old;
            st[r + self.ring_pos] = v;
            st[r + self.ring_pos + l] = v;
            if m.input == input::STATISTICS {
                let mean = st[sum] / l as f64;
                let var = st[sum + 1] / l as f64 - mean * mean;
                let feat = m.features + 3 * s;
                st[feat] = v;
                st[feat + 1] = mean;
                st[feat + 2] = if var > 0.0 { sqrt(var) } else { 0.0 };
            }
        }
        if m.fade.is_some() {
            let r = m.fade_state;
            for (k, v) in a[..na].iter().enumerate() {
                st[r + 2 * l * k + self.ring_pos] = *v;
                st[r + 2 * l * k + self.ring_pos + l] = *v;
            }
        }
        self.ring_pos = (self.ring_pos + 1) % l;
        self.processed += 1;
        if self.processed < l as u64 {
            return None;
        }
        let weight = m
            .fade
            .map(|at| fade_weight(&m, at, st, self.ring_pos, self.processed == l as u64));

        // Predictions.
        let mut out = Output {
            rate_deg_h: [0.0; MAX_CHANNELS],
            error_deg_h: [0.0; MAX_CHANNELS],
            accel_g: a,
            n_channels: nc,
            n_accels: na,
        };
        let first_prediction = self.processed == l as u64;
        // Without a smoother the kernels add onto bias and effects, in
        // the order tables of layout version 1 were evaluated.
        let smoothed = m.n_smooth_sections > 0;
        let mut ys = [0.0; MAX_CHANNELS];
        let mut nets = [0.0; MAX_CHANNELS];
        if !smoothed {
            for (c, ch) in m.channels[..nc].iter().enumerate() {
                ys[c] = m.f(ch.bias) + linear[c];
            }
        }
        network_terms(&m, st, self.ring_pos, &mut ys, &mut nets);
        let na4 = 4 * na;
        for (c, ch) in m.channels[..nc].iter().enumerate() {
            let (mut y, mut net) = (ys[c], nets[c]);
            if let (Some(w), Some(at)) = (weight, m.fade) {
                // The held network part follows the network by the weight's
                // one-pole while the weight is 1 and stays below; the output
                // cross-fades from it to the network by the weight. A
                // record starts it at the network's value at rest. Before
                // the smoother (sysid::operating::fade).
                let h = m.fade_state + 2 * l * na + c;
                let before = if self.processed == l as u64 {
                    m.f(at + 8 * (na4 + 4 + c))
                } else {
                    st[h]
                };
                let faded = if w >= 1.0 {
                    st[h] = before + m.f(at + 8 * (na4 + 3)) * (net - before);
                    net
                } else {
                    st[h] = before;
                    before + w * (net - before)
                };
                if !smoothed {
                    y -= net - faded;
                }
                net = faded;
            }
            // The prediction smoother, on the network part only.
            if smoothed {
                let s0 = m.smooth_state + 2 * m.n_smooth_sections * c;
                let n = m.n_smooth_sections;
                net = cascade(&m, m.smoother, n, &mut st[s0..], net, first_prediction);
                y = m.f(ch.bias) + linear[c] + net;
            }
            out.error_deg_h[c] = y;
            out.rate_deg_h[c] = gyro[c] - y;
        }
        Some(out)
    }
}

/// The calibrated specific force (unit frame, g) of one sample's raw
/// accelerations, and its calibrated accelerometers in `cal`: the triad's
/// static inverse when the tables calibrate it (on x, y, z ordered through
/// the specific-force operator, a permutation then), else the accelerations
/// as given through the operator (the paper's layout: ax, ay, az are x, y, z).
fn calibrated_force(m: &Model, raw: &[f64], cal: &mut [f64]) -> [f64; 3] {
    let mut f = match m.force_op {
        None => [raw[0], raw[1], raw[2]],
        Some(op) => {
            let mut f = [0.0; 3];
            for (i, v) in f.iter_mut().enumerate() {
                *v = dotn(m, op + 8 * m.n_accels * i, raw);
            }
            f
        }
    };
    if m.accel_triad {
        f = compensate_triad(m, &f);
    }
    match (m.force_op, m.accel_triad) {
        (Some(op), true) => {
            // The operator is a permutation: each accelerometer is one axis.
            for (k, c) in cal.iter_mut().enumerate() {
                *c = (0..3)
                    .map(|i| m.f(op + 8 * (m.n_accels * i + k)) * f[i])
                    .fold(0.0, |s, v| s + v);
            }
        }
        (Some(_), false) => cal.copy_from_slice(raw),
        (None, _) => cal.copy_from_slice(&f),
    }
    f
}

/// Each channel's effects through the output filter, weighted and summed:
/// the linear part of its prediction (`inputs`: the calibrated specific
/// force (g), the compensated gyro outputs (deg/h) and the within-interval
/// covariance of the specific force).
fn linear_parts(
    m: &Model,
    st: &mut [f64],
    (a, gyro, cov): (&[f64; 3], &[f64], &[[f64; 3]; 3]),
    first: bool,
) -> [f64; MAX_CHANNELS] {
    let mut linear = [0.0; MAX_CHANNELS];
    let nc = m.n_channels;
    for (c, ch) in m.channels[..nc].iter().enumerate() {
        let mut p = ch.params;
        let mut sum = 0.0;
        for e in 0..ch.n_effects {
            let k = m.w(ch.effect_words + 2 * e);
            let z = match k {
                kind::COLUMN => st[m.st_extra + m.w(ch.effect_words + 2 * e + 1) as usize],
                kind::LINEAR_G => dot3(m, p, a),
                kind::QUADRATIC_G => {
                    let (pf, qf) = (dot3(m, p, a), dot3(m, p + 24, a));
                    pf * qf + quad(m, p, cov, p + 24)
                }
                _ => dotn(m, p, gyro) * dotn(m, p + 8 * nc, gyro),
            };
            p += 8 * kind_params_of(k, nc).unwrap_or(0);
            let s0 = ch.state + 2 * m.n_sections * e;
            let z = cascade(m, m.out_filter, m.n_sections, &mut st[s0..], z, first);
            sum += z * m.f(ch.coefficients + 8 * e);
        }
        linear[c] = sum;
    }
    linear
}

/// Centres taken together. Their squared distances are summed side by side
/// ([`LANES`] centres at a time, one input number against each in turn, so
/// that vector lanes work on several centres), their exponentials taken in
/// one branch-free loop over the block, and each sharing channel's weighted
/// terms kept in one partial sum per lane; the exported C takes the same
/// blocks and lanes.
const KERNEL_BLOCK: usize = 32;
/// Centres whose distances are summed side by side and whose weighted
/// terms keep one partial sum each (the exported C's `DTG_LANES`; the
/// centres of a statistics model are laid out in blocks of this many).
pub const LANES: usize = 8;

/// The table's `f64`s from byte `at`, `n` of them, as 8-byte chunks.
#[inline(always)]
fn f64s(bytes: &[u8], at: usize, n: usize) -> &[[u8; 8]] {
    bytes[at..at + 8 * n].as_chunks::<8>().0
}

/// The lanes of a block summed pairwise (the C sums them in this order).
#[inline(always)]
fn lane_sum(a: &[f64; LANES]) -> f64 {
    let mut v = *a;
    let mut w = LANES;
    while w > 1 {
        w /= 2;
        for i in 0..w {
            v[i] += v[i + w];
        }
    }
    v[0]
}

/// −‖x − cᵢ‖²/βᵢ² of [`LANES`] centres in lane order (`block`: input
/// number j of centre i at `j·LANES + i`, then the 1/βᵢ²), each distance
/// summed in input order: the loop over the centres is the inner one, so
/// that it runs in vector lanes.
#[inline(always)]
fn lanes_arg(block: &[f64], x: &[f64], dim: usize, arg: &mut [f64; LANES]) {
    let block = &block[..(dim + 1) * LANES];
    let mut r2 = [0.0; LANES];
    for (j, &xj) in x[..dim].iter().enumerate() {
        for (r, c) in r2.iter_mut().zip(&block[j * LANES..(j + 1) * LANES]) {
            let d = xj - c;
            *r += d * d;
        }
    }
    for ((a, r), w) in arg.iter_mut().zip(&r2).zip(&block[dim * LANES..]) {
        *a = -(r * w);
    }
}

/// Centre blocks of [`LANES`] for `n` centres.
const fn lane_blocks(n: usize) -> usize {
    n.div_ceil(LANES)
}

/// Each centre set of a statistics model into the state in lane order, for
/// [`lanes_arg`]: per block of [`LANES`] centres, input number j of each
/// centre, then each centre's 1/β²; zeros in the lanes past the last centre.
/// (The exported C has the same numbers as constant arrays.)
fn fill_lanes(m: &Model, st: &mut [f64]) {
    if m.input != input::STATISTICS {
        return;
    }
    let dim = m.dim;
    for (c, ch) in m.channels[..m.n_channels].iter().enumerate() {
        if m.leader[c] != c {
            continue;
        }
        for k in 0..ch.n_centres {
            let at = ch.lanes + (k / LANES) * (dim + 1) * LANES + k % LANES;
            for j in 0..dim {
                st[at + j * LANES] = m.f(ch.centres + 8 * (k * dim + j));
            }
            let beta = m.f(ch.widths + 8 * k);
            st[at + dim * LANES] = 1.0 / (beta * beta);
        }
    }
}

/// Every channel's kernel terms added to its `ys` and `nets` (the input:
/// the statistics in `st`, or the windows of the rings whose oldest sample
/// is at `ring_pos`). Channels that share a centre set take each kernel
/// value computed once, times their own weight.
#[inline(always)]
fn network_terms(
    m: &Model,
    st: &[f64],
    ring_pos: usize,
    ys: &mut [f64; MAX_CHANNELS],
    nets: &mut [f64; MAX_CHANNELS],
) {
    const B: usize = KERNEL_BLOCK;
    let (l, dim) = (m.window_len, m.dim);
    for (c, ch) in m.channels[..m.n_channels].iter().enumerate() {
        if m.leader[c] != c {
            continue;
        }
        let members = &m.members[c][..m.n_members[c]];
        let n = ch.n_centres;
        let widths = f64s(m.bytes, ch.widths, n);
        let mut acc = [[0.0; LANES]; MAX_CHANNELS];
        let mut k0 = 0;
        while k0 < n {
            let nb = B.min(n - k0);
            // −‖x − cᵢ‖²/βᵢ²; 0 in the lanes past the last centre (whose
            // weight is 0).
            let mut arg = [0.0; B];
            if m.input == input::STATISTICS {
                let x = &st[m.features..m.features + dim];
                let stride = (dim + 1) * LANES;
                let first = k0 / LANES;
                let lanes = arg.as_chunks_mut::<LANES>().0;
                for (lb, arg) in lanes[..lane_blocks(nb)].iter_mut().enumerate() {
                    let block = &st[ch.lanes + (first + lb) * stride..][..stride];
                    if dim == 9 {
                        // Three signals' statistics: the loops unrolled.
                        lanes_arg(block, x, 9, arg);
                    } else {
                        lanes_arg(block, x, dim, arg);
                    }
                }
            } else {
                for (i, a) in arg[..nb].iter_mut().enumerate() {
                    let mut at = ch.centres + 8 * dim * (k0 + i);
                    let mut r2 = 0.0;
                    for s in 0..m.n_signals {
                        let win = &st[m.rings + 2 * l * s + ring_pos..][..l];
                        r2 += sq_dist(&m.bytes[at..at + 8 * l], win);
                        at += 8 * l;
                    }
                    let beta = f64::from_le_bytes(widths[k0 + i]);
                    *a = -(r2 / (beta * beta));
                }
            }
            // The chunk's blocks only: a set's last chunk may hold one of
            // its four (past them phi stays 0, times a weight of 0).
            let mut phi = [0.0; B];
            let live = lane_blocks(nb) * LANES;
            for (p, a) in phi[..live].iter_mut().zip(&arg) {
                *p = exp_neg11(*a);
            }
            for (a, &j) in acc.iter_mut().zip(members) {
                let weights = f64s(m.bytes, m.channels[j as usize].weights, n);
                let mut w = [0.0; B];
                for (wi, v) in w[..nb].iter_mut().zip(&weights[k0..k0 + nb]) {
                    *wi = f64::from_le_bytes(*v);
                }
                for (p, w) in phi
                    .as_chunks::<LANES>()
                    .0
                    .iter()
                    .zip(w.as_chunks::<LANES>().0)
                {
                    for ((a, p), w) in a.iter_mut().zip(p).zip(w) {
                        *a += p * w;
                    }
                }
            }
            k0 += nb;
        }
        for (a, &j) in acc.iter().zip(members) {
            let sum = lane_sum(a);
            ys[j as usize] += sum;
            nets[j as usize] += sum;
        }
    }
}

/// The smoothed fade weight of the window that ends at the newest sample
/// (the fade block at byte `at`, its rings in `st` with the oldest sample
/// at `pos`): each axis's window mean and level, the distance beyond the
/// training range in scales, the smoothstep, the one-pole smoother (started
/// at the first window's own weight).
fn fade_weight(m: &Model, at: usize, st: &mut [f64], pos: usize, first: bool) -> f64 {
    let l = m.window_len;
    let n = l as f64;
    let na4 = 4 * m.n_accels;
    let scale = m.f(at + 8 * na4);
    let mut d2 = 0.0;
    for k in 0..m.n_accels {
        let win = &st[m.fade_state + 2 * l * k + pos..][..l];
        let mut sum = 0.0;
        for v in win {
            sum += *v;
        }
        let mean = sum / n;
        let mut ss = 0.0;
        for v in win {
            ss += (*v - mean) * (*v - mean);
        }
        let level = sqrt(ss / n);
        let b = at + 8 * 4 * k;
        let em = excess(mean, m.f(b), m.f(b + 8)) / scale;
        let el = excess(level, m.f(b + 16), m.f(b + 24)) / scale;
        d2 += em * em + el * el;
    }
    let (tolerance, width, alpha) = (
        m.f(at + 8 * (na4 + 1)),
        m.f(at + 8 * (na4 + 2)),
        m.f(at + 8 * (na4 + 3)),
    );
    let d = sqrt(d2);
    let w0 = if d <= tolerance {
        1.0
    } else {
        let u = (d - tolerance) / width;
        let u = if u < 1.0 { u } else { 1.0 };
        1.0 - u * u * (3.0 - 2.0 * u)
    };
    let ws = m.fade_state + 2 * l * m.n_accels + m.n_channels;
    st[ws] = if first {
        w0
    } else {
        // Within 1e-9 of its input the one-pole takes it (sysid's SNAP).
        let w = st[ws] + alpha * (w0 - st[ws]);
        if abs(w0 - w) <= 1e-9 { w0 } else { w }
    };
    st[ws]
}

/// How far `v` lies beyond `[lo, hi]` (0 inside).
#[inline(always)]
fn excess(v: f64, lo: f64, hi: f64) -> f64 {
    let e = if lo - v > v - hi { lo - v } else { v - hi };
    if e > 0.0 { e } else { 0.0 }
}

/// √x by Newton's iteration from the exponent-halved guess (no_std has no
/// `sqrt`): correctly rounded to within an ulp for the window levels and
/// distances here (x ≥ 0; 0 gives 0).
fn sqrt(x: f64) -> f64 {
    if x <= 0.0 || x.is_nan() || x.is_infinite() {
        return if x == 0.0 || x.is_infinite() { x } else { 0.0 };
    }
    let bits = x.to_bits();
    let mut y = f64::from_bits((bits >> 1) + (1023u64 << 51));
    for _ in 0..6 {
        y = 0.5 * (y + x / y);
    }
    y
}

/// ‖x − c‖² of a window against a centre's bytes; four partial sums (the
/// exported C sums the same way) keep the adds independent.
#[inline(always)]
fn sq_dist(centre: &[u8], x: &[f64]) -> f64 {
    let mut acc = [0.0f64; 4];
    let mut cs = centre.chunks_exact(32);
    let mut xs = x.chunks_exact(4);
    for (c4, x4) in (&mut cs).zip(&mut xs) {
        for j in 0..4 {
            let mut b = [0u8; 8];
            b.copy_from_slice(&c4[8 * j..8 * j + 8]);
            let d = x4[j] - f64::from_le_bytes(b);
            acc[j] += d * d;
        }
    }
    let mut tail = 0.0;
    for (c, &v) in cs.remainder().chunks_exact(8).zip(xs.remainder()) {
        let mut b = [0u8; 8];
        b.copy_from_slice(c);
        let d = v - f64::from_le_bytes(b);
        tail += d * d;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// One value through a cascade of second-order sections (transposed direct
/// form II) whose states start at `state`; on the first step the states are
/// set to the steady state of that value first.
#[inline(always)]
fn cascade(m: &Model, at: usize, n: usize, state: &mut [f64], x: f64, first: bool) -> f64 {
    let mut v = x;
    for s in 0..n {
        let o = at + 8 * SECTION * s;
        let z = &mut state[2 * s..2 * s + 2];
        if first {
            z[0] = m.f(o + 40) * x;
            z[1] = m.f(o + 48) * x;
        }
        let (b0, b1, b2, a1, a2) = (m.f(o), m.f(o + 8), m.f(o + 16), m.f(o + 24), m.f(o + 32));
        let y = b0 * v + z[0];
        z[0] = b1 * v - a1 * y + z[1];
        z[1] = b2 * v - a2 * y;
        v = y;
    }
    v
}

#[inline(always)]
fn dot3(m: &Model, at: usize, v: &[f64; 3]) -> f64 {
    m.f(at) * v[0] + m.f(at + 8) * v[1] + m.f(at + 16) * v[2]
}

#[inline(always)]
fn dotn(m: &Model, at: usize, v: &[f64]) -> f64 {
    let mut s = 0.0;
    for (j, x) in v.iter().enumerate() {
        s += m.f(at + 8 * j) * x;
    }
    s
}

/// `pᵀ C q` with p and q in the tables.
#[inline(always)]
fn quad(m: &Model, p: usize, c: &[[f64; 3]; 3], q: usize) -> f64 {
    let pv = [m.f(p), m.f(p + 8), m.f(p + 16)];
    let qv = [m.f(q), m.f(q + 8), m.f(q + 16)];
    quad_v(&pv, c, &qv)
}

#[inline(always)]
fn quad_v(p: &[f64; 3], c: &[[f64; 3]; 3], q: &[f64; 3]) -> f64 {
    let t = [
        p[0] * c[0][0] + p[1] * c[1][0] + p[2] * c[2][0],
        p[0] * c[0][1] + p[1] * c[1][1] + p[2] * c[2][1],
        p[0] * c[0][2] + p[1] * c[1][2] + p[2] * c[2][2],
    ];
    t[0] * q[0] + t[1] * q[1] + t[2] * q[2]
}

/// Within-interval covariance of the middle of three consecutive means
/// (nav_sensors::dtg::within_interval_covariance), g².
fn covariance(m0: &[f64; 3], m1: &[f64; 3], m2: &[f64; 3]) -> [[f64; 3]; 3] {
    let mut c1 = [0.0; 3];
    let mut c2 = [0.0; 3];
    for k in 0..3 {
        c1[k] = (m2[k] - m0[k]) / 2.0;
        c2[k] = (m2[k] + m0[k] - 2.0 * m1[k]) / 2.0;
    }
    let mut c = [[0.0; 3]; 3];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = c1[i] * c1[j] / 12.0 + c2[i] * c2[j] / 180.0;
        }
    }
    c
}

/// Newton's iterations (the calibration's inverses) stop once the next
/// step would be within this many ulps of the estimate (its residual is
/// checked before the division), or after four as in the batch: later
/// steps would move only the last bits, so the two agree to a few ulps, and
/// an inverse takes one division where the batch takes four.
const NEWTON_SETTLED: f64 = 4.0 * f64::EPSILON;

/// The accelerometer triad's static inverse (nav_sensors::accel::compensate_triad:
/// three Gauss–Seidel sweeps, Newton on each axis). A sweep after the first
/// starts each axis's Newton at the last sweep's root, which the µg-sized
/// coupling moves only slightly.
fn compensate_triad(m: &Model, measured: &[f64; 3]) -> [f64; 3] {
    let mut a = *measured;
    let cal = |k: usize, i: usize| m.f(m.accel_cal + 8 * (ACCEL_CAL * k + i));
    let target: [f64; 3] = core::array::from_fn(|k| measured[k] / (1.0 + 1e-6 * cal(k, 1)));
    for sweep in 0..3 {
        for k in 0..3 {
            let c = |i: usize| cal(k, i);
            let (bias, k2, k3, mo, mp, kip, kio) = (c(0), c(2), c(3), c(4), c(5), c(6), c(7));
            let (ap, ao) = (a[(k + 1) % 3], a[(k + 2) % 3]);
            let mut x = if sweep == 0 { target[k] } else { a[k] };
            for _ in 0..4 {
                let core = 1e-6
                    * (bias + x * x * (k2 + k3 * x) + mo * ap - mp * ao
                        + x * (kip * ap + kio * ao));
                let g = x + core - target[k];
                let dg = 1.0 + 1e-6 * (2.0 * k2 * x + 3.0 * k3 * x * x + kip * ap + kio * ao);
                if abs(g) <= NEWTON_SETTLED * abs(dg * x) {
                    break;
                }
                x -= g / dg;
            }
            a[k] = x;
        }
    }
    a
}

/// The frame row `r` (0 = I, 1 = O, 2 = S) of channel `k`.
#[inline(always)]
fn axis(m: &Model, k: usize, r: usize) -> [f64; 3] {
    let o = m.frames + 8 * (9 * k + 3 * r);
    [m.f(o), m.f(o + 8), m.f(o + 16)]
}

#[inline(always)]
fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Each gyro's inverse model, two passes (nav_sensors Calibration::compensate
/// and UnitCalibration::compensate): `gyro` holds the raw outputs and is
/// left holding the calibrated ones.
fn compensate_gyros(m: &Model, gyro: &mut [f64], f: &[f64; 3], cov: &[[f64; 3]; 3]) {
    let n = gyro.len();
    let mut raw = [0.0; MAX_CHANNELS];
    raw[..n].copy_from_slice(gyro);
    for _ in 0..2 {
        let mut rate = [0.0; 3];
        for (i, r) in rate.iter_mut().enumerate() {
            *r = dotn(m, m.ls + 8 * n * i, gyro);
        }
        let mut next = [0.0; MAX_CHANNELS];
        for (k, out) in next[..n].iter_mut().enumerate() {
            let ch = &m.channels[k];
            *out = if ch.model == gyro::RATE {
                rate_inverse(m, ch.cal, raw[k], f, cov)
            } else {
                dtg_inverse(m, k, raw[k], &rate, f, cov)
            };
        }
        gyro.copy_from_slice(&next[..n]);
    }
}

/// A rate gyro's inverse (nav_sensors RateCoefficients::compensate_deg_h):
/// the drift at zero rate from its table at `o` (`RateTerm::ALL` order),
/// removed, divided by the scale factor. It needs no rate.
fn rate_inverse(m: &Model, o: usize, measured: f64, f: &[f64; 3], cov: &[[f64; 3]; 3]) -> f64 {
    let r = [
        1.0,
        0.0,
        f[0],
        f[1],
        f[2],
        f[0] * f[0] + cov[0][0],
        f[1] * f[1] + cov[1][1],
        f[2] * f[2] + cov[2][2],
        f[0] * f[1] + cov[0][1],
        f[0] * f[2] + cov[0][2],
        f[1] * f[2] + cov[1][2],
        0.0,
    ];
    let mut drift = 0.0;
    for (t, rv) in r.iter().enumerate() {
        drift += m.f(o + 8 * t) * rv;
    }
    (measured - drift) / (1.0 + 1e-6 * m.f(o + 8))
}

/// Channel `k`'s inverse DTG model (nav_sensors DtgCoefficients::compensate_deg_h)
/// at the least-squares `rate`.
fn dtg_inverse(
    m: &Model,
    k: usize,
    measured: f64,
    rate: &[f64; 3],
    f: &[f64; 3],
    cov: &[[f64; 3]; 3],
) -> f64 {
    let (ia, oa, sa) = (axis(m, k, 0), axis(m, k, 1), axis(m, k, 2));
    let w = [dot(&ia, rate), dot(&oa, rate), dot(&sa, rate)];
    let fr = [dot(&ia, f), dot(&oa, f), dot(&sa, f)];
    let cv = [
        quad_v(&ia, cov, &ia),
        quad_v(&oa, cov, &oa),
        quad_v(&sa, cov, &sa),
        quad_v(&ia, cov, &oa),
        quad_v(&ia, cov, &sa),
        quad_v(&oa, cov, &sa),
    ];
    let o = m.channels[k].cal;
    let drift = |wi: f64| {
        const PER_S: f64 = 1.0 / 3600.0;
        let r = [
            1.0,
            1e-6 * wi,
            1e-6 * w[1],
            1e-6 * w[2],
            fr[0],
            fr[1],
            fr[2],
            fr[0] * fr[0] + cv[0],
            fr[1] * fr[1] + cv[1],
            fr[2] * fr[2] + cv[2],
            fr[0] * fr[1] + cv[3],
            fr[0] * fr[2] + cv[4],
            fr[1] * fr[2] + cv[5],
            (wi * PER_S) * (w[1] * PER_S),
            (wi * PER_S) * (w[2] * PER_S),
            (w[1] * PER_S) * (w[2] * PER_S),
            0.0,
            0.0,
        ];
        let mut s = 0.0;
        for (t, rv) in r.iter().enumerate() {
            s += rv * m.f(o + 8 * t);
        }
        s
    };
    let nl = m.f(o + 8 * 18);
    let a0 = drift(0.0);
    let b = 1.0 + drift(1.0) - a0;
    let mut wi = (measured - a0) / b;
    for _ in 0..4 {
        let per_s = abs(wi) * (1.0 / 3600.0);
        let fx = a0 + b * wi + 1e-6 * nl * per_s * wi - measured;
        let df = b + 2e-6 * nl * per_s;
        if abs(fx) <= NEWTON_SETTLED * abs(df * wi) {
            break;
        }
        wi -= fx / df;
    }
    wi
}

/// |x|, exactly (clears the sign bit).
#[inline(always)]
fn abs(x: f64) -> f64 {
    f64::from_bits(x.to_bits() & !(1u64 << 63))
}

/// Tables of a small model for the examples: no calibration, one centre,
/// a 4-sample window of `az`, no filters.
#[doc(hidden)]
pub fn doc_tables() -> [u8; 4 * 24 + 8 * (1 + 54 + 18 + 6 * 3 + 6 * 4)] {
    let mut b = [0u8; 4 * 24 + 8 * (1 + 54 + 18 + 6 * 3 + 6 * 4)];
    let words: [u32; 24] = [
        u32::from_le_bytes(MAGIC),
        VERSION,
        24,
        0,
        0,
        0,
        0,
        4,
        1,
        0,
        0,
        0,
        0,
        0,
        0,
        1,
        1,
        1,
        1,
        1,
        1,
        2,
        input::RAW,
        0,
    ];
    for (i, w) in words.iter().enumerate() {
        b[4 * i..4 * i + 4].copy_from_slice(&w.to_le_bytes());
    }
    let mut at = 4 * 24;
    let mut put = |v: f64| {
        b[at..at + 8].copy_from_slice(&v.to_le_bytes());
        at += 8;
    };
    put(0.02);
    for _ in 0..72 {
        put(0.0);
    }
    for c in 0..6 {
        put(c as f64); // bias
        put(1.0); // width
        put(0.5); // weight
        for _ in 0..4 {
            put(1.0); // centre
        }
    }
    b
}

#[cfg(test)]
extern crate std;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_neg_is_within_four_ulps_of_the_c_library() {
        let mut x = 0.0f64;
        while x > -720.0 {
            let (got, want) = (exp_neg11(x), x.exp());
            let ulps = (got.to_bits() as i64 - want.to_bits() as i64).abs();
            assert!(
                ulps <= 4 || want < f64::MIN_POSITIVE * 16.0,
                "x = {x}: {got} vs {want}"
            );
            x -= 0.0123;
        }
        assert_eq!(exp_neg11(0.0), 1.0);
        assert_eq!(exp_neg11(-1000.0), 0.0);
        assert_eq!(abs(-2.5), 2.5);
    }

    #[test]
    fn sqrt_is_within_two_ulps_of_the_library() {
        let mut x = 1e-30f64;
        while x < 1e30 {
            let (got, want) = (sqrt(x), x.sqrt());
            let ulps = (got.to_bits() as i64 - want.to_bits() as i64).abs();
            assert!(ulps <= 2, "x = {x}: {got} vs {want}");
            x *= 1.37;
        }
    }

    #[test]
    fn each_refusal_has_its_error() {
        let good = doc_tables();
        let m = Model::parse(&good).unwrap();
        assert_eq!(m.size_bytes(), good.len());

        let mut bad = good;
        bad[0] = b'X';
        assert_eq!(Model::parse(&bad).unwrap_err(), Error::Magic);

        let mut bad = good;
        bad[4..8].copy_from_slice(&9u32.to_le_bytes());
        assert_eq!(
            Model::parse(&bad).unwrap_err(),
            Error::Version {
                found: 9,
                supported: UNIT_VERSION
            }
        );

        assert_eq!(
            Model::parse(&good[..good.len() - 1]).unwrap_err(),
            Error::Truncated {
                need: good.len(),
                have: good.len() - 1
            }
        );

        let mut bad = good;
        bad[4 * 21..4 * 22].copy_from_slice(&3u32.to_le_bytes()); // signal 3: no extra column
        assert_eq!(Model::parse(&bad).unwrap_err(), Error::Header { word: 21 });

        // Layout 3 with 17 channels: more than the evaluator holds.
        let mut bad = good;
        bad[4..8].copy_from_slice(&UNIT_VERSION.to_le_bytes());
        bad[36..40].copy_from_slice(&17u32.to_le_bytes());
        assert_eq!(
            Model::parse(&bad).unwrap_err(),
            Error::TooMany {
                what: "channels",
                found: 17,
                max: MAX_CHANNELS
            }
        );

        let mut small = [0.0; 4];
        assert_eq!(
            Evaluator::new(m, &mut small).unwrap_err(),
            Error::StateTooSmall {
                need: m.state_len(),
                have: 4
            }
        );
        let mut state = [0.0; 64];
        let mut ev = Evaluator::new(m, &mut state).unwrap();
        assert_eq!(
            ev.step(&[0.0; 6], &[0.0; 3], &[1.0]).unwrap_err(),
            Error::Extra { need: 0, have: 1 }
        );
        assert_eq!(
            ev.step(&[0.0; 4], &[0.0; 3], &[]).unwrap_err(),
            Error::Sensors {
                what: "gyro outputs",
                need: 6,
                have: 4
            }
        );
    }

    #[test]
    fn channels_with_the_same_centres_and_widths_share_one_set() {
        // doc_tables: every channel has the one centre of four 1 g samples
        // and width 1 g; a channel with another width has a set of its own.
        let b = doc_tables();
        let m = Model::parse(&b).unwrap();
        assert!((0..6).all(|c| m.centre_set(c) == 0));
        let mut other = b;
        let width_of_z = 4 * 24 + 8 * (1 + 54 + 18) + 4 * 7 * 8 + 8;
        other[width_of_z..width_of_z + 8].copy_from_slice(&2.0f64.to_le_bytes());
        let m2 = Model::parse(&other).unwrap();
        assert_eq!(
            (0..6)
                .map(|c| m2.centre_set(c))
                .collect::<std::vec::Vec<_>>(),
            [0, 0, 0, 0, 4, 0]
        );
        assert!(m2.flops_per_step() > m.flops_per_step());
    }

    #[test]
    fn the_window_fills_then_every_step_gives_the_rbf_sum() {
        // doc_tables: bias c on channel c, one centre of four 1 g samples,
        // width 1 g, weight 0.5; no calibration, no filter.
        let b = doc_tables();
        let m = Model::parse(&b).unwrap();
        let mut state = [0.0; 64];
        let mut ev = Evaluator::new(m, &mut state).unwrap();
        let az = [1.0, 2.0, 1.0, 0.0, 1.0, 1.0];
        let mut outs = [None; 6];
        // Sample i's output comes with sample i + 1, the last one's from flush.
        for (i, a) in az.iter().enumerate() {
            let o = ev.step(&[10.0; 6], &[0.0, 0.0, *a], &[]).unwrap();
            if i > 0 {
                outs[i - 1] = o;
            }
        }
        outs[5] = ev.flush();
        assert!(outs[..3].iter().all(Option::is_none));
        for (i, o) in outs.iter().enumerate().skip(3) {
            // The window is the last four az samples, oldest first.
            let r2: f64 = az[i - 3..=i].iter().map(|a| (a - 1.0) * (a - 1.0)).sum();
            let o = o.unwrap();
            for c in 0..6 {
                let want = c as f64 + 0.5 * exp_neg11(-r2);
                assert!((o.error_deg_h[c] - want).abs() < 1e-15, "{i} {c}");
                assert!((o.rate_deg_h[c] - (10.0 - want)).abs() < 1e-14);
            }
        }
        assert_eq!(ev.steps(), 0, "flush leaves the evaluator at rest");
    }

    /// doc_tables with the statistics input (current, mean, rms of a
    /// 4-sample az window) and `k` centres on every channel: centre i at
    /// (1 + i/k, 1, 0.1·i/k), width 1 + i/k, weight (−1)ⁱ/(i + 1).
    fn statistics_tables(k: usize) -> std::vec::Vec<u8> {
        let mut words = std::vec::Vec::from(&doc_tables()[..4 * 24]);
        let mut put_word =
            |i: usize, v: u32| words[4 * i..4 * i + 4].copy_from_slice(&v.to_le_bytes());
        for c in 0..6 {
            put_word(15 + c, k as u32);
        }
        put_word(22, input::STATISTICS);
        let mut b = words;
        let mut put = |v: f64| b.extend(v.to_le_bytes());
        put(0.02);
        for _ in 0..72 {
            put(0.0);
        }
        for c in 0..6 {
            put(c as f64);
            for i in 0..k {
                put(1.0 + i as f64 / k as f64);
            }
            for i in 0..k {
                put(if i % 2 == 0 { 1.0 } else { -1.0 } / (i + 1) as f64);
            }
            for i in 0..k {
                let u = i as f64 / k as f64;
                put(1.0 + u);
                put(1.0);
                put(0.1 * u);
            }
        }
        b
    }

    #[test]
    fn the_statistics_kernels_in_lanes_are_the_sum_and_survive_a_reset() {
        // 13 centres: one whole block of lanes and a part block.
        let k = 13;
        let b = statistics_tables(k);
        let m = Model::parse(&b).unwrap();
        assert_eq!((m.input_dim(), m.centre_set(5)), (3, 0));
        let mut state = std::vec![0.0; m.state_len()];
        let mut ev = Evaluator::new(m, &mut state).unwrap();
        let az = [1.0, 1.3, 0.8, 1.1, 0.9, 1.6, 1.2];
        let mut runs = std::vec::Vec::new();
        for _ in 0..2 {
            let mut outs = std::vec::Vec::new();
            for (i, a) in az.iter().enumerate() {
                let o = ev.step(&[10.0; 6], &[0.0, 0.0, *a], &[]).unwrap();
                if i > 0 {
                    outs.push(o);
                }
            }
            outs.push(ev.flush());
            runs.push(outs);
        }
        assert_eq!(runs[0], runs[1], "a flushed evaluator steps as a new one");
        for (i, o) in runs[0].iter().enumerate().skip(3) {
            let w = &az[i - 3..=i];
            let mean = w.iter().sum::<f64>() / 4.0;
            let rms = (w.iter().map(|v| v * v).sum::<f64>() / 4.0 - mean * mean).sqrt();
            let x = [az[i], mean, rms];
            let net: f64 = (0..k)
                .map(|j| {
                    let u = j as f64 / k as f64;
                    let c = [1.0 + u, 1.0, 0.1 * u];
                    let r2: f64 = (0..3).map(|d| (x[d] - c[d]) * (x[d] - c[d])).sum();
                    let beta = 1.0 + u;
                    let wt = if j % 2 == 0 { 1.0 } else { -1.0 } / (j + 1) as f64;
                    wt * (-r2 / (beta * beta)).exp()
                })
                .sum();
            let o = o.unwrap();
            for c in 0..6 {
                let want = c as f64 + net;
                assert!(
                    (o.error_deg_h[c] - want).abs() < 1e-13,
                    "{i} {c}: {} vs {want}",
                    o.error_deg_h[c]
                );
            }
        }
    }
}
