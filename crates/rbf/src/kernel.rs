//! Radial basis functions φ(r; β).
//!
//! Every kernel is written in the scaled distance s = r/β, where β is the width in
//! input units. For the Gaussian this is exactly the seed paper's eq. 8,
//! φ(v) = exp(−v²/β²). The kernels without a natural width (thin-plate spline, cubic)
//! are scaled the same way so that one width rule serves them all; β = 1 gives the
//! unscaled forms r² ln r and r³ used by Chen, Cowan & Grant (1991).

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// A radial basis function.
///
/// | kernel | φ(s), s = r/β | definiteness |
/// |---|---|---|
/// | `Gaussian` | exp(−s²) | positive definite |
/// | `Multiquadric` | √(1 + s²) | conditionally negative definite, order 1 |
/// | `InverseMultiquadric` | 1/√(1 + s²) | positive definite |
/// | `InverseQuadratic` | 1/(1 + s²) | positive definite |
/// | `ThinPlateSpline` | s² ln s, φ(0) = 0 | conditionally positive definite, order 2 |
/// | `Cubic` | s³ | conditionally positive definite, order 2 |
/// | `WendlandC2` | (1 − s)⁴₊ (4s + 1) | positive definite for input dimension ≤ 3 |
///
/// ```
/// use rbf::Kernel;
/// let k: Kernel = "gaussian".parse().unwrap();
/// assert_eq!(k, Kernel::Gaussian);
/// // exp(-r²/β²) with r = 1, β = 2
/// assert!((k.eval(1.0, 2.0) - (-0.25f64).exp()).abs() < 1e-15);
/// assert_eq!(Kernel::ALL.len(), 7);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Kernel {
    /// exp(−r²/β²), the seed paper's eq. 8.
    #[serde(rename = "gaussian")]
    Gaussian,
    /// √(1 + r²/β²) (Hardy).
    #[serde(rename = "multiquadric")]
    Multiquadric,
    /// 1/√(1 + r²/β²).
    #[serde(rename = "inverse-multiquadric")]
    InverseMultiquadric,
    /// 1/(1 + r²/β²).
    #[serde(rename = "inverse-quadratic")]
    InverseQuadratic,
    /// (r/β)² ln(r/β), zero at r = 0.
    #[serde(rename = "thin-plate")]
    ThinPlateSpline,
    /// (r/β)³.
    #[serde(rename = "cubic")]
    Cubic,
    /// Wendland's compactly supported C² function (1 − r/β)⁴₊ (4r/β + 1); β is the support radius.
    #[serde(rename = "wendland-c2")]
    WendlandC2,
}

/// A kernel name that [`Kernel::from_str`] does not know.
///
/// ```
/// let err = "gauss".parse::<rbf::Kernel>().unwrap_err();
/// assert!(err.to_string().contains("thin-plate"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown kernel {name:?}; valid names: {}", Kernel::NAMES.join(", "))]
pub struct UnknownKernel {
    /// The name that was given.
    pub name: String,
}

impl Kernel {
    /// Every kernel, in declaration order.
    ///
    /// ```
    /// for k in rbf::Kernel::ALL {
    ///     assert_eq!(k.name().parse::<rbf::Kernel>().unwrap(), k);
    /// }
    /// ```
    pub const ALL: [Kernel; 7] = [
        Kernel::Gaussian,
        Kernel::Multiquadric,
        Kernel::InverseMultiquadric,
        Kernel::InverseQuadratic,
        Kernel::ThinPlateSpline,
        Kernel::Cubic,
        Kernel::WendlandC2,
    ];

    /// The names accepted by [`FromStr`], in the order of [`Kernel::ALL`].
    ///
    /// ```
    /// assert_eq!(rbf::Kernel::NAMES[4], "thin-plate");
    /// ```
    pub const NAMES: [&'static str; 7] = [
        "gaussian",
        "multiquadric",
        "inverse-multiquadric",
        "inverse-quadratic",
        "thin-plate",
        "cubic",
        "wendland-c2",
    ];

    /// The kernel's name (as accepted by `parse` and written by serde).
    ///
    /// ```
    /// assert_eq!(rbf::Kernel::WendlandC2.name(), "wendland-c2");
    /// ```
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// φ at distance `r ≥ 0` for width `width > 0` (in the units of `r`).
    ///
    /// ```
    /// use rbf::Kernel;
    /// assert_eq!(Kernel::ThinPlateSpline.eval(0.0, 1.0), 0.0);
    /// let e = std::f64::consts::E;
    /// assert!((Kernel::ThinPlateSpline.eval(e, 1.0) - e * e).abs() < 1e-12);
    /// assert_eq!(Kernel::WendlandC2.eval(2.0, 1.0), 0.0); // outside the support
    /// ```
    #[inline]
    pub fn eval(self, r: f64, width: f64) -> f64 {
        self.eval_squared(r * r, width)
    }

    /// φ from the squared distance `r2 = r²`, which avoids a square root for the
    /// kernels that only need r² (the design-matrix kernels compute r² directly).
    ///
    /// ```
    /// use rbf::Kernel;
    /// for k in Kernel::ALL {
    ///     assert!((k.eval_squared(0.64, 1.3) - k.eval(0.8, 1.3)).abs() < 1e-15);
    /// }
    /// ```
    #[inline]
    pub fn eval_squared(self, r2: f64, width: f64) -> f64 {
        let s2 = r2 / (width * width);
        match self {
            Kernel::Gaussian => fastexp::exp_neg(-s2),
            Kernel::Multiquadric => (1.0 + s2).sqrt(),
            Kernel::InverseMultiquadric => 1.0 / (1.0 + s2).sqrt(),
            Kernel::InverseQuadratic => 1.0 / (1.0 + s2),
            // s² ln s = ½ s² ln s²; the limit at s = 0 is 0.
            Kernel::ThinPlateSpline => {
                if s2 > 0.0 {
                    0.5 * s2 * s2.ln()
                } else {
                    0.0
                }
            }
            Kernel::Cubic => s2 * s2.sqrt(),
            Kernel::WendlandC2 => {
                let s = s2.sqrt();
                if s >= 1.0 {
                    0.0
                } else {
                    let t = 1.0 - s;
                    let t2 = t * t;
                    t2 * t2 * (4.0 * s + 1.0)
                }
            }
        }
    }

    /// Whether every kernel matrix of distinct centres is positive definite, so that an
    /// interpolation matrix can be factored by Cholesky without a polynomial tail.
    ///
    /// The Wendland C2 function is positive definite for input dimension ≤ 3 only; in
    /// higher dimensions a Cholesky failure is reported as a typed error.
    ///
    /// ```
    /// assert!(rbf::Kernel::Gaussian.is_positive_definite());
    /// assert!(!rbf::Kernel::ThinPlateSpline.is_positive_definite());
    /// ```
    pub fn is_positive_definite(self) -> bool {
        matches!(
            self,
            Kernel::Gaussian
                | Kernel::InverseMultiquadric
                | Kernel::InverseQuadratic
                | Kernel::WendlandC2
        )
    }

    /// The order of conditional definiteness: the polynomial tail an interpolant needs
    /// (0: none, 1: a constant, 2: a linear polynomial).
    ///
    /// ```
    /// assert_eq!(rbf::Kernel::Multiquadric.polynomial_order(), 1);
    /// assert_eq!(rbf::Kernel::Cubic.polynomial_order(), 2);
    /// assert_eq!(rbf::Kernel::Gaussian.polynomial_order(), 0);
    /// ```
    pub fn polynomial_order(self) -> usize {
        match self {
            Kernel::Multiquadric => 1,
            Kernel::ThinPlateSpline | Kernel::Cubic => 2,
            _ => 0,
        }
    }

    /// +1 if the kernel matrix is (conditionally) positive definite, −1 if it is
    /// conditionally negative definite (the multiquadric; scipy negates it for this reason).
    ///
    /// ```
    /// assert_eq!(rbf::Kernel::Multiquadric.definiteness_sign(), -1.0);
    /// assert_eq!(rbf::Kernel::Cubic.definiteness_sign(), 1.0);
    /// ```
    pub fn definiteness_sign(self) -> f64 {
        if self == Kernel::Multiquadric {
            -1.0
        } else {
            1.0
        }
    }
}

impl fmt::Display for Kernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Kernel {
    type Err = UnknownKernel;

    /// Parses a kernel name; case and `_` versus `-` do not matter.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let key = s.trim().to_ascii_lowercase().replace('_', "-");
        Self::NAMES
            .iter()
            .position(|&n| n == key)
            .map(|i| Self::ALL[i])
            .ok_or_else(|| UnknownKernel {
                name: s.to_string(),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_through_serde() {
        for k in Kernel::ALL {
            let json = serde_json::to_string(&k).unwrap();
            assert_eq!(json, format!("\"{}\"", k.name()));
            assert_eq!(serde_json::from_str::<Kernel>(&json).unwrap(), k);
        }
    }

    #[test]
    fn unknown_name_lists_valid_names() {
        let e = "spline".parse::<Kernel>().unwrap_err();
        for n in Kernel::NAMES {
            assert!(e.to_string().contains(n));
        }
        assert_eq!(
            "Thin_Plate".parse::<Kernel>().unwrap(),
            Kernel::ThinPlateSpline
        );
    }

    #[test]
    fn width_scales_the_distance() {
        for k in Kernel::ALL {
            for &(r, b) in &[(0.3, 0.7), (1.5, 2.0), (0.9, 1.0)] {
                assert!((k.eval(r, b) - k.eval(r / b, 1.0)).abs() < 1e-14, "{k}");
            }
        }
    }

    #[test]
    fn wendland_is_continuous_at_the_support_edge() {
        let k = Kernel::WendlandC2;
        assert!(k.eval(1.0 - 1e-9, 1.0) < 1e-30);
        assert_eq!(k.eval(0.0, 1.0), 1.0);
    }
}
