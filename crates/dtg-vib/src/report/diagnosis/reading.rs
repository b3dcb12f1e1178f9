//! Section "How to read the tables": every column of the diagnosis tables
//! in a sentence — what ERR, the p-value threshold, the worth threshold, the
//! collinearity column and the failing tests mean, and why a rejected
//! candidate's coefficient can be large. The final report's compact
//! diagnosis reads the same sentences.

use crate::diagnose::RankOptions;
use crate::report::common::{fmt, short};
use plot::Section;
use sysid::diagnose::Diagnosis;

/// What the page says of a unit's channels and candidate ids.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelWording {
    /// The channels in the overview's column sentence (the paper's: "X,
    /// X1: gyro 1; Y, Y1: gyro 2; Z, Z1: gyro 3").
    pub channels: String,
    /// How many channels share the suggestion threshold.
    pub n_channels: usize,
    /// Where candidate ids come from.
    pub ids: String,
}

impl ChannelWording {
    /// Any unit: its gyros by name and model, a DTG's two axes together
    /// (they share a spin axis), and the candidate ids its models take.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// let w = dtg_vib::report::ChannelWording::of_unit(&u);
    /// assert_eq!(w.n_channels, 4);
    /// assert!(w.channels.starts_with("g1, g2, g3, g4: rate gyros of"), "{}", w.channels);
    /// let p = dtg_vib::report::ChannelWording::of_unit(&nav_sensors::unit::Unit::paper());
    /// assert_eq!(p.channels, "X, X1: gyro 1; Y, Y1: gyro 2; Z, Z1: gyro 3");
    /// ```
    pub fn of_unit(unit: &nav_sensors::unit::Unit) -> Self {
        let mut rate = Vec::new();
        // DTG axes by rotor: those whose spin axes agree.
        let mut rotors: Vec<(nalgebra::Vector3<f64>, Vec<&str>)> = Vec::new();
        for g in unit.gyros() {
            match &g.model {
                nav_sensors::unit::GyroModel::Rate => rate.push(g.name.as_str()),
                nav_sensors::unit::GyroModel::Dtg { spin, .. } => {
                    match rotors.iter_mut().find(|(s, _)| (s - spin).norm() < 1e-9) {
                        Some((_, axes)) => axes.push(g.name.as_str()),
                        None => rotors.push((*spin, vec![g.name.as_str()])),
                    }
                }
            }
        }
        let mut parts = Vec::new();
        if !rate.is_empty() {
            parts.push(format!(
                "{}: rate gyros of {}",
                rate.join(", "),
                unit.name()
            ));
        }
        for (k, (_, axes)) in rotors.iter().enumerate() {
            parts.push(format!("{}: gyro {}", axes.join(", "), k + 1));
        }
        let mut ids = Vec::new();
        if !rate.is_empty() {
            ids.push("g_x … gg_yz in the unit frame for rate gyros");
        }
        if !rotors.is_empty() {
            ids.push("IEEE Std 813 names for DTG terms");
        }
        ids.push("col:NAME for an extra column of the record");
        Self {
            channels: parts.join("; "),
            n_channels: unit.gyros().len(),
            ids: ids.join(", "),
        }
    }
}

/// `--min-gain` (the cut of the residual rms a suggestion must make) from
/// the ERR threshold it sets: ERR ≥ 1 − (1 − gain)².
fn min_gain(min_err: f64) -> f64 {
    1.0 - (1.0 - min_err.clamp(0.0, 1.0)).sqrt()
}

/// The worth threshold as the page prints it: the ERR number with the flag
/// value it comes from, so that "0.19" is never read as "--min-gain 0.19".
pub(in crate::report) fn worth_text(min_err: f64) -> String {
    let g = min_gain(min_err);
    format!(
        "ERR {} (--min-gain {}: adding the effect must cut the residual rms by at least {:.0}%, which is ERR ≥ 1 − (1 − {})² = {})",
        short(min_err),
        short(g),
        100.0 * g,
        short(g),
        short(min_err)
    )
}

/// The overview table's columns, one sentence each.
pub(in crate::report) const OVERVIEW_COLUMNS: &str = "Overview columns. channel: the gyro channel (X, X1: gyro 1; Y, Y1: gyro 2; Z, Z1: gyro 3). effects: the physical effects the model already has on it. val rms: the rms of the residual (measured minus predicted) on the validation rows, deg/h. val fit %: 100·(1 − ‖residual‖/‖measured − its mean‖) on those rows, as MATLAB's compare reports it (100 = perfect, 0 = no better than a constant). suggested: the candidate effects that pass both thresholds below, to add with --add-effect. failing tests: the residual-correlation tests that fail (whiteness: the residual is correlated with itself past the model's memory; independence:IN: it is correlated with input IN at some lag; billings_voon_u2_e, _e_eu, _u2_e2: Billings–Voon tests for an even function of an input, a residual × input product, or a residual level that follows the input's square), each at 1% after a Bonferroni correction over its lags.";

/// [`OVERVIEW_COLUMNS`] with `wording`'s channels.
fn overview_columns(wording: &ChannelWording) -> String {
    OVERVIEW_COLUMNS.replace(
        "(X, X1: gyro 1; Y, Y1: gyro 2; Z, Z1: gyro 3)",
        &format!("({})", wording.channels),
    )
}

/// The candidate tables' columns and thresholds in `wording`, one sentence
/// each, in three paragraphs: the columns, the thresholds, a rejected
/// candidate.
pub(in crate::report) fn candidate_columns(
    min_err: f64,
    p_threshold: &str,
    wording: &ChannelWording,
) -> String {
    let columns = format!(
        "Candidate columns. effect: the candidate's id ({}); ✓ marks a suggestion. \
         ERR (error-reduction ratio): the share of the channel's residual mean square that the candidate explains on its own, on the cross-fitted residual of the whole record \
         (each half predicted by a model fitted on the other half, with the model's bias, effects and network projected out of the candidate too); 0.25 means a quarter of the residual power. \
         coefficient ± standard error (unit): the candidate's coefficient on that residual with its unit, given the candidates picked before it if it was picked, alone otherwise, ± its Newey–West standard error (valid for a coloured, autocorrelated residual). \
         95% interval: the coefficient's 95% confidence interval, in the same unit. \
         p (forward step): the two-sided p-value of its coefficient given the candidates picked before it. \
         collinear with: other candidates whose columns correlate with this one at |r| ≥ {} on this record, so that the record cannot tell them apart: the coefficient is then that of a combination, and the findings name the run that would separate them. \
         description: the effect's physical name.",
        wording.ids,
        short(RankOptions::default().collinearity)
    );
    let thresholds = format!(
        "The thresholds. A suggestion needs p below α/({}·candidates), here {p_threshold} (α = --alpha, 0.01 by default, is the chance of any suggestion on a record with nothing missing), \
         and a share of what was left of at least {} (the worth threshold): significance alone is not enough with thousands of rows.",
        wording.n_channels,
        worth_text(min_err)
    );
    format!(
        "{columns}\n\n{thresholds}\n\nA rejected candidate's coefficient can be large: it is fitted to a residual it barely explains, and its interval shows how little the record determines it."
    )
}

/// The section.
pub(super) fn section<C, A>(
    diag: &Diagnosis<C, A>,
    min_err: f64,
    wording: &ChannelWording,
) -> Section {
    let p = diag
        .channels
        .first()
        .map_or("—".to_string(), |c| fmt(c.p_threshold));
    Section::new("How to read the tables")
        .text(overview_columns(wording))
        .text(candidate_columns(min_err, &p, wording))
        .text(crate::report::common::colours::LEGEND)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_worth_threshold_names_the_flag_value_it_comes_from() {
        let t = super::worth_text(crate::diagnose::RankOptions::default().min_err());
        assert!(t.starts_with("ERR 0.1164 (--min-gain 0.06: "), "{t}");
        assert!((super::min_gain(0.19) - 0.1).abs() < 1e-12);
    }
}
