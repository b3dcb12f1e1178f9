//! Section "Before and after": residue and channel rms on the validation
//! rows without and with compensation (and against a baseline model).

use super::channels::effect_ids;
use super::ctx::Ctx;
use crate::report::common::colours;
use crate::report::common::{Drawn, fmt};
use nav_sensors::geometry::{Channel, Residue};
use plot::{BarChart, Figure, Section, Table};

/// The before/after bars, with their file stem.
pub(super) fn figure(ctx: &Ctx<'_>) -> (Figure, &'static str) {
    let stats = &ctx.stats;
    let names: Vec<&str> = Residue::ALL.iter().map(|r| r.name()).collect();
    let bars = Figure::new("RMS on the validation rows").panel(
        BarChart::new("Residues", "rms (deg/h)", names)
            .group_coloured(
                "without compensation",
                stats.iter().map(|s| s.rms_before).collect::<Vec<_>>(),
                1,
            )
            .group_coloured(
                "with compensation",
                stats.iter().map(|s| s.rms_after).collect::<Vec<_>>(),
                0,
            ),
    );
    let ch_names: Vec<&str> = Channel::ALL.iter().map(|c| c.name()).collect();
    let mut ch_bars = BarChart::new("Channels: validation residual", "rms (deg/h)", ch_names)
        // Colours as in Fig. 7: orange without compensation, blue with.
        .group_coloured(
            "bias only",
            ctx.scores
                .iter()
                .map(|s| s.val_rms_bias_only)
                .collect::<Vec<_>>(),
            1,
        );
    if let Some((b, bs)) = ctx.baseline() {
        ch_bars = ch_bars.group_coloured(
            b.label,
            bs.iter().map(|s| s.val_rms).collect::<Vec<_>>(),
            colours::BASELINE,
        );
    }
    ch_bars = ch_bars.group_coloured(
        "this model",
        ctx.scores.iter().map(|s| s.val_rms).collect::<Vec<_>>(),
        0,
    );
    (bars.panel(ch_bars), "before_after")
}

/// Each channel's effects and validation rms under the baseline and this model.
fn baseline_table(ctx: &Ctx<'_>) -> Option<Table> {
    let (b, bs) = ctx.baseline()?;
    let mut t = Table::new([
        "channel",
        format!("{} effects", b.label).as_str(),
        format!("{} val rms", b.label).as_str(),
        "this model's effects",
        "this model's val rms",
        "change",
    ]);
    for ((old, new), (old_s, new_s)) in b
        .model
        .channels()
        .iter()
        .zip(ctx.model.channels())
        .zip(bs.iter().zip(&ctx.scores))
    {
        t = t.row([
            new.channel().name().to_string(),
            effect_ids(old),
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
        "Residue and channel rms on the validation rows.",
    );
    match baseline_table(ctx) {
        Some(t) => sec.table(t),
        None => sec,
    }
}
