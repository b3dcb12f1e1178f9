//! The numbers a step reads in vector lanes, computed once from the tables
//! (into the evaluator's state at rest, and by the exporter into the C's
//! constant arrays, from these same functions, so that Rust and C read the
//! same bits):
//!
//! - each centre set's kernels in blocks of [`LANES`] centres. For the
//!   statistics input the squared distance is expanded about the set's
//!   mean m (x′ = x − m, c′ = c − m): −‖x′ − c′‖²/β² = V + W‖x′‖² + Σⱼ x′ⱼUⱼ
//!   with U = 2c′/β², V = −‖c′‖²/β², W = −1/β², so a step takes one
//!   multiply-add per input number and centre instead of a subtraction, a
//!   multiply and an add; for the raw window only W (the window's distance
//!   is summed against the tables' centres);
//! - each channel's weights, padded with zeros to whole blocks;
//! - the ground calibration with the gyros side by side (the calibration
//!   step's sums run term by term over the gyros).

use crate::layout::{LANES, gyro, input};
use crate::model::Model;

/// Centre blocks of [`LANES`] for `n` centres.
pub(crate) const fn lane_blocks(n: usize) -> usize {
    n.div_ceil(LANES)
}

/// Rows of the calibration lanes (each one number per channel):
/// 0–8 each gyro's regressor axes (a DTG's I, O, S; a rate gyro's unit
/// x, y, z), 3 × 3 row-major; 9 the bias; 10–12 the specific-force terms;
/// 13–18 the g² terms (AA, BB, CC, AB, AC, BC of those axes); 19 the scale
/// 1 + 10⁻⁶·scale factor; 20, 21 10⁻⁶ times the DTG's O- and S-rate terms;
/// 22–24 its three anisoinertia terms /3600²; 25 its scale-factor
/// nonlinearity; 26–28 the least-squares rate operator's rows.
pub(crate) const CAL_ROWS: usize = 29;
pub(crate) mod row {
    pub(crate) const BIAS: usize = 9;
    pub(crate) const FORCE: usize = 10;
    pub(crate) const GG: usize = 13;
    pub(crate) const SCALE: usize = 19;
    pub(crate) const RATE_O: usize = 20;
    pub(crate) const RATE_S: usize = 21;
    pub(crate) const AI_IO: usize = 22;
    pub(crate) const AI_IS: usize = 23;
    pub(crate) const AI_OS: usize = 24;
    pub(crate) const NONLINEARITY: usize = 25;
    pub(crate) const RATE_OPERATOR: usize = 26;
}

/// (deg/s per deg/h)²: the anisoinertia terms' rates in deg/s.
const PER_S2: f64 = (1.0 / 3600.0) * (1.0 / 3600.0);

impl Model<'_> {
    /// `f64` numbers of channel `channel`'s centre set in lanes (a leader's;
    /// [`Model::kernel_lanes`]).
    pub fn kernel_lanes_len(&self, channel: usize) -> usize {
        let ch = &self.channels[channel];
        let blocks = lane_blocks(ch.n_centres);
        if self.input == input::STATISTICS {
            ch.dim + blocks * (ch.dim + 2) * LANES
        } else {
            blocks * LANES
        }
    }

    /// Channel `channel`'s centres in lanes into `out`
    /// ([`Model::kernel_lanes_len`] numbers). Statistics input: the set's
    /// mean m (D numbers), then per block of [`LANES`] centres U (D rows of
    /// [`LANES`]: input number j of each centre side by side), V and W
    /// (zeros past the last centre); the raw window: per block W.
    pub fn kernel_lanes(&self, channel: usize, out: &mut [f64]) {
        let ch = self.channels[channel];
        let (dim, n) = (ch.dim, ch.n_centres);
        let centre = |k: usize, j: usize| self.f(ch.centres + 8 * (k * dim + j));
        let inv = |k: usize| {
            let beta = self.f(ch.widths + 8 * k);
            1.0 / (beta * beta)
        };
        out[..self.kernel_lanes_len(channel)].fill(0.0);
        if self.input != input::STATISTICS {
            for (k, w) in out[..n].iter_mut().enumerate() {
                *w = -inv(k);
            }
            return;
        }
        let (mean, blocks) = out.split_at_mut(dim);
        for (j, m) in mean.iter_mut().enumerate() {
            let mut s = 0.0;
            for k in 0..n {
                s += centre(k, j);
            }
            *m = if n > 0 { s / n as f64 } else { 0.0 };
        }
        let stride = (dim + 2) * LANES;
        for k in 0..n {
            let block = &mut blocks[(k / LANES) * stride..][..stride];
            let (i, inv) = (k % LANES, inv(k));
            let mut s = 0.0;
            for (j, m) in mean.iter().enumerate() {
                let c = centre(k, j) - m;
                block[j * LANES + i] = (2.0 * inv) * c;
                s += c * c;
            }
            block[dim * LANES + i] = -(inv * s);
            block[(dim + 1) * LANES + i] = -inv;
        }
    }

    /// Channel `channel`'s weights in lanes into `out`: its centres' weights,
    /// then zeros to a whole number of blocks.
    pub fn weight_lanes(&self, channel: usize, out: &mut [f64]) {
        let ch = self.channels[channel];
        let out = &mut out[..lane_blocks(ch.n_centres) * LANES];
        out.fill(0.0);
        for (k, w) in out[..ch.n_centres].iter_mut().enumerate() {
            *w = self.f(ch.weights + 8 * k);
        }
    }

    /// `f64` numbers of [`Model::calibration_lanes`]: 29 rows of one number
    /// per channel (none without a calibration).
    pub fn calibration_lanes_len(&self) -> usize {
        if self.calibrated {
            CAL_ROWS * self.n_channels
        } else {
            0
        }
    }

    /// The ground calibration with the gyros side by side into `out`
    /// (row r, channel k at `r·n + k`): each gyro's regressor axes, its
    /// drift's terms at zero rate, its scale, a DTG's rate terms and
    /// nonlinearity, and the least-squares rate operator (rows documented
    /// in docs/formats.md, "State"). Nothing without a calibration.
    pub fn calibration_lanes(&self, out: &mut [f64]) {
        if !self.calibrated {
            return;
        }
        let n = self.n_channels;
        let out = &mut out[..CAL_ROWS * n];
        out.fill(0.0);
        for k in 0..n {
            let ch = self.channels[k];
            let c = |t: usize| self.f(ch.cal + 8 * t);
            let mut put = |r: usize, v: f64| out[r * n + k] = v;
            let rate = ch.model == gyro::RATE;
            for a in 0..3 {
                for i in 0..3 {
                    let axis = self.f(self.frames + 8 * (9 * k + 3 * a + i));
                    put(3 * a + i, if rate { f64::from(a == i) } else { axis });
                }
            }
            put(row::BIAS, c(0));
            // The terms' positions in the table: DtgTerm::ALL (bias, three
            // rates, three g, six g², three anisoinertia, temp, rect_2n,
            // nonlinearity) or RateTerm::ALL (bias, scale factor, three g,
            // six g², temp).
            let (force, gg) = if rate { (2, 5) } else { (4, 7) };
            for t in 0..3 {
                put(row::FORCE + t, c(force + t));
            }
            for t in 0..6 {
                put(row::GG + t, c(gg + t));
            }
            put(row::SCALE, 1.0 + 1e-6 * c(1));
            if !rate {
                put(row::RATE_O, 1e-6 * c(2));
                put(row::RATE_S, 1e-6 * c(3));
                put(row::AI_IO, c(13) * PER_S2);
                put(row::AI_IS, c(14) * PER_S2);
                put(row::AI_OS, c(15) * PER_S2);
                put(row::NONLINEARITY, c(18));
            }
            for i in 0..3 {
                put(row::RATE_OPERATOR + i, self.f(self.ls + 8 * (n * i + k)));
            }
        }
    }

    /// Fills the state's lanes from the tables (at rest).
    pub(crate) fn fill_lanes(&self, st: &mut [f64]) {
        self.calibration_lanes(&mut st[self.st.cal_lanes..]);
        for c in 0..self.n_channels {
            let ch = self.channels[c];
            if self.leader[c] == c {
                self.kernel_lanes(c, &mut st[ch.lanes..]);
            }
            self.weight_lanes(c, &mut st[ch.weight_lanes..]);
        }
    }
}
