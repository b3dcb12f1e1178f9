//! The within-interval covariance of the specific force as the g² terms
//! read it (nav_sensors::dtg::within_interval_covariance): from the means
//! of the three samples on each side, so a sample waits for the third
//! after it.

use crate::maths::dot;

/// Means on each side of a sample that its within-interval covariance
/// reads (nav_sensors::dtg::WITHIN_INTERVAL_REACH): a sample is compensated
/// once the third after it has arrived, 3 periods late (60 ms at 50 Hz).
pub const LOOKAHEAD: usize = 3;

/// The within-interval covariance's factors over the seven means
/// n − 3 … n + 3: the one table, which nav_sensors::dtg::WITHIN_INTERVAL_FACTORS
/// names for the desktop (how they were derived is said there, and its test
/// `the_factors_are_their_derivation` derives them again).
pub const WITHIN_INTERVAL_FACTORS: [[f64; 2 * LOOKAHEAD + 1]; FACTORS] = [
    [
        -0.03641163955917553,
        0.12253545567917867,
        -0.2800109800506244,
        0.0,
        0.2800109800506244,
        -0.12253545567917867,
        0.03641163955917553,
    ],
    [
        -0.004015306888144132,
        0.017861172937713325,
        -0.07970322600350409,
        0.1317147199078698,
        -0.07970322600350409,
        0.017861172937713325,
        -0.004015306888144132,
    ],
    [
        -0.0018746642026273908,
        0.0050168163288551205,
        0.002439181035086846,
        0.0,
        -0.002439181035086846,
        -0.0050168163288551205,
        0.0018746642026273908,
    ],
    [
        -0.00020138523908803826,
        0.0007231192274360948,
        -0.0002601277046901288,
        -0.0005232125673158554,
        -0.0002601277046901288,
        0.0007231192274360948,
        -0.00020138523908803826,
    ],
];

/// Factors of the within-interval covariance (C = Σᵣ eᵣeᵣᵀ).
pub(crate) const FACTORS: usize = 4;

/// A sample's within-interval covariance as its factors
/// (nav_sensors::dtg::within_interval_factors): `eᵣ = Σⱼ Fᵣⱼ·m[n+j]` over
/// the specific forces (g) of samples n − 3 … n + 3 (`window(j)`, j = 0..7),
/// each a sum in the order of j as the batch forms it; pᵀCq is then
/// Σᵣ (p·eᵣ)(q·eᵣ).
pub(crate) fn covariance(window: impl Fn(usize) -> [f64; 3]) -> [[f64; 3]; FACTORS] {
    let mut e = [[0.0; 3]; FACTORS];
    for (er, row) in e.iter_mut().zip(&WITHIN_INTERVAL_FACTORS) {
        for (j, w) in row.iter().enumerate() {
            let m = window(j);
            for (x, mk) in er.iter_mut().zip(m) {
                *x += *w * mk;
            }
        }
    }
    e
}

/// `pᵀCq` of the covariance's factors `e`.
#[inline(always)]
pub(crate) fn quad(p: &[f64; 3], e: &[[f64; 3]; FACTORS], q: &[f64; 3]) -> f64 {
    e.iter().fold(0.0, |s, er| s + dot(p, er) * dot(q, er))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The factors' covariance of a linear trend, m[n+j] = (n + j)·s: the
    /// within-interval variance of a slope s is s²/12, the estimate's (as
    /// the batch's) exact for linear trends, and its factors are the
    /// table's sums in order.
    #[test]
    fn the_covariance_factors_give_the_covariance() {
        let slope = [0.5, -2.0, 0.0];
        let e = covariance(|j| core::array::from_fn(|k| (3.0 + j as f64) * slope[k]));
        let (p, q) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let want = slope[0] * slope[1] / 12.0;
        assert!(
            (quad(&p, &e, &q) - want).abs() < 1e-12,
            "{}",
            quad(&p, &e, &q)
        );
        assert_eq!(quad(&[0.0, 0.0, 1.0], &e, &[0.0, 0.0, 1.0]), 0.0);
        let mut e0 = 0.0;
        for (j, w) in WITHIN_INTERVAL_FACTORS[0].iter().enumerate() {
            e0 += *w * (3.0 + j as f64) * slope[0];
        }
        assert_eq!(e[0][0], e0);
    }
}
