//! What a unit's axes give: the measurement matrix H (n×3), the
//! least-squares rate operator, the parity matrix V and the residues, and
//! the specific force from the accelerometers.
//!
//! Orthogonal methods throughout (never the normal equations): the
//! least-squares operator is H's pseudo-inverse by SVD, and V is the last
//! n − 3 columns of the orthogonal factor of the Householder QR of
//! `[H | I]`, which span H's left null space. Every unit, the paper's
//! included, takes both the same way; what differs is data: the residues a
//! unit file names (`[[residue]]`, the paper's K0–K5 of eq. 6) are reported
//! with their own weights, and a unit naming none reports the rows of V.

use nalgebra::{DMatrix, DVector, Vector3};

use super::{Accelerometer, Gyro, NamedResidue};

/// The derived geometry of a unit (see the module documentation).
///
/// ```
/// use nav_sensors::unit::Unit;
/// let u = Unit::builtin("dual-triad").unwrap();
/// let g = u.geometry();
/// let p = g.least_squares_operator();
/// assert!((p * g.measurement_matrix() - nalgebra::DMatrix::<f64>::identity(3, 3)).norm() < 1e-12);
/// assert_eq!(g.parity_matrix().nrows(), 3);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct UnitGeometry {
    h: DMatrix<f64>,
    least_squares: DMatrix<f64>,
    parity: DMatrix<f64>,
    residue_names: Vec<String>,
    /// The residues' weights on the gyro outputs (rows in
    /// `residue_names` order): the named residues', else V.
    residue_weights: DMatrix<f64>,
    /// The unit's specific force from every accelerometer.
    force: ForceSolver,
    /// Each IMU's (by name) from its own accelerometers, for the IMUs
    /// whose accelerometers span 3-D.
    imu_force: Vec<(String, ForceSolver)>,
}

/// The specific force from some of the accelerometers (`indices`, unit
/// order): their outputs themselves when they are exactly the unit axes,
/// one each, else their least-squares combination.
#[derive(Debug, Clone, PartialEq)]
struct ForceSolver {
    indices: Vec<usize>,
    /// `None` on the unit axes: then `axis_of[j]` is the unit axis
    /// `indices[j]` reads.
    least_squares: Option<DMatrix<f64>>,
    axis_of: Vec<usize>,
}

impl ForceSolver {
    /// The solver of accelerometers `indices` (their axes span 3-D).
    fn new(accels: &[Accelerometer], indices: Vec<usize>) -> Self {
        let axes: Vec<Vector3<f64>> = indices.iter().map(|&k| accels[k].input).collect();
        let axis_of: Vec<usize> = axes
            .iter()
            .filter_map(|a| (0..3).find(|&j| *a == Vector3::ith(j, 1.0)))
            .collect();
        let on_axes = axes.len() == 3 && axis_of.len() == 3 && (0..3).all(|j| axis_of.contains(&j));
        let least_squares =
            (!on_axes).then(|| pseudo_inverse(&DMatrix::from_fn(axes.len(), 3, |i, j| axes[i][j])));
        Self {
            indices,
            least_squares,
            axis_of,
        }
    }

    /// The specific force from a sample of every accelerometer.
    fn solve(&self, a: &[f64]) -> Vector3<f64> {
        match &self.least_squares {
            None => {
                let mut f = Vector3::zeros();
                for (&k, &j) in self.indices.iter().zip(&self.axis_of) {
                    f[j] = a[k];
                }
                f
            }
            Some(p) => {
                let mine = DVector::from_iterator(p.ncols(), self.indices.iter().map(|&k| a[k]));
                let f = p * mine;
                Vector3::new(f[0], f[1], f[2])
            }
        }
    }
}

impl UnitGeometry {
    /// Derives the geometry of validated sensors (input axes spanning 3-D;
    /// named residues, if any, in H's left null space and spanning it;
    /// `imus` the IMUs whose accelerometers span 3-D, with their indices).
    pub(super) fn new(
        gyros: &[Gyro],
        accels: &[Accelerometer],
        named: &[NamedResidue],
        imus: Vec<(String, Vec<usize>)>,
    ) -> Self {
        let n = gyros.len();
        let h = DMatrix::from_fn(n, 3, |i, j| gyros[i].input[j]);
        let parity = left_null_space(&h);
        let (residue_names, residue_weights) = if named.is_empty() {
            let names = (0..parity.nrows()).map(|k| format!("P{k}")).collect();
            (names, parity.clone())
        } else {
            (
                named.iter().map(|r| r.name.clone()).collect(),
                DMatrix::from_fn(named.len(), n, |r, j| named[r].weights[j]),
            )
        };
        let imu_force = imus
            .into_iter()
            .map(|(name, indices)| (name, ForceSolver::new(accels, indices)))
            .collect();
        Self {
            least_squares: pseudo_inverse(&h),
            h,
            parity,
            residue_names,
            residue_weights,
            force: ForceSolver::new(accels, (0..accels.len()).collect()),
            imu_force,
        }
    }

    /// H (n×3): row k is gyro k's input axis.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::paper();
    /// let h = u.geometry().measurement_matrix();
    /// let today = nav_sensors::geometry::measurement_matrix();
    /// assert!(h.iter().zip(today.iter()).all(|(a, b)| a.to_bits() == b.to_bits()));
    /// ```
    pub fn measurement_matrix(&self) -> &DMatrix<f64> {
        &self.h
    }

    /// The 3×n least-squares operator `(HᵀH)⁻¹Hᵀ`, computed as H's
    /// pseudo-inverse by SVD (for the paper's unit, eq. 4's operator to
    /// rounding).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// let p = u.geometry().least_squares_operator();
    /// assert!((p * u.measurement_matrix() - nalgebra::DMatrix::<f64>::identity(3, 3)).norm() < 1e-12);
    /// ```
    pub fn least_squares_operator(&self) -> &DMatrix<f64> {
        &self.least_squares
    }

    /// V ((n − 3)×n), orthonormal rows spanning H's left null space (0×n for
    /// three gyros).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// let v = u.geometry().parity_matrix();
    /// assert!((v * v.transpose() - nalgebra::DMatrix::<f64>::identity(1, 1)).norm() < 1e-12);
    /// ```
    pub fn parity_matrix(&self) -> &DMatrix<f64> {
        &self.parity
    }

    /// The residues' names (the unit file's `[[residue]]` names, else `P0`…).
    ///
    /// ```
    /// assert!(nav_sensors::unit::Unit::builtin("triad").unwrap().geometry().residue_names().is_empty());
    /// ```
    pub fn residue_names(&self) -> &[String] {
        &self.residue_names
    }

    /// See [`super::Unit::residues`].
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::paper();
    /// let m = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    /// assert_eq!(u.geometry().residues(&m), nav_sensors::geometry::residues(&m).to_vec());
    /// ```
    #[track_caller]
    pub fn residues(&self, m: &[f64]) -> Vec<f64> {
        assert_eq!(m.len(), self.h.nrows(), "one output per gyro");
        (&self.residue_weights * DVector::from_column_slice(m))
            .iter()
            .copied()
            .collect()
    }

    /// See [`super::Unit::parity_vector`].
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// assert_eq!(u.geometry().parity_vector(&[1.0; 4]), u.residues(&[1.0; 4]));
    /// ```
    #[track_caller]
    pub fn parity_vector(&self, m: &[f64]) -> Vec<f64> {
        assert_eq!(m.len(), self.h.nrows(), "one output per gyro");
        (&self.parity * DVector::from_column_slice(m))
            .iter()
            .copied()
            .collect()
    }

    /// The coefficients of each residue on the gyro outputs (rows in
    /// [`UnitGeometry::residue_names`] order, columns in gyro order): the
    /// named residues' weights (for the paper, eq. 6's), V otherwise.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Residue};
    /// let c = nav_sensors::unit::Unit::paper().geometry().residue_coefficients();
    /// assert_eq!(c[(Residue::K0.index(), Channel::X.index())], 1.0);
    /// ```
    pub fn residue_coefficients(&self) -> DMatrix<f64> {
        self.residue_weights.clone()
    }

    /// See [`super::Unit::least_squares_rate`].
    ///
    /// ```
    /// use nav_sensors::geometry::{ideal_outputs, least_squares_rate};
    /// let m = ideal_outputs(&nalgebra::Vector3::new(1.0, 2.0, 3.0));
    /// let u = nav_sensors::unit::Unit::paper();
    /// assert!((u.geometry().least_squares_rate(&m) - least_squares_rate(&m)).norm() < 1e-14);
    /// ```
    #[track_caller]
    pub fn least_squares_rate(&self, m: &[f64]) -> Vector3<f64> {
        assert_eq!(m.len(), self.h.nrows(), "one output per gyro");
        let w = &self.least_squares * DVector::from_column_slice(m);
        Vector3::new(w[0], w[1], w[2])
    }

    /// See [`super::Unit::specific_force`].
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// assert_eq!(u.geometry().specific_force(&[0.0, 0.0, 1.0]).z, 1.0);
    /// ```
    #[track_caller]
    pub fn specific_force(&self, a: &[f64]) -> Vector3<f64> {
        assert_eq!(
            a.len(),
            self.force.indices.len(),
            "one output per accelerometer"
        );
        self.force.solve(a)
    }

    /// See [`super::Unit::imu_specific_force`].
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// assert!(u.geometry().imu_specific_force("imu1", &[0.0, 0.0, 1.0]).is_none());
    /// ```
    #[track_caller]
    pub fn imu_specific_force(&self, imu: &str, a: &[f64]) -> Option<Vector3<f64>> {
        assert_eq!(
            a.len(),
            self.force.indices.len(),
            "one output per accelerometer"
        );
        let (_, solver) = self.imu_force.iter().find(|(n, _)| n == imu)?;
        Some(solver.solve(a))
    }
}

/// H's pseudo-inverse by SVD (H has full column rank: validated).
fn pseudo_inverse(h: &DMatrix<f64>) -> DMatrix<f64> {
    h.clone()
        .svd(true, true)
        .pseudo_inverse(1e-12)
        .expect("U and V were computed")
}

/// An orthonormal basis of H's left null space as rows: the last n − 3
/// columns of Q in the Householder QR of `[H | I]` (the first three span
/// H's columns). Each row's sign is fixed so its largest entry is positive,
/// so the basis does not depend on the QR's sign conventions.
pub(crate) fn left_null_space(h: &DMatrix<f64>) -> DMatrix<f64> {
    let n = h.nrows();
    let mut a = DMatrix::zeros(n, n + 3);
    a.view_mut((0, 0), (n, 3)).copy_from(h);
    a.view_mut((0, 3), (n, n)).fill_with_identity();
    let q = a.qr().q();
    let mut v = q.columns(3, n - 3).transpose();
    for mut row in v.row_iter_mut() {
        let big = row
            .iter()
            .copied()
            .fold(0.0_f64, |b, x| if x.abs() > b.abs() { x } else { b });
        if big < 0.0 {
            row.neg_mut();
        }
    }
    v
}
