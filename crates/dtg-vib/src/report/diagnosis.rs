//! Figures and page of a diagnosis: measured against predicted, the residual
//! against its top candidates, residual spectra against a white floor, the
//! correlation tests with their bands, and the ERR ranking.

use super::{fmt, save_all};
use crate::diagnose::{ChannelDiagnosis, Diagnosis};
use crate::error::DtgVibError;
use plot::{BarChart, Figure, HtmlReport, Panel, Section, Series, Table};
use std::path::{Path, PathBuf};

fn per_channel(
    title: &str,
    diag: &Diagnosis,
    panel: impl Fn(&ChannelDiagnosis) -> Panel,
) -> Figure {
    diag.channels
        .iter()
        .fold(Figure::new(title), |f, c| f.panel(panel(c)))
}

/// Writes the diagnosis figures and `index.html` into `dir`; `min_err` is
/// the suggestion threshold drawn on the ERR charts.
pub fn write_diagnosis_report(
    diag: &Diagnosis,
    min_err: f64,
    dir: &Path,
) -> Result<PathBuf, DtgVibError> {
    let mut figs: Vec<(Figure, &str)> = Vec::new();
    figs.push((
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
            .series(Series::line("measured", s.t.clone(), s.measured.clone()).colour(1))
            .series(Series::line("predicted", s.t.clone(), s.predicted.clone()).colour(0))
        })
        .share_x(),
        "diag_compare",
    ));
    figs.push((
        per_channel(
            "Residual and its top candidate effect (scaled by its coefficient)",
            diag,
            |c| {
                let s = &c.series;
                let mut p = Panel::new(format!("Channel {}", c.channel), "time (s)", "deg/h")
                    .series(Series::line("residual", s.t.clone(), s.residual.clone()).colour(1));
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
                        .colour(0),
                    );
                }
                p
            },
        )
        .share_x(),
        "diag_top_candidates",
    ));
    figs.push((
        per_channel(
            "Residual spectrum against a white floor through the pre-filter, validation rows",
            diag,
            |c| {
                let mut p = Panel::psd(format!("Channel {}", c.channel), "PSD ((deg/h)²/Hz)");
                if let Some(sp) = &c.series.spectrum {
                    // The floor falls to nothing at Nyquist through the
                    // filter's |H|⁴: drawn down to 1e-4 of its peak so the
                    // axis stays readable.
                    let peak = sp.floor.iter().copied().fold(0.0, f64::max);
                    let (f, floor): (Vec<f64>, Vec<f64>) = sp
                        .frequency_hz
                        .iter()
                        .zip(&sp.floor)
                        .filter(|(_, v)| **v >= 1e-4 * peak)
                        .map(|(a, b)| (*a, *b))
                        .unzip();
                    p = p
                        .series(
                            Series::line("residual", sp.frequency_hz.clone(), sp.density.clone())
                                .colour(0),
                        )
                        .series(Series::line("white floor", f, floor).colour(1));
                }
                p
            },
        ),
        "diag_residual_psd",
    ));
    figs.push((
        per_channel(
            "Whiteness past the model's memory (a window plus the filter's reach)",
            diag,
            |c| match c.checks.iter().find(|k| k.name == "whiteness") {
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
            },
        ),
        "diag_whiteness",
    ));
    figs.push((
        per_channel(
            "Independence test against the acceleration with the worst statistic",
            diag,
            |c| {
                let worst = c
                    .checks
                    .iter()
                    .filter(|k| k.name.starts_with("independence:"))
                    .max_by(|a, b| a.check.statistic.total_cmp(&b.check.statistic));
                match worst {
                    Some(k) => {
                        let lags: Vec<f64> = k.check.lags.iter().map(|&l| l as f64).collect();
                        let band = k.check.band.first().copied().unwrap_or(0.0);
                        Panel::correlation(
                            format!(
                                "Channel {}: {} {}",
                                c.channel,
                                k.name,
                                if k.check.passed { "passes" } else { "FAILS" }
                            ),
                            "lag (samples)",
                            lags,
                            k.check.values.clone(),
                            band,
                        )
                        .band(band, band_label(k.check.confidence))
                    }
                    None => Panel::new(format!("Channel {}", c.channel), "lag", "ρ"),
                }
            },
        ),
        "diag_independence",
    ));
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
    figs.push((err_fig, "diag_err"));
    let names: Vec<&str> = diag.channels.iter().map(|c| c.channel.name()).collect();
    figs.push((
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
    ));
    let files = save_all(figs, dir)?;
    let f = |stem: &str| {
        files
            .iter()
            .find(|(s, _)| *s == stem)
            .map(|(_, f)| f)
            .expect("drawn")
    };

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
            c.channel.name().to_string(),
            if c.effects.is_empty() {
                "—".into()
            } else {
                c.effects.join(", ")
            },
            fmt(c.rms),
            format!("{:.1}", c.compare.val_fit_percent),
            if c.suggested.is_empty() {
                "—".into()
            } else {
                c.suggested.join(", ")
            },
            c.failing.len().to_string(),
        ]);
    }
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
    let mut page = HtmlReport::new("Diagnosis: what the model is missing")
        .summary(if suggestions.is_empty() {
            "No candidate effect explains a significant, worthwhile part of any channel's validation residual.".to_string()
        } else {
            format!("Suggested: refit with {}.", suggestions.join(" "))
        })
        .section(Section::new("Overview").table(overview).figure(f("diag_before_after"), "Validation residual rms: bias-only model against the fitted model."));
    page = page.section(Section::new("How to read the tables").text(format!(
        "ERR is the share of a channel's residual that a candidate effect explains on its own, on the cross-fitted residual of the whole record \
         (each half predicted by a model fitted on the other half, with the model's bias, effects and network projected out of the candidate too). \
         A suggestion (✓) needs two things: its p-value, from the t-statistic of its coefficient given the candidates picked before it, \
         below α/(6·candidates) (here {}), and a share of what was left of at least {:.2} (the worth threshold, --min-gain). \
         Coefficients are given ± their standard error (Newey–West, valid for a coloured residual) with a 95% interval. \
         A rejected candidate's coefficient can be large: it is fitted to a residual it barely explains, and its interval shows how little the record determines it.",
        diag.channels.first().map_or("—".to_string(), |c| fmt(c.p_threshold)),
        min_err
    )));
    for c in &diag.channels {
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
        page = page.section(sec.table(t));
    }
    page = page.section(
        Section::new("Figures")
            .figure(f("diag_err"), "ERR of each candidate effect on the cross-fitted residual of the whole record; the dashed line is the worth threshold (--min-gain).")
            .figure(f("diag_top_candidates"), "The residual and its top candidate, scaled by its estimated coefficient.")
            .figure(f("diag_residual_psd"), "Residual power spectral density.")
            .figure(f("diag_whiteness"), "Whiteness beyond the model's memory: the residual's autocorrelation at lags past one window plus the filter's reach, where a model that left nothing slow has none, with its band.")
            .figure(f("diag_independence"), "Independence: residual–acceleration cross-correlation with its (Bartlett) band.")
            .figure(f("diag_compare"), "Measured against predicted on the validation rows."),
    );
    Ok(page.write(dir)?)
}

/// The legend of a correlation test's band: its per-lag level (the verdict
/// adds a Bonferroni correction over the lags).
fn band_label(confidence: f64) -> String {
    format!("{:.0} % band per lag", 100.0 * confidence)
}
