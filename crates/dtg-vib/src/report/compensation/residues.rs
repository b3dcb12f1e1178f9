//! Section "Parity residues": the unit's residues (the paper's eq. 6 for
//! its unit, V·m otherwise) on the validation rows, Fig. 7 (residues with
//! and without compensation), where their power is and their spectra, and
//! fault detection on them; for a unit of three gyros, why there is none.

use super::ctx::{Ctx, pick};
use super::fdi;
use super::inputs::{ReportExtras, ResidueRms};
use crate::report::common::{Drawn, fmt};
use crate::report::common::{colours, positive_freq};
use plot::{Figure, Panel, Section, Series, Table};

/// The section's heading, which the summary names.
pub(super) const TITLE: &str = "Parity residues";

/// `before / after` of a residue's rms.
pub(super) fn reduction(s: &ResidueRms) -> f64 {
    s.before / s.after.unwrap_or(f64::NAN)
}

/// Why a unit has no residue, in a sentence.
pub(super) fn no_residue(ctx: &Ctx<'_>) -> String {
    format!(
        "The unit has {} gyros: nothing is redundant, so it has no parity residue and no fault detection; its channels are judged by their rms before and after (Summary).",
        ctx.unit.gyros().len()
    )
}

/// The section's figures, with their file stems (none for three gyros).
pub(super) fn figures(ctx: &Ctx<'_>) -> Vec<(Figure, &'static str)> {
    if ctx.stats.is_empty() {
        return Vec::new();
    }
    vec![
        (fig7(ctx), "fig7_residues"),
        (spectra(ctx), "residue_spectra"),
    ]
}

/// Fig. 7: residues with and without compensation, the training rows shaded
/// as in "Measured against predicted".
fn fig7(ctx: &Ctx<'_>) -> Figure {
    let res = &ctx.residues;
    let train = super::fit::training_spans(ctx);
    let mut fig7 = Figure::new(if train.is_some() {
        "Fig. 7 — residues with and without compensation (shaded: training rows; the rest: validation)"
    } else {
        "Fig. 7 — residues with and without compensation (interleaved split: alternate rows train and validate)"
    })
    .share_x();
    for (k, name) in res.names.iter().enumerate() {
        let t = &ctx.rows_t;
        let p = Panel::new(name.as_str(), "time (s)", format!("{name} (deg/h)"))
            .series(
                Series::line("without compensation", t.clone(), res.before[k].clone())
                    .colour(colours::BEFORE),
            )
            .series(
                Series::line("with compensation", t.clone(), res.after[k].clone())
                    .colour(colours::AFTER),
            );
        fig7 = fig7.panel(super::fit::shade_training(p, train.as_deref()));
    }
    fig7
}

/// The Welch segment for `n` validation rows: long enough to resolve
/// 0.1 Hz at 50 Hz, at most 512 samples.
fn segment(n: usize) -> usize {
    512.min(n.next_power_of_two() / 2).max(8)
}

/// The validation rows' sample rate (alternate rows of an interleaved
/// split are two samples apart).
fn fs_val(ctx: &Ctx<'_>) -> f64 {
    1.0 / ctx.dt / crate::split::row_spacing(ctx.val) as f64
}

/// Residue `k` before and after on the validation rows.
fn before_after(ctx: &Ctx<'_>, k: usize) -> (Vec<f64>, Vec<f64>) {
    (
        pick(&ctx.residues.before[k], ctx.val),
        pick(&ctx.residues.after[k], ctx.val),
    )
}

/// Residue spectra before and after, validation rows, at their own rate;
/// the 0 Hz bin (each segment's mean is removed) is left out.
fn spectra(ctx: &Ctx<'_>) -> Figure {
    let fs = fs_val(ctx);
    let mut spectra = Figure::new("Residue spectra on the validation rows (segment means removed)");
    for (k, name) in ctx.residues.names.iter().enumerate() {
        let (b, a) = before_after(ctx, k);
        let seg = segment(b.len());
        if b.len() >= seg {
            let sb = nav_sensors::vibration::welch(&b, fs, seg);
            let sa = nav_sensors::vibration::welch(&a, fs, seg);
            let (fb, db) = positive_freq(&sb.frequency_hz, &sb.density);
            let (fa, da) = positive_freq(&sa.frequency_hz, &sa.density);
            spectra = spectra.panel(
                Panel::psd(name.as_str(), "PSD ((deg/h)²/Hz)")
                    .series(Series::line("without compensation", fb, db).colour(colours::BEFORE))
                    .series(Series::line("with compensation", fa, da).colour(colours::AFTER)),
            );
        }
    }
    spectra
}

/// Where one residue's mean square is, `[before, after]`, (deg/h)²: its
/// mean squared (0 Hz, which the spectra leave out), then the Welch spectrum
/// integrated below 0.2 Hz, over 0.2–2 Hz and above 2 Hz.
pub(super) struct Powers {
    pub(super) residue: String,
    pub(super) mean2: [f64; 2],
    pub(super) bands: [[f64; 2]; 3],
}

/// The bands of [`Powers::bands`], Hz.
pub(super) const BANDS: [(f64, f64); 3] = [(0.0, 0.2), (0.2, 2.0), (2.0, f64::INFINITY)];

/// Each residue's [`Powers`] on the validation rows (residues too short
/// for one Welch segment are left out).
pub(super) fn powers(ctx: &Ctx<'_>) -> Vec<Powers> {
    let fs = fs_val(ctx);
    let mut out = Vec::new();
    for (k, name) in ctx.residues.names.iter().enumerate() {
        let (b, a) = before_after(ctx, k);
        let seg = segment(b.len());
        if b.len() < seg {
            continue;
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let sb = nav_sensors::vibration::welch(&b, fs, seg);
        let sa = nav_sensors::vibration::welch(&a, fs, seg);
        let df = fs / seg as f64;
        let band = |sp: &nav_sensors::vibration::Spectrum, (lo, hi): (f64, f64)| {
            sp.frequency_hz
                .iter()
                .zip(&sp.density)
                .filter(|(f, _)| **f >= lo && **f < hi)
                .map(|(_, d)| d * df)
                .sum::<f64>()
        };
        out.push(Powers {
            residue: name.clone(),
            mean2: [mean(&b).powi(2), mean(&a).powi(2)],
            bands: BANDS.map(|bd| [band(&sb, bd), band(&sa, bd)]),
        });
    }
    out
}

/// Where each residue's mean square is, before and after.
fn power_table(p: &[Powers]) -> Table {
    let mut t = Table::new([
        "residue",
        "mean² before",
        "mean² after",
        "< 0.2 Hz before",
        "< 0.2 Hz after",
        "0.2–2 Hz before",
        "0.2–2 Hz after",
        "> 2 Hz before",
        "> 2 Hz after",
    ])
    .caption("Where the mean square is, (deg/h)², validation rows: the mean, then the Welch spectrum integrated over three bands.");
    for p in p {
        let mut row = vec![p.residue.clone(), fmt(p.mean2[0]), fmt(p.mean2[1])];
        for [b, a] in p.bands {
            row.push(fmt(b));
            row.push(fmt(a));
        }
        t = t.row(row);
    }
    t
}

/// What the spectra show, and what they do not.
const SPECTRA_NOTE: &str = "How to read the spectra. Both curves are computed the same way (the same validation rows, the same rate, Hann-windowed Welch segments, the same normalisation), and each segment's mean is removed, so a spectrum shows nothing of a constant offset or of drifts slower than one segment. Most of what compensation removes is exactly there: the vibration-rectified bias (the mean) and its slow change, which the table above puts in the mean² and < 0.2 Hz columns.";

/// The measured trade, in numbers: what compensation removed below 0.2 Hz
/// (with the mean) and what it added at 0.2–2 Hz and above, with the reason.
fn spectra_numbers(p: &[Powers], window_s: f64) -> String {
    let low = |p: &Powers, k: usize| p.mean2[k] + p.bands[0][k];
    let mut rises = Vec::new();
    for p in p {
        let [b, a] = p.bands[1];
        if a > b {
            rises.push(format!(
                "{} {} → {} ({:.1}×)",
                p.residue,
                fmt(b),
                fmt(a),
                a / b
            ));
        }
    }
    let removed: Vec<String> = p
        .iter()
        .map(|p| format!("{} {} → {}", p.residue, fmt(low(p, 0)), fmt(low(p, 1))))
        .collect();
    let high: Vec<String> = p
        .iter()
        .filter(|p| p.bands[2][1] > p.bands[2][0])
        .map(|p| {
            format!(
                "{} {} → {}",
                p.residue,
                fmt(p.bands[2][0]),
                fmt(p.bands[2][1])
            )
        })
        .collect();
    let mut text = format!(
        "Measured on these rows, (deg/h)²: compensation removed the mean² and the power below 0.2 Hz ({}).",
        removed.join("; ")
    );
    if rises.is_empty() {
        text.push_str(" It added no power at 0.2–2 Hz.");
    } else {
        text.push_str(&format!(
            " It added power at 0.2–2 Hz, where the compensated curve lies above the uncompensated one: {}. The reason: the model predicts the error from the vibration level it estimates over each {} s acceleration window, and that estimate wanders from one window to the next (about 20% for a 50-sample window); the wander is at the window's rate and below, so it lands at 0.2–2 Hz as prediction error while the mean it corrects is right on average. A longer --window estimates the level better and moves the wander lower (measured on the demo record: 2.9–3.4× with a 1-s window, 1.2–1.3× with a 5-s one; docs/dtg-vib.md, \"Why the compensated residue spectrum can lie above the uncompensated one\").",
            rises.join("; "),
            crate::report::common::short(window_s)
        ));
    }
    if !high.is_empty() {
        text.push_str(&format!(
            " Above 2 Hz it added {}: the prediction is a nonlinear function of the acceleration windows, so it is not band-limited like the low-passed output it is subtracted from.",
            high.join("; ")
        ));
    }
    text
}

/// The section, once its figures are drawn.
pub(super) fn section<C>(ctx: &Ctx<'_>, extras: &ReportExtras<'_, C>, drawn: &Drawn) -> Section {
    if ctx.stats.is_empty() {
        return Section::new(TITLE).text(no_residue(ctx));
    }
    let p = powers(ctx);
    let mut residue_table = Table::new([
        "residue",
        "rms before (deg/h)",
        "rms after (deg/h)",
        "reduction",
    ])
    .caption("Validation rows of the model's split.");
    for s in &ctx.stats {
        residue_table = residue_table.row([
            s.name.clone(),
            fmt(s.before),
            fmt(s.after.unwrap_or(f64::NAN)),
            format!("{:.2}×", reduction(s)),
        ]);
    }
    let sec = Section::new(TITLE)
        .text(format!(
            "The residues {} are fixed combinations of the {} gyros' outputs in which the rate cancels (the unit's parity residues), so they show each compensation's gain without a rate reference; here of the pre-processed outputs (calibrated, low-passed), before and after subtracting each channel's prediction.",
            ctx.residues.names.join(", "),
            ctx.unit.gyros().len()
        ))
        .table(residue_table)
        .figure(
            drawn.get("fig7_residues"),
            "Fig. 7: residues with and without compensation over the whole record; the shaded stretch is what the model was fitted on, the rest is validation.",
        )
        .table(power_table(&p))
        .figure(
            drawn.get("residue_spectra"),
            "Residue spectra before and after, validation rows.",
        )
        .text(SPECTRA_NOTE)
        .text(spectra_numbers(&p, ctx.window_s));
    let Some(parity) = extras.parity.filter(|p| !p.residues.is_empty()) else {
        return sec;
    };
    let sec = sec.table(fdi::table(parity));
    match &parity.fdi {
        Some(f) => fdi::paragraphs(f, ctx.unit)
            .into_iter()
            .fold(sec, |sec, text| sec.text(text)),
        None => sec,
    }
}
