//! The summary statistics the workspace's crates share: [`mean`],
//! [`variance`], [`std_dev`] and [`rms`] of a slice, the [`correlation`]
//! of two, and the robust pair [`median`] and [`mad`], in one place so that a
//! figure printed by one crate and checked by another is computed the same
//! way, to the bit.
//!
//! Population forms (divide by `n`, not `n − 1`): these summarise a record
//! (an rms in deg/h, a spread in g), they do not estimate a parent variance.
//! An empty slice gives NaN (0/0), never a panic. `no_std` without the
//! default `std` feature: core has no square root yet, so [`std_dev`] and
//! [`rms`] come with `std`, [`mean`] and [`variance`] always.
//!
//! ```
//! let x = [1.0, 2.0, 3.0, 4.0];
//! assert_eq!(stats::mean(&x), 2.5);
//! assert_eq!(stats::variance(&x), 1.25);
//! assert_eq!(stats::std_dev(&x), 1.25f64.sqrt());
//! assert_eq!(stats::rms(&x), 7.5f64.sqrt());
//! assert!(stats::mean(&[]).is_nan());
//! ```

#![cfg_attr(not(feature = "std"), no_std)]

/// Arithmetic mean, `Σx / n`.
///
/// ```
/// assert_eq!(stats::mean(&[2.0, 4.0]), 3.0);
/// ```
pub fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// Population variance about the mean, `Σ(x − x̄)² / n`.
///
/// ```
/// assert_eq!(stats::variance(&[1.0, 3.0]), 1.0);
/// assert_eq!(stats::variance(&[5.0; 4]), 0.0);
/// ```
pub fn variance(x: &[f64]) -> f64 {
    let m = mean(x);
    x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / x.len() as f64
}

/// Root mean square about the mean (population standard deviation),
/// `√variance`.
///
/// ```
/// assert_eq!(stats::std_dev(&[1.0, 3.0]), 1.0);
/// // A constant offset does not count, unlike in `rms`.
/// assert_eq!(stats::std_dev(&[10.0, 12.0]), 1.0);
/// ```
#[cfg(feature = "std")]
pub fn std_dev(x: &[f64]) -> f64 {
    variance(x).sqrt()
}

/// Root mean square about zero, `√(Σx² / n)`.
///
/// ```
/// assert_eq!(stats::rms(&[3.0, -3.0]), 3.0);
/// assert_eq!(stats::rms(&[10.0, 12.0]), 122.0f64.sqrt());
/// ```
#[cfg(feature = "std")]
pub fn rms(x: &[f64]) -> f64 {
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

/// Pearson correlation of two equally long slices, `Σ(a − ā)(b − b̄) /
/// √(Σ(a − ā)² Σ(b − b̄)²)`; 0 where either is constant (a constant says
/// nothing of shape, and 0/0 would poison a comparison with a threshold).
///
/// ```
/// assert_eq!(stats::correlation(&[1.0, 2.0, 3.0], &[2.0, 4.0, 6.0]), 1.0);
/// assert_eq!(stats::correlation(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]), -1.0);
/// assert_eq!(stats::correlation(&[1.0, 2.0], &[5.0, 5.0]), 0.0);
/// ```
#[cfg(feature = "std")]
#[track_caller]
pub fn correlation(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "correlation of slices of unequal length");
    let (ma, mb) = (mean(a), mean(b));
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    if saa == 0.0 || sbb == 0.0 {
        0.0
    } else {
        sab / (saa * sbb).sqrt()
    }
}

/// The median: the middle value of the sorted slice, or the mean of the two
/// middle ones for an even count; NaN for an empty slice or one holding a
/// NaN (a NaN has no place in an order).
///
/// ```
/// assert_eq!(stats::median(&[3.0, 1.0, 2.0]), 2.0);
/// assert_eq!(stats::median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
/// assert!(stats::median(&[]).is_nan());
/// assert!(stats::median(&[1.0, f64::NAN]).is_nan());
/// ```
#[cfg(feature = "std")]
pub fn median(x: &[f64]) -> f64 {
    if x.is_empty() || x.iter().any(|v| v.is_nan()) {
        return f64::NAN;
    }
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    match n % 2 {
        1 => s[n / 2],
        _ => 0.5 * (s[n / 2 - 1] + s[n / 2]),
    }
}

/// The median absolute deviation about the median, `median(|x − median(x)|)`,
/// unscaled: for normal data `1.4826 · mad` ([`MAD_TO_SIGMA`]) estimates the
/// standard deviation, and one outlier, however far, moves it by at most
/// one rank.
///
/// ```
/// assert_eq!(stats::mad(&[1.0, 2.0, 3.0, 4.0, 100.0]), 1.0);
/// assert_eq!(stats::mad(&[5.0; 3]), 0.0);
/// assert!(stats::mad(&[]).is_nan());
/// ```
#[cfg(feature = "std")]
pub fn mad(x: &[f64]) -> f64 {
    let m = median(x);
    let dev: Vec<f64> = x.iter().map(|v| (v - m).abs()).collect();
    median(&dev)
}

/// `1 / Φ⁻¹(3/4)`: the factor that makes [`mad`] a consistent estimate of
/// the standard deviation of normal data.
///
/// ```
/// // Φ⁻¹(3/4) = 0.674489750196…
/// assert!((stats::MAD_TO_SIGMA * 0.674_489_750_196_081_7 - 1.0).abs() < 1e-12);
/// ```
pub const MAD_TO_SIGMA: f64 = 1.482_602_218_505_602;
