//! Section "Residual distribution": each channel's validation residual
//! after compensation as a histogram, against a normal density of the same
//! mean and standard deviation.

use super::{Ctx, Drawn, pick};
use crate::report::colours;
use nav_sensors::geometry::Channel;
use plot::{Figure, Panel, Section, Series};

/// Bin centres and counts of `v` in `bins` equal bins, with the bin width.
fn histogram(v: &[f64], bins: usize) -> (Vec<f64>, Vec<f64>, f64) {
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if v.is_empty() || hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return (Vec::new(), Vec::new(), 0.0);
    }
    let w = (hi - lo) / bins as f64;
    let mut counts = vec![0.0; bins];
    for &x in v {
        counts[(((x - lo) / w) as usize).min(bins - 1)] += 1.0;
    }
    let centres = (0..bins).map(|i| lo + (i as f64 + 0.5) * w).collect();
    (centres, counts, w)
}

/// The figure, with its file stem.
pub(super) fn figure(ctx: &Ctx<'_>) -> (Figure, &'static str) {
    let a = ctx.applied;
    let mut fig =
        Figure::new("Validation residual after compensation: histogram and a normal density");
    for ch in Channel::ALL {
        let y = pick(a.prepared.target(ch), &a.val);
        let p = pick(&a.predicted[ch.index()], &a.val);
        let r: Vec<f64> = y.iter().zip(&p).map(|(y, p)| y - p).collect();
        let (x, counts, w) = histogram(&r, 40);
        let n = r.len() as f64;
        let mean = r.iter().sum::<f64>() / n.max(1.0);
        let sd = (r.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n.max(1.0)).sqrt();
        let normal: Vec<f64> = x
            .iter()
            .map(|v| {
                n * w * (-0.5 * ((v - mean) / sd).powi(2)).exp()
                    / (sd * (2.0 * std::f64::consts::PI).sqrt())
            })
            .collect();
        fig = fig.panel(
            Panel::new(
                format!("Channel {ch}"),
                format!("residual {ch} (deg/h)"),
                "rows per bin",
            )
            .series(Series::stems("residual", x.clone(), counts).colour(colours::AFTER))
            .series(Series::line("normal, same mean and σ", x, normal).colour(colours::REFERENCE)),
        );
    }
    (fig, "residual_histogram")
}

/// The section, once its figure is drawn.
pub(super) fn section(drawn: &Drawn) -> Section {
    Section::new("Residual distribution").figure(
        drawn.get("residual_histogram"),
        "Each channel's validation residual after compensation in 40 bins, against the normal density with its mean and standard deviation: heavy tails or skew point at an effect the model lacks.",
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn histogram_counts_every_value_once() {
        let v = [0.0, 0.1, 0.5, 0.9, 1.0];
        let (x, c, w) = super::histogram(&v, 2);
        assert_eq!(c, vec![2.0, 3.0]);
        assert_eq!(w, 0.5);
        assert_eq!(x, vec![0.25, 0.75]);
        assert!(super::histogram(&[1.0, 1.0], 4).0.is_empty());
    }
}
