//! A model's tables, read and checked once ([`Model::parse`]): the header's
//! sizes, where each number is, which channels share a centre set, and
//! where each part of the evaluator's state lives. Layouts 2 (the paper's
//! six DTG channels, written before version 3), 3 (any unit, one list of
//! window signals) and 4 (any unit, each channel's network on its own
//! window signals) are read into the one `Model`: a layout-2 or 3 table is
//! a layout-4 one whose channels all read every signal.

use crate::error::Error;
use crate::interval::LOOKAHEAD;
use crate::lanes::{CAL_ROWS, lane_blocks};
use crate::layout::{
    ACCEL_CAL, FIXED_HEADER_WORDS, FLAG_ACCEL_TRIAD, FLAG_CALIBRATION, FLAG_FADE, FLAG_FADE_SHAPE,
    LANES, LAYOUT_2, LAYOUT_2_HEADER_WORDS, LAYOUT_3, MAGIC, MAX_ACCELS, MAX_CHANNELS, MAX_SIGNALS,
    VERSION, fade_floats, gyro, gyro_cal_len, input, kind, kind_params_of,
};
use crate::maths::{SECTION, rd, word};

/// Where one channel's numbers are (byte offsets into the tables) and its
/// parts of the state (`f64` offsets).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ChannelAt {
    pub(crate) n_effects: usize,
    pub(crate) n_centres: usize,
    /// The window signals its network reads (bit s: signal s, in the
    /// tables' order) and its input dimension.
    pub(crate) mask: u32,
    pub(crate) dim: usize,
    /// Header word of the first (kind, index) pair.
    pub(crate) effect_words: usize,
    pub(crate) bias: usize,
    pub(crate) coefficients: usize,
    pub(crate) params: usize,
    pub(crate) widths: usize,
    pub(crate) weights: usize,
    pub(crate) centres: usize,
    /// The gyro's model ([`gyro`]) and the byte offset of its calibration.
    pub(crate) model: u32,
    pub(crate) cal: usize,
    /// State: its effects' filter states, its set's kernel lanes (a
    /// leader's), its weights in lanes.
    pub(crate) effect_state: usize,
    pub(crate) lanes: usize,
    pub(crate) weight_lanes: usize,
}

/// Where each part of the evaluator's state starts (`f64` offsets).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct StateAt {
    pub(crate) len: usize,
    /// The pending samples' calibrated accelerometers, raw gyro outputs
    /// and extra columns, [`LOOKAHEAD`] of each, oldest first (after the
    /// six specific forces, 0..18).
    pub(crate) accel: usize,
    pub(crate) gyro: usize,
    pub(crate) extra: usize,
    pub(crate) in_filter: usize,
    pub(crate) rings: usize,
    /// The fade: a doubled ring of 2L per accelerometer, the held network
    /// part per channel, the smoothed weight.
    pub(crate) fade: usize,
    pub(crate) smooth: usize,
    /// Running sums s₁, s₂ per signal, then the statistics inputs (3 per
    /// signal).
    pub(crate) sums: usize,
    pub(crate) features: usize,
    /// The calibration in lanes ([`crate::lanes`]), if the tables hold one.
    pub(crate) cal_lanes: usize,
}

/// A model's tables, checked once; cheap to copy.
#[derive(Debug, Clone, Copy)]
pub struct Model<'a> {
    pub(crate) bytes: &'a [u8],
    pub(crate) version: u32,
    pub(crate) calibrated: bool,
    /// The accelerometers are calibrated as the x, y, z triad.
    pub(crate) accel_triad: bool,
    pub(crate) n_extra: usize,
    pub(crate) n_sections: usize,
    pub(crate) n_in_sections: usize,
    pub(crate) window_len: usize,
    pub(crate) n_signals: usize,
    pub(crate) signal_words: usize,
    pub(crate) n_channels: usize,
    pub(crate) n_accels: usize,
    pub(crate) dt_s: f64,
    /// The log's rate unit in deg/h and specific-force unit in g (1 and 1
    /// for layout 2).
    pub(crate) rate_to_deg_h: f64,
    pub(crate) force_to_g: f64,
    pub(crate) frames: usize,
    pub(crate) ls: usize,
    /// Byte offset of the specific-force operator (3 × n_accels), `None`
    /// for layout 2 (ax, ay, az are x, y, z).
    pub(crate) force_op: Option<usize>,
    pub(crate) accel_cal: usize,
    pub(crate) out_filter: usize,
    pub(crate) in_filter: usize,
    pub(crate) smoother: usize,
    pub(crate) channels: [ChannelAt; MAX_CHANNELS],
    /// Per channel the first channel with the same window signals, centres
    /// and widths (its kernel values are computed once per step for all of
    /// them), and the channels that share each leader's set.
    pub(crate) leader: [usize; MAX_CHANNELS],
    pub(crate) members: [[u8; MAX_CHANNELS]; MAX_CHANNELS],
    pub(crate) n_members: [usize; MAX_CHANNELS],
    /// The network's input ([`input`]).
    pub(crate) input: u32,
    pub(crate) n_smooth_sections: usize,
    /// Byte offset of the fade block, if the tables have one.
    pub(crate) fade: Option<usize>,
    /// Whether the fade block ends with the vibration shape's range.
    pub(crate) fade_shape: bool,
    pub(crate) st: StateAt,
}

/// The header's sizes before the per-channel lists: channels and
/// accelerometers, and where each per-channel list is (`None`: absent
/// from the layout: layout 2's gyros are all DTGs, layouts 2 and 3 read
/// every signal).
struct Counts {
    n_channels: usize,
    n_accels: usize,
    effects_at: usize,
    centres_at: usize,
    models_at: Option<usize>,
    masks_at: Option<usize>,
    signal_words: usize,
}

fn counts(bytes: &[u8], version: u32) -> Result<Counts, Error> {
    if version == LAYOUT_2 {
        return Ok(Counts {
            n_channels: 6,
            n_accels: 3,
            effects_at: 9,
            centres_at: 15,
            models_at: None,
            masks_at: None,
            signal_words: LAYOUT_2_HEADER_WORDS,
        });
    }
    let n_channels = word(bytes, 9)? as usize;
    let n_accels = word(bytes, 10)? as usize;
    for (what, found, max) in [
        ("channels", n_channels, MAX_CHANNELS),
        ("accelerometers", n_accels, MAX_ACCELS),
    ] {
        if found > max {
            return Err(Error::TooMany { what, found, max });
        }
    }
    for (v, word) in [(n_channels, 9), (n_accels, 10)] {
        if v == 0 {
            return Err(Error::Header { word });
        }
    }
    let (w, n) = (FIXED_HEADER_WORDS, n_channels);
    let lists = if version == LAYOUT_3 { 3 } else { 4 };
    Ok(Counts {
        n_channels,
        n_accels,
        effects_at: w,
        centres_at: w + n,
        models_at: Some(w + 2 * n),
        masks_at: (version == VERSION).then_some(w + 3 * n),
        signal_words: w + lists * n,
    })
}

/// The mask of every one of `n` signals.
const fn all_signals(n: usize) -> u32 {
    if n >= 32 { u32::MAX } else { (1u32 << n) - 1 }
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

/// Each channel's effect and centre counts, gyro model and window
/// signals from the per-channel lists, checked.
fn channel_lists(
    bytes: &[u8],
    n: &Counts,
    n_signals: usize,
) -> Result<[ChannelAt; MAX_CHANNELS], Error> {
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
        ch.mask = match n.masks_at {
            None => all_signals(n_signals),
            Some(at) => word(bytes, at + c)?,
        };
        if ch.mask == 0 || ch.mask & !all_signals(n_signals) != 0 {
            return Err(Error::Header {
                word: n.masks_at.unwrap_or(0) + c,
            });
        }
    }
    Ok(channels)
}

/// The header read and checked: the fixed words, the per-channel lists,
/// the signal codes, the effect pairs, the input and smoother words.
struct Header {
    version: u32,
    flags: u32,
    n_extra: usize,
    n_sections: usize,
    n_in_sections: usize,
    window_len: usize,
    n_signals: usize,
    counts: Counts,
    channels: [ChannelAt; MAX_CHANNELS],
    params_len: [usize; MAX_CHANNELS],
    input: u32,
    n_smooth_sections: usize,
    header_words: usize,
}

fn header(bytes: &[u8]) -> Result<Header, Error> {
    if bytes.len() < 4 || bytes[..4] != MAGIC {
        return Err(Error::Magic);
    }
    let version = word(bytes, 1)?;
    if !(LAYOUT_2..=VERSION).contains(&version) {
        return Err(Error::Version {
            found: version,
            supported: VERSION,
        });
    }
    let header_words = word(bytes, 2)? as usize;
    let flags = word(bytes, 3)?;
    let [n_extra, n_sections, n_in_sections, window_len, n_signals] =
        core::array::from_fn(|i| word(bytes, 4 + i).map(|w| w as usize));
    let (n_extra, n_sections, n_in_sections) = (n_extra?, n_sections?, n_in_sections?);
    let (window_len, n_signals) = (window_len?, n_signals?);
    for (v, word) in [(window_len, 7), (n_signals, 8)] {
        if v == 0 {
            return Err(Error::Header { word });
        }
    }
    if n_signals > MAX_SIGNALS {
        return Err(Error::TooMany {
            what: "window signals",
            found: n_signals,
            max: MAX_SIGNALS,
        });
    }
    let counts = counts(bytes, version)?;
    let mut channels = channel_lists(bytes, &counts, n_signals)?;
    let (w, params_len) = effect_words(
        bytes,
        &mut channels[..counts.n_channels],
        counts.signal_words,
        (n_signals, counts.n_accels, n_extra),
    )?;
    let input = word(bytes, w)?;
    if input != input::RAW && input != input::STATISTICS {
        return Err(Error::Header { word: w });
    }
    let n_smooth_sections = word(bytes, w + 1)? as usize;
    if header_words < w + 2 || !header_words.is_multiple_of(2) {
        return Err(Error::Header { word: 2 });
    }
    Ok(Header {
        version,
        flags,
        n_extra,
        n_sections,
        n_in_sections,
        window_len,
        n_signals,
        counts,
        channels,
        params_len,
        input,
        n_smooth_sections,
        header_words,
    })
}

/// Per channel the first channel with the same window signals, centres
/// and widths (its leader), and each leader's members in channel order.
type Sharing = (
    [usize; MAX_CHANNELS],
    [[u8; MAX_CHANNELS]; MAX_CHANNELS],
    [usize; MAX_CHANNELS],
);

fn sharing(bytes: &[u8], channels: &[ChannelAt]) -> Sharing {
    let mut leader = [0usize; MAX_CHANNELS];
    let mut members = [[0u8; MAX_CHANNELS]; MAX_CHANNELS];
    let mut n_members = [0usize; MAX_CHANNELS];
    let block = |ch: &ChannelAt| {
        let k = ch.n_centres;
        (
            ch.mask,
            &bytes[ch.widths..ch.widths + 8 * k],
            &bytes[ch.centres..ch.centres + 8 * k * ch.dim],
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
    /// Checks the header and sizes of `bytes` (layout version
    /// [`LAYOUT_2`], [`LAYOUT_3`] or [`VERSION`]).
    pub fn parse(bytes: &'a [u8]) -> Result<Self, Error> {
        let h = header(bytes)?;
        let unit = h.version != LAYOUT_2;
        let calibrated = h.flags & FLAG_CALIBRATION != 0;
        let accel_triad = if unit {
            h.flags & FLAG_ACCEL_TRIAD != 0
        } else {
            calibrated
        };
        let (nc, na) = (h.counts.n_channels, h.counts.n_accels);
        if accel_triad && na != 3 {
            return Err(Error::Header { word: 3 });
        }
        let mut channels = h.channels;
        for ch in channels[..nc].iter_mut() {
            let signals = ch.mask.count_ones() as usize;
            ch.dim = signals
                * if h.input == input::STATISTICS {
                    3
                } else {
                    h.window_len
                };
        }
        // Payload offsets, in bytes.
        let mut at = 4 * h.header_words;
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
        let out_filter = take(SECTION * h.n_sections);
        let in_filter = take(SECTION * h.n_in_sections);
        let smoother = take(SECTION * h.n_smooth_sections);
        for (c, ch) in channels[..nc].iter_mut().enumerate() {
            ch.bias = take(1);
            ch.coefficients = take(ch.n_effects);
            ch.params = take(h.params_len[c]);
            ch.widths = take(ch.n_centres);
            ch.weights = take(ch.n_centres);
            ch.centres = take(ch.n_centres * ch.dim);
        }
        let fade_shape = h.flags & FLAG_FADE != 0 && h.flags & FLAG_FADE_SHAPE != 0;
        let fade = (h.flags & FLAG_FADE != 0).then(|| take(fade_floats(na, nc, fade_shape)));
        if bytes.len() < at {
            return Err(Error::Truncated {
                need: at,
                have: bytes.len(),
            });
        }
        let (leader, members, n_members) = sharing(bytes, &channels[..nc]);
        let mut m = Self {
            bytes: &bytes[..at],
            version: h.version,
            calibrated,
            accel_triad,
            n_extra: h.n_extra,
            n_sections: h.n_sections,
            n_in_sections: h.n_in_sections,
            window_len: h.window_len,
            n_signals: h.n_signals,
            signal_words: h.counts.signal_words,
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
            smoother,
            channels,
            leader,
            members,
            n_members,
            input: h.input,
            n_smooth_sections: h.n_smooth_sections,
            fade,
            fade_shape,
            st: StateAt::default(),
        };
        m.lay_out_state();
        Ok(m)
    }

    /// Where each part of the state lives (see docs/formats.md, "State").
    fn lay_out_state(&mut self) {
        let (nc, na, l, ns) = (
            self.n_channels,
            self.n_accels,
            self.window_len,
            self.n_signals,
        );
        let mut at = 3 * 2 * LOOKAHEAD;
        let mut take = |n: usize| {
            let here = at;
            at += n;
            here
        };
        let mut st = StateAt {
            accel: take(LOOKAHEAD * na),
            gyro: take(LOOKAHEAD * nc),
            extra: take(LOOKAHEAD * self.n_extra),
            ..StateAt::default()
        };
        for ch in self.channels[..nc].iter_mut() {
            ch.effect_state = take(2 * self.n_sections * ch.n_effects);
        }
        st.in_filter = take(2 * self.n_in_sections * ns);
        st.rings = take(2 * l * ns);
        st.fade = take(if self.fade.is_some() {
            2 * l * na + nc + 1
        } else {
            0
        });
        st.smooth = take(nc * 2 * self.n_smooth_sections);
        st.sums = take(2 * ns);
        st.features = take(if self.input == input::STATISTICS {
            3 * ns
        } else {
            0
        });
        st.cal_lanes = take(if self.calibrated { CAL_ROWS * nc } else { 0 });
        for c in 0..nc {
            if self.leader[c] == c {
                let n = self.kernel_lanes_len(c);
                self.channels[c].lanes = take(n);
            }
        }
        for c in 0..nc {
            self.channels[c].lanes = self.channels[self.leader[c]].lanes;
            self.channels[c].weight_lanes = take(lane_blocks(self.channels[c].n_centres) * LANES);
        }
        st.len = at;
        self.st = st;
    }

    /// Size of the tables, bytes.
    pub fn size_bytes(&self) -> usize {
        self.bytes.len()
    }

    /// `f64` elements of state an [`crate::Evaluator`] needs.
    pub fn state_len(&self) -> usize {
        self.st.len
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

    /// Centres of one channel (the unit's gyros in its file's order; in
    /// layout 2 X, X1, Y, Y1, Z, Z1).
    pub fn n_centres(&self, channel: usize) -> usize {
        self.channels[channel].n_centres
    }

    /// Effects of one channel.
    pub fn n_effects(&self, channel: usize) -> usize {
        self.channels[channel].n_effects
    }

    /// Channels (gyros): 6 in layout 2.
    pub fn n_channels(&self) -> usize {
        self.n_channels
    }

    /// Accelerometers a step takes: 3 in layout 2.
    pub fn n_accels(&self) -> usize {
        self.n_accels
    }

    /// Window signals (calibrated accelerometers or extra columns).
    pub fn n_signals(&self) -> usize {
        self.n_signals
    }

    /// The layout version of the tables ([`LAYOUT_2`], [`LAYOUT_3`] or
    /// [`VERSION`]).
    pub fn version(&self) -> u32 {
        self.version
    }

    /// The log's rate unit in deg/h and its specific-force unit in g (what
    /// a log's gyro and accelerometer columns are multiplied by before a
    /// step; 1 and 1 in layout 2).
    pub fn log_units(&self) -> (f64, f64) {
        (self.rate_to_deg_h, self.force_to_g)
    }

    /// The first channel whose window signals, centres and widths channel
    /// `channel` shares (itself if none): the kernel values of a shared set
    /// are computed once per step.
    pub fn centre_set(&self, channel: usize) -> usize {
        self.leader[channel]
    }

    /// The window signals channel `channel`'s network reads: bit s for
    /// signal s of the tables' list (every signal in layouts 2 and 3).
    pub fn signal_mask(&self, channel: usize) -> u32 {
        self.channels[channel].mask
    }

    /// Whether the tables fade the network part outside the training range.
    pub fn fades(&self) -> bool {
        self.fade.is_some()
    }

    /// Whether the fade also judges each window's vibration shape (the
    /// tables' fade block ends with its range).
    pub fn fades_by_shape(&self) -> bool {
        self.fade_shape
    }

    /// Whether the tables hold a ground calibration, and whether it
    /// calibrates the accelerometers as the x, y, z triad.
    pub fn calibration(&self) -> (bool, bool) {
        (self.calibrated, self.accel_triad)
    }

    /// The network's input kind ([`input`]).
    pub fn input_kind(&self) -> u32 {
        self.input
    }

    /// The input dimension of channel `channel`'s network.
    pub fn input_dim(&self, channel: usize) -> usize {
        self.channels[channel].dim
    }

    /// Second-order sections of the effect low-pass, the window low-pass
    /// and the prediction smoother (0: none).
    pub fn n_sections(&self) -> [usize; 3] {
        [self.n_sections, self.n_in_sections, self.n_smooth_sections]
    }

    /// Second-order sections of the prediction smoother (0: none).
    pub fn n_smoother_sections(&self) -> usize {
        self.n_smooth_sections
    }

    /// The gyro model of channel `channel` ([`gyro`]).
    pub fn gyro_model(&self, channel: usize) -> u32 {
        self.channels[channel].model
    }

    /// The code of window signal `s`: k < [`Model::n_accels`] for
    /// calibrated accelerometer k, `n_accels + j` for extra column j.
    pub fn signal_code(&self, s: usize) -> usize {
        self.w(self.signal_words + s) as usize
    }

    #[inline]
    /// Effect `e` of channel `channel`: its kind ([`kind`]) and index
    /// (the extra column of kind 0).
    pub fn effect(&self, channel: usize, e: usize) -> (u32, usize) {
        let at = self.channels[channel].effect_words + 2 * e;
        (self.w(at), self.w(at + 1) as usize)
    }

    /// The numbers of one part of the tables, in the layout's order.
    pub fn floats(&self, part: Part) -> Floats<'a> {
        let (nc, na) = (self.n_channels, self.n_accels);
        let (at, n) = match part {
            Part::Frames => (self.frames, 9 * nc),
            Part::RateOperator => (self.ls, 3 * nc),
            Part::ForceOperator => (
                self.force_op.unwrap_or(0),
                3 * na * usize::from(self.force_op.is_some()),
            ),
            Part::GyroCalibration(c) => {
                let ch = &self.channels[c];
                let n = if self.calibrated {
                    gyro_cal_len(ch.model).unwrap_or(0)
                } else {
                    0
                };
                (ch.cal, n)
            }
            Part::AccelCalibration => (
                self.accel_cal,
                if self.accel_triad { 3 * ACCEL_CAL } else { 0 },
            ),
            Part::EffectFilter => (self.out_filter, SECTION * self.n_sections),
            Part::InputFilter => (self.in_filter, SECTION * self.n_in_sections),
            Part::Smoother => (self.smoother, SECTION * self.n_smooth_sections),
            Part::Bias(c) => (self.channels[c].bias, 1),
            Part::Coefficients(c) => (self.channels[c].coefficients, self.channels[c].n_effects),
            Part::Params(c) => {
                let ch = &self.channels[c];
                (ch.params, (ch.widths - ch.params) / 8)
            }
            Part::Widths(c) => (self.channels[c].widths, self.channels[c].n_centres),
            Part::Weights(c) => (self.channels[c].weights, self.channels[c].n_centres),
            Part::Centres(c) => {
                let ch = &self.channels[c];
                (ch.centres, ch.n_centres * ch.dim)
            }
            Part::Fade => (
                self.fade.unwrap_or(0),
                self.fade
                    .map_or(0, |_| fade_floats(na, nc, self.fade_shape)),
            ),
        };
        Floats(&self.bytes[at..at + 8 * n])
    }

    #[inline(always)]
    pub(crate) fn f(&self, at: usize) -> f64 {
        rd(self.bytes, at)
    }

    #[inline(always)]
    pub(crate) fn w(&self, i: usize) -> u32 {
        let mut w = [0u8; 4];
        w.copy_from_slice(&self.bytes[4 * i..4 * i + 4]);
        u32::from_le_bytes(w)
    }
}

/// A part of the tables ([`Model::floats`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Per channel its I, O, S axes (9 each; a rate gyro's I and two zero rows).
    Frames,
    /// The least-squares rate operator, 3 × n row-major.
    RateOperator,
    /// The specific-force operator, 3 × n_a (none in layout 2).
    ForceOperator,
    /// Channel c's calibration table (none without a calibration).
    GyroCalibration(usize),
    /// The accelerometer triad's calibration, 3 × 8 (none without it).
    AccelCalibration,
    /// The effect low-pass's sections, 7 each.
    EffectFilter,
    /// The window low-pass's sections.
    InputFilter,
    /// The prediction smoother's sections.
    Smoother,
    /// Channel c's bias.
    Bias(usize),
    /// Channel c's effect coefficients.
    Coefficients(usize),
    /// Channel c's effect parameters, effect by effect.
    Params(usize),
    /// Channel c's widths β.
    Widths(usize),
    /// Channel c's weights.
    Weights(usize),
    /// Channel c's centres, centre by centre.
    Centres(usize),
    /// The fade block (none without one).
    Fade,
}

/// Little-endian `f64` numbers of the tables, in order.
#[derive(Debug, Clone)]
pub struct Floats<'a>(&'a [u8]);

impl Iterator for Floats<'_> {
    type Item = f64;
    fn next(&mut self) -> Option<f64> {
        let (head, rest) = self.0.split_at_checked(8)?;
        self.0 = rest;
        Some(rd(head, 0))
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.0.len() / 8, Some(self.0.len() / 8))
    }
}

impl ExactSizeIterator for Floats<'_> {}
