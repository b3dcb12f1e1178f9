//! Sections "Where it fails" and "Diagnosis" of the final report: a compact
//! reading of a diagnosis of the model (the worst time segment, frequency
//! band and acceleration per channel, the failing tests; the top candidates
//! with their coefficients), every column explained, and a link to the
//! diagnosis page for the figures and the findings in full.

use super::inputs::DiagnosisExtra;
use crate::diagnose::Band;
use crate::report::common::{fmt, short};
use crate::report::diagnosis::channel::candidate_cells;
use crate::report::diagnosis::overview::failing_cell;
use crate::report::diagnosis::reading::{ChannelWording, candidate_columns};
use nav_sensors::geometry::Axis;
use plot::{Section, Table};
use std::fmt::Display;
use sysid::diagnose::ChannelDiagnosis;

/// The segment with the largest residual rms, against the channel's.
fn worst_segment<C>(c: &ChannelDiagnosis<C, Axis>) -> String {
    c.segments
        .iter()
        .max_by(|a, b| a.residual_rms.total_cmp(&b.residual_rms))
        .map_or("—".into(), |s| {
            format!(
                "{:.0}–{:.0} s: rms {} ({:.1}× the channel's)",
                s.t_start,
                s.t_end,
                fmt(s.residual_rms),
                s.residual_rms / c.rms
            )
        })
}

/// The band furthest above the white floor.
pub(super) fn top_band<C>(c: &ChannelDiagnosis<C, Axis>) -> Option<&Band> {
    c.bands
        .iter()
        .max_by(|a, b| a.ratio_to_floor.total_cmp(&b.ratio_to_floor))
}

/// A band's edges as the page names them: `0–0.1 Hz`.
pub(super) fn band_name(b: &Band) -> String {
    format!("{}–{} Hz", short(b.f_lo_hz), short(b.f_hi_hz))
}

/// The band furthest above the white floor, as the table cell reads.
fn worst_band<C>(c: &ChannelDiagnosis<C, Axis>) -> String {
    top_band(c).map_or("—".into(), |b| {
        format!(
            "{}: {:.1}× the white floor ({:.0}% of the power)",
            band_name(b),
            b.ratio_to_floor,
            100.0 * b.share
        )
    })
}

/// The acceleration axis the residual's mean follows most.
fn worst_regime<C>(c: &ChannelDiagnosis<C, Axis>) -> String {
    c.regimes
        .iter()
        .max_by(|a, b| a.mean_spread_sigma.total_cmp(&b.mean_spread_sigma))
        .map_or("—".into(), |r| {
            format!("{}: bin means spread {:.1} σ", r.axis, r.mean_spread_sigma)
        })
}

/// Section "Where it fails".
fn where_it_fails<C: Display>(d: &DiagnosisExtra<'_, C>) -> Section {
    let mut t = Table::new([
        "channel",
        "val rms (deg/h)",
        "worst time segment",
        "band most above the white floor",
        "acceleration it follows most",
        "failing tests",
    ])
    .caption(format!(
        "Where the residual of {} is largest, validation rows.",
        d.of
    ));
    for c in &d.diagnosis.channels {
        t = t.row([
            c.channel.to_string(),
            fmt(c.rms),
            worst_segment(c),
            worst_band(c),
            worst_regime(c),
            failing_cell(&c.failing),
        ]);
    }
    Section::new("Where it fails")
        .table(t)
        .text("Columns. val rms: the residual's rms on the validation rows. worst time segment: of the record cut into equal segments, the one whose residual rms is largest, against the channel's rms (a segment well above 1× points at a level step, a warm-up or a transient). band most above the white floor: of the frequency bands, the one whose residual power stands furthest above what a white residual of the same level would have there after the pre-filter (≫ 1× is structure the model missed), with its share of the residual power. acceleration it follows most: the residual binned by each acceleration axis; the spread of the bin means in units of their standard error (≫ 3 σ points at a missing g or g² term of that axis). failing tests: the residual-correlation tests that fail, explained under Diagnosis below.")
        .link(
            d.page.clone(),
            "The diagnosis page: the findings in words, the residual spectra, the whiteness and independence tests and every candidate",
        )
}

/// Section "Diagnosis".
fn diagnosis<C: Display>(d: &DiagnosisExtra<'_, C>, wording: &ChannelWording) -> Section {
    let mut t = Table::new([
        "channel",
        "suggested",
        "top candidate",
        "ERR",
        "coefficient ± standard error (unit)",
        "95% interval",
        "p (forward step)",
        "collinear with",
    ])
    .caption(format!(
        "The diagnosis of {}: each channel's suggestions, or its top candidate.",
        d.of
    ));
    let mut advice = Vec::new();
    for c in &d.diagnosis.channels {
        let shown: Vec<_> = if c.suggested.is_empty() {
            c.candidates.iter().take(1).collect()
        } else {
            c.candidates.iter().filter(|k| k.significant).collect()
        };
        if shown.is_empty() {
            t = t.row([
                c.channel.to_string(),
                "nothing".into(),
                "—".into(),
                "—".into(),
                "—".into(),
                "—".into(),
                "—".into(),
                "—".into(),
            ]);
        }
        for k in shown {
            let suggested = if c.suggested.is_empty() {
                "nothing".into()
            } else {
                c.suggested.join(", ")
            };
            t = t.row(
                [c.channel.to_string(), suggested]
                    .into_iter()
                    .chain(candidate_cells(k)),
            );
            if let Some(s) = &k.separation {
                advice.push(format!("{} {}: {}", c.channel, k.effect, s.advice));
            }
        }
    }
    let p = d
        .diagnosis
        .channels
        .first()
        .map_or("—".to_string(), |c| fmt(c.p_threshold));
    let mut sec = Section::new("Diagnosis").table(t);
    for a in advice {
        sec = sec.text(a);
    }
    sec.text(format!(
        "Columns. suggested: the effects to add with --add-effect CHANNEL=ID (both thresholds passed), or nothing. top candidate: the suggestion, or the candidate that explains most when nothing passes. {}",
        candidate_columns(d.min_err, &p, wording),
    ))
    .link(d.page.clone(), "Every candidate, the findings and the tests' figures: the diagnosis page")
}

/// Both sections.
pub(super) fn sections<C: Display>(
    d: &DiagnosisExtra<'_, C>,
    wording: &ChannelWording,
) -> [Section; 2] {
    [where_it_fails(d), diagnosis(d, wording)]
}
