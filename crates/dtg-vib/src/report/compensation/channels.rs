//! Sections "Channel models" (each channel's effects, centres, width and
//! scores on this record) and "Effects found" (every effect with its
//! coefficient, 95% interval and unit, one row each).

use super::ctx::{ChannelView, Ctx};
use crate::report::common::fmt;
use plot::{Section, Table};

/// Section "Channel models".
pub(super) fn section(ctx: &Ctx<'_>) -> Section {
    let mut ch_table = Table::new([
        "channel",
        "gyro",
        "effects: coefficient ± standard error (95% interval)",
        "centres",
        "β (g)",
        "train rms",
        "val rms",
        "bias-only val rms",
        "val fit %",
    ]);
    for (c, g) in ctx.channels.iter().zip(ctx.unit.gyros()) {
        let s = &c.scores;
        ch_table = ch_table.row([
            c.name.clone(),
            g.model.name().to_string(),
            effect_cells(c),
            c.n_centres.to_string(),
            fmt(c.width),
            if ctx.train.is_empty() {
                "—".into()
            } else {
                fmt(s.train_rms)
            },
            fmt(s.val_rms),
            fmt(s.val_rms_bias_only),
            format!("{:.1}", s.val_fit_percent),
        ]);
    }
    Section::new("Channel models").text("Each channel (gyro: `dtg` an axis of a dynamically tuned gyroscope, `rate` a rate gyro): bias, the listed physical effects (linear) and a Gaussian RBF on the acceleration window; centres and width chosen by blocked cross-validation inside the training rows. RMS in deg/h. Each effect's coefficient is estimated with the network partialled out (cross-fitted), ± its Newey–West standard error, with its 95% interval and unit, as `fit --json` gives them.").table(ch_table)
}

/// A channel model's effects, each with its fitted coefficient ± standard
/// error, 95% interval and unit (`fit --json`'s `effect_coefficients`),
/// `;`-separated, or "—" for none. A model file written before standard
/// errors gives the value and unit only.
pub(super) fn effect_cells(c: &ChannelView<'_>) -> String {
    let e: Vec<String> = c
        .effects
        .iter()
        .map(|e| match &e.coefficient {
            Some(k) => format!(
                "{} = {} ± {} {} (95% CI {} to {})",
                e.id,
                fmt(k.value),
                fmt(k.se),
                k.unit,
                fmt(k.ci95[0]),
                fmt(k.ci95[1])
            ),
            None => format!("{} = {} {}", e.id, e.value.map_or("—".into(), fmt), e.unit),
        })
        .collect();
    if e.is_empty() {
        "—".to_string()
    } else {
        e.join("; ")
    }
}

/// A channel model's effect ids, comma-separated, or "—" for none.
pub(super) fn effect_ids(c: &ChannelView<'_>) -> String {
    or_dash(
        c.effects
            .iter()
            .map(|e| e.id.clone())
            .collect::<Vec<_>>()
            .join(", "),
    )
}

/// `s`, or "—" when empty.
pub(super) fn or_dash(s: String) -> String {
    if s.is_empty() { "—".to_string() } else { s }
}

/// Section "Effects found": each effect with its coefficient.
pub(super) fn effects_section(ctx: &Ctx<'_>) -> Section {
    let mut t = Table::new([
        "channel",
        "effect",
        "coefficient ± standard error (unit)",
        "95% interval",
    ]);
    let mut any = false;
    for c in &ctx.channels {
        for e in &c.effects {
            any = true;
            let (coef, ci) = match &e.coefficient {
                Some(k) => (
                    format!("{} ± {} {}", fmt(k.value), fmt(k.se), k.unit),
                    format!("[{}, {}] {}", fmt(k.ci95[0]), fmt(k.ci95[1]), k.unit),
                ),
                None => (
                    format!(
                        "{} {} (no standard error in this file)",
                        e.value.map_or("—".into(), fmt),
                        e.unit
                    ),
                    "—".into(),
                ),
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
