//! Section "Channel models": each channel's effects, centres, width and
//! scores on this record.

use super::{Ctx, fmt};
use plot::{Section, Table};

/// The section.
pub(super) fn section(ctx: &Ctx<'_>) -> Section {
    let mut ch_table = Table::new([
        "channel",
        "effects",
        "centres",
        "β (g)",
        "train rms",
        "val rms",
        "bias-only val rms",
        "val fit %",
    ]);
    for (c, s) in ctx.model.channels().iter().zip(&ctx.scores) {
        ch_table = ch_table.row([
            c.channel().name().to_string(),
            effect_ids(c),
            c.n_centres().to_string(),
            fmt(c.width()),
            fmt(s.train_rms),
            fmt(s.val_rms),
            fmt(s.val_rms_bias_only),
            format!("{:.1}", s.val_fit_percent),
        ]);
    }
    Section::new("Channel models").text("Each channel: bias, the listed physical effects (linear) and a Gaussian RBF on the acceleration window; centres and width chosen by blocked cross-validation inside the training rows. RMS in deg/h.").table(ch_table)
}

/// A channel model's effects, comma-separated, or "—" for none.
pub(super) fn effect_ids(c: &crate::model::ChannelModel) -> String {
    let e: Vec<String> = c.effects().iter().map(|e| e.id()).collect();
    if e.is_empty() {
        "—".to_string()
    } else {
        e.join(", ")
    }
}
