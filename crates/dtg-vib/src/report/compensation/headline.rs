//! The page's summary under its title: what compensation did, what is left
//! and what got worse. Every sentence is built from numbers a section of the
//! page shows, formatted as that section formats them, and names the
//! section, so that the summary and the figures say the same thing (issue
//! 26 item 8: a final page whose residual stood ~3× the noise floor and
//! whose bias instability rose on every channel said neither at the top).

use super::ctx::Ctx;
use super::diagnosis::{band_name, top_band};
use super::inputs::{DiagnosisExtra, ReportExtras};
use super::{histogram, residues};
use crate::allan::{AllanAnalysis, SeriesAllan};
use crate::report::common::{fmt, short};
use nav_sensors::noise::{NoiseTerm, NoiseTerms};
use std::fmt::Display;

/// The summary's paragraphs: the caller's own first, what was done, then
/// "What is left: …" and "What got worse: …" when the page shows either.
pub(super) fn paragraphs<C: Display>(
    ctx: &Ctx<'_>,
    extras: &ReportExtras<'_, C>,
    source: &str,
) -> Vec<String> {
    let mut out = extras.lead.clone();
    out.push(done(ctx, extras, source));
    let left = left(ctx, extras);
    if !left.is_empty() {
        out.push(format!("What is left: {}", left.join(" ")));
    }
    let worse = worse(ctx, extras);
    if !worse.is_empty() {
        out.push(format!("What got worse: {}", worse.join(" ")));
    }
    out
}

/// The unit, the record, the split, the residue rms reduction (section
/// "Parity residues") and what fault detection found on the compensated
/// record; for three gyros, why there is no residue.
fn done<C>(ctx: &Ctx<'_>, extras: &ReportExtras<'_, C>, source: &str) -> String {
    let reduction = if ctx.stats.is_empty() {
        residues::no_residue(ctx)
    } else {
        reduction(ctx)
    };
    let rows = if ctx.train.is_empty() {
        format!(
            "the model's split {} does not fit this record: its {} rows are all compared",
            ctx.split,
            ctx.val.len()
        )
    } else {
        format!(
            "split {} ({} training, {} validation rows)",
            ctx.split,
            ctx.train.len(),
            ctx.val.len(),
        )
    };
    let mut text = format!(
        "Unit {} ({}). Record {} ({} samples at {} Hz); {rows}. {reduction}",
        ctx.unit.name(),
        ctx.unit.file(),
        source,
        ctx.samples,
        fmt(1.0 / ctx.dt),
    );
    if let Some(f) = extras.parity.and_then(|p| p.fdi.as_ref())
        && let Some((what, last)) = f.found.last()
    {
        text.push_str(&format!(
            " Parity {}.",
            crate::unit_sensor::fdi::line(what, last, &f.setting)
        ));
    }
    text
}

/// How far the residue rms fell on the validation rows.
fn reduction(ctx: &Ctx<'_>) -> String {
    let fell: Vec<f64> = ctx
        .stats
        .iter()
        .map(residues::reduction)
        .filter(|r| as_printed(*r, 2) > 1.0)
        .collect();
    let min_red = fell.iter().copied().fold(f64::INFINITY, f64::min);
    let max_red = fell.iter().copied().fold(0.0, f64::max);
    if fell.len() == ctx.stats.len() {
        format!("Residue rms fell {min_red:.2}× to {max_red:.2}× on the validation rows.")
    } else if fell.is_empty() {
        format!(
            "Residue rms fell on none of the {} residues on the validation rows.",
            ctx.stats.len()
        )
    } else {
        format!(
            "Residue rms fell on {} of {} residues on the validation rows ({min_red:.2}× to {max_red:.2}×).",
            fell.len(),
            ctx.stats.len()
        )
    }
}

/// `lo–hi` of already-formatted numbers (one number when all are equal),
/// ordered by value.
fn span(cells: &[(f64, String)]) -> String {
    let lo = cells.iter().min_by(|a, b| a.0.total_cmp(&b.0));
    let hi = cells.iter().max_by(|a, b| a.0.total_cmp(&b.0));
    match (lo, hi) {
        (Some(lo), Some(hi)) if lo.1 != hi.1 => format!("{}–{}", lo.1, hi.1),
        (Some(lo), _) => lo.1.clone(),
        _ => String::new(),
    }
}

/// `v` as a table prints it with `decimals` decimals: a ratio printed
/// "1.00×" is neither better nor worse on the page, so not in its summary.
fn as_printed(v: f64, decimals: usize) -> f64 {
    format!("{v:.decimals$}").parse().unwrap_or(v)
}

/// "LEAD on K of N WHAT (SECTION): ITEMS.", when there are items.
fn counted(
    lead: &str,
    items: &[String],
    (n, what): (usize, &str),
    section: &str,
) -> Option<String> {
    (!items.is_empty()).then(|| {
        format!(
            "{lead} on {} of {n} {what} ({section}): {}.",
            items.len(),
            items.join(", ")
        )
    })
}

/// What is left: the residual against the noise floor, the band most above
/// the white floor, and whether the diagnosis names anything for it.
fn left<C: Display>(ctx: &Ctx<'_>, extras: &ReportExtras<'_, C>) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(rows) = histogram::residual_and_floor(ctx) {
        let ratios: Vec<(f64, String)> = rows
            .iter()
            .map(|(_, sd, fl)| (sd / fl, format!("{:.2}×", sd / fl)))
            .collect();
        out.push(format!(
            "The residual is {} the noise floor on the validation rows of the {} channels (residual σ / noise floor σ; Residual distribution against the noise floor).",
            span(&ratios).replace('–', " to "),
            rows.len()
        ));
    }
    if let Some(d) = &extras.diagnosis {
        out.extend(diagnosis_left(d));
    }
    out
}

/// The band most above the white floor and what the diagnosis suggests.
fn diagnosis_left<C: Display>(d: &DiagnosisExtra<'_, C>) -> Vec<String> {
    let chans = &d.diagnosis.channels;
    let mut out = Vec::new();
    let bands: Vec<(String, &crate::diagnose::Band)> = chans
        .iter()
        .filter_map(|c| top_band(c).map(|b| (c.channel.to_string(), b)))
        .collect();
    if let Some((_, first)) = bands.first() {
        let same = bands.iter().all(|(_, b)| band_name(b) == band_name(first));
        let cells = |f: &dyn Fn(&crate::diagnose::Band) -> (f64, String)| -> Vec<(f64, String)> {
            bands.iter().map(|(_, b)| f(b)).collect()
        };
        let ratio = cells(&|b| (b.ratio_to_floor, format!("{:.1}×", b.ratio_to_floor)));
        let share = cells(&|b| (b.share, format!("{:.0}%", 100.0 * b.share)));
        if same {
            out.push(format!(
                "Its frequency band most above the white floor is {} on all {} channels, {} the white floor ({} of the power; Where it fails).",
                band_name(first),
                bands.len(),
                span(&ratio).replace('–', " to "),
                span(&share).replace('–', " to ")
            ));
        } else {
            let each: Vec<String> = bands
                .iter()
                .map(|(ch, b)| format!("{ch} {} {:.1}×", band_name(b), b.ratio_to_floor))
                .collect();
            out.push(format!(
                "Its frequency band most above the white floor, per channel: {} the white floor (Where it fails).",
                each.join(", ")
            ));
        }
    }
    let suggested: Vec<String> = chans
        .iter()
        .flat_map(|c| {
            c.suggested
                .iter()
                .map(move |e| format!("{}={e}", c.channel))
        })
        .collect();
    let quiet: Vec<_> = chans.iter().filter(|c| c.suggested.is_empty()).collect();
    let tops: Vec<(f64, String)> = quiet
        .iter()
        .filter_map(|c| c.candidates.first())
        .map(|k| (k.err, format!("{:.4}", k.err)))
        .collect();
    let below = quiet
        .iter()
        .all(|c| c.candidates.first().is_none_or(|k| k.err < d.min_err));
    let why = if tops.is_empty() {
        "no candidate was ranked".to_string()
    } else if below {
        format!(
            "its top candidate explains ERR {} of the residual, below the worth threshold ERR {}",
            span(&tops),
            short(d.min_err)
        )
    } else {
        format!(
            "no candidate passes both thresholds (top candidates' ERR {}; worth threshold ERR {})",
            span(&tops),
            short(d.min_err)
        )
    };
    if suggested.is_empty() {
        out.push(format!(
            "The diagnosis of {} found no missing effect that explains it: on every channel {why} (Diagnosis).",
            d.of
        ));
    } else {
        let rest = if quiet.is_empty() {
            String::new()
        } else {
            format!(
                "; on {} {why}",
                quiet
                    .iter()
                    .map(|c| c.channel.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        out.push(format!(
            "The diagnosis of {} finds effects the model lacks: add {}{rest} (Diagnosis).",
            d.of,
            suggested.join(", ")
        ));
    }
    out
}

/// What got worse: channels and residues against before and the baseline,
/// the Allan terms, and the power compensation added at 0.2–2 Hz.
fn worse<C>(ctx: &Ctx<'_>, extras: &ReportExtras<'_, C>) -> Vec<String> {
    let mut out = Vec::new();
    // The Summary table: rms before (bias only) and after, and the
    // reduction as it prints it (a channel at "1.00×" did not get worse).
    let up: Vec<String> = ctx
        .channels
        .iter()
        .map(|c| (c, c.scores.val_rms_bias_only / c.scores.val_rms))
        .filter(|(_, r)| as_printed(*r, 2) < 1.0)
        .map(|(c, r)| {
            format!(
                "{} {} → {} deg/h ({r:.2}×)",
                c.name,
                fmt(c.scores.val_rms_bias_only),
                fmt(c.scores.val_rms)
            )
        })
        .collect();
    out.extend(counted(
        "The validation rms after compensation is higher than before (a bias-only model)",
        &up,
        (ctx.channels.len(), "channels"),
        "Summary",
    ));
    // The residue table, its reduction as printed.
    let rose: Vec<String> = ctx
        .stats
        .iter()
        .map(|s| (s, residues::reduction(s)))
        .filter(|(_, r)| as_printed(*r, 2) < 1.0)
        .map(|(s, r)| {
            format!(
                "{} {} → {} deg/h ({r:.2}×, {:.2}× worse)",
                s.name,
                fmt(s.before),
                fmt(s.after.unwrap_or(f64::NAN)),
                1.0 / r
            )
        })
        .collect();
    out.extend(counted(
        "Residue rms rose",
        &rose,
        (ctx.stats.len(), "residues"),
        residues::TITLE,
    ));
    // The "Before and after" table's change column.
    if let Some(b) = &ctx.baseline {
        let up: Vec<String> = ctx
            .channels
            .iter()
            .zip(&b.scores)
            .map(|(new, old)| (new, 100.0 * (new.scores.val_rms / old.val_rms - 1.0)))
            .filter(|(_, change)| as_printed(*change, 1) > 0.0)
            .map(|(c, change)| format!("{} {change:+.1}%", c.name))
            .collect();
        if !up.is_empty() {
            out.push(format!(
                "The validation rms is higher than the {}'s on {}: {} (Before and after).",
                b.label,
                if up.len() == 1 {
                    "1 channel".to_string()
                } else {
                    format!("{} channels", up.len())
                },
                up.join(", ")
            ));
        }
    }
    if let Some(a) = extras.allan {
        out.extend(allan_worse(a));
    }
    // The spectra's band powers: a rise the page prints as more than 1.0×.
    let powers = residues::powers(ctx);
    let added: Vec<(f64, String)> = powers
        .iter()
        .map(|p| p.bands[1][1] / p.bands[1][0])
        .filter(|r| as_printed(*r, 1) > 1.0)
        .map(|r| (r, format!("{r:.1}×")))
        .collect();
    if !added.is_empty() {
        let (lo, hi) = residues::BANDS[1];
        out.push(format!(
            "Compensation added power at {}–{} Hz to {} of {} residues ({}; {}).",
            short(lo),
            short(hi),
            added.len(),
            powers.len(),
            span(&added).replace('–', " to "),
            residues::TITLE
        ));
    }
    out
}

/// The Allan sentences of both tables (gyro channels, parity residues).
fn allan_worse(a: &AllanAnalysis) -> Vec<String> {
    fn rows(v: &[SeriesAllan]) -> Vec<(&str, NoiseTerms, Option<NoiseTerms>)> {
        v.iter()
            .map(|s| {
                (
                    s.name.as_str(),
                    s.terms_before.clone(),
                    s.terms_after.clone(),
                )
            })
            .collect()
    }
    let (channels, residues) = (rows(&a.channels), rows(&a.residues));
    allan_terms_worse(
        &[(&channels, "channels"), (&residues, "parity residues")],
        &format!("{:.1}%", 100.0 * a.confidence),
        "Allan deviation",
    )
}

/// A term's value and the top of its interval as the table cell shows
/// them: `(value, high)`, an unresolved term's bound for both.
fn value_and_high(t: &NoiseTerm) -> Option<(f64, f64)> {
    match t {
        NoiseTerm::Resolved(e) => Some((e.value, e.high)),
        NoiseTerm::Unresolved {
            upper_bound: Some(b),
            ..
        } => Some((*b, *b)),
        NoiseTerm::Unresolved { .. } => None,
    }
}

/// Series of a table, each with its terms before and after.
type AllanRows<'a> = [(&'a str, NoiseTerms, Option<NoiseTerms>)];

/// One sentence per noise term that is higher after compensation than
/// before on some series of some table: the after term resolved and its
/// interval wholly above the before term's (or above the bound of an
/// unresolved before term), with the before and after values of those
/// series as the tables print them.
fn allan_terms_worse(
    tables: &[(&AllanRows<'_>, &str)],
    confidence: &str,
    section: &str,
) -> Vec<String> {
    type Pick = fn(&NoiseTerms) -> &NoiseTerm;
    let terms: [(&str, &str, Pick); 3] = [
        ("Bias instability", "deg/h", |t| &t.bias_instability),
        ("Angle random walk", "deg/√h", |t| &t.arw),
        ("Rate random walk", "deg/h/√h", |t| &t.rrw),
    ];
    let mut out = Vec::new();
    for (name, unit, pick) in terms {
        let mut parts = Vec::new();
        for (rows, what) in tables {
            let mut names = Vec::new();
            let (mut before, mut after) = (Vec::new(), Vec::new());
            for (series, b, a) in rows.iter() {
                let Some(a) = a else { continue };
                let (Some((bv, bhi)), NoiseTerm::Resolved(e)) = (value_and_high(pick(b)), pick(a))
                else {
                    continue;
                };
                if e.low > bhi {
                    names.push(*series);
                    before.push((bv, fmt(bv)));
                    after.push((e.value, fmt(e.value)));
                }
            }
            if names.is_empty() {
                continue;
            }
            let which = if names.len() == rows.len() {
                String::new()
            } else {
                format!("{}: ", names.join(", "))
            };
            parts.push(format!(
                "on {} of {} {what} ({which}{} → {} {unit})",
                names.len(),
                rows.len(),
                span(&before),
                span(&after)
            ));
        }
        if !parts.is_empty() {
            out.push(format!(
                "{name} after compensation is higher than before {}, the {confidence} intervals apart ({section}).",
                parts.join(" and ")
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nav_sensors::noise::Estimate;

    fn est(value: f64, half: f64) -> NoiseTerm {
        NoiseTerm::Resolved(Estimate {
            value,
            low: value - half,
            high: value + half,
            tau_from_s: 0.32,
            tau_to_s: 0.32,
            edf: 383.0,
        })
    }

    fn terms(arw: NoiseTerm, bi: NoiseTerm) -> NoiseTerms {
        NoiseTerms {
            arw,
            bias_instability: bi,
            rrw: NoiseTerm::Unresolved {
                reason: "short".into(),
                upper_bound: Some(27.0),
            },
        }
    }

    #[test]
    fn the_summary_says_bias_instability_rose_when_the_table_shows_it() {
        // The demo's channels X and Y1: bias instability 0.3969 → 0.5894 and
        // 0.3632 → 0.5684 deg/h, intervals apart; ARW overlapping on X,
        // apart on Y1; a third series whose terms did not move.
        let rows = vec![
            (
                "X",
                terms(est(0.002154, 0.00003), est(0.3969, 0.015)),
                Some(terms(est(0.002186, 0.00003), est(0.5894, 0.02))),
            ),
            (
                "Y1",
                terms(est(0.002018, 0.00002), est(0.3632, 0.013)),
                Some(terms(est(0.002077, 0.00002), est(0.5684, 0.02))),
            ),
            (
                "Z",
                terms(est(0.002, 0.00002), est(0.4, 0.013)),
                Some(terms(est(0.002, 0.00002), est(0.4, 0.013))),
            ),
        ];
        // A residue whose bias instability was not resolved before and is
        // resolved after above the bound the curve allowed.
        let residues = vec![(
            "K0",
            terms(
                est(0.002, 0.00003),
                NoiseTerm::Unresolved {
                    reason: "flat".into(),
                    upper_bound: Some(0.3),
                },
            ),
            Some(terms(est(0.002, 0.00003), est(0.5, 0.02))),
        )];
        let s = allan_terms_worse(
            &[(&rows, "channels"), (&residues, "parity residues")],
            "68.3%",
            "Allan",
        );
        assert_eq!(
            s,
            [
                "Bias instability after compensation is higher than before on 2 of 3 channels (X, Y1: 0.3632–0.3969 → 0.5684–0.5894 deg/h) and on 1 of 1 parity residues (0.3000 → 0.5000 deg/h), the 68.3% intervals apart (Allan).",
                "Angle random walk after compensation is higher than before on 1 of 3 channels (Y1: 0.002018 → 0.002077 deg/√h), the 68.3% intervals apart (Allan).",
            ]
        );
        // Nothing rose: nothing said.
        let same = vec![(
            "X",
            terms(est(0.002, 0.00003), est(0.4, 0.015)),
            Some(terms(est(0.002, 0.00003), est(0.39, 0.015))),
        )];
        assert!(allan_terms_worse(&[(&same, "channels")], "68.3%", "Allan").is_empty());
    }

    #[test]
    fn a_span_is_ordered_by_value_and_collapses_when_equal() {
        let c = |v: &[f64]| -> Vec<(f64, String)> { v.iter().map(|x| (*x, fmt(*x))).collect() };
        assert_eq!(span(&c(&[0.5, 0.25, 2.0])), "0.2500–2.000");
        assert_eq!(span(&c(&[1.5, 1.5])), "1.500");
    }
}
