//! Sections "Channels" and "Effects found": per channel measured against
//! predicted, rms before and after (and a baseline's), and every effect
//! with its coefficient, 95% interval and unit.

use super::UnitReport;
use crate::report::common::{Drawn, colours, fmt};
use plot::{BarChart, Figure, Panel, Section, Series, Table};

/// The page's sentence on the channels: rms before → after.
pub(super) fn summary(r: &UnitReport<'_>) -> String {
    let a = r.applied;
    let each: Vec<String> = a
        .channels
        .iter()
        .map(|c| format!("{} {} → {}", c.name, fmt(c.rms_before), fmt(c.rms_after)))
        .collect();
    format!(
        "{} ({}), {}: rms before (about the mean: what a constant correction leaves) → after the model, deg/h, on {} ({}): {}.",
        r.unit.name(),
        r.unit.file(),
        r.source,
        a.rows,
        a.n_rows,
        each.join("; ")
    )
}

/// Measured against predicted per channel, and the rms bars.
pub(super) fn figures(r: &UnitReport<'_>) -> Vec<(Figure, &'static str)> {
    let a = r.applied;
    let compare = a
        .channels
        .iter()
        .fold(
            Figure::new(format!("Measured against predicted, {}", a.rows)),
            |f, c| {
                f.panel(
                    Panel::new(
                        format!("Channel {}", c.name),
                        "time (s)",
                        format!("{} (deg/h)", c.name),
                    )
                    .series(
                        Series::line("measured", c.t.clone(), c.measured.clone())
                            .colour(colours::BEFORE),
                    )
                    .series(
                        Series::line("predicted", c.t.clone(), c.predicted.clone())
                            .colour(colours::AFTER),
                    ),
                )
            },
        )
        .share_x();
    let names: Vec<String> = a.channels.iter().map(|c| c.name.clone()).collect();
    let mut bars = BarChart::new("Channels", "rms (deg/h)", names).group_coloured(
        "bias only",
        a.channels.iter().map(|c| c.rms_before).collect::<Vec<_>>(),
        colours::BEFORE,
    );
    if let Some((label, b)) = r.baseline {
        bars = bars.group_coloured(
            label,
            b.channels.iter().map(|c| c.rms_after).collect::<Vec<_>>(),
            colours::BASELINE,
        );
    }
    bars = bars.group_coloured(
        "this model",
        a.channels.iter().map(|c| c.rms_after).collect::<Vec<_>>(),
        colours::AFTER,
    );
    vec![
        (compare, "unit_compare"),
        (
            Figure::new(format!("RMS on the {}", a.rows)).panel(bars),
            "unit_before_after",
        ),
    ]
}

/// The change from `before` to `after` in words.
pub(super) fn change(before: f64, after: f64) -> String {
    if before > 0.0 {
        format!("{:+.1}%", 100.0 * (after / before - 1.0))
    } else {
        "—".into()
    }
}

/// Section "Channels".
pub(super) fn section(r: &UnitReport<'_>, drawn: &Drawn) -> Section {
    let a = r.applied;
    let mut header = vec![
        "channel".to_string(),
        "model".into(),
        "effects".into(),
        "rms before (deg/h)".into(),
    ];
    if let Some((label, _)) = r.baseline {
        header.push(format!("rms after, {label}"));
    }
    header.extend(["rms after (deg/h)".to_string(), "change".into()]);
    let mut t = Table::new(header).caption(format!(
        "On the {} ({} rows): rms before is the pre-processed output less the rate reference about its mean (what the best constant correction leaves), rms after that of output − model.",
        a.rows, a.n_rows
    ));
    for (k, c) in a.channels.iter().enumerate() {
        let ids: Vec<&str> = c.effects.iter().map(|e| e.id.as_str()).collect();
        let mut row = vec![
            c.name.clone(),
            c.model.to_string(),
            if ids.is_empty() {
                "—".into()
            } else {
                ids.join(", ")
            },
            fmt(c.rms_before),
        ];
        if let Some((_, b)) = r.baseline {
            row.push(fmt(b.channels[k].rms_after));
        }
        row.extend([fmt(c.rms_after), change(c.rms_before, c.rms_after)]);
        t = t.row(row);
    }
    Section::new("Channels")
        .table(t)
        .figure(
            drawn.get("unit_compare"),
            "Each channel's error measured (vermillion) against the model's prediction (blue).",
        )
        .figure(
            drawn.get("unit_before_after"),
            "Rms of each channel without compensation (bias only) and with the model.",
        )
}

/// Section "Effects found": each effect with its coefficient.
pub(super) fn effects_section(r: &UnitReport<'_>) -> Section {
    let mut t = Table::new([
        "channel",
        "effect",
        "coefficient ± standard error (unit)",
        "95% interval",
    ]);
    let mut any = false;
    for c in &r.applied.channels {
        for e in &c.effects {
            any = true;
            let (coef, ci) = match &e.coefficient {
                Some(k) => (
                    format!("{} ± {} {}", fmt(k.value), fmt(k.se), k.unit),
                    format!("[{}, {}] {}", fmt(k.ci95[0]), fmt(k.ci95[1]), k.unit),
                ),
                None => ("— (not estimated in this file)".into(), "—".into()),
            };
            t = t.row([c.name.clone(), e.id.clone(), coef, ci]);
        }
    }
    let s = Section::new("Effects found");
    if any {
        s.table(t).text("Coefficients by cross-fitted partialling out with Newey–West standard errors; the 95% interval is the estimate's, in the effect's unit.")
    } else {
        s.text("The model has no physical effect on any channel: bias and the network only.")
    }
}
