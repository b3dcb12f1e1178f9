//! Section "Residual distribution against the noise floor": each channel's
//! validation residual after compensation as a histogram, against the
//! normal density of the noise floor when one is known (a simulated
//! record's truth), and against the normal density of the residual's own
//! mean and standard deviation.

use super::ctx::{Ctx, mean_sd};
use crate::report::common::colours;
use crate::report::common::{Drawn, fmt};
use plot::{Figure, Panel, Section, Series, Table};

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

/// The expected count per bin of `n` normal values (mean, sd) in bins of width `w`.
fn normal_counts(x: &[f64], n: f64, w: f64, mean: f64, sd: f64) -> Vec<f64> {
    x.iter()
        .map(|v| {
            n * w * (-0.5 * ((v - mean) / sd).powi(2)).exp()
                / (sd * (2.0 * std::f64::consts::PI).sqrt())
        })
        .collect()
}

/// Per channel, the validation residual's standard deviation and the noise
/// floor's (deg/h), when a floor is known: the section's table, and the
/// page's summary reads the same numbers.
pub(super) fn residual_and_floor<'c>(ctx: &'c Ctx<'_>) -> Option<Vec<(&'c str, f64, f64)>> {
    let (f, _) = ctx.floor.as_ref()?;
    Some(
        ctx.channels
            .iter()
            .enumerate()
            .map(|(k, c)| (c.name.as_str(), mean_sd(&ctx.residual(k)).1, f[k]))
            .collect(),
    )
}

/// The figure, with its file stem.
pub(super) fn figure(ctx: &Ctx<'_>) -> (Figure, &'static str) {
    let floors = ctx.floor.as_ref().map(|(f, _)| f);
    let mut fig = Figure::new(if floors.is_some() {
        "Validation residual after compensation against the noise floor"
    } else {
        "Validation residual after compensation (no noise floor known)"
    });
    for (k, c) in ctx.channels.iter().enumerate() {
        let ch = &c.name;
        let r = ctx.residual(k);
        let (x, counts, w) = histogram(&r, 40);
        let n = r.len() as f64;
        let (mean, sd) = mean_sd(&r);
        let title = match floors {
            Some(f) => format!(
                "Channel {ch}: σ {} deg/h, floor {} deg/h",
                fmt(sd),
                fmt(f[k])
            ),
            None => format!("Channel {ch}: σ {} deg/h", fmt(sd)),
        };
        // The normal density of the residual's mean and a σ, in counts per bin.
        let normal = |label: &str, sigma: f64, line: fn(String, Vec<f64>, Vec<f64>) -> Series| {
            line(
                label.to_string(),
                x.clone(),
                normal_counts(&x, n, w, mean, sigma),
            )
            .colour(colours::REFERENCE)
        };
        let mut p = Panel::new(title, format!("residual {ch} (deg/h)"), "rows per bin")
            .series(Series::stems("residual", x.clone(), counts).colour(colours::AFTER));
        if let Some(fsd) = floors.map(|f| f[k]).filter(|fsd| *fsd > 0.0) {
            p = p.series(normal(
                "noise floor (normal, σ of the floor)",
                fsd,
                Series::line,
            ));
        }
        p = p.series(normal("normal, the residual's σ", sd, Series::dashed));
        fig = fig.panel(p);
    }
    (fig, "residual_histogram")
}

/// The section, once its figure is drawn.
pub(super) fn section(ctx: &Ctx<'_>, drawn: &Drawn) -> Section {
    let mut sec = Section::new("Residual distribution against the noise floor");
    match (residual_and_floor(ctx), &ctx.floor) {
        (Some(rows), Some((_, source))) => {
            let mut t = Table::new([
                "channel",
                "residual σ (deg/h)",
                "noise floor σ (deg/h)",
                "residual / floor",
            ])
            .caption("Validation rows: the residual's standard deviation against the floor's.");
            for (ch, sd, fl) in rows {
                t = t.row([ch.to_string(), fmt(sd), fmt(fl), format!("{:.2}×", sd / fl)]);
            }
            sec = sec
                .text(format!(
                    "The noise floor is what no model of this record can predict: {}. It is passed through the model's pre-filter (as the target was) and its standard deviation taken on the validation rows; the solid black curve is the normal density with that σ, centred on the residual's mean (the floor says nothing of the mean). A residual at the floor has a histogram on that curve and a ratio near 1; a wider histogram is error above the floor that this model does not predict: an effect it lacks (the diagnosis names those it can find among its candidates) or its own estimation error.",
                    source
                ))
                .table(t);
        }
        _ => {
            sec = sec.text("No noise floor is known for this record: a measured record carries no truth, and the residual's own spread cannot tell noise from unmodelled error. (A simulated record's truth file states its floor; `dtg-vib demo` draws it.) The dashed curve is only the normal density with the residual's own mean and σ: heavy tails or skew against it point at an effect the model lacks, but a curve that fits says nothing about how far the residual is above the floor.");
        }
    }
    sec.figure(
        drawn.get("residual_histogram"),
        "Each channel's validation residual after compensation in 40 bins (blue), against the normal density of the noise floor where one is known (solid black) and against the normal density of the residual's own mean and σ (dashed black).",
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
