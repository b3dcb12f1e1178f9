//! Section "Measured against predicted": every channel's target and network
//! output over the whole record, the training rows shaded.

use super::ctx::Ctx;
use crate::report::common::Drawn;
use crate::report::common::colours;
use plot::{Figure, Panel, Section, Series};

/// Contiguous runs of `rows` as `(first time, last time)` spans.
fn spans(t: &[f64], rows: &[usize]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut start: Option<(usize, usize)> = None;
    for &r in rows {
        start = match start {
            Some((a, b)) if r == b + 1 => Some((a, r)),
            Some((a, b)) => {
                out.push((t[a], t[b]));
                Some((r, r))
            }
            None => Some((r, r)),
        };
    }
    if let Some((a, b)) = start {
        out.push((t[a], t[b]));
    }
    out
}

/// The training rows as time spans to shade, or `None` for an interleaved
/// split: it has as many runs as rows, and shading them would paint the
/// whole axis, so the figures say it in their title instead.
pub(super) fn training_spans(ctx: &Ctx<'_>) -> Option<Vec<(f64, f64)>> {
    let train = spans(&ctx.rows_t, ctx.train);
    (train.len() <= 20).then_some(train)
}

/// Shades `spans` (the training rows) on `p`.
pub(super) fn shade_training(mut p: Panel, spans: Option<&[(f64, f64)]>) -> Panel {
    for &(from, to) in spans.unwrap_or_default() {
        p = p.x_span(from, to, "training rows");
    }
    p
}

/// The figure, with its file stem.
pub(super) fn figure(ctx: &Ctx<'_>) -> (Figure, &'static str) {
    let t = &ctx.rows_t;
    let train = training_spans(ctx);
    let shade = train.is_some();
    let mut fig = Figure::new(if shade {
        "Measured against predicted, all rows (shaded: training rows; the rest: validation)"
    } else {
        "Measured against predicted, all rows (interleaved split: alternate rows train and validate)"
    })
    .share_x();
    for c in &ctx.channels {
        let ch = &c.name;
        let p = Panel::new(format!("Channel {ch}"), "time (s)", format!("{ch} (deg/h)"))
            .series(Series::line("measured", t.clone(), c.target.to_vec()).colour(colours::BEFORE))
            .series(
                Series::line("predicted", t.clone(), c.predicted.to_vec()).colour(colours::AFTER),
            );
        fig = fig.panel(shade_training(p, train.as_deref()));
    }
    (fig, "fit_all_channels")
}

/// The section, once its figure is drawn.
pub(super) fn section(drawn: &Drawn) -> Section {
    Section::new("Measured against predicted").figure(
        drawn.get("fit_all_channels"),
        "Each channel's measured rate error (target) and the model's prediction over the record; the shaded stretch is what the model was fitted on, the rest is validation.",
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn spans_are_the_contiguous_runs() {
        let t: Vec<f64> = (0..10).map(f64::from).collect();
        assert_eq!(
            super::spans(&t, &[0, 1, 2, 5, 6, 9]),
            vec![(0.0, 2.0), (5.0, 6.0), (9.0, 9.0)]
        );
        assert!(super::spans(&t, &[]).is_empty());
    }
}
