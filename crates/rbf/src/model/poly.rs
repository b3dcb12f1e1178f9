//! The polynomial tail of a network, as scipy's `RBFInterpolator` builds it: every
//! monomial of degree ≤ D of the inputs shifted and scaled to the unit box.
//!
//! The shift is the middle of each input's training range and the scale its half-range
//! (1 for a constant input), so the tail's columns lie in [−1, 1] whatever the data's
//! offset or units: a tail on inputs near 1e7 is as well conditioned as one near 0. The
//! kernel sees the inputs shifted by the same amount but not scaled: distances, and so
//! the width β, stay in data units (scipy applies its ε to unscaled inputs too), while
//! the shift keeps ‖x‖² + ‖c‖² − 2 x·c, the distance computation, free of the
//! cancellation that an offset of 1e7 would cause.

use std::fmt;
use std::str::FromStr;

use faer::{Mat, MatMut, MatRef};
use serde::{Deserialize, Serialize};

use super::matser;
use crate::kernel::Kernel;

/// The degree of the polynomial tail (`--degree`: −1, 0, 1, 2).
///
/// ```
/// use rbf::PolyTail;
/// assert_eq!("-1".parse::<PolyTail>().unwrap(), PolyTail::None);
/// assert_eq!("2".parse::<PolyTail>().unwrap(), PolyTail::Quadratic);
/// assert!("3".parse::<PolyTail>().is_err());
/// assert_eq!(PolyTail::Linear.n_terms(3), 4);
/// assert_eq!(PolyTail::Quadratic.n_terms(2), 6);
/// assert_eq!(PolyTail::minimum_for(rbf::Kernel::ThinPlateSpline), PolyTail::Linear);
/// assert_eq!(PolyTail::minimum_for(rbf::Kernel::Gaussian), PolyTail::None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PolyTail {
    /// No polynomial (degree −1).
    None,
    /// A constant (degree 0): the bias λ0.
    Constant,
    /// A constant and every input (degree 1).
    Linear,
    /// Every monomial of degree ≤ 2: constant, inputs, products and squares.
    Quadratic,
}

impl PolyTail {
    /// The degree: −1, 0, 1 or 2.
    ///
    /// ```
    /// assert_eq!(rbf::PolyTail::None.degree(), -1);
    /// ```
    pub fn degree(self) -> i32 {
        self as i32 - 1
    }

    /// The tail of degree `degree` (−1 to 2).
    ///
    /// ```
    /// assert_eq!(rbf::PolyTail::from_degree(1), Some(rbf::PolyTail::Linear));
    /// assert_eq!(rbf::PolyTail::from_degree(5), None);
    /// ```
    pub fn from_degree(degree: i32) -> Option<Self> {
        match degree {
            -1 => Some(PolyTail::None),
            0 => Some(PolyTail::Constant),
            1 => Some(PolyTail::Linear),
            2 => Some(PolyTail::Quadratic),
            _ => None,
        }
    }

    /// The lowest degree with which the kernel's interpolation system is uniquely
    /// solvable (scipy's minimum degrees: thin-plate and cubic 1, multiquadric 0).
    pub fn minimum_for(kernel: Kernel) -> Self {
        match kernel.polynomial_order() {
            0 => PolyTail::None,
            1 => PolyTail::Constant,
            _ => PolyTail::Linear,
        }
    }

    /// The number of monomials in `d` inputs: C(d + D, D).
    pub fn n_terms(self, d: usize) -> usize {
        match self {
            PolyTail::None => 0,
            PolyTail::Constant => 1,
            PolyTail::Linear => 1 + d,
            PolyTail::Quadratic => 1 + d + d * (d + 1) / 2,
        }
    }
}

impl fmt::Display for PolyTail {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.degree())
    }
}

/// A polynomial degree that [`PolyTail::from_str`] does not know.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown polynomial degree {given:?}; valid degrees: -1 (none), 0, 1, 2")]
pub struct UnknownPolyTail {
    /// The text given.
    pub given: String,
}

impl FromStr for PolyTail {
    type Err = UnknownPolyTail;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        s.trim()
            .parse::<i32>()
            .ok()
            .and_then(PolyTail::from_degree)
            .ok_or_else(|| UnknownPolyTail {
                given: s.to_string(),
            })
    }
}

/// A fitted polynomial tail: its degree, the unit-box map of the inputs, and the
/// coefficients of its monomials (in scipy's order: the constant, the inputs, then the
/// products x_i·x_j for i ≤ j).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct PolyFit {
    pub(crate) degree: PolyTail,
    /// Middle of each input's training range (also the kernel's shift).
    pub(crate) shift: Vec<f64>,
    /// Half of each input's training range (1 where it is 0).
    pub(crate) scale: Vec<f64>,
    /// n_terms × q.
    #[serde(with = "matser")]
    pub(crate) coefficients: Mat<f64>,
}

/// Shift (middle of the range) and scale (half-range, 1 where 0) of every column of `x`:
/// scipy's `RBFInterpolator` map of the inputs to the unit box.
pub(crate) fn unit_box(x: MatRef<'_, f64>) -> (Vec<f64>, Vec<f64>) {
    let d = x.ncols();
    let mut shift = vec![0.0; d];
    let mut scale = vec![1.0; d];
    for k in 0..d {
        let col = x.col(k);
        let (lo, hi) = (0..x.nrows()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), i| {
            (l.min(col[i]), h.max(col[i]))
        });
        if lo.is_finite() && hi.is_finite() {
            shift[k] = 0.5 * (lo + hi);
            let s = 0.5 * (hi - lo);
            if s > 0.0 {
                scale[k] = s;
            }
        }
    }
    (shift, scale)
}

/// The monomials of `degree` at the rows of `x` mapped by (x − shift)/scale, into `out`
/// (n × n_terms).
pub(crate) fn monomials_into(
    degree: PolyTail,
    x: MatRef<'_, f64>,
    shift: &[f64],
    scale: &[f64],
    mut out: MatMut<'_, f64>,
) {
    let d = x.ncols();
    let u = |i: usize, k: usize| (x[(i, k)] - shift[k]) / scale[k];
    for i in 0..x.nrows() {
        let mut c = 0;
        if degree >= PolyTail::Constant {
            out[(i, 0)] = 1.0;
            c = 1;
        }
        if degree >= PolyTail::Linear {
            for k in 0..d {
                out[(i, c + k)] = u(i, k);
            }
            c += d;
        }
        if degree >= PolyTail::Quadratic {
            for a in 0..d {
                for b in a..d {
                    out[(i, c)] = u(i, a) * u(i, b);
                    c += 1;
                }
            }
        }
    }
}

/// The monomials of `degree` at the rows of `x` (n × n_terms).
pub(crate) fn monomials(
    degree: PolyTail,
    x: MatRef<'_, f64>,
    shift: &[f64],
    scale: &[f64],
) -> Mat<f64> {
    let mut out = Mat::zeros(x.nrows(), degree.n_terms(x.ncols()));
    monomials_into(degree, x, shift, scale, out.as_mut());
    out
}

/// The coordinates the kernel sees: standardised when `scaling` is set, else shifted by
/// `shift` when there is one, else `x` itself.
pub(crate) fn kernel_coordinates(
    scaling: Option<&super::scaling::Scaling>,
    shift: Option<&[f64]>,
    x: MatRef<'_, f64>,
) -> Mat<f64> {
    match (scaling, shift) {
        (Some(s), _) => s.apply(x),
        (None, Some(shift)) => Mat::from_fn(x.nrows(), x.ncols(), |i, k| x[(i, k)] - shift[k]),
        (None, None) => x.to_owned(),
    }
}
