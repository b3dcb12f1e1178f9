//! Section "Before and after": residue and channel rms on the validation
//! rows without and with compensation (and against a baseline model).

use super::channels::{effect_ids, or_dash};
use super::ctx::Ctx;
use crate::report::common::colours;
use crate::report::common::{Drawn, fmt};
use plot::{BarChart, Figure, Section, Table};

/// The before/after bars (the residues', when the unit has any, and the
/// channels'), with their file stem.
pub(super) fn figure(ctx: &Ctx<'_>) -> (Figure, &'static str) {
    let stats = &ctx.stats;
    let mut bars = Figure::new("RMS on the validation rows");
    if !stats.is_empty() {
        let names: Vec<&str> = stats.iter().map(|s| s.name.as_str()).collect();
        bars = bars.panel(
            BarChart::new("Residues", "rms (deg/h)", names)
                .group_coloured(
                    "without compensation",
                    stats.iter().map(|s| s.before).collect::<Vec<_>>(),
                    colours::BEFORE,
                )
                .group_coloured(
                    "with compensation",
                    stats
                        .iter()
                        .map(|s| s.after.unwrap_or(f64::NAN))
                        .collect::<Vec<_>>(),
                    colours::AFTER,
                ),
        );
    }
    let ch_names: Vec<&str> = ctx.channels.iter().map(|c| c.name.as_str()).collect();
    let mut ch_bars = BarChart::new("Channels: validation residual", "rms (deg/h)", ch_names)
        // Colours as in Fig. 7: orange without compensation, blue with.
        .group_coloured(
            "bias only",
            ctx.channels
                .iter()
                .map(|c| c.scores.val_rms_bias_only)
                .collect::<Vec<_>>(),
            colours::BEFORE,
        );
    if let Some(b) = &ctx.baseline {
        ch_bars = ch_bars.group_coloured(
            b.label.as_str(),
            b.scores.iter().map(|s| s.val_rms).collect::<Vec<_>>(),
            colours::BASELINE,
        );
    }
    ch_bars = ch_bars.group_coloured(
        "this model",
        ctx.channels
            .iter()
            .map(|c| c.scores.val_rms)
            .collect::<Vec<_>>(),
        colours::AFTER,
    );
    (bars.panel(ch_bars), "before_after")
}

/// Each channel's effects and validation rms under the baseline and this model.
fn baseline_table(ctx: &Ctx<'_>) -> Option<Table> {
    let b = ctx.baseline.as_ref()?;
    let mut t = Table::new([
        "channel",
        format!("{} effects", b.label).as_str(),
        format!("{} val rms", b.label).as_str(),
        "this model's effects",
        "this model's val rms",
        "change",
    ]);
    for ((old_ids, old_s), new) in b.effect_ids.iter().zip(&b.scores).zip(&ctx.channels) {
        let new_s = &new.scores;
        t = t.row([
            new.name.clone(),
            or_dash(old_ids.clone()),
            fmt(old_s.val_rms),
            effect_ids(new),
            fmt(new_s.val_rms),
            format!("{:+.1}%", 100.0 * (new_s.val_rms / old_s.val_rms - 1.0)),
        ]);
    }
    Some(t)
}

/// The section, once its figure is drawn.
pub(super) fn section(ctx: &Ctx<'_>, drawn: &Drawn) -> Section {
    let sec = Section::new("Before and after").figure(
        drawn.get("before_after"),
        if ctx.stats.is_empty() {
            "Channel rms on the validation rows."
        } else {
            "Residue and channel rms on the validation rows."
        },
    );
    match baseline_table(ctx) {
        Some(t) => sec.table(t),
        None => sec,
    }
}
