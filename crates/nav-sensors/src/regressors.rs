//! Effect regressors: what the physics makes of a record. The
//! accelerations resolved into a channel's (I, O, S) frame (eq. 2), a DTG
//! term's regressor column for a channel (the IEEE Std 813 model's effect
//! of that term, per unit coefficient), and the parity residues K0..K5
//! (eq. 6). The record file format knows nothing of these
//! ([`crate::record`]).

use crate::dtg::{DtgInput, DtgTerm};
use crate::geometry::{Channel, ChannelFrame, residues};
use crate::record::Record;

impl Record {
    /// The accelerations resolved into a channel's frame: `[a_I, a_O, a_S]`
    /// series, g (eq. 2 for every sample).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::geometry::Channel;
    /// let r = Record::new(vec![0.0, 0.02], std::array::from_fn(|_| vec![0.0; 2]),
    ///     [vec![0.0; 2], vec![0.0; 2], vec![1.0; 2]], vec![]).unwrap();
    /// let [a_i, _, a_s] = r.frame_accel(Channel::X1);
    /// let h = 0.5f64.sqrt();
    /// assert!((a_i[0] + h).abs() < 1e-15 && (a_s[0] + h).abs() < 1e-15);
    /// ```
    pub fn frame_accel(&self, channel: Channel) -> [Vec<f64>; 3] {
        let frame = ChannelFrame::of(channel);
        let mut out: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(self.len()));
        for i in 0..self.len() {
            let r = frame.resolve(&self.accel_sample(i));
            out[0].push(r.i);
            out[1].push(r.o);
            out[2].push(r.s);
        }
        out
    }

    /// A DTG term's regressor at every sample for a channel (the effect
    /// column of `term`, in deg/h per coefficient unit), from the record's
    /// accelerations resolved into the channel's frame and a constant
    /// reference rate in the cluster frame (deg/h; e.g. Earth rate, or zero).
    /// `None` for `temp` and `rect_2n`, which the accelerations do not give
    /// (use the `temp` column for the former).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::geometry::Channel;
    /// use nav_sensors::dtg::DtgTerm;
    /// let r = Record::new(vec![0.0, 0.02], std::array::from_fn(|_| vec![0.0; 2]),
    ///     [vec![0.0; 2], vec![0.0; 2], vec![1.0, 3.0]], vec![]).unwrap();
    /// let w = nalgebra::Vector3::zeros();
    /// assert_eq!(r.term_regressor(Channel::Z, DtgTerm::GgII, &w).unwrap(), vec![1.0, 9.0]);
    /// assert!(r.term_regressor(Channel::Z, DtgTerm::Temp, &w).is_none());
    /// ```
    pub fn term_regressor(
        &self,
        channel: Channel,
        term: DtgTerm,
        rate_cluster_deg_h: &nalgebra::Vector3<f64>,
    ) -> Option<Vec<f64>> {
        if matches!(term, DtgTerm::Temp | DtgTerm::Rect2N) {
            return None;
        }
        let frame = ChannelFrame::of(channel);
        Some(
            (0..self.len())
                .map(|i| {
                    term.regressor(&DtgInput::resolved(
                        &frame,
                        rate_cluster_deg_h,
                        &self.accel_sample(i),
                    ))
                })
                .collect(),
        )
    }

    /// The six parity residues K0..K5 (eq. 6) at every sample, deg/h.
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::geometry::{ideal_outputs, Residue};
    /// let m = ideal_outputs(&nalgebra::Vector3::new(13.0, 0.0, 7.5));
    /// let gyro = std::array::from_fn(|k| vec![m[k]; 2]);
    /// let r = Record::new(vec![0.0, 0.02], gyro, [vec![0.0; 2], vec![0.0; 2], vec![1.0; 2]], vec![]).unwrap();
    /// assert!(r.residues()[Residue::K4.index()][1].abs() < 1e-12);
    /// ```
    pub fn residues(&self) -> [Vec<f64>; 6] {
        let mut out: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(self.len()));
        for i in 0..self.len() {
            for (k, v) in residues(&self.gyro_sample(i)).into_iter().enumerate() {
                out[k].push(v);
            }
        }
        out
    }
}
