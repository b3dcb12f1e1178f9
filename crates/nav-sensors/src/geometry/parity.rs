//! Measurement matrix, the three measurements per principal axis and the six
//! parity residues of the skewed DTG set (paper eqs. 4–6), with the
//! least-squares rate and an orthonormal parity matrix.
//!
//! Measurements are `[f64; 6]` in [`Channel::ALL`] order (X, X1, Y, Y1, Z, Z1),
//! any rate unit (the record uses deg/h).
//!
//! Writing `e_c` for channel c's error, the residues are
//!
//! ```text
//! K0 = x0 − x1 = e_X + e_Z + √2 e_Y1
//! K1 = x0 − x2 = e_X − e_Y − √2 e_Z1
//! K2 = y0 − y1 = e_Y − e_Z − √2 e_X1
//! K3 = x1 − x2 = K1 − K0
//! K4 = y1 − y2 = −K1 − K2
//! K5 = z1 − z2 = K0 + K2
//! ```
//!
//! so only three are independent (six channels, three rates: the left null
//! space of eq. 4 has dimension 3). True rates cancel exactly.

use std::fmt;
use std::str::FromStr;

use nalgebra::{Matrix3, Matrix6x3, SMatrix, SVector, Vector3};
use serde::{Deserialize, Serialize};

use super::channel::{Channel, ParseNameError};
use super::frame::input_axis;

const SQRT2: f64 = std::f64::consts::SQRT_2;

/// The 6×3 measurement matrix of eq. 4: row c is channel c's input axis.
///
/// ```
/// let h = nav_sensors::geometry::measurement_matrix();
/// let w = nalgebra::Vector3::new(1.0, 2.0, 3.0);
/// let m = h * w; // ideal outputs X, X1, Y, Y1, Z, Z1
/// assert!((m[1] - (2.0 - 3.0) / 2f64.sqrt()).abs() < 1e-15);
/// ```
pub fn measurement_matrix() -> Matrix6x3<f64> {
    let mut h = Matrix6x3::zeros();
    for c in Channel::ALL {
        h.set_row(c.index(), &input_axis(c).transpose());
    }
    h
}

/// Ideal channel outputs for a cluster-frame rate (eq. 4 without errors).
///
/// ```
/// let m = nav_sensors::geometry::ideal_outputs(&nalgebra::Vector3::new(1.0, 0.0, 0.0));
/// assert_eq!(m[0], 1.0);
/// ```
pub fn ideal_outputs(rate: &Vector3<f64>) -> [f64; 6] {
    let m = measurement_matrix() * rate;
    std::array::from_fn(|i| m[i])
}

/// The three measurements of each principal-axis rate (eq. 5).
///
/// ```
/// use nav_sensors::geometry::{axis_measurements, ideal_outputs};
/// let w = nalgebra::Vector3::new(0.4, -2.0, 7.0);
/// let a = axis_measurements(&ideal_outputs(&w));
/// for k in 0..3 {
///     assert!((a.x[k] - 0.4).abs() < 1e-12);
///     assert!((a.y[k] + 2.0).abs() < 1e-12);
///     assert!((a.z[k] - 7.0).abs() < 1e-12);
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisMeasurements {
    /// x0 = X, x1 = −Z − √2·Y1, x2 = Y + √2·Z1.
    pub x: [f64; 3],
    /// y0 = Y, y1 = Z + √2·X1, y2 = X − √2·Z1.
    pub y: [f64; 3],
    /// z0 = Z, z1 = Y − √2·X1, z2 = −X − √2·Y1.
    pub z: [f64; 3],
}

/// Eq. 5: three measurements per principal axis from the six channel outputs.
///
/// ```
/// let a = nav_sensors::geometry::axis_measurements(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
/// assert_eq!(a.x[0], 1.0);
/// assert_eq!(a.y[2], 1.0); // y2 = X − √2·Z1
/// assert_eq!(a.z[2], -1.0); // z2 = −X − √2·Y1
/// ```
pub fn axis_measurements(m: &[f64; 6]) -> AxisMeasurements {
    let [x, x1, y, y1, z, z1] = *m;
    AxisMeasurements {
        x: [x, -z - SQRT2 * y1, y + SQRT2 * z1],
        y: [y, z + SQRT2 * x1, x - SQRT2 * z1],
        z: [z, y - SQRT2 * x1, -x - SQRT2 * y1],
    }
}

/// One of the six parity residues of eq. 6.
///
/// ```
/// use nav_sensors::geometry::{Channel, Residue};
/// assert_eq!(Residue::K3.name(), "K3");
/// assert_eq!("K5".parse::<Residue>().unwrap(), Residue::K5);
/// // K0 = x0 − x1 = X + Z + √2·Y1
/// let c = Residue::K0.coefficients();
/// assert_eq!(c[Channel::X.index()], 1.0);
/// assert!(Residue::K0.involves(Channel::Y1) && !Residue::K0.involves(Channel::X1));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Residue {
    K0,
    K1,
    K2,
    K3,
    K4,
    K5,
}

impl Residue {
    /// All six, in order.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Residue::ALL[5].name(), "K5");
    /// ```
    pub const ALL: [Residue; 6] = [
        Residue::K0,
        Residue::K1,
        Residue::K2,
        Residue::K3,
        Residue::K4,
        Residue::K5,
    ];

    /// The stable name ("K0".."K5"), also a column name of residue files.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Residue::K2.name(), "K2");
    /// ```
    pub fn name(self) -> &'static str {
        ["K0", "K1", "K2", "K3", "K4", "K5"][self as usize]
    }

    /// Position 0..6.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Residue::K4.index(), 4);
    /// ```
    pub fn index(self) -> usize {
        self as usize
    }

    /// The residue as a linear combination of the six channel outputs
    /// (coefficients in [`Channel::ALL`] order).
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Residue};
    /// // K3 = K1 − K0 = −Y − Z − √2·Y1 − √2·Z1
    /// let c = Residue::K3.coefficients();
    /// assert_eq!(c[Channel::X.index()], 0.0);
    /// assert!((c[Channel::Z1.index()] + 2f64.sqrt()).abs() < 1e-12);
    /// ```
    pub fn coefficients(self) -> [f64; 6] {
        // Each residue is linear: evaluate it on the unit outputs.
        std::array::from_fn(|j| {
            let mut e = [0.0; 6];
            e[j] = 1.0;
            residues(&e)[self.index()]
        })
    }

    /// Whether a channel's error enters this residue.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Residue};
    /// let signature: Vec<bool> = Residue::ALL.iter().map(|r| r.involves(Channel::X1)).collect();
    /// assert_eq!(signature, [false, false, true, false, true, true]);
    /// ```
    pub fn involves(self, channel: Channel) -> bool {
        self.coefficients()[channel.index()].abs() > 1e-12
    }
}

impl fmt::Display for Residue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Residue {
    type Err = ParseNameError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Residue::ALL
            .into_iter()
            .find(|r| r.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| ParseNameError {
                kind: "residue",
                given: s.to_string(),
                valid: Residue::ALL.iter().map(|r| r.name()).collect(),
            })
    }
}

/// The six parity residues K0..K5 exactly as eq. 6 defines them.
///
/// ```
/// use nav_sensors::geometry::{ideal_outputs, residues};
/// let k = residues(&ideal_outputs(&nalgebra::Vector3::new(3.0, -1.0, 0.5)));
/// assert!(k.iter().all(|v| v.abs() < 1e-12));
/// // A unit error on channel X shows in K0, K1, K4 and K5.
/// let k = residues(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
/// assert_eq!(k, [1.0, 1.0, 0.0, 0.0, -1.0, 1.0]);
/// ```
pub fn residues(m: &[f64; 6]) -> [f64; 6] {
    let a = axis_measurements(m);
    [
        a.x[0] - a.x[1],
        a.x[0] - a.x[2],
        a.y[0] - a.y[1],
        a.x[1] - a.x[2],
        a.y[1] - a.y[2],
        a.z[1] - a.z[2],
    ]
}

/// Least-squares estimate of the cluster rate from the six outputs,
/// `(HᵀH)⁻¹ Hᵀ m` with H from eq. 4 (same unit as the outputs).
///
/// ```
/// use nav_sensors::geometry::{ideal_outputs, least_squares_rate};
/// let w = nalgebra::Vector3::new(15.0, 0.0, 7.5);
/// assert!((least_squares_rate(&ideal_outputs(&w)) - w).norm() < 1e-12);
/// ```
pub fn least_squares_rate(m: &[f64; 6]) -> Vector3<f64> {
    least_squares_operator() * SVector::<f64, 6>::from_column_slice(m)
}

/// The 3×6 operator `(HᵀH)⁻¹ Hᵀ` of [`least_squares_rate`].
///
/// ```
/// let p = nav_sensors::geometry::least_squares_operator();
/// let h = nav_sensors::geometry::measurement_matrix();
/// assert!((p * h - nalgebra::Matrix3::identity()).norm() < 1e-12);
/// ```
pub fn least_squares_operator() -> SMatrix<f64, 3, 6> {
    let h = measurement_matrix();
    let hth: Matrix3<f64> = h.transpose() * h;
    let inv = hth
        .try_inverse()
        .expect("HᵀH of eq. 4 is invertible (constant matrix)");
    inv * h.transpose()
}

/// An orthonormal basis of the left null space of eq. 4, as rows: `V·H = 0`,
/// `V·Vᵀ = I₃`.
///
/// Built by Gram–Schmidt on the coefficient rows of K0, K1, K2 (which span
/// the null space), so row 0 is K0 normalised and the signs are fixed.
/// The parity vector `p = V·m` is independent of the true rate, and for
/// independent equal channel noise σ its components are independent with
/// standard deviation σ.
///
/// ```
/// use nav_sensors::geometry::{measurement_matrix, parity_matrix};
/// let v = parity_matrix();
/// assert!((v * measurement_matrix()).norm() < 1e-14);
/// assert!((v * v.transpose() - nalgebra::Matrix3::identity()).norm() < 1e-14);
/// ```
pub fn parity_matrix() -> SMatrix<f64, 3, 6> {
    let rows = [Residue::K0, Residue::K1, Residue::K2]
        .map(|r| SVector::<f64, 6>::from_column_slice(&r.coefficients()));
    let mut basis: Vec<SVector<f64, 6>> = Vec::with_capacity(3);
    for r in rows {
        let mut v = r;
        // Twice for orthogonality to rounding level.
        for _ in 0..2 {
            for b in &basis {
                v -= b * b.dot(&v);
            }
        }
        basis.push(v / v.norm());
    }
    SMatrix::<f64, 3, 6>::from_rows(&[
        basis[0].transpose(),
        basis[1].transpose(),
        basis[2].transpose(),
    ])
}

/// The parity vector `V·m` (see [`parity_matrix`]).
///
/// ```
/// use nav_sensors::geometry::{ideal_outputs, parity_vector};
/// let p = parity_vector(&ideal_outputs(&nalgebra::Vector3::new(1.0, 2.0, 3.0)));
/// assert!(p.norm() < 1e-12);
/// ```
pub fn parity_vector(m: &[f64; 6]) -> Vector3<f64> {
    parity_matrix() * SVector::<f64, 6>::from_column_slice(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn random_rate(rng: &mut impl Rng) -> Vector3<f64> {
        Vector3::new(
            rng.gen_range(-500.0..500.0),
            rng.gen_range(-500.0..500.0),
            rng.gen_range(-500.0..500.0),
        )
    }

    #[test]
    fn ideal_sensors_give_zero_residues_and_three_true_rates_per_axis() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        for _ in 0..1000 {
            let w = random_rate(&mut rng);
            let m = ideal_outputs(&w);
            for k in residues(&m) {
                assert!(k.abs() < 1e-12, "{k}");
            }
            let a = axis_measurements(&m);
            for j in 0..3 {
                assert!((a.x[j] - w.x).abs() < 1e-12);
                assert!((a.y[j] - w.y).abs() < 1e-12);
                assert!((a.z[j] - w.z).abs() < 1e-12);
            }
            assert!((least_squares_rate(&m) - w).norm() < 1e-10);
        }
    }

    #[test]
    fn only_three_residues_are_independent() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(2);
        for _ in 0..100 {
            let m: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-10.0..10.0));
            let k = residues(&m);
            assert!((k[3] - (k[1] - k[0])).abs() < 1e-12);
            assert!((k[4] - (-k[1] - k[2])).abs() < 1e-12);
            assert!((k[5] - (k[0] + k[2])).abs() < 1e-12);
        }
    }

    #[test]
    fn residue_error_signatures_match_the_module_doc() {
        let s = SQRT2;
        let table = [
            (Residue::K0, [1.0, 0.0, 0.0, s, 1.0, 0.0]),
            (Residue::K1, [1.0, 0.0, -1.0, 0.0, 0.0, -s]),
            (Residue::K2, [0.0, -s, 1.0, 0.0, -1.0, 0.0]),
        ];
        for (r, expect) in table {
            let c = r.coefficients();
            for j in 0..6 {
                assert!((c[j] - expect[j]).abs() < 1e-12, "{r} channel {j}");
            }
        }
    }

    #[test]
    fn parity_vector_carries_the_residues() {
        // The residues are linear in the parity vector: K = A·p for some A, so a
        // zero parity vector means zero residues and vice versa.
        let v = parity_matrix();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        for _ in 0..20 {
            let m: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-10.0..10.0));
            let p = parity_vector(&m);
            let back = v.transpose() * p; // projection onto the null space
            let k_direct = residues(&m);
            let k_proj = residues(&std::array::from_fn(|i| back[i]));
            for j in 0..6 {
                assert!((k_direct[j] - k_proj[j]).abs() < 1e-10);
            }
        }
    }
}
