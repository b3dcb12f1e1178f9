//! Effect regressors: what the physics makes of a record of any unit, the
//! paper's included: the specific force in the unit frame, a DTG or
//! rate-gyro term's regressor (per unit coefficient), and the unit's parity
//! residues (eq. 6's K0–K5 for the paper's unit).
//! The record file format knows nothing of these ([`crate::record`]).

use nalgebra::Vector3;

use crate::dtg::{DtgTerm, within_interval_covariance};
use crate::files::record::Record;
use crate::rate::RateTerm;
use crate::unit::{GyroTerm, Sensed, Unit};

/// What the physics makes of a record of any unit: its specific force in the
/// unit frame, a channel term's regressor (the one definition
/// [`crate::unit::Gyro::regressor`] the simulator's truth uses), and the
/// unit's residues.
impl Record {
    /// The specific force in the unit frame at every sample, g (from the
    /// unit's accelerometers, [`Unit::specific_force`]).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::unit::Unit;
    /// let triad = Unit::builtin("triad").unwrap();
    /// let g = |v: f64| vec![v; 2];
    /// let r = Record::from_series(vec![0.0, 0.01],
    ///     vec![("gx".into(), g(0.0)), ("gy".into(), g(0.0)), ("gz".into(), g(0.0))],
    ///     vec![("ax".into(), g(0.1)), ("ay".into(), g(0.0)), ("az".into(), g(1.0))], vec![], None).unwrap();
    /// assert_eq!(r.specific_force(&triad)[1], nalgebra::Vector3::new(0.1, 0.0, 1.0));
    /// ```
    #[track_caller]
    pub fn specific_force(&self, unit: &Unit) -> Vec<Vector3<f64>> {
        (0..self.len())
            .map(|i| unit.specific_force(&self.accel_row(i)))
            .collect()
    }

    /// A term's regressor at every sample for gyro `channel` of `unit`
    /// (deg/h per coefficient unit), from the record's specific force, a
    /// constant reference rate in the unit frame (deg/h; Earth rate, a table
    /// rate, or zero) and, for `temp`, the temperature column minus
    /// `reference_c` (`None` when the record has no temperature column, or
    /// for a DTG's `rect_2n`, which no output-rate record gives). With
    /// `covariance`, the g² terms hold the within-interval covariance
    /// estimated from neighbouring samples (the interval mean of the
    /// product, as the gyro output holds it).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::unit::Unit;
    /// let tetra = Unit::builtin("tetra").unwrap();
    /// let g = |v: f64| vec![v; 3];
    /// let r = Record::from_series(vec![0.0, 0.01, 0.02],
    ///     (1..=4).map(|k| (format!("g{k}"), g(0.0))).collect(),
    ///     vec![("ax".into(), g(0.0)), ("ay".into(), vec![0.2, 0.3, 0.4]), ("az".into(), g(1.0))],
    ///     vec![("temp".into(), g(30.0))], Some("temp".into())).unwrap();
    /// let g_y = tetra.parse_term(1, "g_y").unwrap();
    /// let w = nalgebra::Vector3::zeros();
    /// assert_eq!(r.unit_regressor(&tetra, 1, g_y, &w, 25.0, false).unwrap(), vec![0.2, 0.3, 0.4]);
    /// let temp = tetra.parse_term(1, "temp").unwrap();
    /// assert_eq!(r.unit_regressor(&tetra, 1, temp, &w, 25.0, false).unwrap(), vec![5.0; 3]);
    /// ```
    #[track_caller]
    pub fn unit_regressor(
        &self,
        unit: &Unit,
        channel: usize,
        term: GyroTerm,
        rate_deg_h: &Vector3<f64>,
        reference_c: f64,
        covariance: bool,
    ) -> Option<Vec<f64>> {
        if term == GyroTerm::Dtg(DtgTerm::Rect2N) {
            return None;
        }
        let temperature = match term {
            GyroTerm::Dtg(DtgTerm::Temp) | GyroTerm::Rate(RateTerm::Temp) => {
                Some(self.temperature()?)
            }
            _ => None,
        };
        let force = self.specific_force(unit);
        let cov = if covariance {
            within_interval_covariance(&force)
        } else {
            vec![nalgebra::Matrix3::zeros(); force.len()]
        };
        let gyro = &unit.gyros()[channel];
        Some(
            (0..self.len())
                .map(|i| {
                    let s = Sensed {
                        rate_deg_h: *rate_deg_h,
                        specific_force_g: force[i],
                        specific_force_cov_g2: cov[i],
                        temperature_delta_c: temperature.map_or(0.0, |t| t[i] - reference_c),
                        rate_2n_mean_square_deg2_s2: 0.0,
                    };
                    gyro.regressor(term, &s)
                })
                .collect(),
        )
    }

    /// The unit's residues at every sample (`[residue][sample]`, deg/h;
    /// names [`Unit::residue_names`]): eq. 6's K0–K5 for the paper's
    /// geometry, `V·m` otherwise, none for three gyros.
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::unit::Unit;
    /// let dual = Unit::builtin("dual-triad").unwrap();
    /// let w = nalgebra::Vector3::new(1.0, 2.0, 3.0);
    /// let gyros = dual.gyros().iter().map(|g| (g.name.clone(), vec![g.input.dot(&w); 2])).collect();
    /// let g = |v: f64| vec![v; 2];
    /// let r = Record::from_series(vec![0.0, 0.01], gyros,
    ///     vec![("ax".into(), g(0.0)), ("ay".into(), g(0.0)), ("az".into(), g(1.0))], vec![], None).unwrap();
    /// let p = r.unit_residues(&dual);
    /// assert_eq!(p.len(), 3);
    /// assert!(p.iter().flatten().all(|v| v.abs() < 1e-12));
    /// ```
    #[track_caller]
    pub fn unit_residues(&self, unit: &Unit) -> Vec<Vec<f64>> {
        let mut out = vec![Vec::with_capacity(self.len()); unit.residue_names().len()];
        for i in 0..self.len() {
            for (k, v) in unit.residues(&self.gyro_row(i)).into_iter().enumerate() {
                out[k].push(v);
            }
        }
        out
    }
}
