//! Section "Summary": the table a test engineer reads first — each
//! channel's validation rms before and after, its fit and effects — then
//! the provenance, the other pages and what the colours mean.

use super::channels::effect_cells;
use super::ctx::Ctx;
use super::inputs::ReportExtras;
use crate::report::common::fmt;
use plot::{Section, Table};

/// The per-channel summary table: rms before (bias only) and after, on the
/// validation rows.
fn channel_table(ctx: &Ctx<'_>) -> Table {
    let mut t = Table::new([
        "channel",
        "rms before (deg/h)",
        "rms after (deg/h)",
        "reduction",
        "val fit %",
        "effects: coefficient ± standard error (95% interval)",
    ])
    .caption(
        "Per channel, validation rows: rms before (a bias-only model) and after compensation; each fitted effect with its coefficient ± standard error, 95% interval and unit.",
    );
    for c in &ctx.channels {
        let s = &c.scores;
        t = t.row([
            c.name.clone(),
            fmt(s.val_rms_bias_only),
            fmt(s.val_rms),
            format!("{:.2}×", s.val_rms_bias_only / s.val_rms),
            format!("{:.1}", s.val_fit_percent),
            effect_cells(c),
        ]);
    }
    t
}

/// The section.
pub(super) fn section<C>(ctx: &Ctx<'_>, extras: &ReportExtras<'_, C>) -> Section {
    let mut sec = Section::new("Summary").table(channel_table(ctx));
    if let Some(p) = extras.provenance {
        sec = sec.table(p.table());
    }
    for (path, text) in &extras.links {
        sec = sec.link(path.clone(), text.clone());
    }
    sec.text(crate::report::common::colours::LEGEND)
}
