//! Section "Figures" of the diagnosis: the ERR ranking, the residual against
//! its top candidate, residual spectra, whiteness and independence tests,
//! and measured against predicted.

use crate::report::common::Drawn;
use crate::report::common::{colours, positive_freq};
use plot::{BarChart, Figure, Panel, Section, Series};
use std::fmt::Display;
use sysid::diagnose::{ChannelDiagnosis, Diagnosis};

/// The section's figures, with their file stems.
pub(super) fn figures<C: Display, A>(
    diag: &Diagnosis<C, A>,
    min_err: f64,
) -> Vec<(Figure, &'static str)> {
    vec![
        (compare(diag), "diag_compare"),
        (top_candidates(diag), "diag_top_candidates"),
        (
            per_channel(
                "Residual spectrum against a white floor through the pre-filter, validation rows",
                diag,
                psd_panel,
            ),
            "diag_residual_psd",
        ),
        (
            per_channel(
                "Whiteness past the model's memory (a window plus the filter's reach)",
                diag,
                whiteness_panel,
            ),
            "diag_whiteness",
        ),
        (
            per_channel(
                "Independence: cross-correlation of the residual with every input",
                diag,
                independence_panel,
            ),
            "diag_independence",
        ),
        (err(diag, min_err), "diag_err"),
    ]
}

/// Measured against predicted, validation rows.
fn compare<C: Display, A>(diag: &Diagnosis<C, A>) -> Figure {
    per_channel("Measured against predicted, validation rows", diag, |c| {
        let s = &c.series;
        Panel::new(
            format!(
                "Channel {} (fit {:.1}%)",
                c.channel, c.compare.val_fit_percent
            ),
            "time (s)",
            format!("{} (deg/h)", c.channel),
        )
        .series(Series::line("measured", s.t.clone(), s.measured.clone()).colour(colours::BEFORE))
        .series(Series::line("predicted", s.t.clone(), s.predicted.clone()).colour(colours::AFTER))
    })
    .share_x()
}

/// The residual and its top candidate, scaled by its coefficient.
fn top_candidates<C: Display, A>(diag: &Diagnosis<C, A>) -> Figure {
    per_channel(
        "Residual and its top candidate effect (scaled by its coefficient)",
        diag,
        |c| {
            let s = &c.series;
            let mut p = Panel::new(format!("Channel {}", c.channel), "time (s)", "deg/h").series(
                Series::line("residual", s.t.clone(), s.residual.clone()).colour(colours::AFTER),
            );
            if let Some(top) = c.candidates.first()
                && let Some((_, col)) = s.candidates.iter().find(|(id, _)| *id == top.effect)
            {
                let scaled: Vec<f64> = col.iter().map(|v| top.coef * v).collect();
                p = p.series(
                    Series::line(
                        format!("{} × {:.3} {}", top.effect, top.coef, top.unit),
                        s.t.clone(),
                        scaled,
                    )
                    .colour(colours::REFERENCE),
                );
            }
            p
        },
    )
    .share_x()
}

/// A channel's residual spectrum against the white floor through the pre-filter.
fn psd_panel<C: Display, A>(c: &ChannelDiagnosis<C, A>) -> Panel {
    let mut p = Panel::psd(format!("Channel {}", c.channel), "PSD ((deg/h)²/Hz)");
    if let Some(sp) = &c.series.spectrum {
        // The floor falls to nothing at Nyquist through the filter's |H|⁴:
        // drawn down to 1e-4 of its peak so the axis stays readable.
        let peak = sp.floor.iter().copied().fold(0.0, f64::max);
        let (f, floor): (Vec<f64>, Vec<f64>) = sp
            .frequency_hz
            .iter()
            .zip(&sp.floor)
            .filter(|(f, v)| **f > 0.0 && **v >= 1e-4 * peak)
            .map(|(a, b)| (*a, *b))
            .unzip();
        let (rf, rd) = positive_freq(&sp.frequency_hz, &sp.density);
        p = p
            .series(Series::line("residual", rf, rd).colour(colours::AFTER))
            .series(Series::line("white floor", f, floor).colour(colours::REFERENCE));
    }
    p
}

/// A channel's whiteness test: autocorrelation past the model's memory.
fn whiteness_panel<C: Display, A>(c: &ChannelDiagnosis<C, A>) -> Panel {
    match c.checks.iter().find(|k| k.name == "whiteness") {
        Some(k) => {
            let dev: Vec<f64> = k
                .check
                .values
                .iter()
                .zip(&k.check.expected)
                .map(|(v, e)| v - e)
                .collect();
            let lags: Vec<f64> = k.check.lags.iter().map(|&l| l as f64).collect();
            let band = k.check.band.iter().copied().fold(0.0, f64::max);
            Panel::correlation(
                format!(
                    "Channel {}: {}",
                    c.channel,
                    if k.check.passed { "passes" } else { "FAILS" }
                ),
                "lag (decimated samples)",
                lags,
                dev,
                band,
            )
            // The test's own per-lag level, not the panel's default.
            .band(band, band_label(k.check.confidence))
        }
        None => Panel::new(format!("Channel {}", c.channel), "lag", "ρ"),
    }
}

/// An input's cross-correlation line: green, the input colour, told apart
/// by its pattern (ax solid, ay dashed, az dotted, extra columns as dots),
/// so that no colour that means something else on the page (vermillion,
/// blue) or a near twin of one (orange, sky blue) stands for an input.
fn input_series(i: usize, label: &str, lags: Vec<f64>, values: Vec<f64>) -> Series {
    let s = match i {
        0 => Series::line(label, lags, values),
        1 => Series::dashed(label, lags, values),
        2 => Series::dotted(label, lags, values),
        _ => Series::points(label, lags, values),
    };
    s.colour(colours::INPUT)
}

/// A channel's independence tests against every input (each acceleration
/// axis and each extra column) in one panel, lags in seconds.
fn independence_panel<C: Display, A>(c: &ChannelDiagnosis<C, A>) -> Panel {
    let t = &c.series.t;
    let dt = if t.len() > 1 { t[1] - t[0] } else { 1.0 };
    let tests: Vec<_> = c
        .checks
        .iter()
        .filter(|k| k.name.starts_with("independence:"))
        .collect();
    let failing: Vec<&str> = tests
        .iter()
        .filter(|k| !k.check.passed)
        .map(|k| k.name.trim_start_matches("independence:"))
        .collect();
    let verdict = if failing.is_empty() {
        "all pass".to_string()
    } else {
        format!("FAILS against {}", failing.join(", "))
    };
    let band = tests
        .iter()
        .filter_map(|k| k.check.band.first().copied())
        .fold(0.0, f64::max);
    let mut p = Panel::new(
        format!("Channel {}: {verdict}", c.channel),
        "lag (s)",
        "cross-correlation (–)",
    );
    for (i, k) in tests.iter().enumerate() {
        let lags: Vec<f64> = k.check.lags.iter().map(|&l| l as f64 * dt).collect();
        p = p.series(input_series(
            i,
            k.name.trim_start_matches("independence:"),
            lags,
            k.check.values.clone(),
        ));
    }
    match tests.first() {
        Some(k) => p.band(band, band_label(k.check.confidence)),
        None => p,
    }
}

/// ERR of each channel's candidates, ranked, with the suggestion threshold.
fn err<C: Display, A>(diag: &Diagnosis<C, A>, min_err: f64) -> Figure {
    let mut err_fig = Figure::new("Candidate effects: ERR on the validation residual");
    for c in &diag.channels {
        let items: Vec<(String, f64)> = c
            .candidates
            .iter()
            .map(|k| (k.effect.clone(), k.err))
            .collect();
        if !items.is_empty() {
            err_fig = err_fig.panel(
                BarChart::ranked(
                    format!("Channel {}", c.channel),
                    "ERR (share of residual mean square)",
                    "ERR",
                    items,
                )
                .threshold(min_err, "suggestion threshold"),
            );
        }
    }
    err_fig
}

/// The section, once its figures are drawn.
pub(super) fn section(drawn: &Drawn, min_err: f64) -> Section {
    Section::new("Figures")
        .figure(drawn.get("diag_err"), format!("ERR of each candidate effect on the cross-fitted residual of the whole record; the dashed line is the worth threshold, {}.", super::reading::worth_text(min_err)))
        .figure(drawn.get("diag_top_candidates"), "The residual and its top candidate, scaled by its estimated coefficient.")
        .figure(drawn.get("diag_residual_psd"), "Residual power spectral density.")
        .figure(drawn.get("diag_whiteness"), "Whiteness beyond the model's memory: the residual's autocorrelation at lags past one window plus the filter's reach, where a model that left nothing slow has none, with its band.")
        .figure(drawn.get("diag_independence"), "Independence: the residual's cross-correlation with each acceleration axis (and each extra column) against lag in seconds, with the (Bartlett) band; all inputs are green, ax solid, ay dashed, az dotted, extra columns as dots.")
}

/// One panel per channel under `title`.
fn per_channel<C, A>(
    title: &str,
    diag: &Diagnosis<C, A>,
    panel: impl Fn(&ChannelDiagnosis<C, A>) -> Panel,
) -> Figure {
    diag.channels
        .iter()
        .fold(Figure::new(title), |f, c| f.panel(panel(c)))
}

/// The legend of a correlation test's band: its per-lag level (the verdict
/// adds a Bonferroni correction over the lags).
fn band_label(confidence: f64) -> String {
    format!("{:.0} % band per lag", 100.0 * confidence)
}
