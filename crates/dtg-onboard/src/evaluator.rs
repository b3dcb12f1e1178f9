//! The compensator's state over a model and its step: calibration, the
//! effects, the windows, the kernels, the fade and the smoother, one
//! output period at a time.

use crate::calibration::{calibrated_force, compensate_gyros};
use crate::error::Error;
use crate::fade::fade_weight;
use crate::interval::{FACTORS, LOOKAHEAD, covariance, quad};
use crate::layout::{MAX_ACCELS, MAX_CHANNELS, input, kind, kind_params_of};
use crate::maths::{cascade, dot, sqrt};
use crate::model::Model;
use crate::vector::network_terms;

/// One step's result. Only the first [`Output::n_channels`] (and
/// [`Output::n_accels`]) entries are the model's; the rest are zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Output {
    /// Compensated rates (the unit's gyros in its order; in layout 2 X, X1,
    /// Y, Y1, Z, Z1), deg/h: the calibrated outputs minus the predicted
    /// errors.
    pub rate_deg_h: [f64; MAX_CHANNELS],
    /// The predicted vibration errors, deg/h.
    pub error_deg_h: [f64; MAX_CHANNELS],
    /// Calibrated accelerations (the unit's accelerometers in its order), g.
    pub accel_g: [f64; MAX_ACCELS],
    /// Channels of the model.
    pub n_channels: usize,
    /// Accelerometers of the model.
    pub n_accels: usize,
}

impl Output {
    /// Zero for a model of `n_channels` channels and `n_accels`
    /// accelerometers.
    fn zeros(n_channels: usize, n_accels: usize) -> Self {
        Self {
            rate_deg_h: [0.0; MAX_CHANNELS],
            error_deg_h: [0.0; MAX_CHANNELS],
            accel_g: [0.0; MAX_ACCELS],
            n_channels,
            n_accels,
        }
    }

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
/// [`LOOKAHEAD`] periods of latency (60 ms at 50 Hz): the call with sample
/// n returns the output of sample n − 3, because the g² terms'
/// within-interval covariance of a sample is estimated from the specific
/// forces of samples n − 3 … n + 3. [`Evaluator::flush`] gives the last
/// three samples' outputs at the end of a record.
#[derive(Debug)]
pub struct Evaluator<'m, 's> {
    model: Model<'m>,
    state: &'s mut [f64],
    /// Samples received since rest.
    steps: u64,
    /// Samples processed (three fewer than received, once running).
    processed: u64,
    ring_pos: usize,
}

/// State slots 0..18: the calibrated specific forces (unit frame, g) of
/// the six samples before the newest, oldest first (the oldest pending
/// sample's covariance reads them and the newest); the other slots are the
/// model's (`Model::st`), the pending samples' among them, oldest first.
const FORCES: usize = 0;
const FORCE_SLOTS: usize = 2 * LOOKAHEAD;
/// Where the oldest pending sample's force is.
const PENDING_FORCE: usize = FORCES + 3 * LOOKAHEAD;

/// The pending sample calibrated: its specific force, accelerometers and
/// gyro outputs.
struct Calibrated {
    force: [f64; 3],
    accel: [f64; MAX_ACCELS],
    gyro: [f64; MAX_CHANNELS],
}

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
        let mut ev = Self {
            model,
            state: &mut state[..need],
            steps: 0,
            processed: 0,
            ring_pos: 0,
        };
        ev.reset();
        Ok(ev)
    }

    /// Back to rest, as after [`Evaluator::new`]: the state zero but its
    /// lanes, filled from the tables.
    pub fn reset(&mut self) {
        self.state.fill(0.0);
        self.model.fill_lanes(self.state);
        self.steps = 0;
        self.processed = 0;
        self.ring_pos = 0;
    }

    /// Samples received since rest.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// One output period: raw gyro outputs (the unit's gyros in its order;
    /// in layout 2 X, X1, Y, Y1, Z, Z1), deg/h, raw accelerations (the
    /// unit's accelerometers), g, and the model's extra columns (in the
    /// exporter's order, [`Model::n_extra`] of them) of sample n; returns
    /// the output of sample n − 3 ([`LOOKAHEAD`]), or `None` while the
    /// windows fill (the first output, of sample [`Model::window_len`] − 1,
    /// comes with sample `window_len` + 2). A non-finite input makes every later output
    /// non-finite (the filters keep it): reset.
    pub fn step(
        &mut self,
        gyro_deg_h: &[f64],
        accel_g: &[f64],
        extra: &[f64],
    ) -> Result<Option<Output>, Error> {
        let m = &self.model;
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
        let f = calibrated_force(m, accel_g, &mut cal[..na]);
        let held = (self.steps as usize).min(LOOKAHEAD);
        // Written in place by the step (an output is 400 bytes: moved up
        // through process and step it would be copied twice).
        let mut out = Output::zeros(nc, na);
        let ready = if held == LOOKAHEAD {
            // The oldest pending sample's covariance, centred on it: n − 6
            // … n (zero for the first three samples, which lack three
            // neighbours before them, as in the batch).
            let e = if self.steps >= 2 * LOOKAHEAD as u64 {
                let st = &*self.state;
                covariance(|j| match j {
                    FORCE_SLOTS => f,
                    _ => [st[3 * j], st[3 * j + 1], st[3 * j + 2]],
                })
            } else {
                [[0.0; 3]; FACTORS]
            };
            let ready = self.process(&e, &mut out);
            self.shift_pending();
            ready
        } else {
            false
        };
        let (m, st) = (&self.model, &mut *self.state);
        let at = m.st;
        st.copy_within(FORCES + 3..FORCES + 3 * FORCE_SLOTS, FORCES);
        st[FORCES + 3 * (FORCE_SLOTS - 1)..FORCES + 3 * FORCE_SLOTS].copy_from_slice(&f);
        let slot = held.min(LOOKAHEAD - 1);
        let put = |st: &mut [f64], at: usize, v: &[f64]| {
            st[at + slot * v.len()..at + (slot + 1) * v.len()].copy_from_slice(v)
        };
        put(st, at.accel, &cal[..na]);
        put(st, at.gyro, gyro_deg_h);
        put(st, at.extra, extra);
        self.steps += 1;
        Ok(ready.then_some(out))
    }

    /// The pending samples one on, the oldest (just processed) dropped.
    fn shift_pending(&mut self) {
        let (m, st) = (&self.model, &mut *self.state);
        for (at, len) in [
            (m.st.accel, m.n_accels),
            (m.st.gyro, m.n_channels),
            (m.st.extra, m.n_extra),
        ] {
            st.copy_within(at + len..at + LOOKAHEAD * len, at);
        }
    }

    /// The end of a record: the outputs of the last [`LOOKAHEAD`] samples
    /// received, oldest first (entry k is sample N − 3 + k of N received;
    /// their covariance is zero, as the batch's at a record's end), then
    /// back to rest. An entry is `None` if the record has no such sample
    /// or the windows are not full at it.
    pub fn flush(&mut self) -> [Option<Output>; LOOKAHEAD] {
        let held = (self.steps as usize).min(LOOKAHEAD);
        // Fewer samples than the lookahead received: their forces sit in
        // the newest slots; the oldest held one goes where `process` reads
        // the pending sample's.
        let lag = LOOKAHEAD - held;
        self.state
            .copy_within(FORCES + 3 * lag..FORCES + 3 * FORCE_SLOTS, FORCES);
        let mut outs = [None; LOOKAHEAD];
        for slot in outs[LOOKAHEAD - held..].iter_mut() {
            let m = &self.model;
            let mut out = Output::zeros(m.n_channels, m.n_accels);
            *slot = self.process(&[[0.0; 3]; FACTORS], &mut out).then_some(out);
            self.shift_pending();
            // The next pending sample's force into the oldest's slot.
            self.state
                .copy_within(FORCES + 3..FORCES + 3 * FORCE_SLOTS, FORCES);
        }
        self.reset();
        outs
    }

    /// The pending sample's specific force, accelerometers and gyro
    /// outputs, the gyros through the ground calibration with the
    /// covariance's factors `e`.
    fn calibrated(&self, e: &[[f64; 3]; FACTORS]) -> Calibrated {
        let (m, st) = (&self.model, &*self.state);
        let (nc, na) = (m.n_channels, m.n_accels);
        let mut c = Calibrated {
            force: [
                st[PENDING_FORCE],
                st[PENDING_FORCE + 1],
                st[PENDING_FORCE + 2],
            ],
            accel: [0.0; MAX_ACCELS],
            gyro: [0.0; MAX_CHANNELS],
        };
        c.accel[..na].copy_from_slice(&st[m.st.accel..m.st.accel + na]);
        c.gyro[..nc].copy_from_slice(&st[m.st.gyro..m.st.gyro + nc]);
        if m.calibrated {
            let lanes = &st[m.st.cal_lanes..m.st.cal_lanes + m.calibration_lanes_len()];
            compensate_gyros(m, lanes, &mut c.gyro[..nc], &c.force, e);
        }
        c
    }

    /// Compensates the pending sample with its covariance's factors `e`.
    /// Into `out` once the windows are full (true then).
    fn process(&mut self, e: &[[f64; 3]; FACTORS], out: &mut Output) -> bool {
        let m = &self.model;
        let first = self.processed == 0;
        let c = self.calibrated(e);
        // Effects, filtered, weighted: the linear part of each prediction.
        let linear = linear_parts(m, self.state, (&c.force, &c.gyro[..m.n_channels], e), first);
        self.windows(&c.accel, first);
        let l = self.model.window_len as u64;
        if self.processed < l {
            return false;
        }
        let (m, st) = (&self.model, &mut *self.state);
        let weight = m
            .fade
            .map(|at| fade_weight(m, at, st, self.ring_pos, self.processed == l));
        self.predictions(&c, &linear, weight, out);
        true
    }

    /// The pending sample's window signals (calibrated accelerometers `a`
    /// and extra columns) through the window low-pass into their rings and
    /// running sums (and the statistics inputs), its accelerations into the
    /// fade's rings; one sample on.
    fn windows(&mut self, a: &[f64; MAX_ACCELS], first: bool) {
        let m = &self.model;
        let st = &mut *self.state;
        let (l, na) = (m.window_len, m.n_accels);
        for s in 0..m.n_signals {
            let code = m.signal_code(s);
            let v = if code < na {
                a[code]
            } else {
                st[m.st.extra + code - na]
            };
            let s0 = m.st.in_filter + 2 * m.n_in_sections * s;
            let v = cascade(
                m.bytes,
                (m.in_filter, m.n_in_sections),
                &mut st[s0..],
                v,
                first,
            );
            let r = m.st.rings + 2 * l * s;
            // The running sums: the sample L steps back (0 while the
            // window fills) leaves as this one enters (sysid::input).
            let old = st[r + self.ring_pos];
            let sum = m.st.sums + 2 * s;
            st[sum] = (st[sum] + v) - old;
            st[sum + 1] = (st[sum + 1] + v * v) - old * old;
            st[r + self.ring_pos] = v;
            st[r + self.ring_pos + l] = v;
            if m.input == input::STATISTICS {
                let mean = st[sum] / l as f64;
                let var = st[sum + 1] / l as f64 - mean * mean;
                let feat = m.st.features + 3 * s;
                st[feat] = v;
                st[feat + 1] = mean;
                st[feat + 2] = if var > 0.0 { sqrt(var) } else { 0.0 };
            }
        }
        if m.fade.is_some() {
            let r = m.st.fade;
            for (k, v) in a[..na].iter().enumerate() {
                st[r + 2 * l * k + self.ring_pos] = *v;
                st[r + 2 * l * k + self.ring_pos + l] = *v;
            }
        }
        self.ring_pos = (self.ring_pos + 1) % l;
        self.processed += 1;
    }

    /// Each channel's prediction from its bias, `linear` part and network
    /// part (faded by `weight`, smoothed), and its compensated rate, into
    /// `out` (zero past the model's channels).
    fn predictions(
        &mut self,
        c: &Calibrated,
        linear: &[f64; MAX_CHANNELS],
        weight: Option<f64>,
        out: &mut Output,
    ) {
        let m = &self.model;
        let st = &mut *self.state;
        let (nc, na, l) = (m.n_channels, m.n_accels, m.window_len);
        out.accel_g = c.accel;
        let first_prediction = self.processed == l as u64;
        // Without a smoother the kernels add onto bias and effects, in
        // the order tables of layout version 1 were evaluated.
        let smoothed = m.n_smooth_sections > 0;
        let mut ys = [0.0; MAX_CHANNELS];
        let mut nets = [0.0; MAX_CHANNELS];
        if !smoothed {
            for (k, ch) in m.channels[..nc].iter().enumerate() {
                ys[k] = m.f(ch.bias) + linear[k];
            }
        }
        network_terms(m, st, self.ring_pos, &mut ys, &mut nets);
        let na4 = 4 * na;
        for (k, ch) in m.channels[..nc].iter().enumerate() {
            let (mut y, mut net) = (ys[k], nets[k]);
            if let (Some(w), Some(at)) = (weight, m.fade) {
                // The held network part follows the network by the weight's
                // one-pole while the weight is 1 and stays below; the output
                // cross-fades from it to the network by the weight. A
                // record starts it at the network's value at rest. Before
                // the smoother (sysid::operating::fade).
                let h = m.st.fade + 2 * l * na + k;
                let before = if first_prediction {
                    m.f(at + 8 * (na4 + 4 + k))
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
                let n = m.n_smooth_sections;
                let s0 = m.st.smooth + 2 * n * k;
                net = cascade(
                    m.bytes,
                    (m.smoother, n),
                    &mut st[s0..],
                    net,
                    first_prediction,
                );
                y = m.f(ch.bias) + linear[k] + net;
            }
            out.error_deg_h[k] = y;
            out.rate_deg_h[k] = c.gyro[k] - y;
        }
    }
}

/// Each channel's effects through the effect filter, weighted and summed:
/// the linear part of its prediction (`inputs`: the calibrated specific
/// force (g), the compensated gyro outputs (deg/h) and the factors of the
/// within-interval covariance of the specific force).
fn linear_parts(
    m: &Model,
    st: &mut [f64],
    (a, gyro, e): (&[f64; 3], &[f64], &[[f64; 3]; FACTORS]),
    first: bool,
) -> [f64; MAX_CHANNELS] {
    let mut linear = [0.0; MAX_CHANNELS];
    let nc = m.n_channels;
    let v3 = |at: usize| [m.f(at), m.f(at + 8), m.f(at + 16)];
    let dotn = |at: usize| {
        let mut s = 0.0;
        for (j, x) in gyro.iter().enumerate() {
            s += m.f(at + 8 * j) * x;
        }
        s
    };
    for (c, ch) in m.channels[..nc].iter().enumerate() {
        let mut p = ch.params;
        let mut sum = 0.0;
        for e_i in 0..ch.n_effects {
            let (k, index) = m.effect(c, e_i);
            let z = match k {
                kind::COLUMN => st[m.st.extra + index],
                kind::LINEAR_G => dot(&v3(p), a),
                kind::QUADRATIC_G => {
                    let (pv, qv) = (v3(p), v3(p + 24));
                    dot(&pv, a) * dot(&qv, a) + quad(&pv, e, &qv)
                }
                _ => dotn(p) * dotn(p + 8 * nc),
            };
            p += 8 * kind_params_of(k, nc).unwrap_or(0);
            let s0 = ch.effect_state + 2 * m.n_sections * e_i;
            let z = cascade(
                m.bytes,
                (m.out_filter, m.n_sections),
                &mut st[s0..],
                z,
                first,
            );
            sum += z * m.f(ch.coefficients + 8 * e_i);
        }
        linear[c] = sum;
    }
    linear
}
