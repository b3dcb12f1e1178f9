//! Axis ranges, tick positions and tick labels.
//!
//! The report chooses ticks itself instead of leaving it to plotters, for two
//! reasons: log axes are drawn as linear axes of log10(value) (plotters' own
//! log axis puts few or no ticks on ranges shorter than a decade and prints
//! long decimal labels), and labels must read well at every scale, from
//! 1e-6 V²/Hz to 5000 s.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};

/// One axis after layout: a range and ticks, all in *plot space* (log10 of the
/// value on a log axis, the value itself on a linear one).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
    /// Labelled ticks (and major grid lines).
    pub ticks: Vec<(f64, String)>,
    /// Unlabelled minor grid lines (2..9 × 10ᵏ on log axes).
    pub minor: Vec<f64>,
}

impl Axis {
    /// Lays out an axis over a plot-space range, with about one tick per
    /// `spacing_px` pixels of its `length_px`.
    pub fn new(lo: f64, hi: f64, log: bool, length_px: u32, spacing_px: u32) -> Self {
        let max_ticks = (length_px / spacing_px.max(1)).clamp(2, 12) as usize;
        let (ticks, minor) = if log {
            log_ticks(lo, hi, max_ticks)
        } else {
            (linear_ticks(lo, hi, max_ticks), Vec::new())
        };
        Axis {
            lo,
            hi,
            log,
            ticks,
            minor,
        }
    }

    /// The label of the tick at plot-space position `v` (plotters hands the
    /// positions we gave it back to the label formatter).
    pub fn label(&self, v: f64) -> String {
        self.ticks
            .iter()
            .min_by(|a, b| (a.0 - v).abs().total_cmp(&(b.0 - v).abs()))
            .map(|t| t.1.clone())
            .unwrap_or_default()
    }
}

/// plotters draws the axis from our ticks: bold grid lines and labels at
/// `ticks`, light lines at `minor`. (plotters' own `with_key_points` wrapper
/// loses the label formatter for f64 axes, hence this small impl.)
impl Ranged for Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let span = self.hi - self.lo;
        let frac = if span > 0.0 && span.is_finite() {
            (value - self.lo) / span
        } else if span.is_finite() {
            0.5
        } else {
            // A span beyond f64 (values near ±f64::MAX): halve before subtracting.
            (value / 2.0 - self.lo / 2.0) / (self.hi / 2.0 - self.lo / 2.0)
        };
        // Bounded even for wild values, so no drawing loop ever walks
        // billions of off-screen pixels; NaN lands mid-axis.
        let frac = if frac.is_nan() {
            0.5
        } else {
            frac.clamp(-1.0, 2.0)
        };
        limit.0 + (f64::from(limit.1 - limit.0) * frac + 1e-3).floor() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.ticks.iter().map(|t| t.0).collect()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

/// Maps a data value to plot space: `None` for NaN/±∞, and for values ≤ 0 on a
/// log axis (the caller counts and reports those).
pub(crate) fn to_plot(v: f64, log: bool) -> Option<f64> {
    if !v.is_finite() {
        None
    } else if log {
        (v > 0.0).then(|| v.log10())
    } else {
        Some(v)
    }
}

/// Running minimum and maximum of finite values.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Extent(Option<(f64, f64)>);

impl Extent {
    pub fn add(&mut self, v: f64) {
        if v.is_finite() {
            self.0 = Some(match self.0 {
                None => (v, v),
                Some((lo, hi)) => (lo.min(v), hi.max(v)),
            });
        }
    }
    pub fn merge(&mut self, other: Extent) {
        if let Some((lo, hi)) = other.0 {
            self.add(lo);
            self.add(hi);
        }
    }
    pub fn get(self) -> Option<(f64, f64)> {
        self.0
    }
}

/// A drawable range from a data extent: `pad` is the fraction of the span
/// added on each side. A zero span (a constant series) is widened so the data
/// sits mid-axis instead of on a degenerate axis; no data gives a unit range.
pub(crate) fn padded(extent: Extent, pad: f64, log: bool) -> (f64, f64) {
    let Some((lo, hi)) = extent.get() else {
        // Nothing to show: a neutral range (0..1, or 1..10 on a log axis).
        return (0.0, 1.0);
    };
    let span = hi - lo;
    let scale = lo.abs().max(hi.abs());
    // An extent holds finite values only, so `span` is never NaN here.
    if span <= 1e-12 * scale {
        // Constant (or nearly): half a decade on a log axis, ±10 % (or ±1
        // around zero) on a linear one.
        let half = if log {
            0.5
        } else if scale > 0.0 {
            0.1 * scale
        } else {
            1.0
        };
        return (lo - half, hi + half);
    }
    if !span.is_finite() {
        // Values near ±f64::MAX: padding would overflow; draw as is.
        return (lo, hi);
    }
    (lo - pad * span, hi + pad * span)
}

/// "Nice" linear ticks (steps of 1, 2 or 5 × 10ᵏ), at most `max_ticks`.
pub(crate) fn linear_ticks(lo: f64, hi: f64, max_ticks: usize) -> Vec<(f64, String)> {
    let span = hi - lo;
    if span.is_infinite() && lo.is_finite() && hi.is_finite() {
        // Values near ±f64::MAX: the ends (and zero) are all one can label.
        return [lo, 0.0, hi]
            .into_iter()
            .filter(|v| *v >= lo && *v <= hi)
            .map(|v| (v, format_lone(v)))
            .collect();
    }
    if !(span.is_finite() && span > 0.0) {
        return vec![(lo, format_lone(lo))];
    }
    let raw = span / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| span / s <= max_ticks as f64)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let scale = lo.abs().max(hi.abs());
    (first..=last)
        .map(|k| {
            // k · step, not an accumulated sum: no drift, and exact zero.
            let v = k as f64 * step;
            (v, format_linear(v, step, scale))
        })
        .collect()
}

/// A linear tick label: as many decimals as the step needs, or scientific
/// notation for very large or very small numbers.
fn format_linear(v: f64, step: f64, scale: f64) -> String {
    if v == 0.0 || v.abs() < step * 1e-6 {
        return "0".to_string();
    }
    if scale >= 1e6 || step < 1e-4 {
        // Mantissa digits: enough to tell ticks one step apart.
        let digits = (scale.log10().floor() - step.log10().floor()).clamp(0.0, 8.0) as usize;
        return format!("{v:.digits$e}");
    }
    let decimals = (-step.log10().floor()).clamp(0.0, 10.0) as usize;
    format!("{v:.decimals$}")
}

/// A tick without neighbours to take a step from: compact either way.
fn format_lone(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else if !(1e-4..1e6).contains(&v.abs()) {
        let s = format!("{v:.3e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{exp}", trim_zeros(mantissa))
    } else {
        trim_zeros(&format!("{v:.6}")).to_string()
    }
}

/// Ticks of a log10 axis over plot-space [lo, hi]: decades when the range
/// holds at least two, otherwise 1, 2, 5 × 10ᵏ (or every integer multiple)
/// so that a short range still gets labels. Minor lines at 2..9 × 10ᵏ.
pub(crate) fn log_ticks(lo: f64, hi: f64, max_ticks: usize) -> (Vec<(f64, String)>, Vec<f64>) {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return (Vec::new(), Vec::new());
    }
    let k0 = lo.ceil() as i32;
    let k1 = hi.floor() as i32;
    let inside = |p: f64| p >= lo - 1e-12 && p <= hi + 1e-12;
    let decades = if k1 >= k0 { (k1 - k0 + 1) as usize } else { 0 };
    if decades >= 2 {
        let stride = decades.div_ceil(max_ticks.max(1)).max(1) as i32;
        let ticks = (k0..=k1)
            .filter(|k| (k - k0) % stride == 0)
            .map(|k| (k as f64, format_power(1, k)))
            .collect();
        // Minor lines only when decades are far enough apart to show them.
        let minor = if stride == 1 && decades <= 12 {
            (lo.floor() as i32..=k1)
                .flat_map(|k| (2..10).map(move |m| k as f64 + (m as f64).log10()))
                .filter(|&p| inside(p))
                .collect()
        } else {
            Vec::new()
        };
        return (ticks, minor);
    }
    for multipliers in [&[1u32, 2, 5][..], &[1, 2, 3, 4, 5, 6, 7, 8, 9][..]] {
        let ticks: Vec<(f64, String)> = (lo.floor() as i32..=hi.ceil() as i32)
            .flat_map(|k| multipliers.iter().map(move |&m| (m, k)))
            .map(|(m, k)| (k as f64 + (m as f64).log10(), format_power(m, k)))
            .filter(|(p, _)| inside(*p))
            .collect();
        if ticks.len() >= 2 {
            return (ticks, Vec::new());
        }
    }
    // Less than a factor of two: linear-looking labels of the values.
    let ticks = linear_ticks(10f64.powf(lo), 10f64.powf(hi), 3)
        .into_iter()
        .filter(|(v, _)| *v > 0.0)
        .map(|(v, s)| (v.log10(), s))
        .filter(|(p, _)| inside(*p))
        .collect();
    (ticks, Vec::new())
}

/// `m × 10ᵏ` as a label: a plain number for moderate k, otherwise with a
/// superscript exponent (DejaVu Sans has the glyphs).
fn format_power(m: u32, k: i32) -> String {
    if (-3..=4).contains(&k) {
        let decimals = (-k).max(0) as usize;
        return format!("{:.decimals$}", m as f64 * 10f64.powi(k));
    }
    let exp: String = k
        .to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect();
    if m == 1 {
        format!("10{exp}")
    } else {
        format!("{m}×10{exp}")
    }
}

/// A value with three significant digits and no trailing zeros, for numbers
/// printed on bars ("0.412", "0.004", "9e-4").
pub(crate) fn format_significant(v: f64) -> String {
    if !v.is_finite() {
        return "n/a".to_string();
    }
    if v == 0.0 {
        return "0".to_string();
    }
    let mag = v.abs().log10().floor();
    if !(-3.0..6.0).contains(&mag) {
        let s = format!("{v:.2e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        return format!("{}e{exp}", trim_zeros(mantissa));
    }
    let decimals = (2.0 - mag).max(0.0) as usize;
    trim_zeros(&format!("{v:.decimals$}")).to_string()
}

fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_nice_and_inside() {
        let t = linear_ticks(-0.013, 0.021, 6);
        let labels: Vec<&str> = t.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(labels, ["-0.01", "0", "0.01", "0.02"]);
        let t = linear_ticks(0.0, 100.0, 6);
        assert_eq!(t.first().unwrap().1, "0");
        assert_eq!(t.last().unwrap().1, "100");
        assert!(t.len() <= 7);
    }

    #[test]
    fn tiny_and_huge_ranges_use_scientific_labels() {
        let t = linear_ticks(1.0e-6, 2.0e-6, 5);
        assert!(t.iter().all(|(_, s)| s.contains('e')), "{t:?}");
        let t = linear_ticks(0.0, 5.0e7, 5);
        assert!(t.iter().skip(1).all(|(_, s)| s.contains('e')), "{t:?}");
    }

    #[test]
    fn degenerate_ranges_do_not_loop_or_panic() {
        assert_eq!(linear_ticks(1.0, 1.0, 5).len(), 1);
        assert_eq!(linear_ticks(f64::NAN, 1.0, 5).len(), 1);
        let huge = linear_ticks(-f64::MAX, f64::MAX, 5);
        let labels: Vec<&str> = huge.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(labels, ["-1.798e308", "0", "1.798e308"]);
        assert_eq!(linear_ticks(2.5, 2.5, 5)[0].1, "2.5");
        assert!(log_ticks(1.0, 1.0, 5).0.is_empty());
    }

    #[test]
    fn log_ticks_over_decades_and_within_one() {
        let (t, minor) = log_ticks(-4.2, 1.3, 8);
        let labels: Vec<&str> = t.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(labels, ["10⁻⁴", "0.001", "0.01", "0.1", "1", "10"]);
        assert!(!minor.is_empty());
        // Within a decade: 2 and 5 get labels.
        let (t, _) = log_ticks(0.1, 0.9, 8);
        let labels: Vec<&str> = t.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(labels, ["2", "5"]);
        // Many decades are thinned to the budget.
        let (t, _) = log_ticks(-30.0, 30.0, 6);
        assert!(t.len() <= 6, "{t:?}");
    }

    #[test]
    fn padding_handles_constant_and_empty_data() {
        let mut e = Extent::default();
        e.add(5.0);
        e.add(f64::NAN);
        assert_eq!(padded(e, 0.05, false), (4.5, 5.5));
        let mut z = Extent::default();
        z.add(0.0);
        assert_eq!(padded(z, 0.05, false), (-1.0, 1.0));
        assert_eq!(padded(Extent::default(), 0.05, true), (0.0, 1.0));
    }

    #[test]
    fn significant_digits() {
        assert_eq!(format_significant(0.012345), "0.0123");
        assert_eq!(format_significant(0.004), "0.004");
        assert_eq!(format_significant(0.120), "0.12");
        assert_eq!(format_significant(123.45), "123");
        assert_eq!(format_significant(1200.0), "1200");
        assert_eq!(format_significant(-0.5), "-0.5");
        assert_eq!(format_significant(f64::NAN), "n/a");
        assert_eq!(format_significant(1.5e-7), "1.5e-7");
        assert_eq!(format_significant(9.0e-4), "9e-4");
    }
}
