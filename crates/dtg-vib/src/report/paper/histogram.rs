//! Section "Residual distribution against the noise floor": each channel's
//! validation residual after compensation as a histogram, against the
//! normal density of the noise floor when one is known (a simulated
//! record's truth), and against the normal density of the residual's own
//! mean and standard deviation.

use super::{Ctx, Drawn, fmt, pick};
use crate::report::colours;
use nav_sensors::geometry::Channel;
use plot::{Figure, Panel, Section, Series, Table};

/// What no model of the record can predict, per channel, when it is known.
pub struct NoiseFloor<'a> {
    /// Per channel (X, X1, Y, Y1, Z, Z1 order), the floor at every sample
    /// of the record, deg/h (a simulation's `X_floor` … components).
    pub per_sample: [&'a [f64]; 6],
    /// Where it comes from, in words (shown on the page).
    pub source: String,
}

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

/// Mean and standard deviation (about the mean) of `v`.
fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len().max(1) as f64;
    let mean = v.iter().sum::<f64>() / n;
    let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n).sqrt();
    (mean, sd)
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

/// Each channel's validation residual after compensation.
fn residual(ctx: &Ctx<'_>, ch: Channel) -> Vec<f64> {
    let a = ctx.applied;
    let y = pick(a.prepared.target(ch), &a.val);
    let p = pick(&a.predicted[ch.index()], &a.val);
    y.iter().zip(&p).map(|(y, p)| y - p).collect()
}

/// Each channel's noise floor as the model's target sees it: the per-sample
/// floor through the model's pre-filter, standard deviation on the
/// validation rows, deg/h. `None` when no floor is known (or it cannot be
/// filtered like the targets).
fn floor_sd(ctx: &Ctx<'_>) -> Option<[f64; 6]> {
    let floor = ctx.noise_floor?;
    let a = ctx.applied;
    let first = a.prepared.first_sample();
    let mut out = [0.0; 6];
    for ch in Channel::ALL {
        let series = floor.per_sample[ch.index()];
        if series.len() != ctx.record.len() {
            return None;
        }
        let filtered = a.prepared.filter_like_targets(series).ok()?;
        let v: Vec<f64> = a.val.iter().map(|&r| filtered[first + r]).collect();
        out[ch.index()] = mean_sd(&v).1;
    }
    Some(out)
}

/// Per channel, the validation residual's standard deviation and the noise
/// floor's (deg/h), when a floor is known: the section's table, and the
/// page's summary reads the same numbers.
pub(super) fn residual_and_floor(ctx: &Ctx<'_>) -> Option<Vec<(Channel, f64, f64)>> {
    let f = floor_sd(ctx)?;
    Some(
        Channel::ALL
            .into_iter()
            .map(|ch| (ch, mean_sd(&residual(ctx, ch)).1, f[ch.index()]))
            .collect(),
    )
}

/// The figure, with its file stem.
pub(super) fn figure(ctx: &Ctx<'_>) -> (Figure, &'static str) {
    let floors = floor_sd(ctx);
    let mut fig = Figure::new(if floors.is_some() {
        "Validation residual after compensation against the noise floor"
    } else {
        "Validation residual after compensation (no noise floor known)"
    });
    for ch in Channel::ALL {
        let r = residual(ctx, ch);
        let (x, counts, w) = histogram(&r, 40);
        let n = r.len() as f64;
        let (mean, sd) = mean_sd(&r);
        let title = match floors {
            Some(f) => format!(
                "Channel {ch}: σ {} deg/h, floor {} deg/h",
                fmt(sd),
                fmt(f[ch.index()])
            ),
            None => format!("Channel {ch}: σ {} deg/h", fmt(sd)),
        };
        let mut p = Panel::new(title, format!("residual {ch} (deg/h)"), "rows per bin")
            .series(Series::stems("residual", x.clone(), counts).colour(colours::AFTER));
        if let Some(f) = floors {
            let fsd = f[ch.index()];
            if fsd > 0.0 {
                p = p.series(
                    Series::line(
                        "noise floor (normal, σ of the floor)",
                        x.clone(),
                        normal_counts(&x, n, w, mean, fsd),
                    )
                    .colour(colours::REFERENCE),
                );
            }
        }
        p = p.series(
            Series::dashed(
                "normal, the residual's σ",
                x.clone(),
                normal_counts(&x, n, w, mean, sd),
            )
            .colour(colours::REFERENCE),
        );
        fig = fig.panel(p);
    }
    (fig, "residual_histogram")
}

/// The section, once its figure is drawn.
pub(super) fn section(ctx: &Ctx<'_>, drawn: &Drawn) -> Section {
    let mut sec = Section::new("Residual distribution against the noise floor");
    match (residual_and_floor(ctx), ctx.noise_floor) {
        (Some(rows), Some(floor)) => {
            let mut t = Table::new([
                "channel",
                "residual σ (deg/h)",
                "noise floor σ (deg/h)",
                "residual / floor",
            ])
            .caption("Validation rows: the residual's standard deviation against the floor's.");
            for (ch, sd, fl) in rows {
                t = t.row([
                    ch.name().to_string(),
                    fmt(sd),
                    fmt(fl),
                    format!("{:.2}×", sd / fl),
                ]);
            }
            sec = sec
                .text(format!(
                    "The noise floor is what no model of this record can predict: {}. It is passed through the model's pre-filter (as the target was) and its standard deviation taken on the validation rows; the solid black curve is the normal density with that σ, centred on the residual's mean (the floor says nothing of the mean). A residual at the floor has a histogram on that curve and a ratio near 1; a wider histogram is error above the floor that this model does not predict: an effect it lacks (the diagnosis names those it can find among its candidates) or its own estimation error.",
                    floor.source
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
