//! Section "Channel models": each channel's effects, centres, width and
//! scores on this record.

use super::ctx::Ctx;
use crate::report::common::fmt;
use plot::{Section, Table};

/// The section.
pub(super) fn section(ctx: &Ctx<'_>) -> Section {
    let mut ch_table = Table::new([
        "channel",
        "effects: coefficient ± standard error (95% interval)",
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
            effect_cells(c),
            c.n_centres().to_string(),
            fmt(c.width()),
            fmt(s.train_rms),
            fmt(s.val_rms),
            fmt(s.val_rms_bias_only),
            format!("{:.1}", s.val_fit_percent),
        ]);
    }
    Section::new("Channel models").text("Each channel: bias, the listed physical effects (linear) and a Gaussian RBF on the acceleration window; centres and width chosen by blocked cross-validation inside the training rows. RMS in deg/h. Each effect's coefficient is estimated with the network partialled out (cross-fitted), ± its Newey–West standard error, with its 95% interval and unit, as `fit --json` gives them.").table(ch_table)
}

/// A channel model's effects, each with its fitted coefficient ± standard
/// error, 95% interval and unit (`fit --json`'s `effect_coefficients`),
/// `;`-separated, or "—" for none. A model file written before standard
/// errors gives the value and unit only.
pub(super) fn effect_cells(c: &crate::model::ChannelModel) -> String {
    let values = c.effect_coefficients();
    let e: Vec<String> = c
        .effects()
        .iter()
        .enumerate()
        .map(|(j, e)| match c.coefficients() {
            Some(k) => format!(
                "{} = {} ± {} {} (95% CI {} to {})",
                e.id(),
                fmt(k[j].value),
                fmt(k[j].se),
                k[j].unit,
                fmt(k[j].ci95[0]),
                fmt(k[j].ci95[1])
            ),
            None => format!(
                "{} = {} {}",
                e.id(),
                values.get(j).map_or("—".into(), |v| fmt(*v)),
                e.unit()
            ),
        })
        .collect();
    if e.is_empty() {
        "—".to_string()
    } else {
        e.join("; ")
    }
}

/// A channel model's effect ids, comma-separated, or "—" for none.
pub(super) fn effect_ids(c: &crate::model::ChannelModel) -> String {
    let e: Vec<String> = c.effects().iter().map(|e| e.id()).collect();
    if e.is_empty() {
        "—".to_string()
    } else {
        e.join(", ")
    }
}
