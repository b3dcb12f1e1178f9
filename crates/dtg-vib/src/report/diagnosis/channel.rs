//! One section per channel: the findings and the ranked candidate effects
//! with their coefficients, intervals and p-values.

use crate::report::common::fmt;
use nav_sensors::geometry::Axis;
use plot::{Section, Table};
use std::fmt::Display;
use sysid::diagnose::ChannelDiagnosis;

/// The section of channel `c`.
pub(super) fn section<C: Display>(c: &ChannelDiagnosis<C, Axis>) -> Section {
    let mut sec = Section::new(format!("Channel {}", c.channel));
    for line in &c.findings {
        sec = sec.text(line.clone());
    }
    let mut t = Table::new([
        "effect",
        "ERR",
        "coefficient ± standard error (unit)",
        "95% interval",
        "p (forward step)",
        "collinear with",
        "description",
    ]);
    for k in c.candidates.iter().take(8) {
        t = t.row(
            candidate_cells(k)
                .into_iter()
                .chain([k.description.clone()]),
        );
    }
    sec.table(t)
}

/// A candidate's cells as the diagnosis tables print them: the id (✓ for a
/// suggestion), ERR, coefficient ± standard error with its unit, 95%
/// interval, p-value and the candidates it is collinear with.
pub(in crate::report) fn candidate_cells(k: &crate::diagnose::Candidate) -> [String; 6] {
    [
        format!("{}{}", k.effect, if k.significant { " ✓" } else { "" }),
        format!("{:.4}", k.err),
        format!("{} ± {} {}", fmt(k.coef), fmt(k.coef_se), k.unit),
        format!("[{}, {}]", fmt(k.coef_ci95[0]), fmt(k.coef_ci95[1])),
        k.p_value.map_or("—".into(), |p| {
            crate::diagnose::p_text(p).replace("= ", "")
        }),
        if k.collinear_with.is_empty() {
            "—".into()
        } else {
            k.collinear_with.join(", ")
        },
    ]
}
