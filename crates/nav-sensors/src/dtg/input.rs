//! What a DTG channel senses, resolved into its (I, O, S) frame: the input
//! of every term's regressor and of the channel model.

use crate::geometry::Ios;

/// What one DTG channel senses at one instant, resolved into its (I, O, S) frame.
///
/// ```
/// use nav_sensors::dtg::DtgInput;
/// use nav_sensors::geometry::{Channel, ChannelFrame};
/// use nalgebra::Vector3;
/// let frame = ChannelFrame::of(Channel::Z);
/// let x = DtgInput::resolved(&frame, &Vector3::new(13.0, 0.0, 7.5), &Vector3::new(0.0, 0.0, 1.0));
/// assert_eq!(x.specific_force_g.i, 1.0);
/// assert_eq!(x.rate_deg_h.i, 7.5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DtgInput {
    /// Angular rate about I, O, S, deg/h.
    pub rate_deg_h: Ios,
    /// Specific force along I, O, S, g.
    pub specific_force_g: Ios,
    /// Temperature minus the reference temperature, °C.
    pub temperature_delta_c: f64,
    /// Mean-square angular rate about I in the band around twice the spin
    /// frequency, (deg/s)² (zero where unknown, e.g. in compensation).
    pub rate_2n_mean_square_deg2_s2: f64,
    /// Within-interval covariance of the specific force in the channel frame
    /// (II, OO, SS, IO, IS, OS), g²: what the product of interval means misses
    /// of the interval mean of a product (see
    /// [`within_interval_covariance`](crate::dtg::within_interval_covariance)).
    /// Zero at an instant (the simulator's high rate) and where unknown.
    pub specific_force_cov_g2: [f64; 6],
}

impl DtgInput {
    /// Resolves cluster-frame rate (deg/h) and specific force (g) into a
    /// channel's frame; temperature and 2N terms zero.
    ///
    /// ```
    /// use nav_sensors::dtg::DtgInput;
    /// use nav_sensors::geometry::{Channel, ChannelFrame};
    /// let x = DtgInput::resolved(&ChannelFrame::of(Channel::X), &nalgebra::Vector3::new(15.0, 0.0, 0.0),
    ///     &nalgebra::Vector3::new(0.0, 0.0, 1.0));
    /// assert_eq!((x.rate_deg_h.i, x.specific_force_g.i), (15.0, 0.0));
    /// ```
    pub fn resolved(
        frame: &crate::geometry::ChannelFrame,
        rate_deg_h: &nalgebra::Vector3<f64>,
        specific_force_g: &nalgebra::Vector3<f64>,
    ) -> Self {
        Self {
            rate_deg_h: frame.resolve(rate_deg_h),
            specific_force_g: frame.resolve(specific_force_g),
            ..Self::default()
        }
    }
}
