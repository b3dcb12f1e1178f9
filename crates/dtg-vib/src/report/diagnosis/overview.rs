//! Section "Overview": the page's summary (what to refit with), each
//! channel's effects, rms, fit and suggestions, and the rms bars.

use crate::report::common::{Drawn, fmt};
use plot::{BarChart, Figure, Section, Table};
use std::fmt::Display;
use sysid::diagnose::Diagnosis;

/// The validation rms bars (bias only against the model), with their stem.
pub(super) fn figure<C: Display, A>(diag: &Diagnosis<C, A>) -> (Figure, &'static str) {
    let names: Vec<String> = diag
        .channels
        .iter()
        .map(|c| c.channel.to_string())
        .collect();
    (
        Figure::new("Validation residual rms").panel(
            BarChart::new("Per channel", "rms (deg/h)", names)
                .group_coloured(
                    "bias only",
                    diag.channels
                        .iter()
                        .map(|c| c.compare.val_rms_bias_only)
                        .collect::<Vec<_>>(),
                    1,
                )
                .group_coloured(
                    "model",
                    diag.channels.iter().map(|c| c.rms).collect::<Vec<_>>(),
                    0,
                ),
        ),
        "diag_before_after",
    )
}

/// The page's summary line: the refit the diagnosis suggests, if any.
pub(super) fn summary<C: Display, A>(diag: &Diagnosis<C, A>) -> String {
    let suggestions: Vec<String> = diag
        .channels
        .iter()
        .filter(|c| !c.suggested.is_empty())
        .map(|c| {
            format!(
                "--add-effect {}={}",
                c.channel,
                c.suggested.join(&format!(" --add-effect {}=", c.channel))
            )
        })
        .collect();
    if suggestions.is_empty() {
        "No candidate effect explains a significant, worthwhile part of any channel's validation residual.".to_string()
    } else {
        format!("Suggested: refit with {}.", suggestions.join(" "))
    }
}

/// "—" for nothing, else the items comma-separated.
fn list(items: &[String]) -> String {
    if items.is_empty() {
        "—".into()
    } else {
        items.join(", ")
    }
}

/// The failing tests: "none", or how many and which.
pub(in crate::report) fn failing_cell(failing: &[String]) -> String {
    if failing.is_empty() {
        "none".into()
    } else {
        format!("{}: {}", failing.len(), failing.join(", "))
    }
}

/// The section, once its figure is drawn.
pub(super) fn section<C: Display, A>(diag: &Diagnosis<C, A>, drawn: &Drawn) -> Section {
    let mut overview = Table::new([
        "channel",
        "effects",
        "val rms (deg/h)",
        "val fit %",
        "suggested",
        "failing tests",
    ]);
    for c in &diag.channels {
        overview = overview.row([
            c.channel.to_string(),
            list(&c.effects),
            fmt(c.rms),
            format!("{:.1}", c.compare.val_fit_percent),
            list(&c.suggested),
            failing_cell(&c.failing),
        ]);
    }
    Section::new("Overview")
        .table(overview)
        .text("Every column is explained under \"How to read the tables\" below.")
        .figure(
            drawn.get("diag_compare"),
            "Measured against predicted on the validation rows.",
        )
        .figure(
            drawn.get("diag_before_after"),
            "Validation residual rms: bias-only model against the fitted model.",
        )
}
