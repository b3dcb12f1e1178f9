//! Section "Residues (eq. 6)": the residue table on the validation rows,
//! Fig. 7 (residues with and without compensation) and the residue spectra.

use super::{Ctx, Drawn, fmt, pick};
use nav_sensors::geometry::Residue;
use plot::{Figure, Panel, Section, Series, Table};

/// The section's figures, with their file stems.
pub(super) fn figures(ctx: &Ctx<'_>) -> Vec<(Figure, &'static str)> {
    vec![
        (fig7(ctx), "fig7_residues"),
        (spectra(ctx), "residue_spectra"),
    ]
}

/// Fig. 7: residues with and without compensation.
fn fig7(ctx: &Ctx<'_>) -> Figure {
    let res = &ctx.applied.residues;
    let mut fig7 = Figure::new("Fig. 7 — residues with and without compensation").share_x();
    for r in Residue::ALL {
        let k = r.index();
        fig7 = fig7.panel(
            Panel::new(r.name(), "time (s)", format!("{} (deg/h)", r.name()))
                .series(
                    Series::line("without compensation", res.t.clone(), res.before[k].clone())
                        .colour(1),
                )
                .series(
                    Series::line("with compensation", res.t.clone(), res.after[k].clone())
                        .colour(0),
                ),
        );
    }
    fig7
}

/// Residue spectra before and after, validation rows (at their own rate:
/// alternate rows of an interleaved split are two samples apart).
fn spectra(ctx: &Ctx<'_>) -> Figure {
    let val = &ctx.applied.val;
    let fs_val = 1.0 / ctx.record.dt() / crate::split::row_spacing(val) as f64;
    let mut spectra = Figure::new("Residue spectra on the validation rows");
    for r in Residue::ALL {
        let k = r.index();
        let b = pick(&ctx.applied.residues.before[k], val);
        let a = pick(&ctx.applied.residues.after[k], val);
        let seg = 512.min(b.len().next_power_of_two() / 2).max(8);
        if b.len() >= seg {
            let sb = nav_sensors::vibration::welch(&b, fs_val, seg);
            let sa = nav_sensors::vibration::welch(&a, fs_val, seg);
            spectra = spectra.panel(
                Panel::psd(r.name(), "PSD ((deg/h)²/Hz)")
                    .series(
                        Series::line("without compensation", sb.frequency_hz.clone(), sb.density)
                            .colour(1),
                    )
                    .series(
                        Series::line("with compensation", sa.frequency_hz, sa.density).colour(0),
                    ),
            );
        }
    }
    spectra
}

/// The section, once its figures are drawn.
pub(super) fn section(ctx: &Ctx<'_>, drawn: &Drawn) -> Section {
    let mut residue_table = Table::new([
        "residue",
        "rms before (deg/h)",
        "rms after (deg/h)",
        "reduction",
    ])
    .caption("Validation rows of the model's split.");
    for s in &ctx.stats {
        residue_table = residue_table.row([
            s.residue.name().to_string(),
            fmt(s.rms_before),
            fmt(s.rms_after),
            format!("{:.2}×", s.reduction),
        ]);
    }
    Section::new("Residues (eq. 6)")
        .table(residue_table)
        .figure(
            drawn.get("fig7_residues"),
            "Fig. 7: residues with and without compensation.",
        )
        .figure(
            drawn.get("residue_spectra"),
            "Residue spectra before and after, validation rows.",
        )
}
