//! The Allan-deviation page: log-log curves before and after compensation
//! with the fitted noise-term lines, and a table of the terms.

use super::common::{Drawn, colours, fmt, save_all};
use crate::allan::{AllanAnalysis, SeriesAllan, term_text as cell};
use crate::error::DtgVibError;
use nav_sensors::noise::{AllanCurve, FLICKER_FLOOR, NoiseTerm, NoiseTerms};
use plot::{Figure, HtmlReport, Panel, Section, Series, Table};
use std::path::{Path, PathBuf};

/// The fitted lines of `terms`, each over its region widened by an octave
/// either side (within the curve's τ): a line far from where it was read
/// would only stretch the axis and hide the curves. Black, the colour of a
/// reference line on every page: dashed when read on the curve before
/// compensation, dotted after.
fn term_lines(curve: &AllanCurve, terms: &NoiseTerms, when: &str) -> Vec<Series> {
    let (Some(first), Some(last)) = (curve.points.first(), curve.points.last()) else {
        return Vec::new();
    };
    let span = |from: f64, to: f64| -> Vec<f64> {
        let (a, b) = ((from / 2.0).max(first.tau_s), (to * 2.0).min(last.tau_s));
        curve
            .points
            .iter()
            .map(|p| p.tau_s)
            .filter(|&t| t >= a && t <= b)
            .collect()
    };
    let mut out = Vec::new();
    let line = if when == "before" {
        Series::dashed
    } else {
        Series::dotted
    };
    let mut add = |term: &NoiseTerm, name: &str, unit: &str, f: &dyn Fn(f64, f64) -> f64| {
        if let Some(e) = term.estimate() {
            let tau = span(e.tau_from_s, e.tau_to_s);
            let y: Vec<f64> = tau.iter().map(|&t| f(e.value, t)).collect();
            out.push(
                line(format!("{name} {} {unit} ({when})", fmt(e.value)), tau, y)
                    .colour(colours::REFERENCE),
            );
        }
    };
    add(&terms.arw, "ARW", "deg/√h", &|n, t| 60.0 * n / t.sqrt());
    add(&terms.bias_instability, "BI", "deg/h", &|b, _| {
        FLICKER_FLOOR * b
    });
    add(&terms.rrw, "RRW", "deg/h/√h", &|k, t| {
        k * (t / 10_800.0).sqrt()
    });
    out
}

fn panel(s: &SeriesAllan) -> Panel {
    let mut p = Panel::new(s.name.as_str(), "τ (s)", "Allan deviation (deg/h)")
        .log_x()
        .log_y()
        .series(Series::line("before", s.before.tau_s(), s.before.adev()).colour(colours::BEFORE));
    if let Some(a) = &s.after {
        p = p.series(Series::line("after", a.tau_s(), a.adev()).colour(colours::AFTER));
    }
    for line in term_lines(&s.before, &s.terms_before, "before") {
        p = p.series(line);
    }
    if let (Some(a), Some(t)) = (&s.after, &s.terms_after) {
        for line in term_lines(a, t, "after") {
            p = p.series(line);
        }
    }
    p
}

fn table(rows: &[SeriesAllan], confidence: f64) -> Table {
    let mut t = Table::new([
        "series",
        "ARW before (deg/√h)",
        "ARW after",
        "bias instability before (deg/h)",
        "BI after",
        "RRW before (deg/h/√h)",
        "RRW after",
    ])
    .caption(format!(
        "Estimates with their {:.1}% confidence intervals; a term the curve does not resolve shows the upper bound every τ still allows.",
        100.0 * confidence
    ));
    for s in rows {
        let after = |f: fn(&NoiseTerms) -> &NoiseTerm| {
            s.terms_after.as_ref().map_or("—".into(), |t| cell(f(t)))
        };
        t = t.row([
            s.name.to_string(),
            cell(&s.terms_before.arw),
            after(|t| &t.arw),
            cell(&s.terms_before.bias_instability),
            after(|t| &t.bias_instability),
            cell(&s.terms_before.rrw),
            after(|t| &t.rrw),
        ]);
    }
    t
}

/// The two Allan figures (channels, residues), with their file stems.
pub(super) fn figures(analysis: &AllanAnalysis) -> Vec<(Figure, &'static str)> {
    let figure = |title: &str, rows: &[SeriesAllan]| {
        rows.iter()
            .fold(Figure::new(title), |f, s| f.panel(panel(s)))
    };
    vec![
        (
            figure(
                "Overlapping Allan deviation, gyro channels",
                &analysis.channels,
            ),
            "allan_channels",
        ),
        (
            figure(
                &format!(
                    "Overlapping Allan deviation, parity residues ({})",
                    analysis.residue_source
                ),
                &analysis.residues,
            ),
            "allan_residues",
        ),
    ]
    .into_iter()
    // A unit of three gyros has no residue: no empty figure.
    .filter(|(_, stem)| *stem != "allan_residues" || !analysis.residues.is_empty())
    .collect()
}

/// One section per figure: its noise-term table, notes and figure.
pub(super) fn sections(analysis: &AllanAnalysis, drawn: &Drawn) -> Vec<Section> {
    [
        (
            "allan_channels",
            &analysis.channels,
            "Allan deviation: gyro channels",
        ),
        (
            "allan_residues",
            &analysis.residues,
            "Allan deviation: parity residues",
        ),
    ]
    .into_iter()
    .filter(|(_, rows, _)| !rows.is_empty())
    .map(|(stem, rows, heading)| {
        let files = drawn.get(stem);
        let mut sec = Section::new(heading).table(table(rows, analysis.confidence));
        for w in &files.warnings {
            sec = sec.text(w.clone());
        }
        sec.figure(
            files,
            format!(
                "{stem}: Allan deviation against τ (log-log), before (vermillion) and after (blue), with the fitted noise-term lines in black (dashed: read on the curve before; dotted: after)."
            ),
        )
    })
    .collect()
}

/// What the Allan page's summary says about the series analysed.
pub(super) fn summary(analysis: &AllanAnalysis, data: &str) -> String {
    let what = if analysis.compensated {
        "before (calibrated output, rate reference removed) and after the model's compensation (what `compensate` writes)"
    } else {
        "of the record as given (no model)"
    };
    format!(
        "{data}: {} samples from sample {} at τ₀ = {} s, {what}; octave-spaced τ up to a tenth of the record. Noise terms after IEEE Std 952: angle random walk on the τ^−½ region, bias instability at the minimum / 0.664, rate random walk on the τ^+½ region.",
        analysis.samples, analysis.first_sample, analysis.tau0_s
    )
}

/// Writes `allan_channels` and `allan_residues` (PNG and SVG) and
/// `index.html` into `dir`; `data` names the record on the page.
pub fn write_allan_report(
    analysis: &AllanAnalysis,
    data: &str,
    dir: &Path,
) -> Result<PathBuf, DtgVibError> {
    let drawn = save_all(figures(analysis), dir)?;
    let mut page = HtmlReport::new("Allan deviation").summary(summary(analysis, data));
    for sec in sections(analysis, &drawn) {
        page = page.section(sec);
    }
    Ok(page.write(dir)?)
}
