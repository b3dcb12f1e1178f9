//! What a channel's diagnosis says in words, most actionable first.

use super::locate::{Band, Regime, Segment};
use super::rank::Ranking;
use crate::sensor::Wording;

/// A p-value as text: below double precision's resolution of 1 − cdf it
/// is a bound, not a number.
///
/// ```
/// assert_eq!(sysid::diagnose::p_text(0.0), "< 1e-15");
/// assert_eq!(sysid::diagnose::p_text(0.0123), "= 1.2e-2");
/// ```
pub fn p_text(p: f64) -> String {
    if p < 1e-15 {
        "< 1e-15".into()
    } else {
        format!("= {p:.1e}")
    }
}

/// Plain-language findings, most actionable first.
pub(super) fn findings<A>(
    ranking: &Ranking<A>,
    failing: &[String],
    (segs, bands, regimes): (&[Segment], &[Band], &[Regime]),
    wording: &Wording,
) -> Vec<String> {
    let mut out = ranking_findings(ranking);
    out.extend(residual_findings(failing, (segs, bands, regimes), wording));
    out
}

/// What the ranking found: each suggestion with its evidence, or that
/// nothing is missing, and what the record cannot reveal.
fn ranking_findings<A>(ranking: &Ranking<A>) -> Vec<String> {
    let mut out = Vec::new();
    for id in &ranking.suggested {
        if let Some(c) = ranking.candidates.iter().find(|c| &c.effect == id) {
            let mut s = format!(
                "missing effect {id} ({}): explains {:.0}% of the cross-fitted residual, coefficient {:.4} ± {:.4} {} (95% CI {:.4} to {:.4}; p {})",
                c.description,
                100.0 * c.conditional_err.unwrap_or(c.err),
                c.coef,
                c.coef_se,
                c.unit,
                c.coef_ci95[0],
                c.coef_ci95[1],
                c.p_value.map_or("n/a".into(), p_text)
            );
            for caveat in &c.caveats {
                s.push_str(&format!("; caveat: {caveat}"));
            }
            match &c.separation {
                Some(sep) => s.push_str(&format!(
                    "; cannot be told apart here from {}: {}",
                    c.alternatives.join(", "),
                    sep.advice
                )),
                None if !c.collinear_with.is_empty() => s.push_str(&format!(
                    "; nearly collinear on this record with {}: cannot be told apart here",
                    c.collinear_with.join(", ")
                )),
                None => {}
            }
            for r in &c.record_separations {
                let on = |names: &[String]| {
                    names
                        .iter()
                        .filter_map(|n| r.records.iter().find(|x| &x.file == n))
                        .map(|x| format!("{} (|r| {:.2})", x.file, x.correlation.abs()))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                s.push_str(&format!(
                    "; told apart from {} only by the records together: collinear on {} alone{}",
                    r.effect,
                    on(&r.collinear_on),
                    if r.separated_by.is_empty() {
                        String::new()
                    } else {
                        format!(", separated by {}", on(&r.separated_by))
                    }
                ));
            }
            out.push(s);
        }
    }
    if ranking.suggested.is_empty() {
        out.push(
            "no candidate effect explains a significant part of the validation residual".into(),
        );
    }
    // What this record cannot reveal matters as much as what it does: a
    // stationary test never excites anisoinertia, a held chamber never temperature.
    if !ranking.unexcited.is_empty() {
        let ids: Vec<&str> = ranking
            .unexcited
            .iter()
            .map(|u| u.effect.as_str())
            .collect();
        out.push(format!(
            "not ranked, this record does not excite them: {}",
            ids.join(", ")
        ));
    }
    out
}

/// Where the residual says something is left: slow power, a dependence on
/// an operating signal, a bad stretch of time, failing tests.
fn residual_findings(
    failing: &[String],
    (segs, bands, regimes): (&[Segment], &[Band], &[Regime]),
    w: &Wording,
) -> Vec<String> {
    let mut out = Vec::new();
    // Excess slow power alone is expected of any model (its errors are
    // correlated over its window); "something slow is left" needs the
    // residual to be correlated beyond that memory as well.
    let slow_left = failing.iter().any(|f| f == "whiteness");
    for b in bands
        .iter()
        .filter(|b| b.ratio_to_floor > 3.0 && b.share > 0.1)
        .filter(|b| slow_left || b.f_hi_hz > 0.5)
    {
        out.push(format!(
            "{:.0}% of the residual power lies in {}–{} Hz, {:.1}× a white floor there{}",
            100.0 * b.share,
            // A band edge at a log's Nyquist frequency (60.0024 Hz of a
            // 120.005-Hz log) is printed to 0.1 mHz, not to the last bit.
            (b.f_lo_hz * 1e4).round() / 1e4,
            (b.f_hi_hz * 1e4).round() / 1e4,
            b.ratio_to_floor,
            if b.f_hi_hz <= 0.5 {
                format!(
                    ": something slow is not modelled and the residual stays correlated beyond the model's window ({})",
                    w.slow_hint
                )
            } else {
                String::new()
            }
        ));
    }
    for r in regimes.iter().filter(|r| r.mean_spread_sigma > 5.0) {
        out.push(format!(
            "the residual's mean changes with {} across its range ({:.0}σ): {}",
            r.axis, r.mean_spread_sigma, w.regime_hint
        ));
    }
    if !segs.is_empty() {
        let mut rms: Vec<f64> = segs.iter().map(|s| s.residual_rms).collect();
        rms.sort_by(f64::total_cmp);
        let median = rms[rms.len() / 2];
        for s in segs.iter().filter(|s| s.residual_rms > 2.0 * median) {
            out.push(format!(
                "{:.1}–{:.1} s: residual rms {:.3} {}, {:.1}× the median segment ({}, rms about its record mean: {:.2} {})",
                s.t_start,
                s.t_end,
                s.residual_rms,
                w.target_unit,
                s.residual_rms / median,
                w.operating_noun,
                s.operating_rms,
                w.operating_unit
            ));
        }
    }
    if !failing.is_empty() {
        out.push(format!("failing correlation tests: {}", failing.join(", ")));
    }
    out
}
