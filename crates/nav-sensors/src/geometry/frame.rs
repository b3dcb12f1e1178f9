//! Each channel's frame triple (I, O, S) in the cluster frame (paper eqs. 1–3).
//!
//! The six input axes are the rows of the measurement matrix (eq. 4). A DTG's
//! spin axis is its skewed input axis crossed with its principal one, exactly
//! as eq. 1 builds `Sx = X1 × X`; so `Sy = Y1 × Y` and `Sz = Z1 × Z`.
//!
//! | channel | I (own input axis) | O (other input axis) | S (spin axis) |
//! |---|---|---|---|
//! | X  | ( 1, 0, 0)        | ( 0, 1/√2, −1/√2) | ( 0, −1/√2, −1/√2) |
//! | X1 | ( 0, 1/√2, −1/√2) | ( 1, 0, 0)        | ( 0, −1/√2, −1/√2) |
//! | Y  | ( 0, 1, 0)        | (−1/√2, 0, −1/√2) | ( 1/√2, 0, −1/√2)  |
//! | Y1 | (−1/√2, 0, −1/√2) | ( 0, 1, 0)        | ( 1/√2, 0, −1/√2)  |
//! | Z  | ( 0, 0, 1)        | ( 1/√2, −1/√2, 0) | (−1/√2, −1/√2, 0)  |
//! | Z1 | ( 1/√2, −1/√2, 0) | ( 0, 0, 1)        | (−1/√2, −1/√2, 0)  |
//!
//! The skewed channel's triple (X1, X, Sx) is right-handed (it is eq. 1); the
//! principal channel's triple (X, X1, Sx) is its mirror, left-handed. Terms
//! are defined on these named vectors, so handedness never enters a formula.

use nalgebra::{Matrix3, Vector3};

use super::channel::{Channel, Dtg};

const H: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The input axis of a channel in the cluster frame (a row of eq. 4).
///
/// ```
/// use nav_sensors::geometry::{input_axis, Channel};
/// let y1 = input_axis(Channel::Y1);
/// assert!((y1 - nalgebra::Vector3::new(-0.5f64.sqrt(), 0.0, -0.5f64.sqrt())).norm() < 1e-15);
/// ```
pub fn input_axis(channel: Channel) -> Vector3<f64> {
    match channel {
        Channel::X => Vector3::new(1.0, 0.0, 0.0),
        Channel::X1 => Vector3::new(0.0, H, -H),
        Channel::Y => Vector3::new(0.0, 1.0, 0.0),
        Channel::Y1 => Vector3::new(-H, 0.0, -H),
        Channel::Z => Vector3::new(0.0, 0.0, 1.0),
        Channel::Z1 => Vector3::new(H, -H, 0.0),
    }
}

/// The spin axis of a DTG in the cluster frame: skewed input axis × principal input axis.
///
/// ```
/// use nav_sensors::geometry::{spin_axis, Dtg};
/// let h = 0.5f64.sqrt();
/// assert!((spin_axis(Dtg::X) - nalgebra::Vector3::new(0.0, -h, -h)).norm() < 1e-15);
/// ```
pub fn spin_axis(dtg: Dtg) -> Vector3<f64> {
    let [principal, skewed] = dtg.channels();
    input_axis(skewed).cross(&input_axis(principal))
}

/// The DTG's own frame as rows (skewed input, principal input, spin) — eq. 1 for X.
///
/// Multiplying a cluster-frame vector by this matrix resolves it into the DTG
/// frame (eqs. 2–3).
///
/// ```
/// use nav_sensors::geometry::{dtg_frame, Dtg};
/// let h = 0.5f64.sqrt();
/// let eq1 = nalgebra::Matrix3::new(0.0, h, -h, 1.0, 0.0, 0.0, 0.0, -h, -h);
/// assert!((dtg_frame(Dtg::X) - eq1).norm() < 1e-15);
/// ```
pub fn dtg_frame(dtg: Dtg) -> Matrix3<f64> {
    let [principal, skewed] = dtg.channels();
    Matrix3::from_rows(&[
        input_axis(skewed).transpose(),
        input_axis(principal).transpose(),
        spin_axis(dtg).transpose(),
    ])
}

/// A channel's frame triple: I (own input axis), O (the other input axis of
/// the same DTG), S (that DTG's spin axis), unit vectors in the cluster frame.
///
/// ```
/// use nav_sensors::geometry::{Channel, ChannelFrame};
/// use nalgebra::Vector3;
/// let f = ChannelFrame::of(Channel::X1);
/// // Eq. 2: specific force (fx, fy, fz) resolved into (X1, X, Sx).
/// let (fx, fy, fz) = (0.1, 0.2, 1.0);
/// let r = f.resolve(&Vector3::new(fx, fy, fz));
/// let h = 0.5f64.sqrt();
/// assert!((r.i - (fy - fz) * h).abs() < 1e-15);
/// assert!((r.o - fx).abs() < 1e-15);
/// assert!((r.s + (fy + fz) * h).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChannelFrame {
    /// The channel this frame belongs to.
    pub channel: Channel,
    /// I: the channel's own input axis.
    pub input: Vector3<f64>,
    /// O: the other input axis of the same DTG.
    pub other: Vector3<f64>,
    /// S: the DTG's spin axis.
    pub spin: Vector3<f64>,
}

/// A cluster-frame vector resolved into a channel's (I, O, S) triple.
///
/// ```
/// use nav_sensors::geometry::{Channel, ChannelFrame};
/// let r = ChannelFrame::of(Channel::Z).resolve(&nalgebra::Vector3::new(0.0, 0.0, 1.0));
/// assert_eq!((r.i, r.o, r.s), (1.0, 0.0, 0.0));
/// assert_eq!(r.as_array(), [1.0, 0.0, 0.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Ios {
    /// Component along I.
    pub i: f64,
    /// Component along O.
    pub o: f64,
    /// Component along S.
    pub s: f64,
}

impl Ios {
    /// The components as `[I, O, S]`.
    ///
    /// ```
    /// let r = nav_sensors::geometry::Ios { i: 1.0, o: 2.0, s: 3.0 };
    /// assert_eq!(r.as_array(), [1.0, 2.0, 3.0]);
    /// ```
    pub fn as_array(&self) -> [f64; 3] {
        [self.i, self.o, self.s]
    }
}

impl ChannelFrame {
    /// The frame of one channel.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, ChannelFrame};
    /// let f = ChannelFrame::of(Channel::Z1);
    /// assert_eq!(f.other, nalgebra::Vector3::new(0.0, 0.0, 1.0));
    /// ```
    pub fn of(channel: Channel) -> Self {
        Self {
            channel,
            input: input_axis(channel),
            other: input_axis(channel.partner()),
            spin: spin_axis(channel.dtg()),
        }
    }

    /// The six frames in [`Channel::ALL`] order.
    ///
    /// ```
    /// let frames = nav_sensors::geometry::ChannelFrame::all();
    /// assert_eq!(frames[3].channel, nav_sensors::geometry::Channel::Y1);
    /// ```
    pub fn all() -> [ChannelFrame; 6] {
        Channel::ALL.map(ChannelFrame::of)
    }

    /// Rows I, O, S: multiplying a cluster vector gives its (I, O, S) components.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, ChannelFrame};
    /// let m = ChannelFrame::of(Channel::Y).matrix();
    /// assert!((m * m.transpose() - nalgebra::Matrix3::identity()).norm() < 1e-15);
    /// ```
    pub fn matrix(&self) -> Matrix3<f64> {
        Matrix3::from_rows(&[
            self.input.transpose(),
            self.other.transpose(),
            self.spin.transpose(),
        ])
    }

    /// Resolves a cluster-frame vector (specific force in g, rate in any unit)
    /// into this channel's I, O, S components (eqs. 2–3).
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, ChannelFrame};
    /// let r = ChannelFrame::of(Channel::Y).resolve(&nalgebra::Vector3::new(0.0, 2.0, 0.0));
    /// assert_eq!(r.i, 2.0);
    /// ```
    #[inline]
    pub fn resolve(&self, v: &Vector3<f64>) -> Ios {
        self.axes().resolve(v)
    }

    /// The frame's axes without the channel name.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, ChannelFrame};
    /// let f = ChannelFrame::of(Channel::X);
    /// assert_eq!(f.axes().output, f.other);
    /// ```
    pub fn axes(&self) -> DtgAxes {
        DtgAxes {
            input: self.input,
            output: self.other,
            spin: self.spin,
        }
    }
}

/// A DTG channel's axes in the unit frame — I (its input axis), O (its
/// output axis: the DTG's other input axis, signed as the error model uses
/// it) and S (the rotor's spin axis) — for any unit: a unit file's `dtg`
/// gyro gives them ([`crate::unit::Gyro::dtg_axes`]); the paper's channels
/// are [`ChannelFrame::axes`].
///
/// ```
/// use nav_sensors::geometry::DtgAxes;
/// use nalgebra::Vector3;
/// let a = DtgAxes { input: Vector3::z(), output: Vector3::x(), spin: Vector3::y() };
/// let r = a.resolve(&Vector3::new(1.0, 2.0, 3.0));
/// assert_eq!(r.as_array(), [3.0, 1.0, 2.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DtgAxes {
    /// I: the input axis.
    pub input: Vector3<f64>,
    /// O: the output axis.
    pub output: Vector3<f64>,
    /// S: the spin axis.
    pub spin: Vector3<f64>,
}

impl DtgAxes {
    /// Resolves a unit-frame vector into (I, O, S) components.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, ChannelFrame};
    /// let r = ChannelFrame::of(Channel::Z).axes().resolve(&nalgebra::Vector3::new(0.0, 0.0, 2.0));
    /// assert_eq!(r.i, 2.0);
    /// ```
    #[inline]
    pub fn resolve(&self, v: &Vector3<f64>) -> Ios {
        Ios {
            i: self.input.dot(v),
            o: self.output.dot(v),
            s: self.spin.dot(v),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_and_spin_is_skewed_cross_principal() {
        for c in Channel::ALL {
            let f = ChannelFrame::of(c);
            let m = f.matrix();
            assert!(
                (m * m.transpose() - Matrix3::identity()).norm() < 1e-14,
                "{c}"
            );
            let [p, s] = c.dtg().channels();
            let expect = input_axis(s).cross(&input_axis(p));
            assert!((f.spin - expect).norm() < 1e-15);
        }
    }

    #[test]
    fn equation_3_rates_into_the_x_dtg() {
        // Eq. 3 with the frame rows (X1, X, Sx).
        let w = Vector3::new(0.3, -1.2, 2.5);
        let r = dtg_frame(Dtg::X) * w;
        assert!((r[0] - (w.y - w.z) * H).abs() < 1e-15);
        assert!((r[1] - w.x).abs() < 1e-15);
        assert!((r[2] + (w.y + w.z) * H).abs() < 1e-15);
    }

    #[test]
    fn spin_axes_as_documented() {
        assert!((spin_axis(Dtg::Y) - Vector3::new(H, 0.0, -H)).norm() < 1e-15);
        assert!((spin_axis(Dtg::Z) - Vector3::new(-H, -H, 0.0)).norm() < 1e-15);
    }
}
