//! What a channel's diagnosis says in words, most actionable first.

use super::{Band, Ranking, Regime, Segment};

/// A p-value as text: below double precision's resolution of 1 − cdf it
/// is a bound, not a number.
///
/// ```
/// assert_eq!(dtg_vib::diagnose::p_text(0.0), "< 1e-15");
/// assert_eq!(dtg_vib::diagnose::p_text(0.0123), "= 1.2e-2");
/// ```
pub fn p_text(p: f64) -> String {
    if p < 1e-15 {
        "< 1e-15".into()
    } else {
        format!("= {p:.1e}")
    }
}

/// Plain-language findings, most actionable first.
pub(super) fn findings(
    ranking: &Ranking,
    failing: &[String],
    segs: &[Segment],
    bands: &[Band],
    regimes: &[Regime],
) -> Vec<String> {
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
            b.f_lo_hz,
            b.f_hi_hz,
            b.ratio_to_floor,
            if b.f_hi_hz <= 0.5 {
                ": something slow is not modelled and the residual stays correlated beyond the model's window (a temperature or a drift: add its column as col:NAME)"
            } else {
                ""
            }
        ));
    }
    for r in regimes.iter().filter(|r| r.mean_spread_sigma > 5.0) {
        out.push(format!("the residual's mean changes with {} across its range ({:.0}σ): a g- or g²-sensitive term along it may be missing", r.axis, r.mean_spread_sigma));
    }
    if !segs.is_empty() {
        let mut rms: Vec<f64> = segs.iter().map(|s| s.residual_rms).collect();
        rms.sort_by(f64::total_cmp);
        let median = rms[rms.len() / 2];
        for s in segs.iter().filter(|s| s.residual_rms > 2.0 * median) {
            out.push(format!("{:.1}–{:.1} s: residual rms {:.3} deg/h, {:.1}× the median segment (low-passed specific force, rms about its record mean: {:.2} g)", s.t_start, s.t_end, s.residual_rms, s.residual_rms / median, s.vibration_rms_g));
        }
    }
    if !failing.is_empty() {
        out.push(format!("failing correlation tests: {}", failing.join(", ")));
    }
    out
}
