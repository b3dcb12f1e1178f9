//! Section "How to read the tables": what ERR, the p-value threshold, the
//! worth threshold and a rejected candidate's large coefficient mean.

use super::fmt;
use crate::diagnose::Diagnosis;
use plot::Section;

/// The section.
pub(super) fn section(diag: &Diagnosis, min_err: f64) -> Section {
    Section::new("How to read the tables").text(format!(
        "ERR is the share of a channel's residual that a candidate effect explains on its own, on the cross-fitted residual of the whole record \
         (each half predicted by a model fitted on the other half, with the model's bias, effects and network projected out of the candidate too). \
         A suggestion (✓) needs two things: its p-value, from the t-statistic of its coefficient given the candidates picked before it, \
         below α/(6·candidates) (here {}), and a share of what was left of at least {:.2} (the worth threshold, --min-gain). \
         Coefficients are given ± their standard error (Newey–West, valid for a coloured residual) with a 95% interval. \
         A rejected candidate's coefficient can be large: it is fitted to a residual it barely explains, and its interval shows how little the record determines it.",
        diag.channels.first().map_or("—".to_string(), |c| fmt(c.p_threshold)),
        min_err
    ))
    .text(crate::report::colours::LEGEND)
}
