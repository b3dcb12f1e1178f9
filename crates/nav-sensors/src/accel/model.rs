//! The pendulous servo accelerometer model (IEEE Std 1293 terms), forward and
//! static inverse.
//!
//! For an accelerometer with input axis i, pendulous axis p and output axis o
//! (a right-handed triad), with a_i, a_p, a_o the specific force in g:
//!
//! ```text
//! output/g = (1 + K1·1e-6) · (K0 + a_i + K2·a_i² + K3·a_i³ + δo·a_p − δp·a_o
//!                              + Kip·a_i·a_p + Kio·a_i·a_o)
//! ```
//!
//! with K0 in µg, K1 in ppm, K2 and Kip, Kio in µg/g², K3 in µg/g³, δo and δp
//! in µrad (each converted by 1e-6). The accelerometer on cluster axis X has
//! (i, p, o) = (X, Y, Z); on Y, (Y, Z, X); on Z, (Z, X, Y).
//!
//! K2 rectifies vibration: a zero-mean vibration of variance σ² along I adds
//! a mean output `K2·σ²` (a sine of amplitude A: `K2·A²/2`).

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::geometry::Axis;

/// Error coefficients of one accelerometer, units in the field names.
/// Missing fields in a file read as zero.
///
/// ```
/// use nav_sensors::accel::AccelCoefficients;
/// use nav_sensors::geometry::Axis;
/// use nalgebra::Vector3;
/// let c = AccelCoefficients { bias_ug: 50.0, k2_ug_per_g2: 20.0, ..Default::default() };
/// let f = Vector3::new(0.0, 0.0, 1.0);
/// let out = c.output_g(Axis::Z, &f);
/// assert!((out - (1.0 + 70e-6)).abs() < 1e-15);
/// assert!((c.compensate_g(Axis::Z, out, &f) - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AccelCoefficients {
    /// K0, bias, µg.
    pub bias_ug: f64,
    /// K1 scale-factor error, ppm.
    pub scale_factor_ppm: f64,
    /// K2, second-order nonlinearity, µg/g².
    pub k2_ug_per_g2: f64,
    /// K3, third-order nonlinearity, µg/g³.
    pub k3_ug_per_g3: f64,
    /// δo, input-axis misalignment about the output axis (couples a_p), µrad.
    pub misalignment_o_urad: f64,
    /// δp, input-axis misalignment about the pendulous axis (couples −a_o), µrad.
    pub misalignment_p_urad: f64,
    /// Kip, cross-coupling a_i·a_p, µg/g².
    pub kip_ug_per_g2: f64,
    /// Kio, cross-coupling a_i·a_o, µg/g².
    pub kio_ug_per_g2: f64,
}

/// The (input, pendulous, output) components of a cluster-frame specific
/// force for the accelerometer on `axis`.
///
/// ```
/// use nav_sensors::accel::ipo_components;
/// use nav_sensors::geometry::Axis;
/// let f = nalgebra::Vector3::new(1.0, 2.0, 3.0);
/// assert_eq!(ipo_components(Axis::Y, &f), (2.0, 3.0, 1.0));
/// ```
#[inline]
pub fn ipo_components(axis: Axis, f: &Vector3<f64>) -> (f64, f64, f64) {
    let i = axis.index();
    (f[i], f[(i + 1) % 3], f[(i + 2) % 3])
}

impl AccelCoefficients {
    /// Forward model: the output in g for a cluster-frame specific force in g.
    ///
    /// ```
    /// use nav_sensors::accel::AccelCoefficients;
    /// use nav_sensors::geometry::Axis;
    /// let c = AccelCoefficients { scale_factor_ppm: 100.0, ..Default::default() };
    /// let out = c.output_g(Axis::X, &nalgebra::Vector3::new(2.0, 0.0, 1.0));
    /// assert!((out - 2.0002).abs() < 1e-12);
    /// ```
    #[inline]
    pub fn output_g(&self, axis: Axis, f: &Vector3<f64>) -> f64 {
        let (ai, ap, ao) = ipo_components(axis, f);
        (1.0 + 1e-6 * self.scale_factor_ppm) * (ai + self.error_core_g(ai, ap, ao))
    }

    /// The error inside the scale factor: everything but a_i, in g.
    #[inline]
    fn error_core_g(&self, ai: f64, ap: f64, ao: f64) -> f64 {
        1e-6 * (self.bias_ug
            + ai * ai * (self.k2_ug_per_g2 + self.k3_ug_per_g3 * ai)
            + self.misalignment_o_urad * ap
            - self.misalignment_p_urad * ao
            + ai * (self.kip_ug_per_g2 * ap + self.kio_ug_per_g2 * ao))
    }

    /// Static inverse: the input-axis specific force (g) that gives
    /// `measured_g`, knowing the cross-axis components of `f` (its input
    /// component is ignored). Newton's method from `measured_g`; the model's
    /// nonlinearity is ppm-sized, so three steps reach rounding level.
    ///
    /// ```
    /// use nav_sensors::accel::AccelCoefficients;
    /// use nav_sensors::geometry::Axis;
    /// let c = AccelCoefficients { bias_ug: 100.0, k2_ug_per_g2: 50.0, ..Default::default() };
    /// let f = nalgebra::Vector3::new(0.0, 0.0, 3.0);
    /// assert!((c.compensate_g(Axis::Z, c.output_g(Axis::Z, &f), &f) - 3.0).abs() < 1e-12);
    /// ```
    pub fn compensate_g(&self, axis: Axis, measured_g: f64, f: &Vector3<f64>) -> f64 {
        let (_, ap, ao) = ipo_components(axis, f);
        let target = measured_g / (1.0 + 1e-6 * self.scale_factor_ppm);
        let mut a = target;
        for _ in 0..4 {
            let g = a + self.error_core_g(a, ap, ao) - target;
            let dg = 1.0
                + 1e-6
                    * (2.0 * self.k2_ug_per_g2 * a
                        + 3.0 * self.k3_ug_per_g3 * a * a
                        + self.kip_ug_per_g2 * ap
                        + self.kio_ug_per_g2 * ao);
            a -= g / dg;
        }
        a
    }
}

/// Compensates a triad of accelerometer outputs (x, y, z in g) jointly: each
/// axis's cross-axis inputs come from the others' current estimates
/// (Gauss–Seidel, three sweeps; the coupling is µg/g-sized).
///
/// ```
/// use nav_sensors::accel::{compensate_triad, AccelCoefficients};
/// use nav_sensors::geometry::Axis;
/// use nalgebra::Vector3;
/// let c = [AccelCoefficients { misalignment_o_urad: 300.0, kip_ug_per_g2: 40.0, ..Default::default() }; 3];
/// let f = Vector3::new(0.3, -2.0, 1.0);
/// let m = Vector3::new(c[0].output_g(Axis::X, &f), c[1].output_g(Axis::Y, &f), c[2].output_g(Axis::Z, &f));
/// assert!((compensate_triad(&c, &m) - f).norm() < 1e-12);
/// ```
pub fn compensate_triad(
    coefficients: &[AccelCoefficients; 3],
    measured_g: &Vector3<f64>,
) -> Vector3<f64> {
    let mut a = *measured_g;
    for _ in 0..3 {
        for axis in Axis::ALL {
            let k = axis.index();
            a[k] = coefficients[k].compensate_g(axis, measured_g[k], &a);
        }
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn random(rng: &mut impl Rng) -> AccelCoefficients {
        AccelCoefficients {
            bias_ug: rng.gen_range(-500.0..500.0),
            scale_factor_ppm: rng.gen_range(-500.0..500.0),
            k2_ug_per_g2: rng.gen_range(-50.0..50.0),
            k3_ug_per_g3: rng.gen_range(-5.0..5.0),
            misalignment_o_urad: rng.gen_range(-500.0..500.0),
            misalignment_p_urad: rng.gen_range(-500.0..500.0),
            kip_ug_per_g2: rng.gen_range(-50.0..50.0),
            kio_ug_per_g2: rng.gen_range(-50.0..50.0),
        }
    }

    #[test]
    fn forward_then_inverse_round_trips_single_and_triad() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        for _ in 0..2000 {
            let c = [random(&mut rng), random(&mut rng), random(&mut rng)];
            let f = Vector3::new(
                rng.gen_range(-20.0..20.0),
                rng.gen_range(-20.0..20.0),
                rng.gen_range(-20.0..20.0),
            );
            let m = Vector3::from_fn(|k, _| c[k].output_g(Axis::ALL[k], &f));
            for axis in Axis::ALL {
                let k = axis.index();
                let back = c[k].compensate_g(axis, m[k], &f);
                assert!((back - f[k]).abs() < 1e-11 * f[k].abs().max(1.0));
            }
            let back = compensate_triad(&c, &m);
            assert!(
                (back - f).norm() < 1e-10 * f.norm().max(1.0),
                "{back} vs {f}"
            );
        }
    }

    #[test]
    fn k2_rectifies_a_sine_into_k2_a_squared_over_two() {
        let c = AccelCoefficients {
            k2_ug_per_g2: 30.0,
            ..Default::default()
        };
        let amp = 8.0; // g
        let n = 4000; // exactly 10 cycles of 100 Hz at 4 kHz
        let mean: f64 = (0..n)
            .map(|k| {
                let a = amp * (2.0 * std::f64::consts::PI * 100.0 * k as f64 / 4000.0).sin();
                c.output_g(Axis::Z, &Vector3::new(0.0, 0.0, a))
            })
            .sum::<f64>()
            / n as f64;
        let expect = 30e-6 * amp * amp / 2.0;
        assert!((mean - expect).abs() < 1e-3 * expect, "{mean} vs {expect}");
    }
}
