//! One section per channel: the findings and the ranked candidate effects
//! with their coefficients, intervals and p-values.

use super::fmt;
use crate::diagnose::ChannelDiagnosis;
use plot::{Section, Table};

/// The section of channel `c`.
pub(super) fn section(c: &ChannelDiagnosis) -> Section {
    let mut sec = Section::new(format!("Channel {}", c.channel));
    for line in &c.findings {
        sec = sec.text(line.clone());
    }
    let mut t = Table::new([
        "effect",
        "ERR",
        "coefficient ± standard error",
        "95% interval",
        "unit",
        "p (forward step)",
        "collinear with",
        "description",
    ]);
    for k in c.candidates.iter().take(8) {
        t = t.row([
            format!("{}{}", k.effect, if k.significant { " ✓" } else { "" }),
            format!("{:.4}", k.err),
            format!("{} ± {}", fmt(k.coef), fmt(k.coef_se)),
            format!("[{}, {}]", fmt(k.coef_ci95[0]), fmt(k.coef_ci95[1])),
            k.unit.clone(),
            k.p_value.map_or("—".into(), |p| {
                crate::diagnose::p_text(p).replace("= ", "")
            }),
            if k.collinear_with.is_empty() {
                "—".into()
            } else {
                k.collinear_with.join(", ")
            },
            k.description.clone(),
        ]);
    }
    sec.table(t)
}
