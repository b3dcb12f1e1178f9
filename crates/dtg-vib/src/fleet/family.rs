//! Out of family: a unit whose coefficient lies far from the lot's, by a
//! robust z, and whose own 95% interval also excludes the lot's median (a
//! unit measured too poorly to tell is not named). Both must hold.
//!
//! The robust z is the distance to the lot's median over the spread the
//! unit's value may have: the lot's robust spread between units (1.4826 ×
//! the median absolute deviation, so that the outliers do not widen the
//! yardstick, less the typical unit's measurement variance) combined with
//! the unit's own standard error (its 95% interval's half-width / 1.96). A
//! unit measured as well as the others gets the plain robust z; one
//! measured worse gets a wider yardstick, as its value scatters more.
//! The false-alarm rate of this rule on lots without an outlier is
//! measured by `tests/fleet_false_alarm.rs` and stated in
//! docs/campaign.md.

/// The robust z beyond which a unit is out of family.
pub const DEFAULT_THRESHOLD: f64 = 5.0;

/// The fewest units a coefficient is judged over: with fewer, the
/// median absolute deviation is too rough a yardstick.
pub const MIN_UNITS: usize = 10;

/// The lot's family of one coefficient.
#[derive(Debug, Clone, PartialEq)]
pub struct Family {
    /// The lot's median.
    pub median: f64,
    /// The median absolute deviation about it.
    pub mad: f64,
    /// The robust standard deviation, `1.4826 × mad`.
    pub sigma: f64,
    /// The spread between units, `√max(0, sigma² − median(se²))`.
    pub between: f64,
    /// Each unit's robust z, `(value − median) / √(between² + se²)`.
    pub z: Vec<f64>,
    /// Each unit's verdict: `|z| > threshold` and its interval excludes the median.
    pub out: Vec<bool>,
}

/// The family of `values` (each with its 95% interval), or `None` with
/// fewer than `min_units` values or no spread at all (every z would be
/// infinite or undefined).
///
/// ```
/// use dtg_vib::fleet::family::family;
/// let mut v: Vec<f64> = (0..20).map(|i| 0.5 + 0.01 * (i as f64 - 9.5)).collect();
/// v[3] = 1.0; // far out, measured well
/// v[7] = 0.8; // far out, measured badly
/// let ci: Vec<[f64; 2]> = v.iter().enumerate()
///     .map(|(i, x)| if i == 7 { [x - 0.5, x + 0.5] } else { [x - 0.02, x + 0.02] })
///     .collect();
/// let f = family(&v, &ci, 5.0, 10).unwrap();
/// assert!(f.out[3] && !f.out[7]);
/// assert_eq!(f.out.iter().filter(|&&o| o).count(), 1);
/// ```
pub fn family(
    values: &[f64],
    intervals: &[[f64; 2]],
    threshold: f64,
    min_units: usize,
) -> Option<Family> {
    if values.len() < min_units.max(1) {
        return None;
    }
    let median = stats::median(values);
    let mad = stats::mad(values);
    let sigma = stats::MAD_TO_SIGMA * mad;
    if !(sigma > 0.0 && sigma.is_finite()) {
        return None;
    }
    let se: Vec<f64> = intervals
        .iter()
        .map(|[lo, hi]| (hi - lo) / (2.0 * 1.96))
        .collect();
    let typical = stats::median(&se.iter().map(|s| s * s).collect::<Vec<_>>());
    let between = (sigma * sigma - typical).max(0.0).sqrt();
    let z: Vec<f64> = values
        .iter()
        .zip(&se)
        .map(|(v, s)| (v - median) / (between * between + s * s).sqrt())
        .collect();
    let out = z
        .iter()
        .zip(intervals)
        .map(|(z, [lo, hi])| z.abs() > threshold && !(*lo <= median && median <= *hi))
        .collect();
    Some(Family {
        median,
        mad,
        sigma,
        between,
        z,
        out,
    })
}
